#include "mfs_static.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_eval.h"
#include "mfs_static_impl.h"

/* ------------------------------------------------------------------ */
/* methods                                                             */

const mfs_static_method mfs_static_sph = {
  .name = "sph",
  .what = "symmetrized SPH gradient (eq. 47), Bubnov, nodal quadrature",
  .trial = &mfs_shape_sphs,
  .quadrature = &mfs_quad_nodal,
  .particle_values = 1};
const mfs_static_method mfs_static_jb = {
  .name = "jb",
  .what = "Johnson-Beissel normal-strain correction (eqs 49-52), Bubnov, nodal",
  .trial = &mfs_shape_sphs,
  .quadrature = &mfs_quad_nodal,
  .jb_normal = 1,
  .particle_values = 1};
const mfs_static_method mfs_static_rl = {
  .name = "rl",
  .what = "Randles-Libersky normalized gradient (eqs 68-69), Bubnov, nodal",
  .trial = &mfs_shape_rl,
  .quadrature = &mfs_quad_nodal,
  .particle_values = 1};
const mfs_static_method mfs_static_cd1 = {
  .name = "cd1",
  .what = "corrected derivatives 1 (eqs 55-62), Petrov-Galerkin, Shepard test, nodal",
  .trial = &mfs_shape_kb,
  .test = &mfs_shape_shepard,
  .quadrature = &mfs_quad_nodal};
const mfs_static_method mfs_static_cd2 = {
  .name = "cd2",
  .what = "corrected derivatives 2 (eqs 63-64), Petrov-Galerkin, Shepard test, nodal",
  .trial = &mfs_shape_cd2,
  .test = &mfs_shape_shepard,
  .quadrature = &mfs_quad_nodal};
const mfs_static_method mfs_static_mls = {
  .name = "mls",
  .what = "MLS (eqs 44-46), Bubnov, nodal quadrature",
  .trial = &mfs_shape_mls,
  .quadrature = &mfs_quad_nodal};
const mfs_static_method mfs_static_efg = {
  .name = "efg",
  .what = "MLS, Bubnov, 5 x 5 Gauss points per background cell (EFG)",
  .trial = &mfs_shape_mls,
  .quadrature = &mfs_quad_gauss[4]};

const mfs_static_method *const mfs_static_methods[] = {
  &mfs_static_sph, &mfs_static_jb,  &mfs_static_rl, &mfs_static_cd1,
  &mfs_static_cd2, &mfs_static_mls, &mfs_static_efg, NULL};

const mfs_static_method *mfs_static_method_find(const char *name)
{
  for (int i = 0; name && mfs_static_methods[i]; i++)
    if (strcmp(name, mfs_static_methods[i]->name) == 0)
      return mfs_static_methods[i];
  return NULL;
}

/* ------------------------------------------------------------------ */
/* material and exact solutions                                        */

static void elasticity(const mfs_static_spec *s, double *D)
{
  double E = s->young, nu = s->poisson;
  memset(D, 0, 9 * sizeof *D);
  if (s->plane_strain) {
    double c = E / ((1.0 + nu) * (1.0 - 2.0 * nu));
    D[0] = D[4] = c * (1.0 - nu);
    D[1] = D[3] = c * nu;
    D[8] = c * (1.0 - 2.0 * nu) / 2.0;
  } else {
    double c = E / (1.0 - nu * nu);
    D[0] = D[4] = c;
    D[1] = D[3] = c * nu;
    D[8] = c * (1.0 - nu) / 2.0;
  }
}

static void inverse_elasticity(const double *D, double *Di)
{
  double det = D[0] * D[4] - D[1] * D[3];
  memset(Di, 0, 9 * sizeof *Di);
  Di[0] = D[4] / det;
  Di[4] = D[0] / det;
  Di[1] = -D[1] / det;
  Di[3] = -D[3] / det;
  Di[8] = 1.0 / D[8];
}

/* The field solved for: the problem's, or the patch test's linear field. */
static void field(const mfs_static *m, const double *x, double *u, double *sig)
{
  if (!m->s.patch) {
    m->s.problem->exact(&m->s, x, u, sig);
    return;
  }
  const double *c = m->patch_c, *G = m->patch_G;
  if (u) {
    u[0] = c[0] + G[0] * x[0] + G[1] * x[1];
    u[1] = c[1] + G[2] * x[0] + G[3] * x[1];
  }
  if (sig) {
    double e[3] = {G[0], G[3], G[1] + G[2]};
    for (int i = 0; i < 3; i++)
      sig[i] = m->D[3 * i] * e[0] + m->D[3 * i + 1] * e[1] + m->D[3 * i + 2] * e[2];
  }
}

/* ------------------------------------------------------------------ */
/* spec                                                                */

mfs_static_spec mfs_static_spec_default(void)
{
  return (mfs_static_spec){.problem = &mfs_static_beam,
                           .method = &mfs_static_efg,
                           .kernel = &mfs_kernel_cubic,
                           .dilation = 2.0 * M_SQRT2,
                           .nx = 17,
                           .ny = 3,
                           .young = 1000.0,
                           .poisson = 0.3,
                           .load = 1.0,
                           .length = 8.0,
                           .depth = 1.0,
                           .hole_radius = 1.0,
                           .plate_size = 5.0,
                           .seed = 1};
}

mfs_status mfs_static_check(const mfs_static_spec *s, const char **field)
{
  const char *f = NULL;
  const mfs_quad_type *qt = s->quadrature;
  /* the rules that make sense here: the nodes with their volumes, or Gauss cells */
  int rule_ok = !qt || qt->gauss_n > 0 || (qt->node_share == 1.0 && !qt->centres && !qt->voronoi);
  if (!s->problem || !s->problem->build || !s->problem->exact || !s->problem->check)
    f = "problem";
  else if (!s->method || !s->method->trial || !s->method->quadrature)
    f = "method";
  else if (!rule_ok)
    f = "quadrature";
  else if (!s->kernel)
    f = "kernel";
  else if (!(s->dilation > 0.0) || !isfinite(s->dilation))
    f = "dilation";
  else if (!(s->young > 0.0) || !isfinite(s->young))
    f = "young";
  else if (!(s->poisson > -1.0 && s->poisson < 0.5))
    f = "poisson";
  else if (!isfinite(s->load) || s->load == 0.0)
    f = "load";
  else if (!(s->rcond_min >= 0.0 && s->rcond_min < 1.0))
    f = "rcond_min";
  else if (!(s->solve_rcond_min >= 0.0 && s->solve_rcond_min < 1.0))
    f = "solve_rcond_min";
  else
    f = s->problem->check(s);
  if (field)
    *field = f;
  return f ? MFS_EINVAL : MFS_OK;
}

void mfs_static_free(mfs_static *m)
{
  if (!m)
    return;
  if (m->q != m->gq)
    mfs_quad_free(m->q);
  if (m->eq != m->gq)
    mfs_quad_free(m->eq);
  mfs_quad_free(m->gq);
  mfs_free(m->evol);
  mfs_free(m->pinned);
  mfs_particles_free(m->p);
  mfs_grid_free(m->grid);
  mfs_csr_free(m->K);
  mfs_csr_free(m->Ctr);
  mfs_csr_free(m->Cte);
  mfs_free(m->seg);
  mfs_free(m->bp);
  mfs_free(m->f);
  mfs_free(m->g);
  mfs_free(m->u);
  mfs_free(m);
}

