#include "mfs_bound.h"
#include "mfs_alloc.h"

#include <complex.h>
#undef I
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_eval.h"
#include "mfs_status.h"
#include "mfs_threads.h"

/* Largest eigenvalue of a symmetric n x n matrix (n <= 3, row-major, destroyed),
 * by cyclic Jacobi rotations: accurate to rounding, no LAPACK call per point. */
static double sym_max_eig(int n, double *A)
{
  if (n == 1)
    return A[0];
  if (n == 2) {
    double h = 0.5 * (A[0] - A[3]);
    return 0.5 * (A[0] + A[3]) + hypot(h, A[1]);
  }
  for (int sweep = 0; sweep < 50; sweep++) {
    double off = 0.0, diag = 0.0;
    for (int i = 0; i < n; i++) {
      diag += A[i * n + i] * A[i * n + i];
      for (int j = i + 1; j < n; j++)
        off += A[i * n + j] * A[i * n + j];
    }
    if (off <= 1e-32 * diag || off == 0.0)
      break;
    for (int p = 0; p < n; p++)
      for (int q = p + 1; q < n; q++) {
        double apq = A[p * n + q];
        if (apq == 0.0)
          continue;
        double theta = (A[q * n + q] - A[p * n + p]) / (2.0 * apq);
        double t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
        double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < n; k++) { /* columns p, q */
          double akp = A[k * n + p], akq = A[k * n + q];
          A[k * n + p] = c * akp - s * akq;
          A[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; k++) { /* rows p, q */
          double apk = A[p * n + k], aqk = A[q * n + k];
          A[p * n + k] = c * apk - s * aqk;
          A[q * n + k] = s * apk + c * aqk;
        }
      }
  }
  double m = A[0];
  for (int i = 1; i < n; i++)
    m = A[i * n + i] > m ? A[i * n + i] : m;
  return m;
}

/* 1 / (phi_J S), the weight of neighbour J in lambda^Q; 0 for a fixed
 * neighbour or a phi_J <= 0 (then *negative = 1: no guarantee). */
static double lumped_weight(double phi, double S, int active, int *negative)
{
  if (!active)
    return 0.0;
  if (!(phi > 0.0)) {
    *negative = 1;
    return 0.0;
  }
  return 1.0 / (phi * S);
}

double mfs_bound_point(int dim, const mfs_material *mat, int nn, const double *tab, int ncomp,
                       const unsigned char *active, int *negative)
{
  *negative = 0;
  double S = 0.0; /* row sum of the consistent M^Q over all its columns (eq. 131) */
  for (int J = 0; J < nn; J++)
    S += tab[(size_t)J * ncomp];
  if (!(S > 0.0)) {
    *negative = 1;
    return 0.0;
  }
  if (mat->physics == MFS_PHYS_PLANE_STRAIN && dim == 2) {
    /* X = sum_I B_I B_I^T / (phi_I S), strain order (xx, yy, xy) */
    double X[9] = {0};
    for (int J = 0; J < nn; J++) {
      const double *f = tab + (size_t)J * ncomp;
      double s = lumped_weight(f[0], S, active ? active[J] : 1, negative);
      if (s == 0.0)
        continue;
      double gx = f[1], gy = f[2];
      X[0] += s * gx * gx;
      X[2] += s * gx * gy;
      X[4] += s * gy * gy;
      X[5] += s * gx * gy;
      X[8] += s * (gx * gx + gy * gy);
    }
    X[6] = X[2];
    X[7] = X[5];
    /* D = L L^T (Cholesky, D the plane strain elasticity matrix); the
     * eigenvalues of D X are those of L^T X L */
    double lam = mfs_material_lambda(mat), mu = mat->modulus, d0 = lam + 2.0 * mu;
    double L[9] = {0};
    L[0] = sqrt(d0);
    L[3] = lam / L[0];
    L[4] = sqrt(d0 - L[3] * L[3]);
    L[8] = sqrt(mu);
    double T[9], A[9];
    for (int i = 0; i < 3; i++) /* T = X L */
      for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (int k = 0; k < 3; k++)
          s += X[i * 3 + k] * L[k * 3 + j];
        T[i * 3 + j] = s;
      }
    for (int i = 0; i < 3; i++) /* A = L^T T */
      for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (int k = 0; k < 3; k++)
          s += L[k * 3 + i] * T[k * 3 + j];
        A[i * 3 + j] = s;
      }
    return sym_max_eig(3, A) / mat->density;
  }
  double G[9] = {0}; /* dim x dim; sized for sym_max_eig */
  for (int J = 0; J < nn; J++) {
    const double *f = tab + (size_t)J * ncomp;
    double s = lumped_weight(f[0], S, active ? active[J] : 1, negative);
    if (s == 0.0)
      continue;
    for (int k = 0; k < dim; k++)
      for (int l = 0; l < dim; l++)
        G[k * dim + l] += s * f[1 + k] * f[1 + l];
  }
  /* eq. 132 (1D); 2D: exact largest eigenvalue of the 2 x 2 matrix (eqs 142-144 when eq. 141 holds) */
  return mat->modulus / mat->density * sym_max_eig(dim, G);
}

