#include "mfs_neighbor.h"
#include "mfs_alloc.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_select.h"
#include "mfs_status.h"

void mfs_grid_free(mfs_grid *g)
{
  if (!g)
    return;
  mfs_free(g->start);
  mfs_free(g->item);
  mfs_free(g);
}

/* Cell coordinate of x along direction k, wrapped or clamped. */
static int cell_coord(const mfs_grid *g, int k, double x)
{
  double t = floor((x - g->box.lo[k]) / g->h[k]);
  if (g->box.periodic) { /* wrap in double: no int overflow for far points */
    t = fmod(t, (double)g->nc[k]);
    if (t < 0.0)
      t += g->nc[k];
  }
  if (!(t >= 0.0)) /* also NaN */
    return 0;
  if (t >= (double)g->nc[k])
    return g->nc[k] - 1;
  return (int)t;
}

static size_t cell_of(const mfs_grid *g, const double *x)
{
  size_t c = 0;
  for (int k = g->dim - 1; k >= 0; k--)
    c = c * (size_t)g->nc[k] + (size_t)cell_coord(g, k, x[k]);
  return c;
}

mfs_grid *mfs_grid_alloc(int dim, size_t n, const double *x, const mfs_box *box, double radius,
                         mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_grid *g = NULL;
  if (!(radius > 0.0) || !isfinite(radius) || dim < 1 || dim > 3 || n > (size_t)INT_MAX)
    goto fail;
  for (int k = 0; k < dim; k++)
    if (!isfinite(box->lo[k]) || !isfinite(box->hi[k]) || !(box->hi[k] >= box->lo[k]))
      goto fail;
  for (size_t i = 0; i < n * (size_t)dim; i++)
    if (!isfinite(x[i]))
      goto fail;
  st = MFS_ENOMEM;
  g = mfs_calloc(1, sizeof *g);
  if (!g)
    goto fail;
  g->dim = dim;
  g->n = n;
  g->x = x;
  g->box = *box;
  g->radius = radius;
  size_t ncells = 1;
  double want[3] = {1.0, 1.0, 1.0}; /* cells of side just over radius/2 */
  for (int k = 0; k < 3; k++) {
    g->nc[k] = 1;
    g->h[k] = 1.0;
  }
  double total = 1.0, cap = 4.0 * (double)n + 4.0, ncd[3] = {1.0, 1.0, 1.0};
  for (int pass = 0; pass < 2; pass++) {
    total = 1.0;
    for (int k = 0; k < dim; k++) {
      double L = g->box.hi[k] - g->box.lo[k];
      if (box->periodic && !(L > 2.0 * radius)) {
        st = MFS_ETOOSMALL;
        goto fail;
      }
      /* cells of side h >= hmin, a little over radius/2: a query scans 5 x 5
       * cells holding about (5/2)^2 r^2 of points (3 x 3 cells of side radius
       * hold 9 r^2), and the margin keeps a point within radius at most 2
       * cells away after rounding of the cell coordinates.  The number of
       * cells stays bounded by the number of points. */
      double hmin = 0.5 * radius * (1.0 + 1e-6);
      want[k] = L > 0.0 ? floor(L / hmin) : 1.0;
      if (!(want[k] >= 1.0))
        want[k] = 1.0;
      total *= want[k];
    }
    /* More cells than the cap below (more than 4 n + 4) means points far
     * apart for their number: a few far ones (a coordinate with a wrong
     * exponent) stretch the box, and cells over the whole box would put the
     * rest in one cell, each query scanning all of them (9 10^4 particles
     * and one 10^108 away: 14 s of neighbour search).  Then the cells cover
     * the bulk (the quartiles of each coordinate, widened by their distance
     * on each side) and the points outside go to the edge cells (the cell
     * coordinates clamp, and the queries' ranges with them). */
    if (pass > 0 || !(total > cap) || box->periodic || n < 4)
      break;
    double q1[3], q3[3];
    mfs_quartiles(dim, n, x, q1, q3);
    for (int k = 0; k < dim; k++) {
      double w = q3[k] - q1[k];
      if (w > 0.0) {
        g->box.lo[k] = fmax(box->lo[k], q1[k] - w);
        g->box.hi[k] = fmin(box->hi[k], q3[k] + w);
      }
    }
  }
  /* at most 4 n + 4 cells in all (a sparse set in a large box): the
   * directions are thinned in proportion, then the finest ones again until
   * the product is within the cap (a direction at one cell takes no share
   * of the thinning: one far point on an axis made 2^31 cells) */
  double shrink = total > cap ? pow(cap / total, 1.0 / dim) : 1.0;
  total = 1.0;
  for (int k = 0; k < dim; k++) {
    ncd[k] = fmax(1.0, fmin(floor(want[k] * shrink), (double)INT_MAX));
    total *= ncd[k];
  }
  while (total > cap) {
    int m = 0;
    for (int k = 1; k < dim; k++)
      m = ncd[k] > ncd[m] ? k : m;
    double t = fmax(1.0, floor(ncd[m] * cap / total));
    total = total / ncd[m] * t;
    ncd[m] = t;
  }
  for (int k = 0; k < dim; k++) {
    double L = g->box.hi[k] - g->box.lo[k], hmin = 0.5 * radius * (1.0 + 1e-6);
    int nc = (int)ncd[k];
    g->nc[k] = nc;
    g->h[k] = L > 0.0 ? L / nc : 1.0;
    if (!box->periodic && g->h[k] < hmin)
      g->h[k] = hmin; /* clamping keeps far points in edge cells */
    ncells *= (size_t)nc;
  }
  g->start = mfs_calloc(ncells + 1, sizeof *g->start);
  g->item = mfs_malloc((n ? n : 1) * sizeof *g->item);
  size_t *cellid = mfs_malloc((n ? n : 1) * sizeof *cellid);
  if (!g->start || !g->item || !cellid) {
    mfs_free(cellid);
    goto fail;
  }
  for (size_t i = 0; i < n; i++) {
    cellid[i] = cell_of(g, x + i * dim);
    g->start[cellid[i] + 1]++;
  }
  for (size_t c = 0; c < ncells; c++)
    g->start[c + 1] += g->start[c];
  for (size_t i = 0; i < n; i++) /* counting sort keeps indices ascending per cell */
    g->item[g->start[cellid[i]]++] = (int)i;
  for (size_t c = ncells; c > 0; c--)
    g->start[c] = g->start[c - 1];
  g->start[0] = 0;
  mfs_free(cellid);
  if (status)
    *status = MFS_OK;
  return g;
fail:
  mfs_grid_free(g);
  if (status)
    *status = st;
  return NULL;
}

