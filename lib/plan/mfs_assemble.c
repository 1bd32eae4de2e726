#include "mfs_assemble.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_threads.h"

mfs_forms mfs_forms_stiffness(const mfs_material *m)
{
  mfs_forms f = {.stiffness = 1, .physics = m->physics};
  if (m->physics == MFS_PHYS_PLANE_STRAIN) {
    double lam = mfs_material_lambda(m);
    f.c[0] = lam + 2.0 * m->modulus;
    f.c[1] = lam;
    f.c[2] = m->modulus;
  } else {
    f.c[0] = m->modulus;
  }
  return f;
}

void mfs_row_free(mfs_row *r)
{
  if (!r)
    return;
  mfs_free(r->col);
  mfs_free(r->pcol);
  mfs_free(r->K);
  mfs_free(r->M);
  mfs_free(r->G);
  mfs_free(r->mark);
  mfs_free(r->eidx);
  mfs_free(r->dphi);
  mfs_free(r->dgrad);
  mfs_free(r->dwork);
  mfs_eval_free(&r->ev);
  memset(r, 0, sizeof *r);
}

/* The most columns a row can have: the sum of the list lengths of the
 * points that see the particle, at most n. */
static size_t row_cap(const mfs_plan *pl)
{
  const mfs_particles *p = mfs_plan_particles(pl);
  const size_t n = p->n;
  const size_t *tptr;
  const int *tidx;
  const double *ttab;
  mfs_plan_table(pl, &tptr, &tidx, &ttab);
  size_t cap = 1;
#pragma omp parallel for reduction(max : cap) schedule(static)
  for (size_t I = 0; I < n; I++) {
    size_t nq, s = 0;
    const int *Q;
    mfs_plan_particle_points(pl, I, &nq, &Q);
    for (size_t t = 0; t < nq; t++)
      s += tptr[Q[t] + 1] - tptr[Q[t]];
    cap = s > cap ? s : cap;
  }
  return cap < n ? cap : (n ? n : 1);
}

/* mfs_row_init with the row capacity given; table: the plan's table must
 * have the order the forms need (else the caller supplies chunks). */
static mfs_status row_init_cap(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t cap,
                               int table)
{
  memset(r, 0, sizeof *r);
  int need2 = f->euler != MFS_EULER_NONE || f->ls_beta > 0.0;
  if (table && mfs_plan_order(pl) < (need2 ? 2 : 1))
    return MFS_EINVAL;
  if (need2 && mfs_plan_disc(pl)->kernel->cusp) /* no second derivative at the cone */
    return MFS_ENOTSUP;
  const mfs_particles *p = mfs_plan_particles(pl);
  int euler2 = p->dim == 2 && f->physics == MFS_PHYS_PLANE_STRAIN;
  if (f->euler != MFS_EULER_NONE && !(p->dim == 1 && f->physics == MFS_PHYS_SCALAR) && !euler2)
    return MFS_EINVAL;
  if (f->outer && f->physics != MFS_PHYS_PLANE_STRAIN)
    return MFS_EINVAL;
  if (f->euler == MFS_EULER_CONSISTENT &&
      !(p->dim == 1 ? mfs_plan_disc(pl)->shape->dpos_1d != NULL
                    : mfs_plan_disc(pl)->shape->dpos_grad != NULL))
    return MFS_ENOTSUP;
  size_t n = p->n;
  mfs_plan_table(pl, &r->tptr, &r->tidx, &r->ttab);
  const mfs_quad *q = mfs_plan_quad(pl);
  r->qw = q->w;
  r->qx = q->x;
  r->qnode = q->node;
  r->nc = table ? mfs_plan_ncomp(pl) : mfs_shape_ncomp(p->dim, need2 ? 2 : 1);
  r->dim = p->dim;
  r->ndof = mfs_physics_ndof(f->physics);
  r->gsz = euler2 ? 4 : 1;
  r->cap = cap;
  size_t acc = cap + 1; /* and the discard slot */
  r->col = mfs_malloc(cap * sizeof *r->col);
  r->pcol = mfs_malloc(mfs_plan_max_neighbours(pl) * sizeof *r->pcol);
  r->mark = mfs_malloc((n ? n : 1) * sizeof *r->mark);
  if (f->stiffness)
    r->K = mfs_malloc(acc * (size_t)(r->ndof * r->ndof) * sizeof *r->K);
  if (f->density != 0.0 || f->ls_beta > 0.0)
    r->M = mfs_malloc(acc * sizeof *r->M);
  if (f->euler != MFS_EULER_NONE)
    r->G = mfs_malloc(acc * (size_t)r->gsz * sizeof *r->G);
  if (!r->col || !r->pcol || !r->mark || (f->stiffness && !r->K) ||
      ((f->density != 0.0 || f->ls_beta > 0.0) && !r->M) || (f->euler && !r->G))
    goto nomem;
  for (size_t i = 0; i < n; i++)
    r->mark[i] = -1;
  if (f->euler == MFS_EULER_CONSISTENT) {
    size_t mx = mfs_plan_max_neighbours(pl);
    r->eidx = mfs_malloc(mx * sizeof *r->eidx);
    r->dphi = mfs_malloc(mx * sizeof *r->dphi);
    r->dgrad = mfs_malloc(mx * (size_t)(p->dim * p->dim) * sizeof *r->dgrad);
    r->dwork = mfs_malloc(mfs_shape_work_len(p->dim, (int)mx) * sizeof *r->dwork);
    if (!r->eidx || !r->dphi || !r->dgrad || !r->dwork ||
        mfs_eval_init(&r->ev, mfs_plan_disc(pl), mfs_plan_support(pl), 1, &p->box, mx) != MFS_OK)
      goto nomem;
  }
  return MFS_OK;
nomem:
  mfs_row_free(r);
  return MFS_ENOMEM;
}

mfs_status mfs_row_init(mfs_row *r, const mfs_plan *pl, const mfs_forms *f)
{
  memset(r, 0, sizeof *r);
  mfs_status st = mfs_plan_transpose(pl);
  if (st != MFS_OK)
    return st;
  return row_init_cap(r, pl, f, row_cap(pl), 1);
}

static int add_euler_2d(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I,
                        const mfs_point *pt, size_t iI, const int *col)
{
  const int nc = pt->ncomp;
  const double w = pt->w, *tab = pt->phi, *H = tab + iI * (size_t)nc + 3; /* H_jm = d_m d_j phi_I */
  const size_t nn = pt->nn;
  const mfs_particles *p = mfs_plan_particles(pl);
  const double F[2] = {f->stretch > 0.0 ? f->stretch : 1.0, f->stretch_y > 0.0 ? f->stretch_y : 1.0};
  for (size_t e = 0; e < nn; e++) {
    int K = pt->idx[e];
    const double *fk = tab + e * (size_t)nc;
    double T[4];
    if (pt->node >= 0) {
      if (K != pt->node)
        continue;
      T[0] = T[3] = 1.0;
      T[1] = T[2] = 0.0;
    } else if (f->euler == MFS_EULER_PAPER) {
      double dQK[3], dQI[3]; /* x_K - x_I through the point, minimum image */
      mfs_box_delta(&p->box, pt->x, p->x + (size_t)K * 2, dQK);
      mfs_box_delta(&p->box, pt->x, p->x + I * 2, dQI);
      double u[2] = {(1.0 - 1.0 / F[0]) * (dQK[0] - dQI[0]), (1.0 - 1.0 / F[1]) * (dQK[1] - dQI[1])};
      for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++)
          T[m * 2 + k] = F[m] * ((m == k ? fk[0] : 0.0) - u[m] * fk[1 + k]);
    } else {
      T[0] = T[3] = fk[0];
      T[1] = T[2] = 0.0;
    }
    double *g = r->G + (size_t)col[e] * 4;
    for (int j = 0; j < 2; j++)
      for (int k = 0; k < 2; k++)
        g[j * 2 + k] += w * (H[j * 2] * T[k] + H[j * 2 + 1] * T[2 + k]);
  }
  if (f->euler == MFS_EULER_PAPER) {
    double *g = r->G + (size_t)col[iI] * 4;
    for (int q = 0; q < 4; q++)
      g[q] -= w * H[q];
    return MFS_OK;
  }
  int nk = mfs_eval_gather(&r->ev, pt->x, p->x, p->vol, pt->idx, nn, pt->node, r->eidx);
  if (nk != (int)nn)
    return MFS_EINVAL;
  /* d grad phi_I / d x_K,l for every neighbour K at once */
  mfs_status st = mfs_shape_dpos_grad(r->ev.shape, &r->ev.ctx, nk, mfs_eval_offsets(&r->ev),
                                      mfs_eval_volumes(&r->ev), (int)iI, r->dgrad, r->dwork);
  if (st != MFS_OK)
    return st;
  for (int k = 0; k < nk; k++)
    for (int l = 0; l < 2; l++) {
      double *g = r->G + (size_t)col[k] * 4;
      g[l] += w * r->dgrad[(k * 2 + l) * 2];
      g[2 + l] += w * r->dgrad[(k * 2 + l) * 2 + 1];
    }
  return MFS_OK;
}

/* The forms' contributions of one quadrature point pt to row I (at position
 * iI of the point's list); col[k] is the row position of neighbour k.  The
 * arithmetic of each term is fixed (a += (w c) g, ...) so that the values do
 * not depend on how the loops are split. */
