#include "mfs_assemble.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

void mfs_plan_free(mfs_plan *pl)
{
  if (!pl)
    return;
  mfs_nlist_free(pl->nl);
  free(pl->tab);
  free(pl);
}

mfs_plan *mfs_plan_alloc(const mfs_plan_spec *spec, const mfs_particles *p, const mfs_quad *q,
                         int *status, size_t *bad)
{
  int st = MFS_EINVAL;
  mfs_plan *pl = NULL;
  mfs_grid *g = NULL;
  double *d = NULL, *v = NULL, *work = NULL;
  if (!spec->kernel || !spec->shape || !(spec->dilation > 0.0) || spec->order < 1 ||
      spec->order > 2 || q->dim != p->dim)
    goto done;
  st = MFS_ENOMEM;
  pl = calloc(1, sizeof *pl);
  if (!pl)
    goto done;
  pl->dim = p->dim;
  pl->p = p;
  pl->q = q;
  pl->shape = spec->shape;
  pl->order = spec->order;
  pl->ncomp = mfs_shape_ncomp(p->dim, spec->order);
  pl->ctx = (mfs_shape_ctx){spec->kernel, p->dim, spec->dilation * p->dx, spec->rcond_min};
  pl->rcond = 1.0;
  g = mfs_grid_alloc(p->dim, p->n, p->x, &p->box, pl->ctx.a, &st);
  if (!g)
    goto done;
  pl->nl = mfs_nlist_build(g, q->n, q->x, pl->ctx.a, &st);
  if (!pl->nl)
    goto done;
  st = MFS_ENOMEM;
  size_t nnz = pl->nl->ptr[q->n], maxrow = 1;
  for (size_t Q = 0; Q < q->n; Q++) {
    size_t len = pl->nl->ptr[Q + 1] - pl->nl->ptr[Q];
    maxrow = len > maxrow ? len : maxrow;
  }
  pl->tab = malloc((nnz ? nnz : 1) * pl->ncomp * sizeof *pl->tab);
  d = malloc(maxrow * p->dim * sizeof *d);
  v = malloc(maxrow * sizeof *v);
  work = malloc(mfs_shape_work_len(p->dim, (int)maxrow) * sizeof *work);
  if (!pl->tab || !d || !v || !work)
    goto done;
  for (size_t Q = 0; Q < q->n; Q++) {
    size_t e0 = pl->nl->ptr[Q];
    int nn = (int)(pl->nl->ptr[Q + 1] - e0), self = -1;
    const double *xq = q->x + Q * p->dim;
    for (int J = 0; J < nn; J++) {
      int I = pl->nl->idx[e0 + J];
      mfs_box_delta(&p->box, xq, p->x + (size_t)I * p->dim, d + J * p->dim);
      v[J] = p->vol[I];
      if (I == q->node[Q])
        self = J;
    }
    double rc;
    st = spec->shape->eval(&pl->ctx, nn, d, v, self, pl->order, pl->tab + e0 * pl->ncomp, work,
                           &rc);
    if (rc < pl->rcond)
      pl->rcond = rc;
    if (st != MFS_OK) {
      pl->bad = Q;
      if (bad)
        *bad = Q;
      goto done;
    }
  }
  st = MFS_OK;
done:
  free(d);
  free(v);
  free(work);
  mfs_grid_free(g);
  if (st != MFS_OK) {
    mfs_plan_free(pl);
    pl = NULL;
  }
  if (status)
    *status = st;
  return pl;
}

int mfs_physics_ndof(mfs_physics_kind kind)
{
  return kind == MFS_PHYS_PLANE_STRAIN ? 2 : 1;
}

typedef enum { PAIR_GRAD, PAIR_PLANE, PAIR_MASS } pair_kind;

/* Add w b(I, J) over the list e0 .. e1 of one quadrature point to the row
 * accumulator acc (nd2 per column; mark[J] is J's column, already set).
 * fi: particle I's table entry.  The arithmetic is that of one term
 * a += w c0 g, etc., so that results do not depend on how loops are split. */
