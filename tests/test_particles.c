/* Particle sets given as arrays (lib/core/mfs_particles, mfs_delaunay):
 * Delaunay triangles have empty circumcircles and tile the convex hull (brute
 * force, an independent path); the dual areas of a lattice are the lattice's
 * cell-dual volumes whatever diagonals Qhull chose, and on any set they are
 * positive and sum to the hull area; the hull flags of a rectangle are its
 * boundary; the close-pair search with cell lists finds what brute force
 * finds; the quadrature rules on a set sum to the domain; bad sets are
 * refused with their status. */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static double area2(const double *x, int a, int b, int c)
{
  const double *A = x + 2 * a, *B = x + 2 * b, *C = x + 2 * c;
  return (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
}

/* 1 if d lies strictly inside the circumcircle of the ccw triangle abc
 * (the incircle determinant, relative tolerance tol). */
static int in_circle(const double *x, int a, int b, int c, int d, double tol)
{
  double m[3][3], s = 0.0;
  const int v[3] = {a, b, c};
  for (int i = 0; i < 3; i++) {
    double dx = x[2 * v[i]] - x[2 * d], dy = x[2 * v[i] + 1] - x[2 * d + 1];
    m[i][0] = dx;
    m[i][1] = dy;
    m[i][2] = dx * dx + dy * dy;
    s += fabs(m[i][2]) * (fabs(dx) + fabs(dy));
  }
  double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return det > tol * s * s;
}

static double *random_square(gsl_rng *r, size_t n, double L)
{
  double *x = malloc(2 * n * sizeof *x);
  const double corners[8] = {0, 0, L, 0, L, L, 0, L};
  memcpy(x, corners, sizeof corners);
  for (size_t i = 4; i < n; i++) {
    x[2 * i] = L * gsl_rng_uniform(r);
    x[2 * i + 1] = L * gsl_rng_uniform(r);
  }
  return x;
}

static void test_delaunay(gsl_rng *r)
{
  size_t n = 300;
  double L = 2.385, *x = random_square(r, n, L);
  size_t nt;
  int *t;
  mfs_status st = mfs_delaunay_2d(n, x, &nt, &t);
  CHECK(st == MFS_OK, "delaunay: %s", mfs_strerror(st));
  if (st != MFS_OK)
    return;
  double sum = 0.0;
  int bad = 0, ccw = 1;
  for (size_t k = 0; k < nt; k++) {
    double A = area2(x, t[3 * k], t[3 * k + 1], t[3 * k + 2]);
    ccw &= A > 0.0;
    sum += 0.5 * A;
    for (size_t d = 0; d < n; d++)
      bad += (int)d != t[3 * k] && (int)d != t[3 * k + 1] && (int)d != t[3 * k + 2] &&
             in_circle(x, t[3 * k], t[3 * k + 1], t[3 * k + 2], (int)d, 1e-12);
  }
  CHECK(ccw, "triangles counter-clockwise");
  CHECK(bad == 0, "%d points inside circumcircles (brute force)", bad);
  CHECK_NEAR(sum, L * L, 1e-12 * L * L, "triangles tile the hull (the square)");
  /* Euler: a triangulation of n points with h on the hull has 2n - 2 - h triangles */
  unsigned char *hull = malloc(n);
  mfs_convex_hull_2d(n, x, hull);
  size_t h = 0;
  for (size_t i = 0; i < n; i++)
    h += hull[i];
  CHECK(h == 4, "random points in a square with its corners: %zu hull vertices, want 4", h);
  CHECK(nt == 2 * n - 2 - h, "%zu triangles, want 2n - 2 - h = %zu", nt, 2 * n - 2 - h);
  /* hull vertices against brute force on a disc (many of them): i is on the hull
   * iff some line through i and another point has every point on one side */
  {
    size_t m = 80;
    double *y = malloc(2 * m * sizeof *y);
    for (size_t i = 0; i < m; i++) {
      double t = 2 * M_PI * gsl_rng_uniform(r), rr = i < m / 2 ? 1.0 : sqrt(gsl_rng_uniform(r));
      y[2 * i] = rr * cos(t);
      y[2 * i + 1] = rr * sin(t);
    }
    unsigned char *hf = malloc(m);
    mfs_convex_hull_2d(m, y, hf);
    int agree = 1;
    for (size_t i = 0; i < m; i++) {
      int on = 0;
      for (size_t j = 0; j < m && !on; j++) {
        if (j == i)
          continue;
        int pos = 0, neg = 0;
        for (size_t k = 0; k < m; k++) {
          double c = area2(y, (int)i, (int)j, (int)k);
          pos += c > 1e-14;
          neg += c < -1e-14;
        }
        on = pos == 0 || neg == 0;
      }
      agree &= on == (hf[i] != 0);
    }
    CHECK(agree, "convex hull vertices of a disc against brute force");
    free(hf);
    free(y);
  }
  double *A = malloc(n * sizeof *A), asum = 0.0;
  mfs_dual_areas(n, x, nt, t, A);
  int pos = 1;
  for (size_t i = 0; i < n; i++) {
    pos &= A[i] > 0.0;
    asum += A[i];
  }
  CHECK(pos, "dual areas positive");
  CHECK_NEAR(asum, L * L, 1e-12 * L * L, "dual areas sum to the domain");
  free(A);
  free(hull);
  free(t);
  free(x);

  /* all on a line: no triangulation */
  double line[10] = {0, 0, 1, 1, 2, 2, 3, 3, 4.5, 4.5};
  CHECK(mfs_delaunay_2d(5, line, &nt, &t) == MFS_EDOMAIN && t == NULL, "collinear: EDOMAIN");
  CHECK(mfs_delaunay_2d(2, line, &nt, &t) == MFS_EINVAL, "two points: EINVAL");
}

/* A lattice given as points: the dual areas are the lattice volumes. */
static void test_lattice_as_points(void)
{
  mfs_lattice_spec ls = {.dim = 2, .lattice = MFS_LATTICE_SQUARE, .nx = 9, .ny = 7, .dx = 0.37,
                         .gamma = 1.3, .cells = MFS_CELLS_QUAD};
  mfs_status st;
  mfs_particles *lat = mfs_lattice_alloc(&ls, &st);
  mfs_point_set s = {.dim = 2, .n = lat->n, .x = lat->x, .vol = NULL};
  mfs_particles *p = mfs_particles_from_set(&s, 0, &st);
  CHECK(p != NULL, "lattice as points: %s", mfs_strerror(st));
  if (p) {
    double e = 0.0;
    int flags_ok = 1;
    for (size_t i = 0; i < p->n; i++) {
      e = fmax(e, fabs(p->vol[i] - lat->vol[i]) / lat->vol[i]);
      flags_ok &= (p->flags[i] != 0) == (lat->flags[i] != 0);
    }
    CHECK(e < 1e-14, "dual areas of the lattice vs its cell-dual volumes: %.3g", e);
    CHECK(flags_ok, "hull flags = the lattice's boundary");
    CHECK(p->lattice == MFS_LATTICE_POINTS && p->nvert == 3 && p->ncell == 2 * 8 * 6,
          "cells: %zu triangles", p->ncell);
    CHECK_NEAR(mfs_particles_domain_volume(p), 8 * 0.37 * 6 * 0.37 * 1.3, 1e-14,
               "domain volume");
    CHECK_NEAR(p->dx, 0.37 * sqrt(1.3), 1e-15, "2D spacing: sqrt of the median volume, sqrt(dx dy)");
    mfs_particles_free(p);
  }
  /* with volumes and without cells: no triangulation */
  s.vol = lat->vol;
  p = mfs_particles_from_set(&s, 0, &st);
  CHECK(p && p->ncell == 0 && p->vol[3] == lat->vol[3], "volumes given: no cells");
  mfs_quad *q = p ? mfs_quad_alloc(&mfs_quad_stress_tri, p, &st) : NULL;
  CHECK(!q && st == MFS_EINVAL, "stress points on a set built without cells: EINVAL");
  mfs_particles_free(p);
  mfs_particles_free(lat);
}

static void test_quadrature(gsl_rng *r)
{
  size_t n = 200;
  double L = 1.37, *x = random_square(r, n, L);
  mfs_point_set s = {.dim = 2, .n = n, .x = x};
  mfs_status st;
  mfs_particles *p = mfs_particles_from_set(&s, 1, &st);
  CHECK(p != NULL, "random set: %s", mfs_strerror(st));
  const char *rules[] = {"nodal", "stress-tri", "gauss1", "gauss2", "gauss3"};
  for (int k = 0; p && k < 5; k++) {
    mfs_quad *q = mfs_quad_alloc(mfs_quad_find(rules[k]), p, &st);
    CHECK(q != NULL, "%s on a set: %s", rules[k], mfs_strerror(st));
    if (!q)
      continue;
    double w = 0.0, mx = 0.0;
    for (size_t i = 0; i < q->n; i++) {
      w += q->w[i];
      mx += q->w[i] * q->x[2 * i]; /* exact for linear fields (nodal: not) */
    }
    CHECK_NEAR(w, L * L, 1e-12, "%s: weights sum to the domain", rules[k]);
    if (k >= 2)
      CHECK_NEAR(mx, 0.5 * L * L * L, 1e-12, "%s: integral of x", rules[k]);
    mfs_quad_free(q);
  }
  CHECK(!mfs_quad_applies(&mfs_quad_stress_quad, 2, MFS_LATTICE_POINTS) &&
          !mfs_quad_applies(&mfs_quad_stress_star, 2, MFS_LATTICE_POINTS),
        "stress-quad and stress-star need a square lattice");
  mfs_particles_free(p);
  free(x);

  /* 1D: unsorted points; volumes half the adjacent intervals */
  double x1[6] = {0.5, 0.1, 0.9, 0.0, 0.35, 1.2};
  mfs_point_set s1 = {.dim = 1, .n = 6, .x = x1};
  p = mfs_particles_from_set(&s1, 1, &st);
  CHECK(p != NULL, "1D set: %s", mfs_strerror(st));
  if (p) {
    const double want[6] = {0.275, 0.175, 0.35, 0.05, 0.2, 0.15};
    for (int i = 0; i < 6; i++)
      CHECK_NEAR(p->vol[i], want[i], 1e-15, "1D volume %d", i);
    CHECK(p->flags[3] == MFS_BND_XLO && p->flags[5] == MFS_BND_XHI && p->flags[0] == 0,
          "1D ends flagged");
    CHECK_NEAR(p->dx, 0.1875, 1e-15, "1D spacing: the median volume");
    mfs_quad *q = mfs_quad_alloc(&mfs_quad_stress, p, &st);
    double w = 0.0;
    for (size_t i = 0; q && i < q->n; i++)
      w += q->w[i];
    CHECK(q && q->n == 11, "1D stress points: %zu", q ? q->n : 0);
    CHECK_NEAR(w, 1.2, 1e-15, "1D stress weights");
    mfs_quad_free(q);
    mfs_particles_free(p);
  }
}

static void test_close_pair(gsl_rng *r)
{
  size_t n = 2000;
  double *x = random_square(r, n, 1.0);
  mfs_point_set s = {.dim = 2, .n = n, .x = x};
  int found;
  size_t i, j;
  /* brute force on the same set: the closest pair */
  double dmin = INFINITY;
  size_t bi = 0, bj = 0;
  for (size_t a = 0; a < n; a++)
    for (size_t b = a + 1; b < n; b++) {
      double d = hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1]);
      if (d < dmin) {
        dmin = d;
        bi = a;
        bj = b;
      }
    }
  CHECK(mfs_point_set_close_pair(&s, 0.999 * dmin, &found, &i, &j) == MFS_OK && !found,
        "no pair closer than the closest");
  CHECK(mfs_point_set_close_pair(&s, 1.001 * dmin, &found, &i, &j) == MFS_OK && found &&
          i == bi && j == bj,
        "the closest pair %zu %zu (brute force %zu %zu)", i, j, bi, bj);
  x[2 * 1234] = x[2 * 77];
  x[2 * 1234 + 1] = x[2 * 77 + 1];
  mfs_point_set_close_pair(&s, 1e-12, &found, &i, &j);
  CHECK(found && i == 77 && j == 1234, "a duplicate: %d %zu %zu", found, i, j);
  CHECK(mfs_point_set_close_pair(&s, 0.0, &found, &i, &j) == MFS_EINVAL, "r = 0: EINVAL");
  /* many duplicates, some in one cell, some in clusters of copies (a cell's
   * scan stops at its first point with a partner): the first pair by index,
   * as brute force finds it */
  for (size_t k = 0; k < 40; k++) {
    size_t a = (k * 977 + 13) % n, b = (k * 331 + 1500) % n;
    x[2 * b] = x[2 * a];
    x[2 * b + 1] = x[2 * a + 1];
  }
  for (size_t k = 1700; k < 1800; k++) { /* 100 copies of particle 1699 */
    x[2 * k] = x[2 * 1699];
    x[2 * k + 1] = x[2 * 1699 + 1];
  }
  bi = bj = n;
  for (size_t a = 0; a < n && bi == n; a++)
    for (size_t b = a + 1; b < n; b++)
      if (x[2 * a] == x[2 * b] && x[2 * a + 1] == x[2 * b + 1]) {
        bi = a;
        bj = b;
        break;
      }
  CHECK(mfs_point_set_close_pair(&s, 1e-12, &found, &i, &j) == MFS_OK && found && i == bi &&
          j == bj,
        "the first of many duplicates: %zu %zu (brute force %zu %zu)", i, j, bi, bj);
  free(x);
}