static inline int add_point(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I,
                            const mfs_point *pt, size_t iI, const int *col)
{
  const int nc = pt->ncomp, dim = r->dim, nd = r->ndof, nd2 = nd * nd;
  const double w = pt->w, *tab = pt->phi, *fi = tab + iI * (size_t)nc;
  const size_t nn = pt->nn;
  if (f->stiffness) {
    double *K = r->K;
    if (f->outer) { /* A^{jl}: grad phi_I (x) grad phi_J */
      double ix = w * fi[1], iy = w * fi[2];
      for (size_t e = 0; e < nn; e++) {
        const double *fj = tab + e * (size_t)nc;
        double *a = K + (size_t)col[e] * nd2, jx = fj[1], jy = fj[2];
        a[0] += ix * jx;
        a[1] += ix * jy;
        a[2] += iy * jx;
        a[3] += iy * jy;
      }
    } else if (f->physics == MFS_PHYS_PLANE_STRAIN) { /* B_I^T D B_J */
      double c0 = f->c[0], c1 = f->c[1], c2 = f->c[2];
      double ix = fi[1], iy = fi[2];
      for (size_t e = 0; e < nn; e++) {
        const double *fj = tab + e * (size_t)nc;
        double *a = K + (size_t)col[e] * nd2, jx = fj[1], jy = fj[2];
        a[0] += w * (c0 * ix * jx + c2 * iy * jy);
        a[1] += w * (c1 * ix * jy + c2 * iy * jx);
        a[2] += w * (c1 * iy * jx + c2 * ix * jy);
        a[3] += w * (c0 * iy * jy + c2 * ix * jx);
      }
    } else if (dim == 2) {
      double wc = w * f->c[0], i1 = fi[1], i2 = fi[2];
      for (size_t e = 0; e < nn; e++) {
        const double *fj = tab + e * (size_t)nc;
        double g = 0.0;
        g += i1 * fj[1];
        g += i2 * fj[2];
        K[col[e]] += wc * g;
      }
    } else {
      double wc = w * f->c[0];
      for (size_t e = 0; e < nn; e++) {
        const double *fj = tab + e * (size_t)nc;
        double g = 0.0;
        for (int k = 0; k < dim; k++)
          g += fi[1 + k] * fj[1 + k];
        K[col[e]] += wc * g;
      }
    }
  }
  if (f->density != 0.0) {
    double wf = w * f->density * fi[0];
    for (size_t e = 0; e < nn; e++)
      r->M[col[e]] += wf * tab[e * (size_t)nc];
  }
  double lapI = 0.0;
  if (f->ls_beta > 0.0 || f->euler != MFS_EULER_NONE)
    for (int k = 0; k < dim; k++)
      lapI += fi[1 + dim + k * dim + k];
  if (f->ls_beta > 0.0) {
    double beta = f->ls_beta;
    for (size_t e = 0; e < nn; e++) {
      const double *fk = tab + e * (size_t)nc;
      double lapK = 0.0;
      for (int k = 0; k < dim; k++)
        lapK += fk[1 + dim + k * dim + k];
      r->K[col[e] * nd2] += beta * w * lapI * lapK;
      r->M[col[e]] -= beta * w * lapI * fk[0];
    }
  }
  if (f->euler != MFS_EULER_NONE && r->gsz == 4)
    return add_euler_2d(r, pl, f, I, pt, iI, col);
  if (f->euler == MFS_EULER_PAPER) {
    /* kernel motion, phi_I''(Q) (u~_Q - u~_I): eqs 71, 89-92 */
    const mfs_particles *p = mfs_plan_particles(pl);
    double F = f->stretch > 0.0 ? f->stretch : 1.0;
    for (size_t e = 0; e < nn; e++) {
      int K = pt->idx[e];
      const double *fk = tab + e * (size_t)nc;
      if (pt->node >= 0) {
        if (K == pt->node)
          r->G[col[e]] += w * lapI;
      } else {
        double dQK[3], dQI[3]; /* x_K - x_I through the point, minimum image */
        mfs_box_delta(&p->box, pt->x, p->x + (size_t)K * dim, dQK);
        mfs_box_delta(&p->box, pt->x, p->x + I * dim, dQI);
        double uK = (1.0 - 1.0 / F) * (dQK[0] - dQI[0]); /* eq. 92 */
        r->G[col[e]] += w * lapI * F * (fk[0] - fk[1] * uK);
      }
    }
    r->G[col[iI]] -= w * lapI;
  } else if (f->euler == MFS_EULER_CONSISTENT) {
    /* phi_I''(Q) u~_Q with u~_Q = u~_node or sum_K phi_K(Q) u~_K, then the
     * position derivatives d phi_I'(Q) / d x_K */
    for (size_t e = 0; e < nn; e++) {
      int K = pt->idx[e];
      if (pt->node >= 0) {
        if (K == pt->node)
          r->G[col[e]] += w * lapI;
      } else {
        r->G[col[e]] += w * lapI * tab[e * (size_t)nc];
      }
    }
    const mfs_particles *p = mfs_plan_particles(pl);
    int nk = mfs_eval_gather(&r->ev, pt->x, p->x, p->vol, pt->idx, nn, pt->node, r->eidx);
    if (nk != (int)nn)
      return MFS_EINVAL;
    for (int k = 0; k < nk; k++) {
      mfs_status st = mfs_shape_dpos_1d(r->ev.shape, &r->ev.ctx, nk, mfs_eval_offsets(&r->ev),
                                 mfs_eval_volumes(&r->ev), k, r->dphi, r->dgrad);
      if (st != MFS_OK)
        return st;
      r->G[col[k]] += w * r->dgrad[iI];
    }
  }
  return MFS_OK;
}

/* Point Q of the plan as a row reads it: its list, and its table row from
 * the plan's table or from the chunk of the sweep. */
static inline void row_point(const mfs_row *r, size_t Q, mfs_point *pt)
{
  size_t e0 = r->tptr[Q]; /* mfs_plan_point, from the cached table */
  /* field by field: an initializer would clear the padding (a memset) */
  pt->nn = r->tptr[Q + 1] - e0;
  pt->idx = r->tidx + e0;
  pt->phi = r->cslot ? r->ctab + (size_t)r->cslot[Q - r->cq0] * (size_t)r->nc
                     : r->ttab + e0 * (size_t)r->nc;
  pt->ncomp = r->nc;
  pt->w = r->qw[Q];
  pt->x = r->qx + Q * (size_t)r->dim;
  pt->node = r->qnode[Q];
}

/* Zero the accumulators of column s. */
static inline void row_zero(mfs_row *r, size_t s)
{
  const int nd2 = r->ndof * r->ndof;
  if (r->K) {
    if (nd2 == 1)
      r->K[s] = 0.0;
    else
      for (int k = 0; k < nd2; k++)
        r->K[s * nd2 + k] = 0.0;
  }
  if (r->M)
    r->M[s] = 0.0;
  if (r->G)
    for (int k = 0; k < r->gsz; k++)
      r->G[s * (size_t)r->gsz + k] = 0.0;
}

/* A point's table row of particle I (in its list: its point sees it), and
 * rho w phi_I added to *lump where rho != 0 (the lumped mass's row sum). */
static inline const double *point_self(const mfs_point *pt, size_t I, double rho, double *lump)
{
  size_t iI = 0;
  while (iI < pt->nn && pt->idx[iI] != (int)I)
    iI++;
  if (iI == pt->nn)
    iI = 0; /* as the general loop (never: I is in the list of each of its points) */
  const double *fi = pt->phi + iI * (size_t)pt->ncomp;
  if (rho != 0.0)
    *lump += rho * pt->w * fi[0];
  return fi;
}

/* mfs_row_assemble for the stiffness of a 2D scalar (anti-plane) model
 * alone, the rows of K and of its Gershgorin bound: one pass over each
 * point's list (the columns met and their terms together) instead of two,
 * with the same arithmetic as add_point's (the same values, bit for bit). */
static mfs_status row_assemble_scalar_2d(mfs_row *r, const mfs_forms *f, size_t I,
                                         size_t nq, const int *Qs)
{
  const double rho = f->lumped_density, c0 = f->c[0];
  double *K = r->K;
  for (size_t t = 0; t < nq; t++) {
    mfs_point pt;
    row_point(r, (size_t)Qs[t], &pt);
    const int nc = pt.ncomp;
    const double *tab = pt.phi;
    const double *fi = point_self(&pt, I, rho, &r->lump), wc = pt.w * c0, i1 = fi[1], i2 = fi[2];
    for (size_t e = 0; e < pt.nn; e++) {
      int J = pt.idx[e], s = r->mark[J];
      if (s < 0) {
        s = (int)r->len++;
        r->mark[J] = s;
        r->col[s] = J;
        K[s] = 0.0;
      }
      const double *fj = tab + e * (size_t)nc;
      double g = 0.0;
      g += i1 * fj[1];
      g += i2 * fj[2];
      K[s] += wc * g;
    }
  }
  return MFS_OK;
}

/* The points of particle I into row r (r->len, r->col and r->mark set up):
 * with grow, a column met for the first time is appended; without, every
 * neighbour must already have a mark (a column of the pattern or the discard
 * slot r->cap), and one without is MFS_EINVAL. */
