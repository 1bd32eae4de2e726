#include "mfs_assemble.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

mfs_status mfs_row_init(mfs_row *r, const mfs_plan *pl, const mfs_forms *f)
{
  memset(r, 0, sizeof *r);
  int need2 = f->euler != MFS_EULER_NONE || f->ls_beta > 0.0;
  if (mfs_plan_order(pl) < (need2 ? 2 : 1))
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
  r->nc = mfs_plan_ncomp(pl);
  r->dim = p->dim;
  /* a row has at most the sum of the list lengths of the points that see I */
  size_t cap = 1;
  for (size_t I = 0; I < n; I++) {
    size_t nq, s = 0;
    const int *Q;
    mfs_plan_particle_points(pl, I, &nq, &Q);
    for (size_t t = 0; t < nq; t++)
      s += r->tptr[Q[t] + 1] - r->tptr[Q[t]];
    cap = s > cap ? s : cap;
  }
  cap = cap < n ? cap : (n ? n : 1);
  r->ndof = mfs_physics_ndof(f->physics);
  r->gsz = euler2 ? 4 : 1;
  r->cap = cap;
  r->col = mfs_malloc(cap * sizeof *r->col);
  r->pcol = mfs_malloc(mfs_plan_max_neighbours(pl) * sizeof *r->pcol);
  r->mark = mfs_malloc((n ? n : 1) * sizeof *r->mark);
  if (f->stiffness)
    r->K = mfs_malloc(cap * (size_t)(r->ndof * r->ndof) * sizeof *r->K);
  if (f->density != 0.0 || f->ls_beta > 0.0)
    r->M = mfs_malloc(cap * sizeof *r->M);
  if (f->euler != MFS_EULER_NONE)
    r->G = mfs_malloc(cap * (size_t)r->gsz * sizeof *r->G);
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

/* The 2D Eulerian term of one point (mfs_assemble.h): G^{jk}_IK += w (H T)_jk
 * with the point's motion T, minus w H at K = I (paper), plus w d grad
 * phi_I / d x_K (consistent). */
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

mfs_status mfs_row_assemble(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t I)
{
  const int nd2 = r->ndof * r->ndof;
  for (size_t s = 0; s < r->len; s++) /* reset the marks of the last row */
    r->mark[r->col[s]] = -1;
  r->len = 0;
  size_t nq;
  const int *Qs;
  mfs_plan_particle_points(pl, I, &nq, &Qs);
  int *col = r->pcol, st = MFS_OK;
  for (size_t t = 0; t < nq && st == MFS_OK; t++) {
    size_t Q = (size_t)Qs[t], e0 = r->tptr[Q]; /* mfs_plan_point, from the cached table */
    mfs_point pt; /* field by field: an initializer would clear the padding (a memset) */
    pt.nn = r->tptr[Q + 1] - e0;
    pt.idx = r->tidx + e0;
    pt.phi = r->ttab + e0 * (size_t)r->nc;
    pt.ncomp = r->nc;
    pt.w = r->qw[Q];
    pt.x = r->qx + Q * (size_t)r->dim;
    pt.node = r->qnode[Q];
    size_t iI = 0;
    for (size_t e = 0; e < pt.nn; e++) { /* columns met for the first time, and I's entry */
      int J = pt.idx[e];
      iI = J == (int)I ? e : iI;
      if (r->mark[J] < 0) {
        size_t s = r->len++;
        r->mark[J] = (int)s;
        r->col[s] = J;
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
      col[e] = r->mark[J];
    }
    st = add_point(r, pl, f, I, &pt, iI, col);
  }
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
static mfs_status assemble_csr(const mfs_plan *pl, const mfs_forms *f, int want_mass,
                               mfs_csr **out)
{
  *out = NULL;
  const size_t n = mfs_plan_particles(pl)->n;
  const int ndof = mfs_physics_ndof(f->physics), nd2 = ndof * ndof;
  mfs_row r;
  mfs_status st = mfs_row_init(&r, pl, f);
  if (st != MFS_OK)
    return st;
  size_t cap = 8 * n * nd2 + 16;
  mfs_csr *A = mfs_csr_alloc(n * ndof, n * ndof, cap);
  st = A ? MFS_OK : MFS_ENOMEM;
  size_t pos = 0;
  for (size_t I = 0; I < n && st == MFS_OK; I++) {
    st = mfs_row_assemble(&r, pl, f, I);
    if (st != MFS_OK)
      break;
    size_t len = r.len;
    if (pos + len * nd2 > cap) {
      size_t ncap = 2 * cap + len * nd2;
      int *ti = mfs_realloc(A->idx, ncap * sizeof *ti);
      if (ti)
        A->idx = ti;
      double *tv = ti ? mfs_realloc(A->val, ncap * sizeof *tv) : NULL;
      if (!tv) {
        st = MFS_ENOMEM;
        break;
      }
      A->val = tv;
      cap = ncap;
    }
    for (int a = 0; a < ndof; a++) {
      for (size_t s = 0; s < len; s++)
        for (int b = 0; b < ndof; b++) {
          A->idx[pos] = r.col[s] * ndof + b;
          A->val[pos] = want_mass ? (a == b ? r.M[s] : 0.0) : r.K[s * nd2 + a * ndof + b];
          pos++;
        }
      A->ptr[I * ndof + a + 1] = pos;
    }
  }
  mfs_row_free(&r);
  if (st != MFS_OK) {
    mfs_csr_free(A);
    return st;
  }
  *out = A;
  return MFS_OK;
}

mfs_status mfs_assemble_stiffness(const mfs_plan *pl, const mfs_material *mat, mfs_csr **K)
{
  *K = NULL;
  if (mat->physics == MFS_PHYS_PLANE_STRAIN && mfs_plan_particles(pl)->dim != 2)
    return MFS_EINVAL;
  mfs_forms f = mfs_forms_stiffness(mat);
  return assemble_csr(pl, &f, 0, K);
}

mfs_status mfs_assemble_mass_consistent(const mfs_plan *pl, const mfs_material *mat,
                                        mfs_csr **M)
{
  mfs_forms f = {.physics = mat->physics, .density = mat->density};
  return assemble_csr(pl, &f, 1, M);
}

mfs_status mfs_assemble_mass_lumped(const mfs_plan *pl, const mfs_material *mat, double *m)
{
  const mfs_particles *p = mfs_plan_particles(pl);
  int ndof = mfs_physics_ndof(mat->physics);
  for (size_t i = 0; i < p->n * ndof; i++)
    m[i] = 0.0;
  const mfs_disc *d = mfs_plan_disc(pl);
  if (!d->shape->partition_of_unity || d->node_volume_mass) {
    /* particle masses rho V_I (SPH, eq. 51), or rho times the lattice's area per node
     * (eq. 119's node volume, asked for) */
    for (size_t I = 0; I < p->n; I++)
      for (int k = 0; k < ndof; k++)
        m[I * ndof + k] = mat->density * (d->node_volume_mass ? mfs_particles_node_volume(p)
                                                               : p->vol[I]);
    return MFS_OK;
  }
  if (mfs_plan_order(pl) < 1)
    return MFS_EINVAL;
  /* rho times the integral of phi_I: the row sum of the consistent mass
   * (eq. 131) for a partition of unity */
  for (size_t Q = 0; Q < mfs_plan_npoints(pl); Q++) {
    mfs_point pt;
    mfs_plan_point(pl, Q, &pt);
    double f = mat->density * pt.w;
    for (size_t e = 0; e < pt.nn; e++)
      for (int k = 0; k < ndof; k++)
        m[(size_t)pt.idx[e] * ndof + k] += f * pt.phi[e * (size_t)pt.ncomp];
  }
  return MFS_OK;
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