/* The boundary quadrature points: the trapezoid rule at the nodes (a point
 * at each end of each segment, half its length) for a nodal rule; ng Gauss
 * points per segment otherwise. */
static int boundary_points(mfs_static *m)
{
  int ng = m->qt->gauss_n;
  size_t per = ng > 0 ? (size_t)ng : 2;
  m->bp = mfs_malloc((m->nseg * per + 1) * sizeof *m->bp);
  if (!m->bp)
    return MFS_ENOMEM;
  double tt[10], tw[10];
  if (ng > 0 && mfs_static_impl_gauss01(ng, tt, tw) != MFS_OK)
    return MFS_ENOMEM;
  for (size_t k = 0; k < m->nseg; k++) {
    const segment *sg = m->seg + k;
    const double *xa = m->p->x + 2 * (size_t)sg->a, *xb = m->p->x + 2 * (size_t)sg->b;
    for (size_t i = 0; i < per; i++) {
      bpoint *b = m->bp + m->nbp++;
      double t = ng > 0 ? tt[i] : (double)i;
      b->t = t;
      b->x[0] = xa[0] + t * (xb[0] - xa[0]);
      b->x[1] = xa[1] + t * (xb[1] - xa[1]);
      b->n[0] = sg->n[0];
      b->n[1] = sg->n[1];
      b->w = ng > 0 ? tw[i] * sg->len : 0.5 * sg->len;
      b->node = ng > 0 ? -1 : (i == 0 ? sg->a : sg->b);
      b->seg = k;
    }
  }
  return MFS_OK;
}

mfs_static *mfs_static_alloc(const mfs_static_spec *s, mfs_status *status, const char **field)
{
  mfs_status st = mfs_static_check(s, field);
  mfs_static *m = NULL;
  if (st != MFS_OK)
    goto fail;
  st = MFS_ENOMEM;
  m = mfs_calloc(1, sizeof *m);
  if (!m)
    goto fail;
  m->s = *s;
  if (m->s.rcond_min == 0.0)
    m->s.rcond_min = 1e-12;
  if (m->s.solve_rcond_min == 0.0)
    m->s.solve_rcond_min = 1e-15;
  m->qt = s->quadrature ? s->quadrature : s->method->quadrature;
  elasticity(&m->s, m->D);
  inverse_elasticity(m->D, m->Dinv);
  s->problem->patch_field(m->patch_c, m->patch_G);
  st = (mfs_status)s->problem->build(m);
  if (st != MFS_OK)
    goto fail;
  m->a = s->dilation * m->h;
  if (m->qt->gauss_n == 5) {
    m->q = m->gq;
    m->q_block = m->gq_block;
  } else if (m->qt->gauss_n > 0) { /* built by the problem */
    m->q_block = (size_t)m->qt->gauss_n * (size_t)m->qt->gauss_n;
  } else {
    m->q = mfs_quad_alloc(&mfs_quad_nodal, m->p, &st);
    if (!m->q)
      goto fail;
    m->q_block = 1;
  }
  if (!m->eq)
    m->eq = m->gq;
  st = MFS_ENOMEM;
  if (!m->evol) {
    m->evol = mfs_malloc(m->p->n * sizeof *m->evol);
    if (!m->evol)
      goto fail;
    memcpy(m->evol, m->p->vol, m->p->n * sizeof *m->evol);
  }
  st = (mfs_status)boundary_points(m);
  if (st != MFS_OK)
    goto fail;
  m->grid = mfs_grid_alloc(2, m->p->n, m->p->x, &m->p->box, m->a, &st);
  if (!m->grid)
    goto fail;
  if (status)
    *status = MFS_OK;
  return m;
fail:
  mfs_static_free(m);
  if (status)
    *status = st;
  return NULL;
}

/* ------------------------------------------------------------------ */
/* evaluation at one point                                             */

/* The trial and test functions at a point: values, and the strain
 * coefficients B = (a, b, c, d) per neighbour: eps_xx = sum a u_x, eps_yy =
 * sum b u_y, gamma_xy = sum (c u_x + d u_y). */
typedef struct {
  mfs_eval tr, te;
  int has_test, jb, pv;
  size_t cap;
  int nn;
  int *idx, *idx2;
  double *otr, *ote;     /* nn * 3 table rows (otr owns the block of all six) */
  double *vtr, *vte;     /* values */
  double *Btr, *Bte;     /* nn * 4 */
} pev;

static void pev_free(pev *e)
{
  mfs_eval_free(&e->tr);
  mfs_eval_free(&e->te);
  mfs_free(e->idx);
  mfs_free(e->idx2);
  mfs_free(e->otr); /* one block for all the tables */
  memset(e, 0, sizeof *e);
}

static int pev_reserve(pev *e, size_t cap)
{
  if (cap <= e->cap)
    return MFS_OK;
  cap = cap < 2 * e->cap ? 2 * e->cap : cap;
  if (mfs_eval_reserve(&e->tr, cap) != MFS_OK ||
      (e->has_test && mfs_eval_reserve(&e->te, cap) != MFS_OK))
    return MFS_ENOMEM;
  int *i1 = mfs_malloc(cap * sizeof *i1), *i2 = mfs_malloc(cap * sizeof *i2);
  double *d = mfs_malloc(cap * 16 * sizeof *d); /* otr, ote (3 each), vtr, vte, Btr, Bte (4 each) */
  if (!i1 || !i2 || !d) {
    mfs_free(i1);
    mfs_free(i2);
    mfs_free(d);
    return MFS_ENOMEM;
  }
  mfs_free(e->idx);
  mfs_free(e->idx2);
  mfs_free(e->otr);
  e->idx = i1;
  e->idx2 = i2;
  e->otr = d;
  e->ote = d + 3 * cap;
  e->vtr = d + 6 * cap;
  e->vte = d + 7 * cap;
  e->Btr = d + 8 * cap;
  e->Bte = d + 12 * cap;
  e->cap = cap;
  return MFS_OK;
}

static int pev_init(pev *e, const mfs_static *m)
{
  memset(e, 0, sizeof *e);
  const mfs_static_method *me = m->s.method;
  mfs_disc d = {.dim = 2, .kernel = m->s.kernel, .shape = me->trial, .rcond_min = m->s.rcond_min};
  e->has_test = me->test != NULL;
  e->jb = me->jb_normal;
  e->pv = me->particle_values;
  int st = mfs_eval_init(&e->tr, &d, m->a, 1, &m->p->box, 16);
  if (st != MFS_OK)
    return st;
  e->tr.within = 1;
  if (e->has_test) {
    d.shape = me->test;
    st = mfs_eval_init(&e->te, &d, m->a, 1, &m->p->box, 16);
    if (st != MFS_OK)
      return st;
    e->te.within = 1;
  }
  return pev_reserve(e, 64);
}

/* Evaluate at x with the candidates cand[0..nc) (all within a), self the
 * node at x or -1. */
static int pev_point_opt(pev *e, const mfs_static *m, const double *x, int self, const int *cand,
                         size_t nc, int trial_only, mfs_static_where *where);

static int pev_point(pev *e, const mfs_static *m, const double *x, int self, const int *cand,
                     size_t nc, mfs_static_where *where)
{
  return pev_point_opt(e, m, x, self, cand, nc, 0, where);
}