static void result_init(mfs_bound_result *r)
{
  memset(r, 0, sizeof *r);
}

static void result_add(mfs_bound_result *r, double lam, int neg, size_t Q, const double *x,
                       int dim, size_t mult)
{
  if (lam > r->lambda || r->points == 0) {
    r->lambda = lam;
    r->argmax = Q;
    r->xmax[0] = x[0];
    r->xmax[1] = dim > 1 ? x[1] : 0.0;
  }
  r->points += mult;
  if (neg)
    r->negative_phi += mult;
}

/* The bound over the points of a plan, in parallel: each thread a
 * contiguous range of points in increasing order, its partial result merged
 * in thread order (a later range takes the maximum only when it is larger:
 * the first point of the maximum, as the serial loop).  With the plan's
 * table, or, without one, each point evaluated by the thread's evaluator
 * (mfs_plan_eval_point: the table's values). */
static mfs_status bound_plan(const mfs_plan *pl, const mfs_material *mat,
                             const unsigned char *fixed, mfs_bound_result *r, size_t *bad)
{
  result_init(r);
  if (!pl || !mat || !(mat->density > 0.0))
    return MFS_EINVAL;
  const int dim = mfs_plan_particles(pl)->dim, table = mfs_plan_order(pl) >= 1;
  const int ncomp = table ? mfs_plan_ncomp(pl) : mfs_shape_ncomp(dim, 1);
  if (ncomp < 1 + dim || (mat->physics == MFS_PHYS_PLANE_STRAIN && dim != 2))
    return MFS_EINVAL;
  const int nt = mfs_threads();
  const size_t nq = mfs_plan_npoints(pl), mx = mfs_plan_max_neighbours(pl);
  mfs_status st = MFS_ENOMEM;
  mfs_bound_result *part = mfs_calloc((size_t)nt, sizeof *part);
  unsigned char *act = mfs_malloc((size_t)nt * mx);
  mfs_eval *ev = table ? NULL : mfs_calloc((size_t)nt, sizeof *ev);
  double *row = table ? NULL : mfs_malloc((size_t)nt * mx * (size_t)ncomp * sizeof *row);
  int *kept = table ? NULL : mfs_malloc((size_t)nt * mx * sizeof *kept);
  mfs_status *tst = mfs_calloc((size_t)nt, sizeof *tst);
  size_t *tbad = mfs_calloc((size_t)nt, sizeof *tbad);
  if (!part || !act || !tst || !tbad || (!table && (!ev || !row || !kept)))
    goto done;
  for (int t = 0; t < nt && !table; t++)
    if ((st = mfs_plan_evaluator(pl, 1, ev + t)) != MFS_OK)
      goto done;
#pragma omp parallel num_threads(nt)
  {
    const int t = mfs_thread_id();
    mfs_bound_result *rt = part + t;
    unsigned char *at = act + (size_t)t * mx;
    tbad[t] = SIZE_MAX;
#pragma omp for schedule(static)
    for (size_t Q = 0; Q < nq; Q++) {
      if (tst[t] != MFS_OK)
        continue;
      mfs_point pt;
      mfs_plan_point(pl, Q, &pt);
      if (!table) {
        double *o = row + (size_t)t * mx * (size_t)ncomp;
        mfs_status s = mfs_plan_eval_point(pl, ev + t, Q, kept + (size_t)t * mx, o, NULL);
        if (s != MFS_OK) {
          tst[t] = s;
          tbad[t] = Q;
          continue;
        }
        pt.phi = o;
        pt.ncomp = ncomp;
      }
      if (fixed)
        for (size_t J = 0; J < pt.nn; J++)
          at[J] = !fixed[pt.idx[J]];
      int neg;
      double lam = mfs_bound_point(dim, mat, (int)pt.nn, pt.phi, pt.ncomp, fixed ? at : NULL, &neg);
      result_add(rt, lam, neg, Q, pt.x, dim, 1);
    }
  }
  st = MFS_OK;
  for (int t = 0; t < nt; t++) { /* in thread order: increasing ranges of points */
    if (tst[t] != MFS_OK && st == MFS_OK) {
      st = tst[t]; /* the smallest failing point: the first failing range's */
      if (bad)
        *bad = tbad[t];
    }
    const mfs_bound_result *q = part + t;
    if (q->points == 0)
      continue;
    if (q->lambda > r->lambda || r->points == 0) {
      r->lambda = q->lambda;
      r->argmax = q->argmax;
      r->xmax[0] = q->xmax[0];
      r->xmax[1] = q->xmax[1];
    }
    r->points += q->points;
    r->negative_phi += q->negative_phi;
  }
  r->evaluated = nq;
done:
  if (ev)
    for (int t = 0; t < nt; t++)
      mfs_eval_free(ev + t);
  mfs_free(ev);
  mfs_free(row);
  mfs_free(kept);
  mfs_free(part);
  mfs_free(act);
  mfs_free(tst);
  mfs_free(tbad);
  if (st != MFS_OK)
    result_init(r);
  return st;
}

