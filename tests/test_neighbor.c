/* The cell grid, the neighbour lists and their count without lists
 * (lib/core/mfs_neighbor.h) against a brute-force search with the same
 * distance arithmetic: uniform sets in 1D and 2D, rows of hundreds, a
 * periodic box, queries inside and outside the box, and sets
 * with a few particles 10^12 to 10^108 away (a coordinate with a wrong
 * exponent).  For those the grid must keep the bulk spread over its cells:
 * with cells over the whole stretched box, every bulk particle fell in one
 * cell and each query scanned them all (the lists stayed right, the search
 * was quadratic). */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static int cmp_int(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The lists of nq queries against brute force; returns the largest cell
 * occupancy of the grid. */
static size_t compare(const char *what, int dim, size_t n, const double *x, const mfs_box *box,
                      size_t nq, const double *xq, double r)
{
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(dim, n, x, box, r, &st);
  mfs_nlist *nl = g ? mfs_nlist_build(g, nq, xq, r, &st) : NULL;
  CHECK(g && nl, "%s: grid and lists: %s", what, mfs_strerror(st));
  size_t most = 0;
  int *want = malloc((n ? n : 1) * sizeof *want);
  if (g && nl && want) {
    size_t cells = (size_t)g->nc[0] * (size_t)g->nc[1] * (size_t)g->nc[2], bad = 0;
    CHECK((double)cells <= 4.0 * (double)n + 4.0, "%s: %zu cells for %zu points", what, cells, n);
    for (size_t c = 0; c < cells; c++)
      most = g->start[c + 1] - g->start[c] > most ? g->start[c + 1] - g->start[c] : most;
    for (size_t q = 0; q < nq; q++) {
      size_t m = 0;
      for (size_t i = 0; i < n; i++) {
        double d[3] = {0.0, 0.0, 0.0}, d2 = 0.0;
        mfs_box_delta(box, xq + q * (size_t)dim, x + i * (size_t)dim, d);
        for (int k = 0; k < dim; k++)
          d2 += d[k] * d[k];
        if (d2 < r * r)
          want[m++] = (int)i;
      }
      qsort(want, m, sizeof *want, cmp_int);
      size_t got = nl->ptr[q + 1] - nl->ptr[q];
      bad += got != m || memcmp(nl->idx + nl->ptr[q], want, m * sizeof *want) != 0;
    }
    CHECK(bad == 0, "%s: %zu of %zu lists differ from brute force", what, bad, nq);
    /* the count without lists: all of them, and stopped past a limit */
    double all = (double)nl->ptr[nq], cnt = -1.0, part = -1.0, lim = 0.3 * all;
    size_t longest = 0;
    for (size_t q = 0; q < nq; q++)
      longest = nl->ptr[q + 1] - nl->ptr[q] > longest ? nl->ptr[q + 1] - nl->ptr[q] : longest;
    CHECK(mfs_grid_count(g, nq, xq, r, 1e300, &cnt) == MFS_OK && cnt == all,
          "%s: counted %.0f pairs, the lists hold %.0f", what, cnt, all);
    CHECK(mfs_grid_count(g, nq, xq, r, lim, &part) == MFS_OK && part > lim &&
            part <= lim + (double)longest,
          "%s: the count stopped at %.0f past %.0f (longest list %zu)", what, part, lim, longest);
  }
  free(want);
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  return most;
}

/* n random points in [0, 1]^dim, then `far` of them moved far away. */
static double *points(gsl_rng *rng, int dim, size_t n, int far)
{
  double *x = malloc(n * (size_t)dim * sizeof *x);
  if (!x)
    return NULL;
  for (size_t i = 0; i < n * (size_t)dim; i++)
    x[i] = gsl_rng_uniform(rng);
  static const double away[3] = {1e108, -3.7e12, 2.385e50};
  for (int f = 0; f < far && f < 3; f++)
    x[(size_t)(7 + 131 * f) * (size_t)dim + (size_t)(f % dim)] = away[f];
  return x;
}

static void bounding_box(int dim, size_t n, const double *x, mfs_box *box)
{
  *box = (mfs_box){.dim = dim, .periodic = 0};
  for (int k = 0; k < dim; k++) {
    box->lo[k] = box->hi[k] = x[k];
    for (size_t i = 1; i < n; i++) {
      box->lo[k] = fmin(box->lo[k], x[i * (size_t)dim + (size_t)k]);
      box->hi[k] = fmax(box->hi[k], x[i * (size_t)dim + (size_t)k]);
    }
  }
}

static void test_sets(gsl_rng *rng)
{
  for (int dim = 1; dim <= 2; dim++)
    for (int far = 0; far <= 3; far += 3) {
      size_t n = dim == 1 ? 2000 : 3000, nq = n + 200;
      double r = dim == 1 ? 2.385e-3 : 0.0385;
      double *x = points(rng, dim, n, far), *xq = malloc(nq * (size_t)dim * sizeof *xq);
      if (!x || !xq) {
        CHECK(0, "allocation");
        free(x);
        free(xq);
        return;
      }
      /* the points themselves, then queries in [-0.2, 1.2]^dim (some outside
       * the box) and at the far points */
      memcpy(xq, x, n * (size_t)dim * sizeof *x);
      for (size_t i = n * (size_t)dim; i < nq * (size_t)dim; i++)
        xq[i] = -0.2 + 1.4 * gsl_rng_uniform(rng);
      for (int f = 0; f < far; f++)
        memcpy(xq + (n + (size_t)f) * (size_t)dim, x + (size_t)(7 + 131 * f) * (size_t)dim,
               (size_t)dim * sizeof *x);
      mfs_box box;
      bounding_box(dim, n, x, &box);
      char what[64];
      snprintf(what, sizeof what, "%dD, %d far points", dim, far);
      size_t most = compare(what, dim, n, x, &box, nq, xq, r);
      CHECK(most <= 64, "%s: %zu points in one cell (the bulk gathered)", what, most);
      free(x);
      free(xq);
    }
}

/* Wide supports: rows of hundreds (sorted by qsort past 64 entries), and
 * the particle set's own count (mfs_point_set_neighbours) against the
 * lists. */
static void test_wide(gsl_rng *rng)
{
  size_t n = 3000;
  double *x = points(rng, 2, n, 0);
  if (!x) {
    CHECK(0, "allocation");
    return;
  }
  mfs_box box;
  bounding_box(2, n, x, &box);
  compare("2D, rows of hundreds", 2, n, x, &box, n, x, 0.2);
  mfs_point_set s = {.dim = 2, .n = n, .x = x};
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(2, n, x, &box, 0.2, &st);
  mfs_nlist *nl = g ? mfs_nlist_build(g, n, x, 0.2, &st) : NULL;
  double c = -1.0;
  CHECK(nl && mfs_point_set_neighbours(&s, 0.2, 1e300, &c) == MFS_OK && c == (double)nl->ptr[n],
        "the set's pairs within 0.2: %.0f, the lists %zu", c, nl ? nl->ptr[n] : 0);
  CHECK(mfs_point_set_neighbours(&s, 0.0, 1e300, &c) == MFS_EINVAL &&
          mfs_point_set_neighbours(&s, 0.2, -1.0, &c) == MFS_EINVAL,
        "r = 0, limit < 0: EINVAL");
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  free(x);
}

/* A periodic box: the minimum image, queries wrapped from outside. */
static void test_periodic(gsl_rng *rng)
{
  size_t n = 2500, nq = 2700;
  double *x = points(rng, 2, n, 0), *xq = malloc(nq * 2 * sizeof *xq);
  if (!x || !xq) {
    CHECK(0, "allocation");
    free(x);
    free(xq);
    return;
  }
  memcpy(xq, x, n * 2 * sizeof *x);
  for (size_t i = 2 * n; i < 2 * nq; i++)
    xq[i] = gsl_rng_uniform(rng);
  mfs_box box = {.dim = 2, .lo = {0.0, 0.0}, .hi = {1.0, 1.0}, .periodic = 1};
  compare("2D periodic", 2, n, x, &box, nq, xq, 0.061);
  free(x);
  free(xq);
}

int main(void)
{
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 2385);
  test_sets(rng);
  test_wide(rng);
  test_periodic(rng);
  gsl_rng_free(rng);
  return check_summary("test_neighbor");
}