static void add_point(const mfs_plan *pl, pair_kind kind, int ndof, const double *coef,
                      double w, const double *fi, size_t e0, size_t e1, const int *mark,
                      double *acc)
{
  const int *idx = pl->nl->idx;
  const double *tab = pl->tab;
  int nc = pl->ncomp, dim = pl->dim, nd2 = ndof * ndof;
  double c0 = coef[0], c1 = coef[1], c2 = coef[2];
  switch (kind) {
  case PAIR_GRAD: {
    double wc = w * c0; /* w * c0 * g evaluates as (w * c0) * g */
    if (dim == 2) {
      double i1 = fi[1], i2 = fi[2];
      for (size_t e = e0; e < e1; e++) {
        const double *fj = tab + e * nc;
        double g = 0.0;
        g += i1 * fj[1];
        g += i2 * fj[2];
        acc[mark[idx[e]]] += wc * g;
      }
    } else {
      for (size_t e = e0; e < e1; e++) {
        const double *fj = tab + e * nc;
        double g = 0.0;
        for (int k = 0; k < dim; k++)
          g += fi[1 + k] * fj[1 + k];
        acc[mark[idx[e]]] += wc * g;
      }
    }
    break;
  }
  case PAIR_PLANE: /* B_I^T D B_J, c0 = lambda + 2 mu, c1 = lambda, c2 = mu */
    for (size_t e = e0; e < e1; e++) {
      const double *fj = tab + e * nc;
      double *a = acc + (size_t)mark[idx[e]] * nd2;
      double ix = fi[1], iy = fi[2], jx = fj[1], jy = fj[2];
      a[0] += w * (c0 * ix * jx + c2 * iy * jy);
      a[1] += w * (c1 * ix * jy + c2 * iy * jx);
      a[2] += w * (c1 * iy * jx + c2 * ix * jy);
      a[3] += w * (c0 * iy * jy + c2 * ix * jx);
    }
    break;
  case PAIR_MASS: {
    double wf = w * c0 * fi[0]; /* w * c0 * fi0 * fj0 evaluates left to right */
    for (size_t e = e0; e < e1; e++) {
      double m = wf * tab[e * nc];
      double *a = acc + (size_t)mark[idx[e]] * nd2;
      for (int k = 0; k < ndof; k++)
        a[k * ndof + k] += m;
    }
    break;
  }
  }
}

/* Row-wise assembly of sum_Q w_Q b(I, J, Q) with a marker array (as in
 * CSparse's cs_multiply): for each particle I, the quadrature points that
 * see it (the transposed lists), and for each of those, the particles J
 * they see.  Columns of a row are in order of first appearance. */