static mfs_status row_points(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I, int grow)
{
  size_t nq;
  const int *Qs;
  mfs_plan_particle_points(pl, I, &nq, &Qs);
  int *col = r->pcol, st = MFS_OK;
  const double rho = f->lumped_density;
  r->lump = 0.0;
  for (size_t t = 0; t < nq && st == MFS_OK; t++) {
    mfs_point pt;
    row_point(r, (size_t)Qs[t], &pt);
    size_t iI = 0;
    for (size_t e = 0; e < pt.nn; e++) {
      int J = pt.idx[e];
      iI = J == (int)I ? e : iI;
      if (grow && r->mark[J] < 0) { /* a column met for the first time */
        size_t s = r->len++;
        r->mark[J] = (int)s;
        r->col[s] = J;
        row_zero(r, s);
      }
      col[e] = r->mark[J];
      if (col[e] < 0) { /* not in the pattern */
        st = MFS_EINVAL;
        break;
      }
    }
    if (st != MFS_OK)
      break;
    if (rho != 0.0) /* as mfs_assemble_mass_lumped's loop over the points adds it */
      r->lump += rho * pt.w * pt.phi[iI * (size_t)pt.ncomp];
    st = add_point(r, pl, f, I, &pt, iI, col);
  }
  return st;
}

mfs_status mfs_row_assemble(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I)
{
  for (size_t s = 0; s < r->len; s++) /* reset the marks of the last row */
    r->mark[r->col[s]] = -1;
  r->len = 0;
  r->lump = 0.0;
  if (r->dim == 2 && r->ndof == 1 && f->stiffness && !f->outer &&
      f->physics != MFS_PHYS_PLANE_STRAIN && f->density == 0.0 && f->ls_beta <= 0.0 &&
      f->euler == MFS_EULER_NONE && !r->M && !r->G) {
    size_t nq;
    const int *Qs;
    mfs_plan_particle_points(pl, I, &nq, &Qs);
    return row_assemble_scalar_2d(r, f, I, nq, Qs);
  }
  return row_points(r, pl, f, I, 1);
}

/* Row I into given columns: cols[0..len) (particle indices, the row of a
 * pattern); neighbours not among them must have their mark at r->cap (the
 * discard slot: the fixed particles of the pattern). */
static mfs_status row_assemble_into(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I,
                                    const int *cols, size_t len)
{
  for (size_t s = 0; s < len; s++) {
    r->mark[cols[s]] = (int)s;
    r->col[s] = cols[s];
    row_zero(r, s);
  }
  row_zero(r, r->cap);
  r->len = len;
  mfs_status st = row_points(r, pl, f, I, 0);
  for (size_t s = 0; s < len; s++)
    r->mark[cols[s]] = -1;
  return st;
}

void mfs_row_sort(mfs_row *r)
{
  const int nd2 = r->ndof * r->ndof;
  for (size_t e = 1; e < r->len; e++) { /* insertion sort: rows are short */
    int c = r->col[e];
    const int gs = r->gsz;
    double k[4] = {0, 0, 0, 0}, m = 0.0, g[4] = {0, 0, 0, 0};
    if (r->K)
      memcpy(k, r->K + e * nd2, nd2 * sizeof *k);
    if (r->M)
      m = r->M[e];
    if (r->G)
      memcpy(g, r->G + e * gs, gs * sizeof *g);
    size_t s = e;
    for (; s > 0 && r->col[s - 1] > c; s--) {
      r->col[s] = r->col[s - 1];
      if (r->K)
        memcpy(r->K + s * nd2, r->K + (s - 1) * nd2, nd2 * sizeof *k);
      if (r->M)
        r->M[s] = r->M[s - 1];
      if (r->G)
        memcpy(r->G + s * gs, r->G + (s - 1) * gs, gs * sizeof *g);
    }
    r->col[s] = c;
    if (r->K)
      memcpy(r->K + s * nd2, k, nd2 * sizeof *k);
    if (r->M)
      r->M[s] = m;
    if (r->G)
      memcpy(r->G + s * gs, g, gs * sizeof *g);
  }
  for (size_t s = 0; s < r->len; s++)
    r->mark[r->col[s]] = (int)s;
}

/* Every row of the forms f into CSR: the stiffness blocks (want_mass = 0)
 * or the consistent mass on the diagonal of each block (want_mass = 1). */
/* ------------------------------------------------------------------ */
/* the row sweep: blocks of rows in parallel, with or without a table    */

/* A thread's workspace. */
typedef struct {
  mfs_row r;
  mfs_eval ev;     /* streaming: the plan's evaluator */
  int *slot;       /* the widest block's window of points: entry of each point's row in
                      ctab (slot[Q - q0], q0 the block's smallest point), or -1 */
  int *need;       /* the points of the block */
  int *kept;       /* a point's neighbours (equal to its list) */
  double *ctab;    /* the block's table rows */
  int *cols;       /* the pattern's columns of a row (fill) */
} sweep_ws;

/* What a sweep does. */
typedef struct {
  const mfs_plan *pl;
  const mfs_forms *f;
  const unsigned char *skip;
  /* rows into a pattern (mfs_assemble_fill): pat (ndof rows per particle
   * row), prow (particle -> pattern particle row, or -1), part (the inverse) */
  const mfs_csr *pat;
  int ndof;
  const int *prow, *part;
  mfs_row_fn fn;
  void *ctx;
  size_t cap; /* the rows' capacity, or 0: row_cap(pl) */
  /* if not NULL (and no pattern): row I assembled and delivered by this
   * instead of mfs_row_assemble and fn (r: the thread's row workspace) */
  mfs_status (*row)(void *ctx, mfs_row *r, size_t I, int thread);
  /* if set: the blocks in as many contiguous ranges as threads (range g:
   * blocks sweep_range(g) .. sweep_range(g + 1) - 1), each range's blocks in
   * order by one thread (mfs_assemble's rows appended range by range) */
  int ranges;
} sweep_job;

/* The first block of range g of nb blocks in nt ranges. */
static inline size_t sweep_range(size_t g, size_t nb, int nt)
{
  return g * nb / (size_t)nt;
}

static void sweep_ws_free(sweep_ws *w)
{
  mfs_row_free(&w->r);
  mfs_eval_free(&w->ev);
  mfs_free(w->slot);
  mfs_free(w->need);
  mfs_free(w->kept);
  mfs_free(w->ctab);
  mfs_free(w->cols);
}

/* Rows per block: without a table the points of a block's boundary are
 * evaluated by both neighbouring blocks, so blocks are large (a few percent
 * of them on a lattice of 10^6 particles) but still several per thread; each
 * thread holds the table rows of its block, so with nt threads a block has
 * at most 65536 / nt rows: the threads' tables together no larger than one
 * thread's (the sweep's memory does not grow with the threads). */
static size_t sweep_block(size_t n, int table, int nt)
{
  if (table)
    return 2048;
  size_t b = n / (4 * (size_t)nt), hi = 65536 / (size_t)nt;
  hi = hi < 1024 ? 1024 : hi;
  return b < 1024 ? 1024 : b > hi ? hi : b;
}

/* The window of the points the rows of [r0, r1) need: the smallest, *q0,
 * and their span (0: none); the particles' lists of points are sorted. */
static size_t block_window(const mfs_plan *pl, size_t r0, size_t r1, size_t *q0)
{
  size_t lo = SIZE_MAX, hi = 0;
  for (size_t I = r0; I < r1; I++) {
    size_t nq;
    const int *Q;
    mfs_plan_particle_points(pl, I, &nq, &Q);
    if (nq) {
      lo = (size_t)Q[0] < lo ? (size_t)Q[0] : lo;
      hi = (size_t)Q[nq - 1] > hi ? (size_t)Q[nq - 1] : hi;
    }
  }
  *q0 = lo == SIZE_MAX ? 0 : lo;
  return lo == SIZE_MAX ? 0 : hi - lo + 1;
}

/* The points the rows of [r0, r1) need, counted (npts) with their entries
 * (nent); with slot/need, also listed in need with their entries in slot
 * (slot[Q - q0], q0 the block's window's start, block_window).  slot is left
 * reset when need is NULL. */
static void block_points(const mfs_plan *pl, size_t r0, size_t r1, size_t q0, int *slot,
                         int *need, size_t *npts, size_t *nent)
{
  const size_t *tptr;
  const int *tidx;
  const double *ttab;
  mfs_plan_table(pl, &tptr, &tidx, &ttab);
  size_t np = 0, ne = 0;
  for (size_t I = r0; I < r1; I++) {
    size_t nq;
    const int *Q;
    mfs_plan_particle_points(pl, I, &nq, &Q);
    for (size_t t = 0; t < nq; t++)
      if (slot[Q[t] - q0] < 0) {
        slot[Q[t] - q0] = (int)ne;
        ne += tptr[Q[t] + 1] - tptr[Q[t]];
        if (need)
          need[np] = Q[t];
        np++;
      }
  }
  if (!need) /* reset: walk the rows again */
    for (size_t I = r0; I < r1; I++) {
      size_t nq;
      const int *Q;
      mfs_plan_particle_points(pl, I, &nq, &Q);
      for (size_t t = 0; t < nq; t++)
        slot[Q[t] - q0] = -1;
    }
  *npts = np;
  *nent = ne;
}

/* One block of rows; *bad_q / *bad_row and their statuses are the block's
 * first failures (points: the smallest failing one). */