mfs_status mfs_bound_plan(const mfs_plan *pl, const mfs_material *mat,
                          const unsigned char *fixed, mfs_bound_result *r)
{
  return bound_plan(pl, mat, fixed, r, NULL);
}

mfs_status mfs_bound_of_model(const mfs_model *m, mfs_bound_result *r)
{
  if (!m->pl) {
    result_init(r);
    return MFS_EINVAL;
  }
  return mfs_bound_plan(m->pl, &m->mat, m->spec.fixed != MFS_FIX_NONE ? m->fixed : NULL, r);
}

/* ------------------------------------------------------------------ */
/* streaming bound with memoization of equivalent lattice points        */

typedef struct {
  int cx, cy, node, used;
  int64_t ux, uy;
  double lambda;
  int neg;
} memo_entry;

typedef struct {
  memo_entry *e;
  size_t cap, count;
} memo;

static uint64_t memo_hash(int cx, int cy, int node, int64_t ux, int64_t uy)
{
  uint64_t h = 1469598103934665603ULL;
  uint64_t v[5] = {(uint64_t)(int64_t)cx, (uint64_t)(int64_t)cy, (uint64_t)node, (uint64_t)ux,
                   (uint64_t)uy};
  for (int i = 0; i < 5; i++) {
    h ^= v[i] + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h *= 1099511628211ULL;
  }
  return h ^ (h >> 29);
}

static memo_entry *memo_find(memo *m, int cx, int cy, int node, int64_t ux, int64_t uy)
{
  size_t i = memo_hash(cx, cy, node, ux, uy) & (m->cap - 1);
  for (;;) {
    memo_entry *e = m->e + i;
    if (!e->used)
      return e;
    if (e->cx == cx && e->cy == cy && e->node == node && e->ux == ux && e->uy == uy)
      return e;
    i = (i + 1) & (m->cap - 1);
  }
}

static int memo_grow(memo *m)
{
  memo old = *m;
  m->cap = old.cap ? 2 * old.cap : 1024;
  m->e = mfs_calloc(m->cap, sizeof *m->e);
  if (!m->e) {
    *m = old;
    return MFS_ENOMEM;
  }
  m->count = 0;
  for (size_t i = 0; i < old.cap; i++)
    if (old.e[i].used) {
      memo_entry *e = memo_find(m, old.e[i].cx, old.e[i].cy, old.e[i].node, old.e[i].ux,
                                old.e[i].uy);
      *e = old.e[i];
      m->count++;
    }
  mfs_free(old.e);
  return MFS_OK;
}