/* trial_only: the test functions are not needed (the error norms) */
static int pev_point_opt(pev *e, const mfs_static *m, const double *x, int self, const int *cand,
                         size_t nc, int trial_only, mfs_static_where *where)
{
  int st = pev_reserve(e, nc);
  if (st != MFS_OK)
    return st;
  const mfs_particles *p = m->p;
  int nn;
  double rc = 1.0;
  st = mfs_eval_point_general(&e->tr, x, p->x, p->vol, cand, nc, self, e->idx, e->otr, &nn, &rc);
  int test = e->has_test && !trial_only;
  if (st == MFS_OK && test)
    st = mfs_eval_point_general(&e->te, x, p->x, p->vol, cand, nc, self, e->idx2, e->ote, &nn,
                                &rc);
  e->nn = nn;
  double bx = 1.0, by = 1.0;
  if (st == MFS_OK && e->jb) { /* eq. 52: beta = 1 / sum_J g_J (x_J - x) per direction */
    const double *d = mfs_eval_offsets(&e->tr);
    double sx = 0.0, sy = 0.0;
    for (int J = 0; J < nn; J++) {
      sx += e->otr[3 * J + 1] * d[2 * J];
      sy += e->otr[3 * J + 2] * d[2 * J + 1];
    }
    if (!(sx > 0.0) || !(sy > 0.0) || !isfinite(sx) || !isfinite(sy))
      st = MFS_ESINGULAR;
    bx = 1.0 / sx;
    by = 1.0 / sy;
    rc = fmin(fabs(sx), fabs(sy));
  }
  if (st != MFS_OK) {
    if (where) {
      where->x[0] = x[0];
      where->x[1] = x[1];
      where->nn = nn;
      where->rcond = rc;
    }
    return st;
  }
  int me = e->pv && self >= 0 ? e->tr.self : -1;
  for (int J = 0; J < nn; J++) {
    const double *o = e->otr + 3 * J;
    e->vtr[J] = me >= 0 ? (J == me ? 1.0 : 0.0) : o[0];
    double *B = e->Btr + 4 * J;
    B[0] = bx * o[1];
    B[1] = by * o[2];
    B[2] = o[2];
    B[3] = o[1];
    if (test) {
      const double *t = e->ote + 3 * J;
      e->vte[J] = t[0];
      double *T = e->Bte + 4 * J;
      T[0] = t[1];
      T[1] = t[2];
      T[2] = t[2];
      T[3] = t[1];
    }
  }
  return MFS_OK;
}

static const double *pev_test_values(const pev *e)
{
  return e->has_test ? e->vte : e->vtr;
}

static const double *pev_test_B(const pev *e)
{
  return e->has_test ? e->Bte : e->Btr;
}

/* ------------------------------------------------------------------ */
/* point lists in chunks                                               */

typedef struct {
  const mfs_quad *q;
  size_t bs;      /* points per block */
  size_t nblock;
  size_t b0, b1;  /* the blocks of the chunk */
  mfs_nlist *nl;  /* the lists of its points */
} cursor;

enum { CHUNK_POINTS = 1 << 16 };

static void cursor_init(cursor *c, const mfs_quad *q, size_t bs)
{
  *c = (cursor){.q = q, .bs = bs, .nblock = q->n / bs};
}

/* The next chunk; 0 at the end, or -status on failure. */
static int cursor_next(cursor *c, const mfs_static *m)
{
  mfs_nlist_free(c->nl);
  c->nl = NULL;
  c->b0 = c->b1;
  if (c->b0 >= c->nblock)
    return 0;
  size_t per = CHUNK_POINTS / c->bs ? CHUNK_POINTS / c->bs : 1;
  c->b1 = c->b0 + per < c->nblock ? c->b0 + per : c->nblock;
  mfs_status st;
  c->nl = mfs_nlist_build(m->grid, (c->b1 - c->b0) * c->bs, c->q->x + 2 * c->b0 * c->bs, m->a,
                          &st);
  return c->nl ? 1 : -(int)st;
}

static void cursor_free(cursor *c)
{
  mfs_nlist_free(c->nl);
  c->nl = NULL;
}

/* ------------------------------------------------------------------ */
/* assembly                                                            */

typedef struct {
  size_t n, cap;
  int *row, *col;
  double *val;
} coo;

static int coo_add(coo *t, int r, int c, double v)
{
  if (v == 0.0)
    return MFS_OK;
  if (t->n == t->cap) {
    size_t cap = t->cap ? 2 * t->cap : 1024;
    int *r2 = mfs_realloc(t->row, cap * sizeof *r2);
    if (r2)
      t->row = r2;
    int *c2 = mfs_realloc(t->col, cap * sizeof *c2);
    if (c2)
      t->col = c2;
    double *v2 = mfs_realloc(t->val, cap * sizeof *v2);
    if (v2)
      t->val = v2;
    if (!r2 || !c2 || !v2)
      return MFS_ENOMEM;
    t->cap = cap;
  }
  t->row[t->n] = r;
  t->col[t->n] = c;
  t->val[t->n++] = v;
  return MFS_OK;
}

static void coo_free(coo *t)
{
  mfs_free(t->row);
  mfs_free(t->col);
  mfs_free(t->val);
  memset(t, 0, sizeof *t);
}

/* CSR of nrow x ncol from triplets, duplicates summed, rows sorted. */
static mfs_csr *coo_csr(const coo *t, size_t nrow, size_t ncol)
{
  mfs_csr *A = mfs_csr_alloc(nrow, ncol, t->n);
  size_t *next = mfs_malloc((nrow + 1) * sizeof *next);
  int *mark = mfs_malloc((ncol ? ncol : 1) * sizeof *mark);
  if (!A || !next || !mark) {
    mfs_csr_free(A);
    A = NULL;
    goto done;
  }
  for (size_t e = 0; e < t->n; e++)
    A->ptr[t->row[e] + 1]++;
  for (size_t i = 0; i < nrow; i++)
    A->ptr[i + 1] += A->ptr[i];
  memcpy(next, A->ptr, (nrow + 1) * sizeof *next);
  for (size_t e = 0; e < t->n; e++) {
    size_t k = next[t->row[e]]++;
    A->idx[k] = t->col[e];
    A->val[k] = t->val[e];
  }
  /* sum duplicates in place (marker per row), then sort each row */
  for (size_t j = 0; j < ncol; j++)
    mark[j] = -1;
  size_t out = 0;
  for (size_t i = 0; i < nrow; i++) {
    size_t start = out;
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
      int c = A->idx[e];
      if (mark[c] >= (int)start) {
        A->val[mark[c]] += A->val[e];
      } else {
        mark[c] = (int)out;
        A->idx[out] = c;
        A->val[out++] = A->val[e];
      }
    }
    A->ptr[i] = start;
    /* insertion sort: constraint rows are short */
    for (size_t e = start + 1; e < out; e++) {
      int c = A->idx[e];
      double v = A->val[e];
      size_t k = e;
      while (k > start && A->idx[k - 1] > c) {
        A->idx[k] = A->idx[k - 1];
        A->val[k] = A->val[k - 1];
        k--;
      }
      A->idx[k] = c;
      A->val[k] = v;
    }
  }
  A->ptr[nrow] = out;
done:
  mfs_free(next);
  mfs_free(mark);
  return A;
}