static void sweep_block_run(const sweep_job *j, sweep_ws *w, size_t r0, size_t r1, int stream,
                            int thread, size_t *bad_q, mfs_status *st_q, size_t *bad_row,
                            mfs_status *st_row)
{
  const mfs_plan *pl = j->pl;
  size_t np = 0, ne = 0, q0 = 0;
  if (stream) {
    block_window(pl, r0, r1, &q0);
    w->r.cq0 = q0;
    block_points(pl, r0, r1, q0, w->slot, w->need, &np, &ne);
    for (size_t k = 0; k < np; k++) {
      size_t Q = (size_t)w->need[k];
      mfs_status s = mfs_plan_eval_point(
          pl, &w->ev, Q, w->kept, w->ctab + (size_t)w->slot[Q - q0] * (size_t)w->r.nc, NULL);
      if (s != MFS_OK && Q < *bad_q) {
        *bad_q = Q;
        *st_q = s;
      }
    }
  }
  if (*bad_q == SIZE_MAX)
    for (size_t I = r0; I < r1; I++) {
      if (j->skip && j->skip[I])
        continue;
      mfs_status s;
      if (j->pat) {
        size_t rp = (size_t)j->prow[I], nd = (size_t)j->ndof, e0 = j->pat->ptr[rp * nd];
        size_t len = (j->pat->ptr[rp * nd + 1] - e0) / nd;
        for (size_t c = 0; c < len; c++)
          w->cols[c] = j->part[(size_t)j->pat->idx[e0 + c * nd] / nd];
        s = len <= w->r.cap ? row_assemble_into(&w->r, pl, j->f, I, w->cols, len) : MFS_EINVAL;
      } else if (j->row) {
        s = j->row(j->ctx, &w->r, I, thread);
      } else {
        s = mfs_row_assemble(&w->r, pl, j->f, I);
      }
      if (s == MFS_OK && !j->row)
        s = j->fn(j->ctx, &w->r, I, thread);
      if (s != MFS_OK) {
        *bad_row = I;
        *st_row = s;
        break;
      }
    }
  if (stream)
    for (size_t k = 0; k < np; k++)
      w->slot[w->need[k] - q0] = -1;
}

/* sweep_block_run, its failures merged into the sweep's (the smallest). */
static void sweep_block_note(const sweep_job *j, sweep_ws *w, size_t r0, size_t r1, int stream,
                             int thread, size_t *bad_q, mfs_status *st_q, size_t *bad_row,
                             mfs_status *st_row)
{
  size_t bq = SIZE_MAX, br = SIZE_MAX;
  mfs_status sq = MFS_OK, sr = MFS_OK;
  sweep_block_run(j, w, r0, r1, stream, thread, &bq, &sq, &br, &sr);
  if (bq != SIZE_MAX || br != SIZE_MAX) {
#pragma omp critical(mfs_row_sweep)
    {
      if (bq < *bad_q) {
        *bad_q = bq;
        *st_q = sq;
      }
      if (br < *bad_row) {
        *bad_row = br;
        *st_row = sr;
      }
    }
  }
}

static mfs_status sweep_run(const sweep_job *j, size_t *bad)
{
  const mfs_plan *pl = j->pl;
  if (mfs_plan_transpose(pl) != MFS_OK)
    return MFS_ENOMEM;
  const mfs_particles *p = mfs_plan_particles(pl);
  const size_t n = p->n, nq = mfs_plan_npoints(pl);
  const int need2 = j->f->euler != MFS_EULER_NONE || j->f->ls_beta > 0.0;
  const int order = need2 ? 2 : 1, table = mfs_plan_order(pl) >= order, stream = !table;
  const int nt = mfs_threads();
  const size_t B = sweep_block(n, table, nt), nb = (n + B - 1) / B;
  const size_t cap = j->cap ? j->cap : row_cap(pl);
  mfs_status st = MFS_ENOMEM;
  sweep_ws *ws = mfs_calloc((size_t)nt, sizeof *ws);
  size_t *bnp = NULL, *bne = NULL;
  if (!ws)
    return MFS_ENOMEM;
  size_t max_np = 0, max_ne = 0, span = 1; /* the widest block's window of points */
  if (stream)
#pragma omp parallel for reduction(max : span) schedule(static) num_threads(nt)
    for (size_t b = 0; b < nb; b++) {
      size_t q0, r1 = (b + 1) * B < n ? (b + 1) * B : n, w = block_window(pl, b * B, r1, &q0);
      span = w > span ? w : span;
    }
  for (int t = 0; t < nt; t++) { /* every workspace before the parallel part */
    sweep_ws *w = ws + t;
    if ((st = row_init_cap(&w->r, pl, j->f, cap, table)) != MFS_OK)
      goto done;
    st = MFS_ENOMEM;
    if (j->pat && !(w->cols = mfs_malloc(cap * sizeof *w->cols)))
      goto done;
    if (j->pat) /* the pattern's fixed columns go to the discard slot */
      for (size_t J = 0; J < n; J++)
        if (j->prow[J] < 0)
          w->r.mark[J] = (int)cap;
    if (stream) {
      if ((st = mfs_plan_evaluator(pl, order, &w->ev)) != MFS_OK)
        goto done;
      st = MFS_ENOMEM;
      w->slot = mfs_malloc(span * sizeof *w->slot);
      w->kept = mfs_malloc(mfs_plan_max_neighbours(pl) * sizeof *w->kept);
      if (!w->slot || !w->kept)
        goto done;
      for (size_t k = 0; k < span; k++)
        w->slot[k] = -1;
    }
  }
  if (stream) { /* the largest block, to size the chunks */
    bnp = mfs_malloc((nb ? nb : 1) * sizeof *bnp);
    bne = mfs_malloc((nb ? nb : 1) * sizeof *bne);
    if (!bnp || !bne)
      goto done;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
    for (size_t b = 0; b < nb; b++) {
      size_t q0, r1 = (b + 1) * B < n ? (b + 1) * B : n;
      block_window(pl, b * B, r1, &q0);
      block_points(pl, b * B, r1, q0, ws[mfs_thread_id()].slot, NULL, bnp + b, bne + b);
    }
    for (size_t b = 0; b < nb; b++) {
      max_np = bnp[b] > max_np ? bnp[b] : max_np;
      max_ne = bne[b] > max_ne ? bne[b] : max_ne;
    }
    if (max_ne > (size_t)INT32_MAX) {
      st = MFS_ENOMEM;
      goto done;
    }
    for (int t = 0; t < nt; t++) {
      sweep_ws *w = ws + t;
      w->need = mfs_malloc((max_np ? max_np : 1) * sizeof *w->need);
      w->ctab = mfs_malloc((max_ne ? max_ne : 1) * (size_t)w->r.nc * sizeof *w->ctab);
      if (!w->need || !w->ctab)
        goto done;
      w->r.ctab = w->ctab;
      w->r.cslot = w->slot;
    }
  }
  /* a point that no particle sees has no row to be evaluated for: its
   * evaluation (the table's) is checked here */
  size_t bad_q = SIZE_MAX, bad_row = SIZE_MAX;
  mfs_status st_q = MFS_OK, st_row = MFS_OK;
  if (stream) {
    const size_t *tptr;
    const int *tidx;
    const double *ttab;
    mfs_plan_table(pl, &tptr, &tidx, &ttab);
    for (size_t Q = 0; Q < nq && bad_q == SIZE_MAX; Q++)
      if (tptr[Q + 1] == tptr[Q]) {
        mfs_status s = mfs_plan_eval_point(pl, &ws[0].ev, Q, ws[0].kept, ws[0].ctab, NULL);
        if (s != MFS_OK) {
          bad_q = Q;
          st_q = s;
        }
      }
  }
  if (j->ranges) {
#pragma omp parallel for schedule(static, 1) num_threads(nt)
    for (int g = 0; g < nt; g++) {
      const int t = mfs_thread_id();
      for (size_t b = sweep_range((size_t)g, nb, nt); b < sweep_range((size_t)g + 1, nb, nt); b++) {
        size_t r1 = (b + 1) * B < n ? (b + 1) * B : n;
        sweep_block_note(j, ws + t, b * B, r1, stream, t, &bad_q, &st_q, &bad_row, &st_row);
      }
    }
  } else {
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
    for (size_t b = 0; b < nb; b++) {
      const int t = mfs_thread_id();
      size_t r1 = (b + 1) * B < n ? (b + 1) * B : n;
      sweep_block_note(j, ws + t, b * B, r1, stream, t, &bad_q, &st_q, &bad_row, &st_row);
    }
  }
  st = MFS_OK;
  if (bad_q != SIZE_MAX) { /* the table would have failed first, at its smallest point */
    st = st_q;
    if (bad)
      *bad = bad_q;
  } else if (bad_row != SIZE_MAX) {
    st = st_row;
  }
done:
  for (int t = 0; t < nt; t++)
    sweep_ws_free(ws + t);
  mfs_free(ws);
  mfs_free(bnp);
  mfs_free(bne);
  return st;
}

mfs_status mfs_row_sweep(const mfs_plan *pl, const mfs_forms *f, const unsigned char *skip,
                         mfs_row_fn fn, void *ctx, size_t *bad)
{
  if (!pl || !f || !fn)
    return MFS_EINVAL;
  sweep_job j = {.pl = pl, .f = f, .skip = skip, .fn = fn, .ctx = ctx};
  return sweep_run(&j, bad);
}