/* Cell index and class of coordinate t (in units of the spacing) along a
 * direction with n particles: classes near the ends are the cell index
 * itself (i <= B) or i - n (negative), the interior is INT_MIN: there the
 * window of particles i - B .. i + 1 + B lies strictly inside 1 .. n - 2,
 * so no end particle (fixed, or of another volume) can be a neighbour. */
static void cell_class(double t, int n, int periodic, int B, int *cell, int *cls, int64_t *u)
{
  int i = (int)floor(t);
  double f = t - i;
  if (periodic) {
    i %= n;
    if (i < 0)
      i += n;
    *cls = INT_MIN;
  } else {
    if (i > n - 2) { /* the last particle closes the last cell */
      f += i - (n - 2);
      i = n - 2;
    }
    if (i < 0) {
      f += i;
      i = 0;
    }
    if (i - B < 1)
      *cls = i;
    else if (i + 1 + B > n - 2)
      *cls = i - n;
    else
      *cls = INT_MIN;
  }
  *cell = i;
  *u = llround(f * 1073741824.0); /* 2^30 */
}

/* Window of lattice indices around cell i: the particles that can lie
 * within the support radius; wraps when periodic; each index once. */
static int window(int i, int n, int periodic, int B, int *out)
{
  int m = 0;
  if (periodic && 2 * B + 2 >= n) {
    for (int k = 0; k < n; k++)
      out[m++] = k;
    return m;
  }
  for (int k = i - B; k <= i + 1 + B; k++) {
    int kk = k;
    if (periodic) {
      kk %= n;
      if (kk < 0)
        kk += n;
    } else if (kk < 0 || kk >= n) {
      continue;
    }
    out[m++] = kk;
  }
  return m;
}

/* The bound through a plan, points evaluated one by one (mfs_bound_plan
 * without a table): particle sets and perturbed lattices, whose points have
 * no translates. */
static mfs_status bound_by_plan(const mfs_model_spec *spec, mfs_bound_result *r, size_t *bad)
{
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  unsigned char *fixed = NULL;
  const mfs_disc *disc = &spec->disc;
  mfs_status st = mfs_disc_geometry(disc, &p, &q);
  if (st != MFS_OK)
    return st;
  pl = mfs_plan_alloc(disc, p, q, &st);
  if (!pl)
    goto done;
  if (spec->fixed != MFS_FIX_NONE) {
    st = MFS_ENOMEM;
    fixed = mfs_malloc(p->n);
    if (!fixed)
      goto done;
    for (size_t I = 0; I < p->n; I++)
      fixed[I] = spec->fixed == MFS_FIX_MASK ? spec->fix_mask[I] != 0 : p->flags[I] != 0;
  }
  st = bound_plan(pl, &disc->material, fixed, r, bad);
done:
  mfs_free(fixed);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return st;
}