static int assemble_pairs(const mfs_plan *pl, pair_kind kind, int ndof, const double *coef,
                          mfs_csr **out)
{
  const mfs_nlist *nl = pl->nl;
  size_t n = pl->p->n, nq = nl->nq, nnz = nl->ptr[nq];
  int nd2 = ndof * ndof;
  int st = MFS_ENOMEM;
  size_t *tptr = calloc(n + 1, sizeof *tptr), *next = malloc((n ? n : 1) * sizeof *next);
  int *tq = malloc((nnz ? nnz : 1) * sizeof *tq), *mark = malloc((n ? n : 1) * sizeof *mark);
  int *cols = NULL;
  double *acc = NULL;
  mfs_csr *A = NULL;
  if (!tptr || !next || !tq || !mark)
    goto done;
  for (size_t e = 0; e < nnz; e++)
    tptr[nl->idx[e] + 1]++;
  for (size_t i = 0; i < n; i++)
    tptr[i + 1] += tptr[i];
  memcpy(next, tptr, n * sizeof *next);
  for (size_t Q = 0; Q < nq; Q++)
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++)
      tq[next[nl->idx[e]]++] = (int)Q;
  size_t maxrow = 0;
  for (size_t i = 0; i < n; i++) { /* bound on the row length: sum of list lengths */
    size_t s = 0;
    for (size_t t = tptr[i]; t < tptr[i + 1]; t++)
      s += nl->ptr[tq[t] + 1] - nl->ptr[tq[t]];
    maxrow = s > maxrow ? s : maxrow;
  }
  for (size_t i = 0; i < n; i++)
    mark[i] = -1;
  cols = malloc((maxrow ? maxrow : 1) * sizeof *cols);
  acc = malloc((maxrow ? maxrow : 1) * nd2 * sizeof *acc);
  size_t cap = 8 * n * nd2 + 16;
  A = mfs_csr_alloc(n * ndof, n * ndof, cap);
  if (!cols || !acc || !A)
    goto done;
  size_t pos = 0;
  for (size_t I = 0; I < n; I++) {
    int len = 0;
    for (size_t t = tptr[I]; t < tptr[I + 1]; t++) {
      size_t Q = (size_t)tq[t], e0 = nl->ptr[Q], e1 = nl->ptr[Q + 1], ei = e0;
      for (size_t e = e0; e < e1; e++) { /* columns met for the first time, and I's entry */
        int J = nl->idx[e];
        ei = J == (int)I ? e : ei;
        if (mark[J] < 0) {
          mark[J] = len;
          cols[len] = J;
          for (int k = 0; k < nd2; k++)
            acc[(size_t)len * nd2 + k] = 0.0;
          len++;
        }
      }
      add_point(pl, kind, ndof, coef, pl->q->w[Q], pl->tab + ei * pl->ncomp, e0, e1, mark, acc);
    }
    if (pos + (size_t)len * nd2 > cap) {
      size_t ncap = 2 * cap + (size_t)len * nd2;
      int *ti = realloc(A->idx, ncap * sizeof *ti);
      if (!ti)
        goto done;
      A->idx = ti;
      double *tv = realloc(A->val, ncap * sizeof *tv);
      if (!tv)
        goto done;
      A->val = tv;
      cap = ncap;
    }
    for (int r = 0; r < ndof; r++) {
      for (int s = 0; s < len; s++)
        for (int b = 0; b < ndof; b++) {
          A->idx[pos] = cols[s] * ndof + b;
          A->val[pos] = acc[s * nd2 + r * ndof + b];
          pos++;
        }
      A->ptr[I * ndof + r + 1] = pos;
    }
    for (int s = 0; s < len; s++)
      mark[cols[s]] = -1;
  }
  st = MFS_OK;
done:
  free(tptr);
  free(next);
  free(tq);
  free(mark);
  free(cols);
  free(acc);
  if (st != MFS_OK) {
    mfs_csr_free(A);
    A = NULL;
  }
  *out = A;
  return st;
}

int mfs_assemble_stiffness(const mfs_plan *pl, const mfs_material *mat, mfs_csr **K)
{
  *K = NULL;
  if (mat->kind == MFS_PHYS_PLANE_STRAIN) {
    if (pl->dim != 2)
      return MFS_EINVAL;
    double c[3] = {mat->lambda + 2.0 * mat->modulus, mat->lambda, mat->modulus};
    return assemble_pairs(pl, PAIR_PLANE, 2, c, K);
  }
  double c[3] = {mat->modulus, 0.0, 0.0};
  return assemble_pairs(pl, PAIR_GRAD, 1, c, K);
}

int mfs_assemble_mass_consistent(const mfs_plan *pl, const mfs_material *mat, mfs_csr **M)
{
  double c[3] = {mat->density, 0.0, 0.0};
  return assemble_pairs(pl, PAIR_MASS, mfs_physics_ndof(mat->kind), c, M);
}