/* ------------------------------------------------------------------ */
/* symbolic and numeric assembly of finite models                       */

/* The free particles: prow[I] their number in order, or -1; part the
 * inverse.  Returns the count. */
static size_t free_rows(size_t n, const unsigned char *fixed, int *prow, int *part)
{
  size_t k = 0;
  for (size_t I = 0; I < n; I++) {
    prow[I] = fixed && fixed[I] ? -1 : (int)k;
    if (prow[I] >= 0) {
      if (part)
        part[k] = (int)I;
      k++;
    }
  }
  return k;
}

/* The smallest and largest column of the (sorted) lists of the points
 * Q[0..nq): lo > hi if they are all empty. */
static inline void col_window(const size_t *tptr, const int *tidx, const int *Q, size_t nq,
                              int *lo, int *hi)
{
  int l = INT32_MAX, h = -1;
  for (size_t t = 0; t < nq; t++) {
    size_t e0 = tptr[Q[t]], e1 = tptr[Q[t] + 1];
    if (e1 > e0) {
      l = tidx[e0] < l ? tidx[e0] : l;
      h = tidx[e1 - 1] > h ? tidx[e1 - 1] : h;
    }
  }
  *lo = l;
  *hi = h;
}

enum { PATTERN_WORDS = 1024 }; /* the bitmaps of a row's window of columns: 65536 particles */

/* The distinct free columns of row I, sorted, into cols (if not NULL);
 * returns their count.  The columns lie between the smallest first and the
 * largest last entry of the (sorted) lists of the points that see I: where
 * that window is at most 64 PATTERN_WORDS wide (lattices and sorted sets), a
 * bitmap of it gives them in order without a sort; else a marker (mark[J] ==
 * tag: met) and an insertion sort. */
static size_t pattern_row(const mfs_plan *pl, size_t I, const int *prow, int *mark, int tag,
                          uint64_t *bits, int *cols)
{
  const size_t *tptr;
  const int *tidx;
  const double *ttab;
  mfs_plan_table(pl, &tptr, &tidx, &ttab);
  size_t nq, len = 0;
  const int *Q;
  mfs_plan_particle_points(pl, I, &nq, &Q);
  int lo, hi;
  col_window(tptr, tidx, Q, nq, &lo, &hi);
  if (hi < lo)
    return 0;
  size_t nw = ((size_t)(hi - lo) >> 6) + 1;
  if (nw <= PATTERN_WORDS) {
    /* four bitmaps taken in turn, so that consecutive columns (which share a
     * word) do not wait on each other's read-modify-write */
    uint64_t *b0 = bits, *b1 = bits + nw, *b2 = bits + 2 * nw, *b3 = bits + 3 * nw;
    memset(bits, 0, 4 * nw * sizeof *bits);
    for (size_t t = 0; t < nq; t++) {
      const int *ix = tidx + tptr[Q[t]];
      size_t m = tptr[Q[t] + 1] - tptr[Q[t]], e = 0;
      for (; e + 4 <= m; e += 4) {
        unsigned d0 = (unsigned)(ix[e] - lo), d1 = (unsigned)(ix[e + 1] - lo);
        unsigned d2 = (unsigned)(ix[e + 2] - lo), d3 = (unsigned)(ix[e + 3] - lo);
        b0[d0 >> 6] |= (uint64_t)1 << (d0 & 63);
        b1[d1 >> 6] |= (uint64_t)1 << (d1 & 63);
        b2[d2 >> 6] |= (uint64_t)1 << (d2 & 63);
        b3[d3 >> 6] |= (uint64_t)1 << (d3 & 63);
      }
      for (; e < m; e++) {
        unsigned d = (unsigned)(ix[e] - lo);
        b0[d >> 6] |= (uint64_t)1 << (d & 63);
      }
    }
    for (size_t w = 0; w < nw; w++)
      for (uint64_t b = b0[w] | b1[w] | b2[w] | b3[w]; b; b &= b - 1) {
        int J = lo + (int)(w << 6) + __builtin_ctzll(b);
        if (prow[J] >= 0) {
          if (cols)
            cols[len] = J;
          len++;
        }
      }
    return len;
  }
  for (size_t t = 0; t < nq; t++)
    for (size_t e = tptr[Q[t]]; e < tptr[Q[t] + 1]; e++) {
      int J = tidx[e];
      if (mark[J] != tag && prow[J] >= 0) {
        mark[J] = tag;
        if (cols)
          cols[len] = J;
        len++;
      }
    }
  if (cols) /* insertion: the rows are short */
    for (size_t e = 1; e < len; e++) {
      int v = cols[e];
      size_t k = e;
      for (; k > 0 && cols[k - 1] > v; k--)
        cols[k] = cols[k - 1];
      cols[k] = v;
    }
  return len;
}

mfs_status mfs_assemble_pattern(const mfs_plan *pl, int ndof, const unsigned char *fixed,
                                mfs_csr **out)
{
  *out = NULL;
  if (!pl || ndof < 1 || ndof > 2)
    return MFS_EINVAL;
  if (mfs_plan_transpose(pl) != MFS_OK)
    return MFS_ENOMEM;
  const size_t n = mfs_plan_particles(pl)->n, nd = (size_t)ndof;
  const int nt = mfs_threads();
  const size_t cap = row_cap(pl);
  mfs_status st = MFS_ENOMEM;
  mfs_csr *A = NULL;
  int *prow = mfs_malloc((n ? n : 1) * sizeof *prow);
  size_t *cnt = mfs_malloc((n ? n : 1) * sizeof *cnt);
  int *mark = mfs_malloc((size_t)nt * (n ? n : 1) * sizeof *mark);
  int *cols = mfs_malloc((size_t)nt * cap * sizeof *cols);
  uint64_t *bits = mfs_malloc((size_t)nt * 4 * PATTERN_WORDS * sizeof *bits);
  if (!prow || !cnt || !mark || !cols || !bits)
    goto done;
  size_t nf = free_rows(n, fixed, prow, NULL);
  for (size_t i = 0; i < (size_t)nt * n; i++)
    mark[i] = -1;
  /* pass 1: the row lengths (per thread a bitmap, or a marker tagged by the row) */
#pragma omp parallel for schedule(dynamic, 1024) num_threads(nt)
  for (size_t I = 0; I < n; I++) {
    const int t = mfs_thread_id();
    cnt[I] = prow[I] >= 0 ? pattern_row(pl, I, prow, mark + (size_t)t * n, (int)I,
                                        bits + (size_t)t * 4 * PATTERN_WORDS, NULL)
                          : 0;
  }
  size_t nnz = 0;
  for (size_t I = 0; I < n; I++)
    nnz += cnt[I] * nd * nd;
  A = mfs_csr_alloc(nf * nd, nf * nd, nnz);
  if (!A)
    goto done;
  for (size_t I = 0, r = 0; I < n; I++)
    if (prow[I] >= 0)
      for (size_t a = 0; a < nd; a++, r++)
        A->ptr[r + 1] = A->ptr[r] + cnt[I] * nd;
  for (size_t i = 0; i < (size_t)nt * n; i++)
    mark[i] = -1;
  /* pass 2: the columns in order, written at their rows' places */
#pragma omp parallel for schedule(dynamic, 1024) num_threads(nt)
  for (size_t I = 0; I < n; I++) {
    if (prow[I] < 0)
      continue;
    const int t = mfs_thread_id();
    int *c = cols + (size_t)t * cap;
    size_t len = pattern_row(pl, I, prow, mark + (size_t)t * n, (int)I,
                             bits + (size_t)t * 4 * PATTERN_WORDS, c);
    size_t r0 = (size_t)prow[I] * nd;
    for (size_t a = 0; a < nd; a++) {
      int *ix = A->idx + A->ptr[r0 + a];
      for (size_t s = 0; s < len; s++)
        for (size_t b = 0; b < nd; b++)
          ix[s * nd + b] = (int)((size_t)prow[c[s]] * nd + b);
    }
  }
  *out = A;
  A = NULL;
  st = MFS_OK;
done:
  mfs_csr_free(A);
  mfs_free(prow);
  mfs_free(cnt);
  mfs_free(mark);
  mfs_free(cols);
  mfs_free(bits);
  return st;
}

/* The forms of an assembly: the stiffness, the consistent mass, the
 * lumped mass's row sums (a partition of unity), each where asked for. */
static mfs_forms assembly_forms(const mfs_material *mat, int stiffness, int mass, int lumped)
{
  mfs_forms f = mfs_forms_stiffness(mat);
  f.stiffness = stiffness;
  if (mass)
    f.density = mat->density;
  if (lumped)
    f.lumped_density = mat->density;
  return f;
}

typedef struct {
  mfs_csr *K, *M;
  double *m;
  const int *prow;
  int ndof, pu;
  double density;
  const double *vol; /* the particles' volumes, or NULL: node_vol for every one */
  double node_vol;
} fill_ctx;