mfs_status mfs_bound_model(const mfs_model_spec *spec, mfs_bound_result *r, size_t *bad)
{
  result_init(r);
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  memo mm = {NULL, 0, 0};
  int *wx = NULL, *wy = NULL, *cand = NULL, *nb = NULL;
  double *tab = NULL;
  unsigned char *act = NULL;
  mfs_eval ev = {0};
  mfs_status st = mfs_model_spec_check(spec, NULL);
  if (st != MFS_OK)
    return st;
  const mfs_disc *disc = &spec->disc;
  if (mfs_disc_points(disc) || disc->source.perturb > 0.0 || spec->fixed == MFS_FIX_MASK)
    return bound_by_plan(spec, r, bad);
  st = mfs_disc_geometry(disc, &p, &q);
  if (st != MFS_OK)
    goto done;
  int dim = disc->dim, periodic = disc->source.periodic;
  double dx = p->dx, dy = dim > 1 ? p->dy : 1.0;
  double a = disc->support > 0.0 ? disc->support : disc->dilation * dx;
  int nx = p->nx, ny = dim > 1 ? p->ny : 1;
  int Bx = (int)ceil(a / dx) + 1, By = dim > 1 ? (int)ceil(a / dy) + 1 : 0;
  size_t wlx = (size_t)(2 * Bx + 2) < (size_t)nx ? (size_t)(2 * Bx + 2) : (size_t)nx;
  size_t wly = dim > 1 ? ((size_t)(2 * By + 2) < (size_t)ny ? (size_t)(2 * By + 2) : (size_t)ny) : 1;
  size_t maxnn = wlx * wly;
  int ncomp = mfs_shape_ncomp(dim, 1);
  st = mfs_eval_init(&ev, disc, a, 1, &p->box, maxnn);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  wx = mfs_malloc((size_t)(2 * Bx + 2 + nx) * sizeof *wx);
  wy = mfs_malloc((size_t)(2 * By + 2 + ny) * sizeof *wy);
  cand = mfs_malloc(maxnn * sizeof *cand);
  nb = mfs_malloc(maxnn * sizeof *nb);
  tab = mfs_malloc(maxnn * ncomp * sizeof *tab);
  act = mfs_malloc(maxnn);
  if (!wx || !wy || !cand || !nb || !tab || !act || memo_grow(&mm) != MFS_OK)
    goto done;
  const mfs_material mat = disc->material;
  int fixed = spec->fixed != MFS_FIX_NONE;
  for (size_t Q = 0; Q < q->n; Q++) {
    const double *xq = q->x + Q * dim;
    int ix, iy = 0, cx, cy = 0;
    int64_t ux, uy = 0;
    cell_class((xq[0] - p->box.lo[0]) / dx, nx, periodic, Bx, &ix, &cx, &ux);
    if (dim > 1)
      cell_class((xq[1] - p->box.lo[1]) / dy, ny, periodic, By, &iy, &cy, &uy);
    int node = q->node[Q] >= 0;
    memo_entry *e = memo_find(&mm, cx, cy, node, ux, uy);
    if (!e->used) {
      int mx = window(ix, nx, periodic, Bx, wx);
      int my = dim > 1 ? window(iy, ny, periodic, By, wy) : 1;
      if (dim == 1)
        wy[0] = 0;
      size_t nc = 0;
      for (int b = 0; b < my; b++)
        for (int c = 0; c < mx; c++)
          cand[nc++] = wy[b] * nx + wx[c];
      int nn;
      double rc;
      st = mfs_eval_point(&ev, xq, p->x, p->vol, cand, nc, q->node[Q], nb, tab, &nn, &rc);
      if (st != MFS_OK) {
        if (bad)
          *bad = Q;
        goto done;
      }
      for (int J = 0; J < nn; J++)
        act[J] = !(fixed && p->flags[nb[J]]);
      e->used = 1;
      e->cx = cx;
      e->cy = cy;
      e->node = node;
      e->ux = ux;
      e->uy = uy;
      e->lambda = mfs_bound_point(dim, &mat, nn, tab, ncomp, fixed ? act : NULL, &e->neg);
      r->evaluated++;
      result_add(r, e->lambda, e->neg, Q, xq, dim, 1);
      if (++mm.count * 2 > mm.cap && memo_grow(&mm) != MFS_OK) {
        st = MFS_ENOMEM;
        goto done;
      }
    } else {
      result_add(r, e->lambda, e->neg, Q, xq, dim, 1);
    }
  }
  st = MFS_OK;
done:
  mfs_eval_free(&ev);
  mfs_free(mm.e);
  mfs_free(wx);
  mfs_free(wy);
  mfs_free(cand);
  mfs_free(nb);
  mfs_free(tab);
  mfs_free(act);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return st;
}

/* ------------------------------------------------------------------ */
/* closed forms                                                        */

/* f(z) = w'(z)^2 / w(z), 0 where w <= 0. */
static double fw(const mfs_kernel_type *k, double z)
{
  double w, dw, d2w;
  k->eval(z, &w, &dw, &d2w);
  return w > 0.0 ? dw * dw / w : 0.0;
}

/* int_0^1 f(z) z^p dz by composite 8-point Gauss-Legendre on 4096 panels
 * (the kernels are piecewise polynomials: panels end on their breaks). */