static int cmp_int(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The union of the neighbour lists of each block of q: U (one row per block). */
static int block_unions(const mfs_static *m, const mfs_quad *q, size_t bs, mfs_nlist **U,
                        size_t *maxnn)
{
  size_t n = m->p->n, cap = 1 << 16;
  int st = MFS_ENOMEM;
  cursor c;
  cursor_init(&c, q, bs);
  mfs_nlist *u = mfs_calloc(1, sizeof *u);
  int *mark = mfs_malloc(n * sizeof *mark);
  if (!u || !mark)
    goto done;
  u->nq = c.nblock;
  u->ptr = mfs_calloc(c.nblock + 1, sizeof *u->ptr);
  u->idx = mfs_malloc(cap * sizeof *u->idx);
  if (!u->ptr || !u->idx)
    goto done;
  for (size_t i = 0; i < n; i++)
    mark[i] = -1;
  size_t nnz = 0;
  *maxnn = 0;
  int r = 0;
  while ((r = cursor_next(&c, m)) > 0) {
    for (size_t b = c.b0; b < c.b1; b++) {
      for (size_t Q = (b - c.b0) * bs; Q < (b - c.b0 + 1) * bs; Q++) {
        size_t len = c.nl->ptr[Q + 1] - c.nl->ptr[Q];
        *maxnn = len > *maxnn ? len : *maxnn;
        for (size_t e = c.nl->ptr[Q]; e < c.nl->ptr[Q + 1]; e++) {
          int J = c.nl->idx[e];
          if (mark[J] == (int)b)
            continue;
          mark[J] = (int)b;
          if (nnz == cap) {
            cap *= 2;
            int *t = mfs_realloc(u->idx, cap * sizeof *t);
            if (!t)
              goto done;
            u->idx = t;
          }
          u->idx[nnz++] = J;
        }
      }
      u->ptr[b + 1] = nnz;
      qsort(u->idx + u->ptr[b], nnz - u->ptr[b], sizeof *u->idx, cmp_int);
    }
  }
  if (r < 0) {
    st = -r;
    goto done;
  }
  st = MFS_OK;
done:
  cursor_free(&c);
  mfs_free(mark);
  if (st != MFS_OK) {
    mfs_nlist_free(u);
    u = NULL;
  }
  *U = u;
  return st;
}

/* The stiffness pattern: node I couples with the union of the blocks that
 * see it; K in CSR with 2 x 2 blocks, rows 2I + c, columns 2J + d, the
 * node columns of each node row sorted. */
static int stiffness_pattern(const mfs_static *m, const mfs_nlist *U, mfs_csr **Kout,
                             size_t **nptr_out, int **nidx_out)
{
  size_t n = m->p->n;
  int st = MFS_ENOMEM;
  mfs_nlist *T = mfs_nlist_transpose(U, n, (mfs_status *)&st);
  size_t *nptr = mfs_calloc(n + 1, sizeof *nptr), cap = 1 << 16, nnz = 0;
  int *nidx = mfs_malloc(cap * sizeof *nidx), *mark = mfs_malloc(n * sizeof *mark);
  mfs_csr *K = NULL;
  if (!T || !nptr || !nidx || !mark)
    goto done;
  for (size_t i = 0; i < n; i++)
    mark[i] = -1;
  for (size_t I = 0; I < n; I++) {
    for (size_t e = T->ptr[I]; e < T->ptr[I + 1]; e++) {
      int b = T->idx[e];
      for (size_t k = U->ptr[b]; k < U->ptr[b + 1]; k++) {
        int J = U->idx[k];
        if (mark[J] == (int)I)
          continue;
        mark[J] = (int)I;
        if (nnz == cap) {
          cap *= 2;
          int *t = mfs_realloc(nidx, cap * sizeof *t);
          if (!t)
            goto done;
          nidx = t;
        }
        nidx[nnz++] = J;
      }
    }
    nptr[I + 1] = nnz;
    qsort(nidx + nptr[I], nnz - nptr[I], sizeof *nidx, cmp_int);
  }
  K = mfs_csr_alloc(2 * n, 2 * n, 4 * nnz);
  if (!K)
    goto done;
  for (size_t I = 0; I < n; I++) {
    size_t len = nptr[I + 1] - nptr[I];
    for (int c = 0; c < 2; c++) {
      size_t r = 2 * I + (size_t)c, start = 4 * nptr[I] + (size_t)c * 2 * len;
      K->ptr[r] = start;
      for (size_t k = 0; k < len; k++) {
        K->idx[start + 2 * k] = 2 * nidx[nptr[I] + k];
        K->idx[start + 2 * k + 1] = 2 * nidx[nptr[I] + k] + 1;
        K->val[start + 2 * k] = K->val[start + 2 * k + 1] = 0.0;
      }
    }
  }
  K->ptr[2 * n] = 4 * nnz;
  st = MFS_OK;
done:
  mfs_nlist_free(T);
  mfs_free(mark);
  if (st != MFS_OK) {
    mfs_free(nptr);
    mfs_free(nidx);
    mfs_csr_free(K);
    nptr = NULL;
    nidx = NULL;
    K = NULL;
  }
  *Kout = K;
  *nptr_out = nptr;
  *nidx_out = nidx;
  return st;
}

/* K += w B_test^T D B_trial over the point's neighbours, into the block's
 * dense local matrix Kl (2 nu x 2 nu, local indices loc[]); DB: room for
 * 6 nn doubles (D B_J of each trial neighbour).  Bubnov: the upper blocks
 * and their transposes. */
static void point_stiffness(const mfs_static *m, const pev *e, double w, const int *loc,
                            size_t nu, double *Kl, double *DB)
{
  const double *D = m->D;
  const double d11 = D[0], d12 = D[1], d22 = D[4], d33 = D[8];
  const double *Bt = pev_test_B(e), *Br = e->Btr;
  const int *idx = e->idx;
  const size_t ld = 2 * nu;
  const int nn = e->nn, sym = !e->has_test;
  for (int J = 0; J < nn; J++) {
    const double *bj = Br + 4 * J;
    double *p = DB + 6 * J;
    p[0] = d11 * bj[0];
    p[1] = d12 * bj[1];
    p[2] = d33 * bj[2];
    p[3] = d33 * bj[3];
    p[4] = d12 * bj[0];
    p[5] = d22 * bj[1];
  }
  for (int I = 0; I < nn; I++) {
    const double *bi = Bt + 4 * I;
    double aI = w * bi[0], bI = w * bi[1], cI = w * bi[2], dI = w * bi[3];
    size_t ci = 2 * (size_t)loc[idx[I]];
    double *row0 = Kl + ci * ld, *row1 = row0 + ld;
    for (int J = sym ? I : 0; J < nn; J++) {
      const double *p = DB + 6 * J;
      size_t cj = 2 * (size_t)loc[idx[J]];
      double k00 = aI * p[0] + cI * p[2], k01 = aI * p[1] + cI * p[3];
      double k10 = bI * p[4] + dI * p[2], k11 = bI * p[5] + dI * p[3];
      row0[cj] += k00;
      row0[cj + 1] += k01;
      row1[cj] += k10;
      row1[cj + 1] += k11;
      if (sym && J != I) { /* K_JI = K_IJ^T */
        double *r0 = Kl + cj * ld, *r1 = r0 + ld;
        r0[ci] += k00;
        r0[ci + 1] += k10;
        r1[ci] += k01;
        r1[ci + 1] += k11;
      }
    }
  }
}

static int assemble_stiffness(mfs_static *m, mfs_static_where *where)
{
  size_t n = m->p->n, maxnn = 0;
  mfs_nlist *U = NULL;
  size_t *nptr = NULL;
  int *nidx = NULL, *loc = NULL, *rowmark = NULL;
  double *Kl = NULL, *DB = NULL;
  pev e;
  cursor c;
  cursor_init(&c, m->q, m->q_block);
  int st = pev_init(&e, m);
  if (st != MFS_OK)
    goto done;
  st = block_unions(m, m->q, m->q_block, &U, &maxnn);
  if (st != MFS_OK)
    goto done;
  m->max_nn = maxnn;
  st = stiffness_pattern(m, U, &m->K, &nptr, &nidx);
  if (st != MFS_OK)
    goto done;
  size_t maxu = 0;
  for (size_t b = 0; b < U->nq; b++)
    maxu = U->ptr[b + 1] - U->ptr[b] > maxu ? U->ptr[b + 1] - U->ptr[b] : maxu;
  st = MFS_ENOMEM;
  loc = mfs_malloc(n * sizeof *loc);
  rowmark = mfs_malloc(n * sizeof *rowmark);
  Kl = mfs_malloc((4 * maxu * maxu + 1) * sizeof *Kl);
  DB = mfs_malloc((6 * maxnn + 6) * sizeof *DB);
  if (!loc || !rowmark || !Kl || !DB)
    goto done;
  int r = 0;
  st = MFS_OK;
  while (st == MFS_OK && (r = cursor_next(&c, m)) > 0) {
    for (size_t b = c.b0; b < c.b1 && st == MFS_OK; b++) {
      const int *ub = U->idx + U->ptr[b];
      size_t nu = U->ptr[b + 1] - U->ptr[b];
      for (size_t k = 0; k < nu; k++)
        loc[ub[k]] = (int)k;
      memset(Kl, 0, 4 * nu * nu * sizeof *Kl);
      for (size_t i = 0; i < c.bs && st == MFS_OK; i++) {
        size_t Q = b * c.bs + i, L = Q - c.b0 * c.bs;
        const int *cand = c.nl->idx + c.nl->ptr[L];
        size_t nc = c.nl->ptr[L + 1] - c.nl->ptr[L];
        st = pev_point(&e, m, m->q->x + 2 * Q, m->q->node[Q], cand, nc, where);
        if (st == MFS_OK)
          point_stiffness(m, &e, m->q->w[Q], loc, nu, Kl, DB);
      }
      /* scatter the block into K */
      for (size_t k = 0; k < nu && st == MFS_OK; k++) {
        int I = ub[k];
        size_t len = nptr[I + 1] - nptr[I];
        for (size_t t = 0; t < len; t++)
          rowmark[nidx[nptr[I] + t]] = (int)t;
        for (int cI = 0; cI < 2; cI++) {
          double *val = m->K->val + m->K->ptr[2 * (size_t)I + cI];
          const double *kr = Kl + (2 * k + cI) * 2 * nu;
          for (size_t l = 0; l < nu; l++) {
            size_t t = (size_t)rowmark[ub[l]];
            val[2 * t] += kr[2 * l];
            val[2 * t + 1] += kr[2 * l + 1];
          }
        }
      }
    }
  }
  if (st == MFS_OK && r < 0)
    st = -r;
done:
  cursor_free(&c);
  pev_free(&e);
  mfs_nlist_free(U);
  mfs_free(nptr);
  mfs_free(nidx);
  mfs_free(loc);
  mfs_free(rowmark);
  mfs_free(Kl);
  mfs_free(DB);
  return st;
}

/* Neighbour lists of the boundary points. */
static mfs_nlist *boundary_lists(const mfs_static *m, mfs_status *st)
{
  double *x = mfs_malloc((2 * m->nbp + 2) * sizeof *x);
  if (!x) {
    *st = MFS_ENOMEM;
    return NULL;
  }
  for (size_t k = 0; k < m->nbp; k++) {
    x[2 * k] = m->bp[k].x[0];
    x[2 * k + 1] = m->bp[k].x[1];
  }
  mfs_nlist *nl = mfs_nlist_build(m->grid, m->nbp, x, m->a, st);
  mfs_free(x);
  return nl;
}

/* The traction load and the constraints (Lagrange multipliers, piecewise
 * linear on the nodes of Gamma_u, one per node and prescribed component). */
static int assemble_boundary(mfs_static *m, mfs_static_where *where)
{
  size_t n = m->p->n;
  mfs_status st0;
  mfs_nlist *nl = boundary_lists(m, &st0);
  int st = st0;
  pev e;
  memset(&e, 0, sizeof e);
  coo ctr = {0}, cte = {0};
  int *mult = NULL; /* per node and component: the multiplier, or -1 */
  double *gsum = NULL;
  if (!nl)
    goto done;
  st = pev_init(&e, m);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  m->f = mfs_calloc(2 * n, sizeof *m->f);
  mult = mfs_malloc(2 * n * sizeof *mult);
  if (!m->f || !mult)
    goto done;
  for (size_t i = 0; i < 2 * n; i++)
    mult[i] = -1;
  m->m = 0;
  for (size_t k = 0; k < m->nseg; k++)
    for (int c = 0; c < 2; c++)
      if (m->seg[k].fixed >> c & 1u) {
        int ends[2] = {m->seg[k].a, m->seg[k].b};
        for (int t = 0; t < 2; t++)
          if (mult[2 * (size_t)ends[t] + c] < 0)
            mult[2 * (size_t)ends[t] + c] = (int)m->m++;
      }
  for (size_t I = 0; m->pinned && I < n; I++)
    if (m->pinned[I])
      for (int c = 0; c < 2; c++)
        mult[2 * I + c] = (int)m->m++;
  gsum = mfs_calloc(m->m + 1, sizeof *gsum);
  if (!gsum)
    goto done;
  /* scale of the constraint rows: E/h makes C_IJ ~ E like K */
  m->cscale = m->s.young / m->h;
  st = MFS_OK;
  /* prescribed parameters (ghosts): u_I = u(x_I) */
  for (size_t I = 0; m->pinned && I < n && st == MFS_OK; I++)
    if (m->pinned[I]) {
      double u[2];
      field(m, m->p->x + 2 * I, u, NULL);
      for (int c = 0; c < 2 && st == MFS_OK; c++) {
        int row = mult[2 * I + c];
        gsum[row] = m->cscale * u[c];
        st = coo_add(&ctr, row, 2 * (int)I + c, m->cscale);
        if (st == MFS_OK)
          st = coo_add(&cte, row, 2 * (int)I + c, m->cscale);
      }
    }
  for (size_t k = 0; k < m->nbp && st == MFS_OK; k++) {
    const bpoint *b = m->bp + k;
    const segment *sg = m->seg + b->seg;
    st = pev_point(&e, m, b->x, b->node, nl->idx + nl->ptr[k], nl->ptr[k + 1] - nl->ptr[k], where);
    if (st != MFS_OK)
      break;
    const double *psi = pev_test_values(&e), *phi = e.vtr;
    double u[2], sig[3];
    field(m, b->x, u, sig);
    double t[2] = {sig[0] * b->n[0] + sig[2] * b->n[1], sig[2] * b->n[0] + sig[1] * b->n[1]};
    int loaded = m->s.patch || sg->kind == SEG_TRACTION;
    for (int c = 0; c < 2; c++) {
      if (sg->fixed >> c & 1u) {
        /* the hat functions of the two ends; at a nodal point only the node's */
        double N[2] = {1.0 - b->t, b->t};
        int ends[2] = {sg->a, sg->b};
        for (int s = 0; s < 2 && st == MFS_OK; s++) {
          if (N[s] == 0.0)
            continue;
          int row = mult[2 * (size_t)ends[s] + c];
          double w = m->cscale * b->w * N[s];
          gsum[row] += w * u[c];
          for (int J = 0; J < e.nn && st == MFS_OK; J++) {
            st = coo_add(&ctr, row, 2 * e.idx[J] + c, w * phi[J]);
            if (st == MFS_OK)
              st = coo_add(&cte, row, 2 * e.idx[J] + c, w * psi[J]);
          }
        }
      } else if (loaded) {
        for (int J = 0; J < e.nn; J++)
          m->f[2 * (size_t)e.idx[J] + c] += b->w * psi[J] * t[c];
      }
    }
  }
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  m->Ctr = coo_csr(&ctr, m->m, 2 * n);
  m->Cte = coo_csr(&cte, m->m, 2 * n);
  m->g = gsum;
  gsum = NULL;
  if (!m->Ctr || !m->Cte)
    goto done;
  /* eliminations: each row one entry, test = trial */
  int elim = 1;
  for (size_t k = 0; k < m->m && elim; k++) {
    size_t a0 = m->Ctr->ptr[k], a1 = m->Ctr->ptr[k + 1];
    elim = a1 - a0 == 1 && m->Cte->ptr[k + 1] - m->Cte->ptr[k] == 1 &&
           m->Cte->idx[m->Cte->ptr[k]] == m->Ctr->idx[a0] &&
           m->Cte->val[m->Cte->ptr[k]] == m->Ctr->val[a0];
  }
  m->eliminated = elim;
  st = MFS_OK;
done:
  pev_free(&e);
  mfs_nlist_free(nl);
  coo_free(&ctr);
  coo_free(&cte);
  mfs_free(mult);
  mfs_free(gsum);
  return st;
}

mfs_status mfs_static_assemble(mfs_static *m, mfs_static_where *where)
{
  if (!m)
    return MFS_EINVAL;
  mfs_csr_free(m->K);
  mfs_csr_free(m->Ctr);
  mfs_csr_free(m->Cte);
  mfs_free(m->f);
  mfs_free(m->g);
  m->K = m->Ctr = m->Cte = NULL;
  m->f = m->g = NULL;
  m->assembled = m->solved = 0;
  int st = assemble_stiffness(m, where);
  if (st == MFS_OK)
    st = assemble_boundary(m, where);
  m->assembled = st == MFS_OK;
  return (mfs_status)st;
}

/* ------------------------------------------------------------------ */
/* solve                                                               */

static int solve_eliminated(mfs_static *m)
{
  size_t nd = 2 * m->p->n;
  int st = MFS_ENOMEM;
  int *map = mfs_malloc(nd * sizeof *map);
  double *up = mfs_calloc(nd, sizeof *up), *rhs = NULL, *x = NULL;
  mfs_csr *A = NULL;
  if (!map || !up)
    goto done;
  for (size_t i = 0; i < nd; i++)
    map[i] = 0;
  for (size_t k = 0; k < m->m; k++) {
    size_t e = m->Ctr->ptr[k];
    int d = m->Ctr->idx[e];
    map[d] = -1;
    up[d] = m->g[k] / m->Ctr->val[e];
  }
  size_t nf = 0;
  for (size_t i = 0; i < nd; i++)
    map[i] = map[i] < 0 ? -1 : (int)nf++;
  size_t nnz = 0;
  for (size_t i = 0; i < nd; i++)
    if (map[i] >= 0)
      for (size_t e = m->K->ptr[i]; e < m->K->ptr[i + 1]; e++)
        nnz += map[m->K->idx[e]] >= 0;
  A = mfs_csr_alloc(nf, nf, nnz);
  rhs = mfs_malloc((nf + 1) * sizeof *rhs);
  x = mfs_malloc((nf + 1) * sizeof *x);
  if (!A || !rhs || !x)
    goto done;
  size_t pos = 0;
  for (size_t i = 0; i < nd; i++) {
    if (map[i] < 0)
      continue;
    double r = m->f[i];
    for (size_t e = m->K->ptr[i]; e < m->K->ptr[i + 1]; e++) {
      int j = m->K->idx[e];
      if (map[j] >= 0) {
        A->idx[pos] = map[j];
        A->val[pos++] = m->K->val[e];
      } else {
        r -= m->K->val[e] * up[j];
      }
    }
    rhs[map[i]] = r;
    A->ptr[map[i] + 1] = pos;
  }
  int sym = m->s.method->test == NULL;
  m->solver = m->s.solver ? m->s.solver : (sym ? &mfs_spsolve_cholmod : &mfs_spsolve_umfpack);
  st = MFS_EINVAL;
  if (m->solver->symmetric_only && !sym)
    goto done;
  st = mfs_spsolve(m->solver, A, rhs, x, m->s.solve_rcond_min, &m->sinfo);
  if (st != MFS_OK)
    goto done;
  for (size_t i = 0; i < nd; i++)
    m->u[i] = map[i] >= 0 ? x[map[i]] : up[i];
done:
  mfs_free(map);
  mfs_free(up);
  mfs_free(rhs);
  mfs_free(x);
  mfs_csr_free(A);
  return st;
}

static int solve_kkt(mfs_static *m)
{
  int sym = m->s.method->test == NULL;
  m->solver = m->s.solver ? m->s.solver : (sym ? &mfs_spsolve_cholmod : &mfs_spsolve_umfpack);
  return mfs_spsolve_constrained(m->solver, m->K, m->Ctr, sym ? NULL : m->Cte, m->f, m->g, m->u,
                                 NULL, m->s.solve_rcond_min, &m->sinfo);
}

mfs_status mfs_static_solve(mfs_static *m)
{
  if (!m || !m->assembled)
    return MFS_EINVAL;
  m->solved = 0;
  mfs_free(m->u);
  m->u = mfs_calloc(2 * m->p->n, sizeof *m->u);
  if (!m->u)
    return MFS_ENOMEM;
  int st = m->eliminated ? solve_eliminated(m) : solve_kkt(m);
  m->solved = st == MFS_OK;
  return (mfs_status)st;
}

/* ------------------------------------------------------------------ */
/* results                                                             */

void mfs_static_get_info(const mfs_static *m, mfs_static_info *info)
{
  *info = (mfs_static_info){.nodes = m->p->n,
                            .unknowns = 2 * m->p->n,
                            .multipliers = m->eliminated ? 0 : m->m,
                            .quad_points = m->q->n,
                            .boundary_points = m->nbp,
                            .h = m->h,
                            .support = m->a,
                            .max_neighbours = m->max_nn,
                            .nnz_K = m->K ? m->K->ptr[m->K->nrow] : 0,
                            .symmetric = m->s.method->test == NULL,
                            .eliminated = m->eliminated,
                            .solver = m->solver ? m->solver->name : "",
                            .rcond = m->solver ? m->sinfo.rcond : NAN,
                            .backward = m->solved ? m->sinfo.backward : NAN,
                            .factor_nnz = m->solver ? m->sinfo.factor_nnz : NAN};
  for (size_t I = 0; I < m->p->n; I++)
    info->volume += m->p->vol[I];
  for (size_t Q = 0; Q < m->eq->n; Q++)
    info->cell_area += m->eq->w[Q];
}

/* K_ij by binary search in the sorted node columns of row i (K's rows are
 * sorted by construction). */
static double csr_sorted_get(const mfs_csr *A, size_t i, int j)
{
  size_t lo = A->ptr[i], hi = A->ptr[i + 1];
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (A->idx[mid] < j)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < A->ptr[i + 1] && A->idx[lo] == j ? A->val[lo] : 0.0;
}

double mfs_static_asymmetry(const mfs_static *m)
{
  if (!m || !m->K)
    return NAN;
  const mfs_csr *K = m->K;
  double as = 0.0, amax = 0.0;
  for (size_t i = 0; i < K->nrow; i++)
    for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++) {
      amax = fmax(amax, fabs(K->val[e]));
      as = fmax(as, fabs(K->val[e] - csr_sorted_get(K, (size_t)K->idx[e], (int)i)));
    }
  return amax > 0.0 ? as / amax : 0.0;
}