/* A row of the sweep into its place in K, M and m. */
static mfs_status fill_row(void *vc, const mfs_row *r, size_t I, int thread)
{
  (void)thread;
  const fill_ctx *c = vc;
  const size_t nd = (size_t)c->ndof, nd2 = nd * nd, rp = (size_t)c->prow[I], len = r->len;
  const mfs_csr *P = c->K ? c->K : c->M;
  for (size_t a = 0; a < nd; a++) {
    size_t base = P ? P->ptr[rp * nd + a] : 0;
    if (c->K)
      for (size_t s = 0; s < len; s++)
        for (size_t b = 0; b < nd; b++)
          c->K->val[base + s * nd + b] = r->K[s * nd2 + a * nd + b];
    if (c->M)
      for (size_t s = 0; s < len; s++)
        for (size_t b = 0; b < nd; b++)
          c->M->val[base + s * nd + b] = a == b ? r->M[s] : 0.0;
    if (c->m) /* sph: the particle masses rho V_I (eq. 51) */
      c->m[rp * nd + a] = c->pu ? r->lump : c->density * (c->vol ? c->vol[I] : c->node_vol);
  }
  return MFS_OK;
}

mfs_status mfs_assemble_fill(const mfs_plan *pl, const mfs_material *mat,
                             const unsigned char *fixed, mfs_csr *K, mfs_csr *M, double *m,
                             size_t *bad)
{
  if (!pl || !mat)
    return MFS_EINVAL;
  const mfs_particles *p = mfs_plan_particles(pl);
  if (mat->physics == MFS_PHYS_PLANE_STRAIN && p->dim != 2)
    return MFS_EINVAL;
  const size_t n = p->n;
  const int nd = mfs_physics_ndof(mat->physics);
  /* the lumped mass: rho times the integral of phi_I (the row sum of eq. 131)
   * for a partition of unity; else the particle masses rho V_I (SPH, eq. 51),
   * or rho times the lattice's area per node (eq. 119's node volume, asked for) */
  const mfs_disc *d = mfs_plan_disc(pl);
  const int pu = d->shape->partition_of_unity && !d->node_volume_mass;
  const double *vol = d->node_volume_mass ? NULL : p->vol;
  const double node_vol = d->node_volume_mass ? mfs_particles_node_volume(p) : 0.0;
  int *prow = mfs_malloc((n ? n : 1) * sizeof *prow), *part = mfs_malloc((n ? n : 1) * sizeof *part);
  if (!prow || !part) {
    mfs_free(prow);
    mfs_free(part);
    return MFS_ENOMEM;
  }
  size_t nf = free_rows(n, fixed, prow, part);
  mfs_status st = MFS_EINVAL;
  const mfs_csr *P = K ? K : M;
  if ((K && (K->nrow != nf * nd || K->ncol != nf * nd)) ||
      (M && (M->nrow != nf * nd || M->ncol != nf * nd)) ||
      (K && M && K->ptr[K->nrow] != M->ptr[M->nrow]))
    goto done;
  mfs_forms f = assembly_forms(mat, K != NULL, M != NULL, m && pu);
  fill_ctx c = {.K = K, .M = M, .m = m, .prow = prow, .ndof = nd, .pu = pu,
                .density = mat->density, .vol = vol, .node_vol = node_vol};
  if (!P) { /* the lumped mass alone: no pattern to fill */
    sweep_job j = {.pl = pl, .f = &f, .skip = fixed, .fn = fill_row, .ctx = &c};
    if (!pu) { /* nothing to assemble */
      for (size_t I = 0; I < n; I++)
        for (int a = 0; a < nd && prow[I] >= 0; a++)
          m[(size_t)prow[I] * nd + a] = mat->density * (vol ? vol[I] : node_vol);
      st = MFS_OK;
      goto done;
    }
    st = sweep_run(&j, bad);
    goto done;
  }
  sweep_job j = {.pl = pl, .f = &f, .skip = fixed, .pat = P, .ndof = nd, .prow = prow,
                 .part = part, .fn = fill_row, .ctx = &c};
  st = sweep_run(&j, bad);
done:
  mfs_free(prow);
  mfs_free(part);
  return st;
}

/* ------------------------------------------------------------------ */
/* one-shot assembly: the pattern and the values in one sweep            */

/* The entries the free rows can have, for blocks of B rows: s_I = min(n,
 * the sum of the list lengths of the points that see I) columns of ndof^2
 * entries.  *total: their sum; *cap:
 * the largest s_I over every row (row_cap's); bsum[b]: the sum over block b. */
static void row_bounds(const mfs_plan *pl, const unsigned char *fixed, size_t B, size_t nd2,
                       size_t *total, size_t *bsum, size_t *cap)
{
  const size_t n = mfs_plan_particles(pl)->n, nb = (n + B - 1) / B;
  const size_t *tptr;
  const int *tidx;
  const double *ttab;
  mfs_plan_table(pl, &tptr, &tidx, &ttab);
  size_t tot = 0, cp = 1;
#pragma omp parallel for reduction(+ : tot) reduction(max : cp) schedule(static)
  for (size_t b = 0; b < nb; b++) {
    size_t r1 = (b + 1) * B < n ? (b + 1) * B : n, sum = 0;
    for (size_t I = b * B; I < r1; I++) {
      size_t nq, s = 0;
      const int *Q;
      mfs_plan_particle_points(pl, I, &nq, &Q);
      for (size_t t = 0; t < nq; t++)
        s += tptr[Q[t] + 1] - tptr[Q[t]];
      s = s < n ? s : n;
      cp = s > cp ? s : cp;
      if (!fixed || !fixed[I])
        sum += s * nd2;
    }
    tot += sum;
    bsum[b] = sum;
  }
  *total = tot;
  *cap = cp < n ? cp : (n ? n : 1);
}

/* Entries in row order: the matrix's, or a thread's block of them. */
typedef struct {
  int *idx;
  double *kv, *mv; /* K's and M's values (each if asked for) */
  size_t len;
} fuse_buf;

typedef struct {
  /* the entries of range g of the sweep's blocks (sweep_job.ranges), in row
   * order, in tb[g] (at the bound of its rows; tb[0] at the bound of all
   * rows: the others are appended to it after the sweep) */
  fuse_buf *tb;
  fuse_buf out;   /* the matrices' entries, tb[0]'s after the sweep */
  size_t B, nb;
  int *srt;       /* per thread: a row's free columns, sorted (cap each) */
  uint64_t *bits; /* per thread: PATTERN_WORDS */
  size_t cap;
  size_t *rlen;   /* the free columns of the row of free particle k at rlen[k ndof] (K's
                     ptr + 1: made the row pointers after the sweep) */
  double *acc;    /* scalar_2d, per thread: PATTERN_WORDS * 64 columns, zero */
  int scalar_2d;  /* the forms: the stiffness of a 2D scalar model alone (fuse_scalar_2d) */
  const mfs_forms *f;
  const mfs_plan *pl;
  const int *prow;
  int ndof, pu, nt;
  double density, node_vol;
  const double *vol;
  double *m;
} fuse_ctx;