/* A set with one particle 10^108 away (a fuzzer's finding: the cells of
 * the duplicate test, thinned in proportion over both directions, left 2^31
 * cells along the far one, and the bounding box's spacing made every pair
 * a duplicate): the grid's cells stay within 4 n + 4, the bulk spacing is
 * the lattice's, and close_pair finds the real pair and no other. */
static void test_far_particle(void)
{
  enum { M = 40 };
  size_t n = M * M + 2;
  double *x = malloc(2 * n * sizeof *x);
  CHECK(x != NULL, "far particle: allocation");
  if (!x)
    return;
  for (int i = 0; i < M; i++)
    for (int j = 0; j < M; j++) {
      x[2 * (i * M + j)] = 0.01 * i;
      x[2 * (i * M + j) + 1] = 0.01 * j;
    }
  x[2 * M * M] = 0.25; /* off the lattice for now; the duplicate below */
  x[2 * M * M + 1] = 0.255;
  x[2 * M * M + 2] = 0.5;
  x[2 * M * M + 3] = 1e108;
  mfs_point_set s = {.dim = 2, .n = n, .x = x};
  mfs_box box = {.dim = 2, .lo = {0.0, 0.0}, .hi = {0.5, 1e108}};
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(2, n, x, &box, 1e54, &st);
  CHECK(g && (double)g->nc[0] * g->nc[1] <= 4.0 * n + 4.0, "far particle: %d x %d cells for %zu",
        g ? g->nc[0] : 0, g ? g->nc[1] : 0, n);
  mfs_grid_free(g);
  double h = mfs_point_set_bulk_spacing(&s);
  CHECK(h > 0.009 && h < 0.011, "far particle: bulk spacing %.6g, the lattice's 0.01", h);
  int found = 1;
  size_t i = 0, j = 0;
  CHECK(mfs_point_set_close_pair(&s, 1e-10 * h, &found, &i, &j) == MFS_OK && !found,
        "far particle: no pair closer than 1e-12 (found %d: %zu %zu)", found, i, j);
  x[2 * M * M + 1] = 0.25; /* now on lattice particle 25 * M + 25 */
  CHECK(mfs_point_set_close_pair(&s, 1e-10 * h, &found, &i, &j) == MFS_OK && found &&
          i == 25 * M + 25 && j == M * M,
        "far particle: the duplicate %zu %zu (found %d)", i, j, found);
  x[0] = INFINITY;
  CHECK(mfs_point_set_close_pair(&s, 1e-10 * h, &found, &i, &j) == MFS_EINVAL &&
          isnan(mfs_point_set_bulk_spacing(&s)),
        "a coordinate not finite: EINVAL, NAN");
  double flat[10] = {0, 0, 0, 1, 0, 2, 0, 3, 1, 0}; /* four of five on x = 0 */
  mfs_point_set sf = {.dim = 2, .n = 5, .x = flat};
  CHECK(isnan(mfs_point_set_bulk_spacing(&sf)), "a flat bulk: NAN");
  sf.n = 3;
  CHECK(isnan(mfs_point_set_bulk_spacing(&sf)) && isnan(mfs_point_set_bulk_spacing(NULL)),
        "three particles, no set: NAN");
  double line[10] = {0.0, 0.3, 0.7, 1.0, 9.0}; /* 1D: quartiles 0.3, 1.0 hold 3 particles */
  mfs_point_set s1 = {.dim = 1, .n = 5, .x = line};
  CHECK(mfs_point_set_bulk_spacing(&s1) == 0.35, "1D bulk spacing %.17g, want 0.35",
        mfs_point_set_bulk_spacing(&s1));
  free(x);
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The spacing's median (a radix selection on the values, no allocation) against a
 * sorted copy: odd and even counts, repeated values, values of both signs. */
static void test_spacing_median(gsl_rng *r)
{
  for (size_t n = 1; n <= 40; n++) {
    double v[40], sorted[40];
    for (size_t i = 0; i < n; i++)
      v[i] = i % 5 == 3 ? v[i / 2] : (gsl_rng_uniform(r) - 0.2) * pow(10.0, (double)(i % 7) - 3.0);
    memcpy(sorted, v, n * sizeof *v);
    qsort(sorted, n, sizeof *sorted, cmp_double);
    double med = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2] + sorted[n / 2 - 1]);
    mfs_point_set s1 = {.dim = 1, .n = n, .vol = v};
    double got = mfs_point_set_spacing(&s1);
    CHECK(got == med, "1D spacing of %zu values: %.17g, the sorted median %.17g", n, got, med);
    if (med > 0.0) {
      mfs_point_set s2 = {.dim = 2, .n = n, .vol = v};
      CHECK(mfs_point_set_spacing(&s2) == sqrt(med), "2D spacing of %zu values: sqrt of the median",
            n);
    }
  }
}