static double f_moment(const mfs_kernel_type *k, int p)
{
  static const double x8[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
  static const double w8[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};
  int np = 4096;
  double h = 1.0 / np, s = 0.0;
  for (int i = 0; i < np; i++) {
    double c = (i + 0.5) * h;
    for (int g = 0; g < 4; g++)
      for (int sg = -1; sg <= 1; sg += 2) {
        double z = c + sg * 0.5 * h * x8[g];
        s += 0.5 * h * w8[g] * fw(k, z) * (p ? z : 1.0);
      }
  }
  return s;
}

double mfs_bound_alpha(const mfs_kernel_type *k, int dim)
{
  if (dim == 2)
    return M_PI * k->norm[1] * f_moment(k, 1);
  /* max of f on (0, 1): a fine scan, then golden-section refinement */
  int n = 20000;
  double best = 0.0, zb = 0.5;
  for (int i = 1; i < n; i++) {
    double z = (double)i / n, f = fw(k, z);
    if (f > best) {
      best = f;
      zb = z;
    }
  }
  double lo = zb - 1.0 / n, hi = zb + 1.0 / n, g = 0.5 * (sqrt(5.0) - 1.0);
  lo = lo < 0.0 ? 0.0 : lo;
  hi = hi > 1.0 ? 1.0 : hi;
  for (int it = 0; it < 100; it++) {
    double z1 = hi - g * (hi - lo), z2 = lo + g * (hi - lo);
    if (fw(k, z1) > fw(k, z2))
      hi = z2;
    else
      lo = z1;
  }
  double fm = fw(k, 0.5 * (lo + hi));
  best = fm > best ? fm : best;
  return k->norm[0] * best;
}

double mfs_bound_alpha_continuum(const mfs_kernel_type *k, int dim)
{
  if (dim == 2)
    return mfs_bound_alpha(k, 2);
  return 2.0 * k->norm[0] * f_moment(k, 0);
}

/* Largest real omega^2 over the branches at (kappa, theta); -inf on failure. */
static double omega2_max(const mfs_disp_plan *pl, double kappa, double theta, mfs_status *st)
{
  double complex w[4];
  *st = mfs_disp_omega2(pl, 0.0, kappa, theta, w);
  if (*st != MFS_OK)
    return -INFINITY;
  double m = -INFINITY;
  for (int b = 0; b < mfs_disp_branches(pl); b++)
    m = creal(w[b]) > m ? creal(w[b]) : m;
  return m;
}

mfs_status mfs_bound_fourier(const mfs_model_spec *s, int npts, int nangles, double *lambda,
                             double *kappa, double *theta)
{
  mfs_status st = mfs_model_spec_check(s, NULL);
  if (st != MFS_OK && st != MFS_ETOOSMALL) /* a small periodic model has a lattice all the same */
    return st;
  const mfs_disc *d = &s->disc;
  double dx = mfs_disc_dx(d);
  double dy = d->dim == 1 ? dx : mfs_disc_dy(d);
  /* the infinite lattice of the model's spacings (a particle set: the line or
   * square lattice of its mean spacing; a perturbed lattice: the unperturbed
   * one), normalized to dx = 1 with the dilation a / dx; Lagrangian kernel */
  mfs_disp_spec ds = {.disc = *d, .stretch = 1.0};
  mfs_lattice_kind lat = d->source.lattice;
  if (mfs_disc_points(d))
    lat = d->dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE;
  ds.disc.source = (mfs_source){
    .lattice = lat, .spacing = 1.0, .gamma = d->dim == 1 ? 1.0 : dy / dx};
  if (d->support > 0.0)
    ds.disc.dilation = d->support / dx;
  ds.disc.support = 0.0;
  ds.disc.frame = MFS_FRAME_LAGRANGIAN;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&ds, &st);
  if (!pl)
    return st;
  if (npts < 2)
    npts = 2;
  if (d->dim == 1 || nangles < 1)
    nangles = 1;
  double best = -INFINITY, kb = 0.0, tb = 0.0;
  for (int t = 0; t < nangles; t++) {
    double th = nangles > 1 ? 0.5 * M_PI * t / (nangles - 1) : 0.0;
    double km = mfs_disp_kappa_max(pl, th);
    double bl = -INFINITY, kl = 0.0;
    for (int i = 0; i < npts; i++) {
      double k = km * i / (npts - 1), o = omega2_max(pl, k, th, &st);
      if (st != MFS_OK)
        goto done;
      if (o > bl) {
        bl = o;
        kl = k;
      }
    }
    /* refine: golden section on the bracket around the best sample */
    double h = km / (npts - 1), lo = kl - h > 0.0 ? kl - h : 0.0, hi = kl + h < km ? kl + h : km;
    double g = 0.5 * (sqrt(5.0) - 1.0);
    for (int it = 0; it < 60; it++) {
      double k1 = hi - g * (hi - lo), k2 = lo + g * (hi - lo);
      double o1 = omega2_max(pl, k1, th, &st), o2 = omega2_max(pl, k2, th, &st);
      if (st != MFS_OK)
        goto done;
      if (o1 > o2)
        hi = k2;
      else
        lo = k1;
    }
    double km2 = 0.5 * (lo + hi), o = omega2_max(pl, km2, th, &st);
    if (st != MFS_OK)
      goto done;
    if (o > bl) {
      bl = o;
      kl = km2;
    }
    if (bl > best) {
      best = bl;
      kb = kl;
      tb = th;
    }
  }
  st = isfinite(best) ? MFS_OK : MFS_EDOMAIN;
  *lambda = best * d->material.modulus / d->material.density / (dx * dx);
  if (kappa)
    *kappa = kb;
  if (theta)
    *theta = tb;
done:
  mfs_disp_plan_free(pl);
  return st;
}