static int cmp_int(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The free columns of row r of particle I (r->col, in order of first
 * appearance) sorted into srt; returns their count.  As pattern_row: the
 * columns lie between the smallest first and the largest last entry of the
 * (sorted) lists of I's points; a bitmap of that window where it is at most
 * PATTERN_WORDS wide, else a sort.  nd == 1 (and the one sweep's row, mark
 * its positions): the entries are written at once, idx into ix and the
 * values into kv and mv (each if not NULL), and srt is not used. */
static size_t row_sorted_free(const mfs_plan *pl, size_t I, const mfs_row *r, const int *prow,
                              uint64_t *bits, int *srt, size_t nd, int *ix, double *kv,
                              double *mv)
{
  const size_t len = r->len;
  const int *col = r->col;
  size_t nq, k = 0;
  const int *Q;
  mfs_plan_particle_points(pl, I, &nq, &Q);
  int lo, hi;
  col_window(r->tptr, r->tidx, Q, nq, &lo, &hi);
  if (hi < lo)
    return 0;
  size_t nw = ((size_t)(hi - lo) >> 6) + 1;
  if (nw <= PATTERN_WORDS) {
    memset(bits, 0, nw * sizeof *bits);
    for (size_t s = 0; s < len; s++) {
      unsigned d = (unsigned)(col[s] - lo);
      bits[d >> 6] |= (uint64_t)1 << (d & 63);
    }
    if (nd == 1) {
      const int *mark = r->mark;
      for (size_t w = 0; w < nw; w++)
        for (uint64_t b = bits[w]; b; b &= b - 1) {
          int J = lo + (int)(w << 6) + __builtin_ctzll(b);
          if (prow[J] >= 0) {
            ix[k] = prow[J];
            if (kv)
              kv[k] = r->K[mark[J]];
            if (mv)
              mv[k] = r->M ? r->M[mark[J]] : 0.0;
            k++;
          }
        }
      return k;
    }
    for (size_t w = 0; w < nw; w++)
      for (uint64_t b = bits[w]; b; b &= b - 1) {
        int J = lo + (int)(w << 6) + __builtin_ctzll(b);
        if (prow[J] >= 0)
          srt[k++] = J;
      }
    return k;
  }
  for (size_t s = 0; s < len; s++)
    if (prow[col[s]] >= 0)
      srt[k++] = col[s];
  qsort(srt, k, sizeof *srt, cmp_int);
  if (nd == 1)
    for (size_t s = 0; s < k; s++) {
      int J = srt[s];
      ix[s] = prow[J];
      if (kv)
        kv[s] = r->K[r->mark[J]];
      if (mv)
        mv[s] = r->M ? r->M[r->mark[J]] : 0.0;
    }
  return k;
}

/* A row of the sweep, its free columns sorted, appended to its thread's
 * entries (to the matrix's with one thread); the lumped mass as fill_row. */
static mfs_status fuse_row_into(fuse_ctx *c, const mfs_row *r, size_t I, int thread, fuse_buf *b)
{
  int *srt = c->srt + (size_t)thread * c->cap;
  const size_t nd = (size_t)c->ndof, nd2 = nd * nd, rp = (size_t)c->prow[I];
  int *ix = b->idx + b->len;
  double *kv = b->kv ? b->kv + b->len : NULL, *mv = b->mv ? b->mv + b->len : NULL;
  const size_t len = row_sorted_free(c->pl, I, r, c->prow, c->bits + (size_t)thread * PATTERN_WORDS,
                                     srt, nd, ix, kv, mv);
  c->rlen[rp * nd] = len;
  if (nd > 1)
    for (size_t a = 0, e = 0; a < nd; a++)
      for (size_t s = 0; s < len; s++) {
        size_t q = (size_t)r->mark[srt[s]];
        for (size_t bb = 0; bb < nd; bb++, e++) {
          ix[e] = (int)((size_t)c->prow[srt[s]] * nd + bb);
          if (kv)
            kv[e] = r->K[q * nd2 + a * nd + bb];
          if (mv)
            mv[e] = a == bb && r->M ? r->M[q] : 0.0;
        }
      }
  b->len += len * nd2;
  if (c->m) /* sph: the particle masses rho V_I (eq. 51) */
    for (size_t a = 0; a < nd; a++)
      c->m[rp * nd + a] = c->pu ? r->lump : c->density * (c->vol ? c->vol[I] : c->node_vol);
  return MFS_OK;
}

/* Row I of the stiffness of a 2D scalar model alone (the forms of
 * row_assemble_scalar_2d, its arithmetic: the same values, bit for bit)
 * accumulated straight into a dense window of the columns, lo .. hi (the
 * smallest first and the largest last entry of the sorted lists of I's
 * points), with a bitmap of the columns met: they come out sorted, without
 * a marker or a sort, and the window is cleared as it is read.  A window
 * wider than PATTERN_WORDS: the general row and fuse_row. */
static mfs_status fuse_scalar_2d(fuse_ctx *c, mfs_row *r, size_t I, int thread, fuse_buf *b)
{
  size_t nq;
  const int *Qs;
  mfs_plan_particle_points(c->pl, I, &nq, &Qs);
  int lo, hi;
  col_window(r->tptr, r->tidx, Qs, nq, &lo, &hi);
  size_t nw = hi < lo ? 0 : ((size_t)(hi - lo) >> 6) + 1;
  if (nw > PATTERN_WORDS) {
    mfs_status st = mfs_row_assemble(r, c->pl, c->f, I);
    return st == MFS_OK ? fuse_row_into(c, r, I, thread, b) : st;
  }
  uint64_t *bits = c->bits + (size_t)thread * PATTERN_WORDS;
  double *acc = c->acc + (size_t)thread * PATTERN_WORDS * 64;
  const double rho = c->f->lumped_density, c0 = c->f->c[0];
  double lump = 0.0;
  memset(bits, 0, nw * sizeof *bits);
  for (size_t t = 0; t < nq; t++) {
    mfs_point pt;
    row_point(r, (size_t)Qs[t], &pt);
    const int nc = pt.ncomp;
    const double *tab = pt.phi;
    const double *fi = point_self(&pt, I, rho, &lump), wc = pt.w * c0, i1 = fi[1], i2 = fi[2];
    for (size_t e = 0; e < pt.nn; e++) {
      unsigned d = (unsigned)(pt.idx[e] - lo);
      const double *fj = tab + e * (size_t)nc;
      double g = 0.0;
      g += i1 * fj[1];
      g += i2 * fj[2];
      acc[d] += wc * g;
      bits[d >> 6] |= (uint64_t)1 << (d & 63);
    }
  }
  int *ix = b->idx + b->len;
  double *kv = b->kv + b->len;
  size_t k = 0;
  for (size_t w = 0; w < nw; w++)
    for (uint64_t m = bits[w]; m; m &= m - 1) {
      unsigned d = (unsigned)(w << 6) + (unsigned)__builtin_ctzll(m);
      int J = lo + (int)d;
      if (c->prow[J] >= 0) {
        ix[k] = c->prow[J];
        kv[k] = acc[d];
        k++;
      }
      acc[d] = 0.0;
    }
  c->rlen[c->prow[I]] = k;
  b->len += k;
  if (c->m) /* sph: the particle masses rho V_I (eq. 51) */
    c->m[c->prow[I]] = c->pu ? lump : c->density * (c->vol ? c->vol[I] : c->node_vol);
  return MFS_OK;
}

/* The one sweep's row: the 2D scalar stiffness by its window, any other
 * forms by the general row (mfs_row_assemble) and fuse_row. */
static mfs_status fuse_any(void *vc, mfs_row *r, size_t I, int thread)
{
  fuse_ctx *c = vc;
  size_t k = I / c->B, g = 0; /* I's block and its range */
  while (g + 1 < (size_t)c->nt && sweep_range(g + 1, c->nb, c->nt) <= k)
    g++;
  fuse_buf *b = c->tb + g;
  mfs_status st;
  if (c->scalar_2d) {
    st = fuse_scalar_2d(c, r, I, thread, b);
  } else {
    st = mfs_row_assemble(r, c->pl, c->f, I);
    if (st == MFS_OK)
      st = fuse_row_into(c, r, I, thread, b);
  }
  return st;
}

/* The sweep's row function (not called: the job's row does the rows). */
static mfs_status fuse_row(void *vc, const mfs_row *r, size_t I, int thread)
{
  (void)vc;
  (void)r;
  (void)I;
  (void)thread;
  return MFS_EINVAL;
}

static mfs_status fuse_buf_alloc(fuse_buf *b, size_t len, int k, int m)
{
  len = len ? len : 1;
  b->idx = mfs_malloc(len * sizeof *b->idx);
  b->kv = k ? mfs_malloc(len * sizeof *b->kv) : NULL;
  b->mv = m ? mfs_malloc(len * sizeof *b->mv) : NULL;
  return b->idx && (!k || b->kv) && (!m || b->mv) ? MFS_OK : MFS_ENOMEM;
}

static void fuse_buf_free(fuse_buf *b)
{
  mfs_free(b->idx);
  mfs_free(b->kv);
  mfs_free(b->mv);
}

/* A block shrunk to len entries (kept as it is if the shrinking fails). */
static void *shrink(void *p, size_t bytes)
{
  void *t = p ? mfs_realloc(p, bytes ? bytes : 1) : NULL;
  return t ? t : p;
}

/* Range g's entries appended to range 0's (which has room for them: its
 * bound is the bound of every row), from its end, a chunk at a time, range
 * g's arrays shrunk after each chunk: the pages of the two ranges together
 * never more than the entries and a chunk. */
static void fuse_append(fuse_buf *to, fuse_buf *from)
{
  const size_t chunk = (size_t)1 << 20;
  size_t len = from->len;
  while (len > 0) {
    size_t c = len < chunk ? len : chunk;
    len -= c;
    memcpy(to->idx + to->len + len, from->idx + len, c * sizeof *from->idx);
    from->idx = shrink(from->idx, len * sizeof *from->idx);
    if (from->kv) {
      memcpy(to->kv + to->len + len, from->kv + len, c * sizeof *from->kv);
      from->kv = shrink(from->kv, len * sizeof *from->kv);
    }
    if (from->mv) {
      memcpy(to->mv + to->len + len, from->mv + len, c * sizeof *from->mv);
      from->mv = shrink(from->mv, len * sizeof *from->mv);
    }
  }
  to->len += from->len;
  fuse_buf_free(from);
  *from = (fuse_buf){0};
}

mfs_status mfs_assemble(const mfs_plan *pl, const mfs_material *mat, const unsigned char *fixed,
                        mfs_csr **K, mfs_csr **M, double *m, size_t *bad)
{
  if (K)
    *K = NULL;
  if (M)
    *M = NULL;
  if (!pl || !mat || (!K && !M))
    return MFS_EINVAL;
  const mfs_particles *p = mfs_plan_particles(pl);
  if (mat->physics == MFS_PHYS_PLANE_STRAIN && p->dim != 2)
    return MFS_EINVAL;
  if (mfs_plan_transpose(pl) != MFS_OK)
    return MFS_ENOMEM;
  const size_t n = p->n;
  const int nd = mfs_physics_ndof(mat->physics), nt = mfs_threads();
  const size_t nd2 = (size_t)nd * (size_t)nd;
  const mfs_disc *d = mfs_plan_disc(pl); /* the lumped mass: as mfs_assemble_fill */
  const int pu = d->shape->partition_of_unity && !d->node_volume_mass;
  mfs_forms f = assembly_forms(mat, K != NULL, M != NULL, m && pu);
  /* the blocks of mfs_row_sweep's, for the forms' order (1) */
  const size_t B = sweep_block(n, mfs_plan_order(pl) >= 1, nt);
  const size_t nb = (n + B - 1) / B;
  size_t total, cap, *bsum = mfs_malloc((nb + 1) * sizeof *bsum);
  if (!bsum)
    return MFS_ENOMEM;
  row_bounds(pl, fixed, B, nd2, &total, bsum, &cap);
  mfs_status st = MFS_ENOMEM;
  mfs_csr *A = NULL, *C = NULL;
  int *prow = mfs_malloc((n ? n : 1) * sizeof *prow);
  size_t nr = 0;
  fuse_ctx c = {.cap = cap, .ndof = nd, .pu = pu, .nt = nt, .density = mat->density,
                .node_vol = d->node_volume_mass ? mfs_particles_node_volume(p) : 0.0,
                .vol = d->node_volume_mass ? NULL : p->vol, .m = m, .pl = pl, .prow = prow};
  if ((A = mfs_calloc(1, sizeof *A)))
    A->ptr = mfs_calloc(n * (size_t)nd + 1, sizeof *A->ptr);
  c.rlen = A ? A->ptr + 1 : NULL;
  c.srt = mfs_malloc((size_t)nt * cap * sizeof *c.srt);
  c.bits = mfs_malloc((size_t)nt * PATTERN_WORDS * sizeof *c.bits);
  c.f = &f;
  c.scalar_2d = p->dim == 2 && nd == 1 && K && !M;
  if (c.scalar_2d)
    c.acc = mfs_calloc((size_t)nt * PATTERN_WORDS * 64, sizeof *c.acc);
  if (!prow || !A || !A->ptr || !c.srt || !c.bits || (c.scalar_2d && !c.acc))
    goto done;
  c.B = B;
  nr = free_rows(n, fixed, prow, NULL) * (size_t)nd;
  /* the entries: range g of the blocks (one per thread) appended in row
   * order to tb[g], allocated at the bound of its rows (the pages past the
   * rows' are never touched), tb[0] at the bound of all rows; after the sweep
   * the other ranges are appended to tb[0] (fuse_append), which is shrunk to
   * the entries: no count pass, each entry written once and moved at most
   * once, the pages at most the entries' and a chunk */
  c.nb = nb;
  c.tb = mfs_calloc((size_t)nt, sizeof *c.tb);
  if (!c.tb)
    goto done;
  for (int g = 0; g < nt; g++) {
    size_t bound = 0;
    for (size_t k = sweep_range((size_t)g, nb, nt); g > 0 && k < sweep_range((size_t)g + 1, nb, nt); k++)
      bound += bsum[k];
    if (fuse_buf_alloc(c.tb + g, g ? bound : total, K != NULL, M != NULL) != MFS_OK)
      goto done;
  }
  sweep_job j = {.pl = pl, .f = &f, .skip = fixed, .fn = fuse_row, .ctx = &c, .cap = cap,
                 .row = fuse_any, .ranges = 1};
  if ((st = sweep_run(&j, bad)) != MFS_OK)
    goto done;
  for (int g = 1; g < nt; g++)
    fuse_append(c.tb, c.tb + g);
  c.out = c.tb[0];
  c.tb[0] = (fuse_buf){0};
  st = MFS_ENOMEM;
  A->nrow = A->ncol = nr;
  A->ptr[0] = 0;
  for (size_t r = 0; r < nr; r += (size_t)nd) { /* a row's length is at ptr[r + 1] */
    size_t len = A->ptr[r + 1] * (size_t)nd;
    for (int a = 0; a < nd; a++)
      A->ptr[r + (size_t)a + 1] = A->ptr[r + (size_t)a] + len;
  }
  A->ptr = shrink(A->ptr, (nr + 1) * sizeof *A->ptr);
  const size_t nnz = c.out.len;
  if (K && M) { /* M: a copy of the pattern */
    if (!(C = mfs_calloc(1, sizeof *C)) || !(C->ptr = mfs_malloc((nr + 1) * sizeof *C->ptr)) ||
        !(C->idx = mfs_malloc((nnz ? nnz : 1) * sizeof *C->idx)))
      goto done;
    C->nrow = C->ncol = nr;
    memcpy(C->ptr, A->ptr, (nr + 1) * sizeof *C->ptr);
    memcpy(C->idx, c.out.idx, nnz * sizeof *C->idx);
  }
  A->idx = shrink(c.out.idx, nnz * sizeof *A->idx);
  A->val = shrink(K ? c.out.kv : c.out.mv, nnz * sizeof *A->val);
  c.out.idx = NULL;
  if (K) {
    c.out.kv = NULL;
    *K = A;
    A = NULL;
  } else {
    c.out.mv = NULL;
    *M = A;
    A = NULL;
  }
  if (C) {
    C->val = shrink(c.out.mv, nnz * sizeof *C->val);
    c.out.mv = NULL;
    *M = C;
    C = NULL;
  }
  st = MFS_OK;
done:
  mfs_csr_free(A);
  mfs_csr_free(C);
  fuse_buf_free(&c.out);
  for (int g = 0; c.tb && g < nt; g++)
    fuse_buf_free(c.tb + g);
  mfs_free(c.tb);
  mfs_free(bsum);
  mfs_free(c.srt);
  mfs_free(c.bits);
  mfs_free(c.acc);
  mfs_free(prow);
  return st;
}

/* The matrix of the forms over every particle, in one sweep. */
static mfs_status assemble_csr(const mfs_plan *pl, const mfs_material *mat, int want_mass,
                               mfs_csr **out)
{
  return want_mass ? mfs_assemble(pl, mat, NULL, NULL, out, NULL, NULL)
                   : mfs_assemble(pl, mat, NULL, out, NULL, NULL, NULL);
}

mfs_status mfs_assemble_stiffness(const mfs_plan *pl, const mfs_material *mat, mfs_csr **K)
{
  *K = NULL;
  if (mat->physics == MFS_PHYS_PLANE_STRAIN && mfs_plan_particles(pl)->dim != 2)
    return MFS_EINVAL;
  return assemble_csr(pl, mat, 0, K);
}

mfs_status mfs_assemble_mass_consistent(const mfs_plan *pl, const mfs_material *mat,
                                        mfs_csr **M)
{
  return assemble_csr(pl, mat, 1, M);
}

mfs_status mfs_assemble_mass_lumped(const mfs_plan *pl, const mfs_material *mat, double *m)
{
  return mfs_assemble_fill(pl, mat, NULL, NULL, NULL, m, NULL);
}

static int cmp_entry(const void *a, const void *b)
{
  const mfs_stencil_entry *x = a, *y = b;
  if (x->k != y->k)
    return (x->k > y->k) - (x->k < y->k);
  return (x->j > y->j) - (x->j < y->j);
}

mfs_status mfs_stencil(const mfs_disc *d, mfs_stencil_entry **entries, size_t *n, size_t *bad)
{
  *entries = NULL;
  *n = 0;
  mfs_status st = mfs_disc_check(d, NULL);
  if (st != MFS_OK)
    return st;
  if (!mfs_disc_infinite(d) || d->material.physics != MFS_PHYS_SCALAR)
    return MFS_EINVAL;
  /* entries couple particles closer than 2a; the box must hold more than
   * twice that so that no two images of a particle both couple with node 0 */
  double gamma = d->source.gamma > 0.0 ? d->source.gamma : 1.0;
  double hy = d->source.lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
  int nx = 2 * (int)ceil(2.0 * d->dilation) + 3;
  int ny = 2 * (int)ceil(2.0 * d->dilation / hy) + 4;
  if (nx % 2)
    nx++;
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  double *ml = NULL;
  mfs_stencil_entry *out = NULL;
  mfs_row r = {0};
  st = mfs_disc_periodic_box(d, nx, ny, &p, &q);
  if (st != MFS_OK)
    goto done;
  pl = mfs_plan_alloc(d, p, q, &st);
  if (!pl)
    goto done;
  st = mfs_plan_tabulate(pl, 1, bad);
  if (st != MFS_OK)
    goto done;
  mfs_forms f = mfs_forms_stiffness(&d->material);
  if (d->consistent_mass)
    f.density = d->material.density;
  st = mfs_row_init(&r, pl, &f);
  if (st != MFS_OK)
    goto done;
  st = mfs_row_assemble(&r, pl, &f, 0);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  if (!d->consistent_mass) {
    ml = mfs_malloc(p->n * sizeof *ml);
    if (!ml || mfs_assemble_mass_lumped(pl, &d->material, ml) != MFS_OK)
      goto done;
  }
  out = mfs_malloc((r.len ? r.len : 1) * sizeof *out);
  if (!out)
    goto done;
  for (size_t i = 0; i < r.len; i++) { /* lattice offsets by the minimum image */
    int J = r.col[i];
    double dd[3];
    mfs_box_delta(&p->box, p->x, p->x + (size_t)J * p->dim, dd);
    int kk = d->dim == 1 ? 0 : (int)lround(dd[1] / p->a2[1]);
    int jj = (int)lround((dd[0] - kk * p->a2[0]) / p->a1[0]);
    out[i] = (mfs_stencil_entry){
      .j = jj, .k = kk, .K = r.K[i], .M = d->consistent_mass ? r.M[i] : (J == 0 ? ml[0] : 0.0)};
  }
  qsort(out, r.len, sizeof *out, cmp_entry);
  *entries = out;
  *n = r.len;
  out = NULL;
  st = MFS_OK;
done:
  mfs_row_free(&r);
  mfs_free(out);
  mfs_free(ml);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return st;
}
