#include "mfs_neighbor.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

void mfs_grid_free(mfs_grid *g)
{
  if (!g)
    return;
  free(g->start);
  free(g->item);
  free(g);
}

/* Cell coordinate of x along direction k, wrapped or clamped. */
static int cell_coord(const mfs_grid *g, int k, double x)
{
  int c = (int)floor((x - g->box.lo[k]) / g->h[k]);
  if (g->box.periodic) {
    c %= g->nc[k];
    if (c < 0)
      c += g->nc[k];
  } else if (c < 0) {
    c = 0;
  } else if (c >= g->nc[k]) {
    c = g->nc[k] - 1;
  }
  return c;
}

static size_t cell_of(const mfs_grid *g, const double *x)
{
  size_t c = 0;
  for (int k = g->dim - 1; k >= 0; k--)
    c = c * (size_t)g->nc[k] + (size_t)cell_coord(g, k, x[k]);
  return c;
}

mfs_grid *mfs_grid_alloc(int dim, size_t n, const double *x, const mfs_box *box, double radius,
                         int *status)
{
  int st = MFS_EINVAL;
  mfs_grid *g = NULL;
  if (!(radius > 0.0) || dim < 1 || dim > 3)
    goto fail;
  st = MFS_ENOMEM;
  g = calloc(1, sizeof *g);
  if (!g)
    goto fail;
  g->dim = dim;
  g->n = n;
  g->x = x;
  g->box = *box;
  g->radius = radius;
  size_t ncells = 1;
  for (int k = 0; k < 3; k++) {
    g->nc[k] = 1;
    g->h[k] = 1.0;
  }
  for (int k = 0; k < dim; k++) {
    double L = box->hi[k] - box->lo[k];
    if (box->periodic && !(L > 2.0 * radius)) {
      st = MFS_ETOOSMALL;
      goto fail;
    }
    /* keep the number of cells bounded by the number of points */
    int nc = L > 0.0 ? (int)floor(L / radius) : 1;
    if (nc < 1)
      nc = 1;
    if ((size_t)nc > 4 * n + 4)
      nc = (int)(4 * n + 4);
    g->nc[k] = nc;
    g->h[k] = L > 0.0 ? L / nc : 1.0;
    if (!box->periodic && g->h[k] < radius)
      g->h[k] = radius; /* clamping keeps far points in edge cells */
    ncells *= (size_t)nc;
  }
  g->start = calloc(ncells + 1, sizeof *g->start);
  g->item = malloc((n ? n : 1) * sizeof *g->item);
  size_t *cellid = malloc((n ? n : 1) * sizeof *cellid);
  if (!g->start || !g->item || !cellid) {
    free(cellid);
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
  free(cellid);
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
  free(nl->ptr);
  free(nl->idx);
  free(nl);
}

/* Rows are short (tens of entries): insertion sort beats qsort here. */
static void sort_ints(int *a, size_t n)
{
  for (size_t i = 1; i < n; i++) {
    int v = a[i];
    size_t j = i;
    for (; j > 0 && a[j - 1] > v; j--)
      a[j] = a[j - 1];
    a[j] = v;
  }
}

/* Distinct cell coordinates along k that may hold points within r of x. */
static int cell_range(const mfs_grid *g, int k, double x, int *out)
{
  int c = (int)floor((x - g->box.lo[k]) / g->h[k]);
  int span = (int)ceil(g->radius / g->h[k]); /* 1 when h >= radius */
  int m = 0;
  if (g->box.periodic && 2 * span + 1 >= g->nc[k]) {
    for (int i = 0; i < g->nc[k]; i++)
      out[m++] = i;
    return m;
  }
  for (int d = -span; d <= span; d++) {
    int ci = c + d;
    if (g->box.periodic) {
      ci %= g->nc[k];
      if (ci < 0)
        ci += g->nc[k];
    } else if (ci < 0 || ci >= g->nc[k]) {
      continue;
    }
    out[m++] = ci;
  }
  return m;
}

mfs_nlist *mfs_nlist_build(const mfs_grid *g, size_t nq, const double *xq, double r, int *status)
{
  int st = MFS_EINVAL;
  mfs_nlist *nl = NULL;
  if (!(r > 0.0) || r > g->radius)
    goto fail;
  st = MFS_ENOMEM;
  nl = calloc(1, sizeof *nl);
  if (!nl)
    goto fail;
  nl->nq = nq;
  nl->ptr = malloc((nq + 1) * sizeof *nl->ptr);
  size_t cap = 16 * nq + 16, nnz = 0;
  nl->idx = malloc(cap * sizeof *nl->idx);
  if (!nl->ptr || !nl->idx)
    goto fail;
  int dim = g->dim;
  double r2 = r * r;
  int rng[3][64];
  int nr[3] = {1, 1, 1};
  rng[1][0] = rng[2][0] = 0;
  nl->ptr[0] = 0;
  for (size_t q = 0; q < nq; q++) {
    const double *y = xq + q * dim;
    for (int k = 0; k < dim; k++)
      nr[k] = cell_range(g, k, y[k], rng[k]);
    size_t row0 = nnz;
    for (int c2 = 0; c2 < nr[2]; c2++)
      for (int c1 = 0; c1 < nr[1]; c1++)
        for (int c0 = 0; c0 < nr[0]; c0++) {
          size_t c = ((size_t)rng[2][c2] * g->nc[1] + rng[1][c1]) * g->nc[0] + rng[0][c0];
          for (size_t s = g->start[c]; s < g->start[c + 1]; s++) {
            int i = g->item[s];
            double d[3], d2 = 0.0;
            mfs_box_delta(&g->box, y, g->x + (size_t)i * dim, d);
            for (int k = 0; k < dim; k++)
              d2 += d[k] * d[k];
            if (d2 >= r2)
              continue;
            if (nnz == cap) {
              size_t ncap = 2 * cap;
              int *t = realloc(nl->idx, ncap * sizeof *t);
              if (!t)
                goto fail;
              nl->idx = t;
              cap = ncap;
            }
            nl->idx[nnz++] = i;
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

mfs_nlist *mfs_nlist_transpose(const mfs_nlist *nl, size_t n, int *status)
{
  mfs_nlist *t = calloc(1, sizeof *t);
  size_t nnz = nl->ptr[nl->nq];
  if (!t)
    goto fail;
  t->nq = n;
  t->ptr = calloc(n + 1, sizeof *t->ptr);
  t->idx = malloc((nnz ? nnz : 1) * sizeof *t->idx);
  if (!t->ptr || !t->idx)
    goto fail;
  for (size_t e = 0; e < nnz; e++)
    t->ptr[nl->idx[e] + 1]++;
  for (size_t i = 0; i < n; i++)
    t->ptr[i + 1] += t->ptr[i];
  size_t *next = malloc((n ? n : 1) * sizeof *next);
  if (!next)
    goto fail;
  memcpy(next, t->ptr, n * sizeof *next);
  for (size_t q = 0; q < nl->nq; q++)
    for (size_t e = nl->ptr[q]; e < nl->ptr[q + 1]; e++)
      t->idx[next[nl->idx[e]]++] = (int)q;
  free(next);
  if (status)
    *status = MFS_OK;
  return t;
fail:
  mfs_nlist_free(t);
  if (status)
    *status = MFS_ENOMEM;
  return NULL;
}