double mfs_step_lambda(double lambda_power, double lambda_bound, size_t negative_phi)
{
  double lam = 1.05 * lambda_power;
  if (negative_phi == 0 && lambda_bound > 0.0 && lambda_bound < lam)
    lam = lambda_bound;
  return lam > 0.0 && isfinite(lam) ? lam : NAN;
}

double mfs_dt_crit(double lambda_max)
{
  return 2.0 / sqrt(lambda_max);
}

/* ------------------------------------------------------------------ */
/* Gershgorin                                                          */

static void gersh_init(mfs_gershgorin_result *r)
{
  *r = (mfs_gershgorin_result){.lambda = 0.0, .min_mass = INFINITY};
}

/* Row i (full dof f) with absolute row sum s and mass mi. */
static void gersh_row(mfs_gershgorin_result *r, double s, double mi, size_t f)
{
  if (mi < r->min_mass) {
    r->min_mass = mi;
    r->argmin_mass = f;
  }
  if (!(mi > 0.0)) {
    if (r->nonpositive++ == 0)
      r->first_nonpositive = f;
    return;
  }
  double lam = s / mi;
  if (lam > r->lambda) {
    r->lambda = lam;
    r->argmax = f;
  }
}

static void gersh_finish(mfs_gershgorin_result *r)
{
  if (r->nonpositive > 0)
    r->lambda = NAN;
}

/* Per-thread partial results merged as the serial loop over the rows would
 * have found them: the largest ratio at its smallest dof, the smallest mass
 * at its smallest dof, the first nonpositive mass. */
static void gersh_merge(mfs_gershgorin_result *r, const mfs_gershgorin_result *q)
{
  if (q->lambda > r->lambda || (q->lambda == r->lambda && q->lambda > 0.0 && q->argmax < r->argmax)) {
    r->lambda = q->lambda;
    r->argmax = q->argmax;
  }
  if (q->min_mass < r->min_mass ||
      (q->min_mass == r->min_mass && q->argmin_mass < r->argmin_mass)) {
    r->min_mass = q->min_mass;
    r->argmin_mass = q->argmin_mass;
  }
  if (q->nonpositive > 0 && (r->nonpositive == 0 || q->first_nonpositive < r->first_nonpositive))
    r->first_nonpositive = q->first_nonpositive;
  r->nonpositive += q->nonpositive;
}