size_t mfs_static_nnodes(const mfs_static *m)
{
  return m->p->n;
}

int mfs_static_node_in_domain(const mfs_static *m, size_t I)
{
  return m->evol[I] > 0.0;
}

void mfs_static_node(const mfs_static *m, size_t I, double x[2])
{
  x[0] = m->p->x[2 * I];
  x[1] = m->p->x[2 * I + 1];
}

const mfs_csr *mfs_static_stiffness(const mfs_static *m)
{
  return m->K;
}

const double *mfs_static_load(const mfs_static *m)
{
  return m->f;
}

/* u^h and the strains at the points of q (all of them), in order; fn is
 * called per point with the values. */
typedef void (*point_fn)(void *ctx, size_t Q, const double *x, double w, const double *uh,
                         const double *eps);

static int field_pass(mfs_static *m, const mfs_quad *q, size_t bs, const double *u, point_fn fn,
                      void *ctx, mfs_static_where *where)
{
  pev e;
  cursor c;
  cursor_init(&c, q, bs);
  int st = pev_init(&e, m), r = 0;
  while (st == MFS_OK && (r = cursor_next(&c, m)) > 0) {
    for (size_t Q = c.b0 * bs; Q < c.b1 * bs && st == MFS_OK; Q++) {
      size_t L = Q - c.b0 * bs;
      st = pev_point_opt(&e, m, q->x + 2 * Q, q->node[Q], c.nl->idx + c.nl->ptr[L],
                         c.nl->ptr[L + 1] - c.nl->ptr[L], 1, where);
      if (st != MFS_OK)
        break;
      double uh[2] = {0.0, 0.0}, eps[3] = {0.0, 0.0, 0.0};
      for (int J = 0; J < e.nn; J++) {
        const double *uj = u + 2 * (size_t)e.idx[J], *B = e.Btr + 4 * J;
        uh[0] += e.vtr[J] * uj[0];
        uh[1] += e.vtr[J] * uj[1];
        eps[0] += B[0] * uj[0];
        eps[1] += B[1] * uj[1];
        eps[2] += B[2] * uj[0] + B[3] * uj[1];
      }
      fn(ctx, Q, q->x + 2 * Q, q->w[Q], uh, eps);
    }
  }
  if (st == MFS_OK && r < 0)
    st = -r;
  cursor_free(&c);
  pev_free(&e);
  return st;
}