void mfs_nlist_free(mfs_nlist *nl)
{
  if (!nl)
    return;
  mfs_free(nl->ptr);
  mfs_free(nl->idx);
  mfs_free(nl);
}

static int cmp_int(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Ascending; insertion for the short rows of a discretization (tens of
 * entries, few out of order: it beats qsort there), qsort beyond: a row of
 * 20 000 neighbours (a cluster of particles) took 4 10^8 moves by
 * insertion. */
static void sort_ints(int *a, size_t n)
{
  if (n > 64) {
    qsort(a, n, sizeof *a, cmp_int);
    return;
  }
  for (size_t i = 1; i < n; i++) {
    int v = a[i];
    size_t j = i;
    for (; j > 0 && a[j - 1] > v; j--)
      a[j] = a[j - 1];
    a[j] = v;
  }
}

/* Distinct cell coordinates along k that may hold points within r of x:
 * span = ceil(radius / h[k]) cells either side (2: cells of side > radius/2)
 * of x's own cell, wrapped or clamped as the points' are (cell_coord: a
 * query outside the box, as far as it may be, scans the edge cells where
 * the points near it are; the cast of its unclamped coordinate to int
 * overflowed). */
static int cell_range(const mfs_grid *g, int k, int span, double x, int *out)
{
  int c = cell_coord(g, k, x), nc = g->nc[k];
  int m = 0;
  if (!g->box.periodic) {
    int c0 = c - span < 0 ? 0 : c - span, c1 = c + span >= nc ? nc - 1 : c + span;
    for (int ci = c0; ci <= c1; ci++)
      out[m++] = ci;
    return m;
  }
  if (2 * span + 1 >= nc) {
    for (int i = 0; i < nc; i++)
      out[m++] = i;
    return m;
  }
  for (int d = -span; d <= span; d++) {
    int ci = (c + d) % nc;
    out[m++] = ci < 0 ? ci + nc : ci;
  }
  return m;
}

/* Squared distance from y to xi, with the arithmetic of mfs_box_delta
 * (minimum image when periodic), so that the lists do not depend on which
 * of the two computed it. */
static inline double dist2(int dim, int periodic, const double *L, const double *y,
                           const double *xi)
{
  double d2 = 0.0;
  for (int k = 0; k < dim; k++) {
    double t = xi[k] - y[k];
    if (periodic)
      t -= L[k] * nearbyint(t / L[k]);
    d2 += t * t;
  }
  return d2;
}

/* Append every candidate item[s0 .. s1) at out[nnz ..], keeping (advancing
 * past) those within r2 of y: no branch to mispredict.  out has room for
 * s1 - s0 more.  Returns the new count.  dim and periodic are arguments so
 * that the calls below, with constants, are specialized. */
static inline size_t scan(int dim, int periodic, const double *L, const double *x,
                          const int *item, const double *y, double r2, size_t s0, size_t s1,
                          int *out, size_t nnz)
{
  for (size_t s = s0; s < s1; s++) {
    int i = item[s];
    out[nnz] = i;
    nnz += dist2(dim, periodic, L, y, x + (size_t)i * dim) < r2;
  }
  return nnz;
}

/* Room for `more` further entries in nl->idx. */
static int reserve(mfs_nlist *nl, size_t nnz, size_t more, size_t *cap)
{
  if (nnz + more <= *cap)
    return MFS_OK;
  size_t ncap = 2 * *cap > nnz + more ? 2 * *cap : nnz + more;
  int *t = mfs_realloc(nl->idx, ncap * sizeof *t);
  if (!t)
    return MFS_ENOMEM;
  nl->idx = t;
  *cap = ncap;
  return MFS_OK;
}

/* The cells along direction 0 are scanned in runs of consecutive cells,
 * whose items are contiguous in g->item. */
mfs_nlist *mfs_nlist_build(const mfs_grid *g, size_t nq, const double *xq, double r, mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_nlist *nl = NULL;
  if (!(r > 0.0) || r > g->radius)
    goto fail;
  st = MFS_ENOMEM;
  nl = mfs_calloc(1, sizeof *nl);
  if (!nl)
    goto fail;
  nl->nq = nq;
  nl->ptr = mfs_malloc((nq + 1) * sizeof *nl->ptr);
  size_t cap = 16 * nq + 16, nnz = 0;
  nl->idx = mfs_malloc(cap * sizeof *nl->idx);
  if (!nl->ptr || !nl->idx)
    goto fail;
  int dim = g->dim, per = g->box.periodic;
  double r2 = r * r, L[3];
  for (int k = 0; k < 3; k++)
    L[k] = g->box.hi[k] - g->box.lo[k];
  int rng[3][64], run0[64], run1[64], span[3];
  int nr[3] = {1, 1, 1};
  for (int k = 0; k < dim; k++)
    span[k] = (int)ceil(g->radius / g->h[k]);
  rng[1][0] = rng[2][0] = 0;
  nl->ptr[0] = 0;
  for (size_t q = 0; q < nq; q++) {
    const double *y = xq + q * dim;
    for (int k = 0; k < dim; k++)
      nr[k] = cell_range(g, k, span[k], y[k], rng[k]);
    int nrun = 0;
    for (int c0 = 0; c0 < nr[0]; c0++) {
      if (nrun > 0 && rng[0][c0] == run1[nrun - 1] + 1) {
        run1[nrun - 1]++;
      } else {
        run0[nrun] = run1[nrun] = rng[0][c0];
        nrun++;
      }
    }
    size_t row0 = nnz;
    for (int c2 = 0; c2 < nr[2]; c2++)
      for (int c1 = 0; c1 < nr[1]; c1++) {
        size_t base = ((size_t)rng[2][c2] * g->nc[1] + rng[1][c1]) * g->nc[0];
        for (int u = 0; u < nrun; u++) {
          size_t s0 = g->start[base + run0[u]], s1 = g->start[base + run1[u] + 1];
          if (reserve(nl, nnz, s1 - s0, &cap) != MFS_OK)
            goto fail;
          if (dim == 2 && !per)
            nnz = scan(2, 0, L, g->x, g->item, y, r2, s0, s1, nl->idx, nnz);
          else
            nnz = scan(dim, per, L, g->x, g->item, y, r2, s0, s1, nl->idx, nnz);
        }
      }
    sort_ints(nl->idx + row0, nnz - row0);
    nl->ptr[q + 1] = nnz;
  }
  if (status)
    *status = MFS_OK;
  return nl;
fail:
  mfs_nlist_free(nl);
  if (status)
    *status = st;
  return NULL;
}

mfs_status mfs_grid_count(const mfs_grid *g, size_t nq, const double *xq, double r, double limit,
                          double *count)
{
  *count = 0.0;
  if (!(r > 0.0) || r > g->radius || !(limit >= 0.0))
    return MFS_EINVAL;
  int dim = g->dim, per = g->box.periodic;
  double r2 = r * r, L[3], total = 0.0;
  for (int k = 0; k < 3; k++)
    L[k] = g->box.hi[k] - g->box.lo[k];
  int rng[3][64], span[3], nr[3] = {1, 1, 1};
  for (int k = 0; k < dim; k++)
    span[k] = (int)ceil(g->radius / g->h[k]);
  rng[1][0] = rng[2][0] = 0;
  for (size_t q = 0; q < nq && total <= limit; q++) {
    const double *y = xq + q * dim;
    for (int k = 0; k < dim; k++)
      nr[k] = cell_range(g, k, span[k], y[k], rng[k]);
    size_t m = 0;
    for (int c2 = 0; c2 < nr[2]; c2++)
      for (int c1 = 0; c1 < nr[1]; c1++)
        for (int c0 = 0; c0 < nr[0]; c0++) {
          size_t c = ((size_t)rng[2][c2] * g->nc[1] + rng[1][c1]) * g->nc[0] + rng[0][c0];
          for (size_t s = g->start[c]; s < g->start[c + 1]; s++)
            m += dist2(dim, per, L, y, g->x + (size_t)g->item[s] * dim) < r2;
        }
    total += (double)m;
  }
  *count = total;
  return MFS_OK;
}

mfs_nlist *mfs_nlist_transpose(const mfs_nlist *nl, size_t n, mfs_status *status)
{
  mfs_nlist *t = mfs_calloc(1, sizeof *t);
  size_t nnz = nl->ptr[nl->nq];
  if (!t)
    goto fail;
  t->nq = n;
  t->ptr = mfs_calloc(n + 1, sizeof *t->ptr);
  t->idx = mfs_malloc((nnz ? nnz : 1) * sizeof *t->idx);
  if (!t->ptr || !t->idx)
    goto fail;
  for (size_t e = 0; e < nnz; e++)
    t->ptr[nl->idx[e] + 1]++;
  for (size_t i = 0; i < n; i++)
    t->ptr[i + 1] += t->ptr[i];
  size_t *next = mfs_malloc((n ? n : 1) * sizeof *next);
  if (!next)
    goto fail;
  memcpy(next, t->ptr, n * sizeof *next);
  for (size_t q = 0; q < nl->nq; q++)
    for (size_t e = nl->ptr[q]; e < nl->ptr[q + 1]; e++)
      t->idx[next[nl->idx[e]]++] = (int)q;
  mfs_free(next);
  if (status)
    *status = MFS_OK;
  return t;
fail:
  mfs_nlist_free(t);
  if (status)
    *status = MFS_ENOMEM;
  return NULL;
}

mfs_status mfs_nlist_rebuild(int dim, size_t n, const double *x, const mfs_box *box, size_t nq,
                             const double *xq, double r, mfs_nlist **lists, size_t *maxlen)
{
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(dim, n, x, box, r, &st);
  if (!g)
    return st;
  mfs_nlist *nl = mfs_nlist_build(g, nq, xq, r, &st);
  mfs_grid_free(g);
  if (!nl)
    return st;
  mfs_nlist_free(*lists);
  *lists = nl;
  size_t m = 1;
  for (size_t Q = 0; Q < nq; Q++) {
    size_t len = nl->ptr[Q + 1] - nl->ptr[Q];
    m = len > m ? len : m;
  }
  *maxlen = m;
  return MFS_OK;
}