mfs_status mfs_gershgorin_csr(const mfs_csr *K, const double *m, const size_t *dof,
                              mfs_gershgorin_result *r)
{
  gersh_init(r);
  if (!K || !m || K->nrow != K->ncol)
    return MFS_EINVAL;
  /* no allocation: the partial results of at most MFS_MAX_THREADS threads */
  const int nt = mfs_threads() < MFS_MAX_THREADS ? mfs_threads() : MFS_MAX_THREADS;
  mfs_gershgorin_result part[MFS_MAX_THREADS];
#pragma omp parallel num_threads(nt)
  {
    mfs_gershgorin_result *q = part + mfs_thread_id();
    gersh_init(q);
#pragma omp for schedule(static)
    for (size_t i = 0; i < K->nrow; i++) {
      double s = 0.0;
      for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++)
        s += fabs(K->val[e]);
      gersh_row(q, s, m[i], dof ? dof[i] : i);
    }
  }
  for (int t = 0; t < nt; t++)
    gersh_merge(r, part + t);
  gersh_finish(r);
  return MFS_OK;
}

typedef struct {
  const mfs_gershgorin_op *op;
  const unsigned char *fixed;
  const double *vol;
  int pu;
  mfs_gershgorin_result *part; /* per thread */
} gop_ctx;

/* Row I of the operator: the absolute sums of its ndof dof rows. */
static mfs_status gersh_row_fn(void *vc, const mfs_row *row, size_t I, int thread)
{
  const gop_ctx *c = vc;
  const mfs_gershgorin_op *op = c->op;
  const int nd = op->ndof, nd2 = nd * nd;
  double blk[4];
  for (int a = 0; a < nd; a++) {
    double s = 0.0;
    for (size_t k = 0; k < row->len; k++) {
      if (c->fixed && c->fixed[row->col[k]])
        continue;
      const double *b = row->K + k * (size_t)nd2;
      if (op->block) {
        op->block(op->ctx, row, k, blk);
        b = blk;
      }
      for (int j = 0; j < nd; j++)
        s += fabs(b[a * nd + j]);
    }
    size_t dof = I * (size_t)nd + (size_t)a;
    double mi = op->mass ? op->mass[dof] : c->pu ? row->lump : op->density * c->vol[I];
    gersh_row(c->part + thread, s, mi, dof);
  }
  return MFS_OK;
}

mfs_status mfs_gershgorin_op_plan(const mfs_plan *pl, const mfs_gershgorin_op *op,
                                  const unsigned char *fixed, mfs_gershgorin_result *r,
                                  size_t *bad)
{
  gersh_init(r);
  if (!pl || !op || !op->forms || op->ndof < 1 || op->ndof > 2 ||
      mfs_physics_ndof(op->forms->physics) != op->ndof || (!op->block && !op->forms->stiffness))
    return MFS_EINVAL;
  const int nt = mfs_threads();
  const mfs_particles *p = mfs_plan_particles(pl);
  mfs_forms f = *op->forms;
  int pu = mfs_plan_disc(pl)->shape->partition_of_unity;
  if (!op->mass && pu)
    f.lumped_density = op->density;
  mfs_gershgorin_result *part = mfs_malloc((size_t)nt * sizeof *part);
  if (!part)
    return MFS_ENOMEM;
  for (int t = 0; t < nt; t++)
    gersh_init(part + t);
  gop_ctx c = {.op = op, .fixed = fixed, .vol = p->vol, .pu = pu, .part = part};
  mfs_status st = mfs_row_sweep(pl, &f, fixed, gersh_row_fn, &c, bad);
  for (int t = 0; t < nt && st == MFS_OK; t++)
    gersh_merge(r, part + t);
  mfs_free(part);
  if (st != MFS_OK) {
    gersh_init(r);
    return st;
  }
  gersh_finish(r);
  return MFS_OK;
}

mfs_status mfs_gershgorin_plan(const mfs_plan *pl, const mfs_material *mat,
                               const unsigned char *fixed, mfs_gershgorin_result *r)
{
  gersh_init(r);
  if (!pl || !mat)
    return MFS_EINVAL;
  mfs_forms f = mfs_forms_stiffness(mat);
  mfs_gershgorin_op op = {.forms = &f, .ndof = mfs_physics_ndof(mat->physics),
                          .density = mat->density};
  return mfs_gershgorin_op_plan(pl, &op, fixed, r, NULL);
}