typedef struct {
  const mfs_static *m;
  double num_u, den_u, num_e, den_e, max_du, max_u;
  double *uh; /* optional: store u^h per point (2 per point) */
} norm_acc;

static void acc_norms(void *ctx, size_t Q, const double *x, double w, const double *uh,
                      const double *eps)
{
  norm_acc *a = ctx;
  double u[2], sig[3], ex[3], de[3];
  field(a->m, x, u, sig);
  const double *Di = a->m->Dinv, *D = a->m->D;
  for (int i = 0; i < 3; i++)
    ex[i] = Di[3 * i] * sig[0] + Di[3 * i + 1] * sig[1] + Di[3 * i + 2] * sig[2];
  for (int i = 0; i < 3; i++)
    de[i] = eps[i] - ex[i];
  double du0 = uh[0] - u[0], du1 = uh[1] - u[1];
  a->num_u += w * (du0 * du0 + du1 * du1);
  a->den_u += w * (u[0] * u[0] + u[1] * u[1]);
  double en = 0.0, ee = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      en += de[i] * D[3 * i + j] * de[j];
      ee += ex[i] * D[3 * i + j] * ex[j];
    }
  a->num_e += w * en;
  a->den_e += w * ee;
  a->max_du = fmax(a->max_du, fmax(fabs(du0), fabs(du1)));
  a->max_u = fmax(a->max_u, fmax(fabs(u[0]), fabs(u[1])));
  if (a->uh) {
    a->uh[2 * Q] = uh[0];
    a->uh[2 * Q + 1] = uh[1];
  }
}