static void test_errors(void)
{
  mfs_status st;
  double x[6] = {0, 0, 1, 0, 0, 1}, v[3] = {1, 0, 1};
  mfs_point_set s = {.dim = 2, .n = 2, .x = x};
  CHECK(!mfs_particles_from_set(&s, 0, &st) && st == MFS_EINVAL, "2 particles in 2D");
  s.n = 3;
  s.vol = v;
  CHECK(!mfs_particles_from_set(&s, 0, &st) && st == MFS_EINVAL, "zero volume");
  v[1] = 1.0;
  x[3] = NAN;
  CHECK(!mfs_particles_from_set(&s, 0, &st) && st == MFS_EINVAL, "NaN coordinate");
  double xl[6] = {0, 0, 1, 1, 2, 2};
  mfs_point_set sl = {.dim = 2, .n = 3, .x = xl};
  CHECK(!mfs_particles_from_set(&sl, 0, &st) && st == MFS_EDOMAIN, "collinear 2D set");
  double x1[3] = {0.0, 0.5, 0.5};
  mfs_point_set s1 = {.dim = 1, .n = 3, .x = x1};
  CHECK(!mfs_particles_from_set(&s1, 0, &st) && st == MFS_EINVAL, "1D duplicate");
  s1.dim = 3;
  CHECK(!mfs_particles_from_set(&s1, 0, &st) && st == MFS_EINVAL, "dim 3");
}

int main(void)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 2385);
  test_delaunay(r);
  test_lattice_as_points();
  test_quadrature(r);
  test_close_pair(r);
  test_far_particle();
  test_spacing_median(r);
  test_errors();
  gsl_rng_free(r);
  return check_summary("test_particles");
}