int mfs_assemble_mass_lumped(const mfs_plan *pl, const mfs_material *mat, double *m)
{
  const mfs_nlist *nl = pl->nl;
  int ndof = mfs_physics_ndof(mat->kind), nc = pl->ncomp;
  for (size_t i = 0; i < pl->p->n * ndof; i++)
    m[i] = 0.0;
  if (!pl->shape->partition_of_unity) { /* particle masses rho V_I (eq. 51) */
    for (size_t I = 0; I < pl->p->n; I++)
      for (int k = 0; k < ndof; k++)
        m[I * ndof + k] = mat->density * pl->p->vol[I];
    return MFS_OK;
  }
  /* rho times the integral of phi_I: the row sum of the consistent mass
   * (eq. 131) for a partition of unity */
  for (size_t Q = 0; Q < nl->nq; Q++) {
    double f = mat->density * pl->q->w[Q];
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++)
      for (int k = 0; k < ndof; k++)
        m[(size_t)nl->idx[e] * ndof + k] += f * pl->tab[e * nc];
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

int mfs_stencil(const mfs_stencil_spec *s, mfs_stencil_entry **entries, size_t *n, size_t *bad)
{
  *entries = NULL;
  *n = 0;
  mfs_quad_rule rule;
  int st = mfs_quad_rule_parse(s->quadrature, &rule);
  if (st != MFS_OK || s->mat.kind != MFS_PHYS_SCALAR)
    return MFS_EINVAL;
  st = mfs_quad_rule_check(&rule, s->dim, s->lattice);
  if (st != MFS_OK)
    return st;
  /* entries couple particles closer than 2a; the box must hold more than
   * twice that so that no two images of a particle both couple with node 0 */
  double gamma = s->gamma > 0.0 ? s->gamma : 1.0;
  double hy = s->lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
  int nx = 2 * (int)ceil(2.0 * s->plan.dilation) + 3;
  int ny = 2 * (int)ceil(2.0 * s->plan.dilation / hy) + 4;
  if (nx % 2)
    nx++;
  mfs_lattice_spec ls = {s->dim, s->lattice, nx, s->dim == 1 ? 1 : ny, s->dx, gamma, 1,
                         rule.cells, 0.0, 0};
  mfs_particles *p = mfs_lattice_alloc(&ls, &st);
  mfs_quad *q = p ? mfs_quad_alloc(&rule, p, &st) : NULL;
  mfs_plan *pl = q ? mfs_plan_alloc(&s->plan, p, q, &st, bad) : NULL;
  mfs_csr *K = NULL, *M = NULL;
  double *ml = NULL;
  mfs_stencil_entry *out = NULL;
  if (!pl)
    goto done;
  st = mfs_assemble_stiffness(pl, &s->mat, &K);
  if (st != MFS_OK)
    goto done;
  if (s->consistent_mass) {
    st = mfs_assemble_mass_consistent(pl, &s->mat, &M);
  } else {
    st = MFS_ENOMEM;
    ml = malloc(p->n * sizeof *ml);
    if (ml)
      st = mfs_assemble_mass_lumped(pl, &s->mat, ml);
  }
  if (st != MFS_OK)
    goto done;
  /* union of the patterns of row 0 of K and M */
  size_t cap = (K->ptr[1] - K->ptr[0]) + (M ? M->ptr[1] - M->ptr[0] : 0) + 1, cnt = 0;
  st = MFS_ENOMEM;
  out = malloc(cap * sizeof *out);
  if (!out)
    goto done;
  for (int pass = 0; pass < 2; pass++) {
    const mfs_csr *A = pass == 0 ? K : M;
    if (!A)
      continue;
    for (size_t e = A->ptr[0]; e < A->ptr[1]; e++) {
      int J = A->idx[e];
      int seen = 0;
      for (size_t i = 0; i < cnt && !seen; i++)
        seen = out[i].j == J; /* temporarily the particle index */
      if (seen)
        continue;
      out[cnt].j = J;
      out[cnt].K = mfs_csr_get(K, 0, J);
      out[cnt].M = M ? mfs_csr_get(M, 0, J) : (J == 0 ? ml[0] : 0.0);
      cnt++;
    }
  }
  for (size_t i = 0; i < cnt; i++) { /* lattice offsets by the minimum image */
    int J = out[i].j;
    double d[3];
    mfs_box_delta(&p->box, p->x, p->x + (size_t)J * p->dim, d);
    int kk = s->dim == 1 ? 0 : (int)lround(d[1] / p->a2[1]);
    int jj = (int)lround((d[0] - kk * p->a2[0]) / p->a1[0]);
    out[i].j = jj;
    out[i].k = kk;
  }
  qsort(out, cnt, sizeof *out, cmp_entry);
  *entries = out;
  *n = cnt;
  out = NULL;
  st = MFS_OK;
done:
  free(out);
  free(ml);
  mfs_csr_free(K);
  mfs_csr_free(M);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return st;
}