/* The nodes of the domain as a quadrature rule (their volumes in it), with
 * self; all: every node, in order. */
static mfs_quad *node_quad(const mfs_static *m, int all, mfs_status *st)
{
  size_t n = m->p->n;
  mfs_quad *q = mfs_quad_empty(2, n);
  *st = MFS_ENOMEM;
  if (!q)
    return NULL;
  for (size_t I = 0; I < n; I++)
    if (all || m->evol[I] > 0.0) {
      memcpy(q->x + 2 * q->n, m->p->x + 2 * I, 2 * sizeof(double));
      q->w[q->n] = m->evol[I];
      q->node[q->n++] = (int)I;
    }
  *st = MFS_OK;
  return q;
}

mfs_status mfs_static_error_norms(mfs_static *m, mfs_static_errors *out, mfs_static_where *where)
{
  if (!m || !m->solved)
    return MFS_EINVAL;
  mfs_status st;
  mfs_quad *nq = node_quad(m, 0, &st);
  if (!nq)
    return st;
  norm_acc a = {.m = m};
  st = (mfs_status)field_pass(m, nq, 1, m->u, acc_norms, &a, where);
  if (st == MFS_OK) {
    out->l2 = sqrt(a.num_u / a.den_u);
    out->energy_nodal = sqrt(a.num_e / a.den_e);
    out->max_nodal = a.max_u > 0.0 ? a.max_du / a.max_u : NAN;
    a = (norm_acc){.m = m};
    st = (mfs_status)field_pass(m, m->eq, m->gq_block, m->u, acc_norms, &a, where);
  }
  if (st == MFS_OK) {
    out->L2 = sqrt(a.num_u / a.den_u);
    out->energy = sqrt(a.num_e / a.den_e);
  }
  mfs_quad_free(nq);
  return st;
}

mfs_status mfs_static_nodal_solution(mfs_static *m, double *uh, double *uexact)
{
  if (!m || !m->solved)
    return MFS_EINVAL;
  mfs_status st;
  mfs_quad *nq = node_quad(m, 1, &st);
  if (!nq)
    return st;
  norm_acc a = {.m = m, .uh = uh};
  st = (mfs_status)field_pass(m, nq, 1, m->u, acc_norms, &a, NULL);
  for (size_t I = 0; uexact && I < m->p->n; I++)
    field(m, m->p->x + 2 * I, uexact + 2 * I, NULL);
  mfs_quad_free(nq);
  return st;
}

/* ------------------------------------------------------------------ */
/* consistency: reproduction, integrability, test-gradient reproduction */

typedef struct {
  const mfs_static *m;
  double max_de, max_e, max_du, max_u;
} repro_acc;

static void acc_repro(void *ctx, size_t Q, const double *x, double w, const double *uh,
                      const double *eps)
{
  (void)Q;
  (void)w;
  repro_acc *r = ctx;
  const double *c = r->m->patch_c, *G = r->m->patch_G;
  double u[2] = {c[0] + G[0] * x[0] + G[1] * x[1], c[1] + G[2] * x[0] + G[3] * x[1]};
  double e[3] = {G[0], G[3], G[1] + G[2]};
  for (int i = 0; i < 3; i++) {
    r->max_de = fmax(r->max_de, fabs(eps[i] - e[i]));
    r->max_e = fmax(r->max_e, fabs(e[i]));
  }
  r->max_du = fmax(r->max_du, hypot(uh[0] - u[0], uh[1] - u[1]));
  r->max_u = fmax(r->max_u, hypot(u[0], u[1]));
}

mfs_status mfs_static_check_consistency(mfs_static *m, mfs_static_consistency *out,
                                        mfs_static_where *where)
{
  if (!m)
    return MFS_EINVAL;
  size_t n = m->p->n;
  int st = MFS_ENOMEM;
  double *ul = mfs_malloc(2 * n * sizeof *ul), *R = mfs_calloc(6 * n, sizeof *R);
  mfs_nlist *bl = NULL;
  pev e;
  memset(&e, 0, sizeof e);
  cursor c;
  cursor_init(&c, m->q, m->q_block);
  if (!ul || !R)
    goto done;
  /* (1) reproduction: u_I = c + G x_I */
  const double *pc = m->patch_c, *G = m->patch_G;
  for (size_t I = 0; I < n; I++) {
    const double *x = m->p->x + 2 * I;
    ul[2 * I] = pc[0] + G[0] * x[0] + G[1] * x[1];
    ul[2 * I + 1] = pc[1] + G[2] * x[0] + G[3] * x[1];
  }
  repro_acc ra = {.m = m};
  st = field_pass(m, m->q, m->q_block, ul, acc_repro, &ra, where);
  if (st != MFS_OK)
    goto done;
  out->reproduction = ra.max_de / ra.max_e;
  out->values = ra.max_du / ra.max_u;
  /* (2) integration constraint residuals R[c][2I + d] and (3) the test gradients */
  st = pev_init(&e, m);
  if (st != MFS_OK)
    goto done;
  double lam_sum = 0.0, lam_dev = 0.0;
  size_t lam_n = 0;
  int r = 0;
  while (st == MFS_OK && (r = cursor_next(&c, m)) > 0) {
    for (size_t Q = c.b0 * c.bs; Q < c.b1 * c.bs && st == MFS_OK; Q++) {
      size_t L = Q - c.b0 * c.bs;
      const double *x = m->q->x + 2 * Q;
      st = pev_point(&e, m, x, m->q->node[Q], c.nl->idx + c.nl->ptr[L],
                     c.nl->ptr[L + 1] - c.nl->ptr[L], where);
      if (st != MFS_OK)
        break;
      const double *B = pev_test_B(&e), *d = mfs_eval_offsets(&e.tr);
      double w = m->q->w[Q], lam[8] = {0};
      for (int J = 0; J < e.nn; J++) {
        const double *b = B + 4 * J;
        size_t I = (size_t)e.idx[J];
        R[0 * 2 * n + 2 * I] += w * b[0];     /* unit s_xx: (a, 0) */
        R[1 * 2 * n + 2 * I + 1] += w * b[1]; /* unit s_yy: (0, b) */
        R[2 * 2 * n + 2 * I] += w * b[2];     /* unit s_xy: (c, d) */
        R[2 * 2 * n + 2 * I + 1] += w * b[3];
        double dx = d[2 * J], dy = d[2 * J + 1];
        lam[0] += b[0] * dx; /* -> 1 */
        lam[1] += b[1] * dy;
        lam[2] += b[2] * dy;
        lam[3] += b[3] * dx;
        lam[4] += b[0] * dy; /* -> 0 */
        lam[5] += b[1] * dx;
        lam[6] += b[2] * dx;
        lam[7] += b[3] * dy;
      }
      if (m->s.problem->distance(&m->s, x) >= m->a) {
        for (int k = 0; k < 8; k++)
          lam_dev = fmax(lam_dev, fabs(lam[k] - (k < 4 ? 1.0 : 0.0)));
        lam_sum += 0.25 * (lam[0] + lam[1] + lam[2] + lam[3]);
        lam_n++;
      }
    }
  }
  if (st == MFS_OK && r < 0)
    st = -r;
  if (st != MFS_OK)
    goto done;
  out->test_lambda = lam_n ? lam_sum / (double)lam_n : NAN;
  out->test_lambda_dev = lam_n ? lam_dev : NAN;
  out->lambda_points = lam_n;
  /* minus the boundary terms, over every segment */
  mfs_status bs;
  bl = boundary_lists(m, &bs);
  st = bs;
  if (!bl)
    goto done;
  for (size_t k = 0; k < m->nbp && st == MFS_OK; k++) {
    const bpoint *b = m->bp + k;
    st = pev_point(&e, m, b->x, b->node, bl->idx + bl->ptr[k], bl->ptr[k + 1] - bl->ptr[k],
                   where);
    if (st != MFS_OK)
      break;
    const double *psi = pev_test_values(&e);
    for (int J = 0; J < e.nn; J++) {
      size_t I = (size_t)e.idx[J];
      double wp = b->w * psi[J];
      R[0 * 2 * n + 2 * I] -= wp * b->n[0];
      R[1 * 2 * n + 2 * I + 1] -= wp * b->n[1];
      R[2 * 2 * n + 2 * I] -= wp * b->n[1];
      R[2 * 2 * n + 2 * I + 1] -= wp * b->n[0];
    }
  }
  if (st != MFS_OK)
    goto done;
  double ri = 0.0, ra_all = 0.0;
  size_t ni = 0;
  for (size_t I = 0; I < n; I++) {
    double v = 0.0;
    for (int s = 0; s < 3; s++)
      v = fmax(v, fmax(fabs(R[s * 2 * n + 2 * I]), fabs(R[s * 2 * n + 2 * I + 1])));
    ra_all = fmax(ra_all, v);
    if (m->s.problem->distance(&m->s, m->p->x + 2 * I) > 2.0 * m->a) {
      ri = fmax(ri, v);
      ni++;
    }
  }
  out->int_all = ra_all / m->h;
  out->int_interior = ni ? ri / m->h : NAN;
  out->interior_nodes = ni;
  st = MFS_OK;
done:
  cursor_free(&c);
  pev_free(&e);
  mfs_nlist_free(bl);
  mfs_free(ul);
  mfs_free(R);
  return (mfs_status)st;
}

double mfs_static_rate(size_t n, const double *h, const double *err)
{
  if (n < 2)
    return NAN;
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (!(err[i] > 0.0) || !(h[i] > 0.0))
      return NAN;
    double x = log(h[i]), y = log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  double den = n * sxx - sx * sx;
  return den > 0.0 ? (n * sxy - sx * sy) / den : NAN;
}
