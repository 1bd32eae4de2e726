#include "mfs_delaunay.h"
#include "mfs_alloc.h"

#include <libqhull_r/qhull_ra.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

static double tri_area2(const double *x, int a, int b, int c)
{
  const double *A = x + 2 * (size_t)a, *B = x + 2 * (size_t)b, *C = x + 2 * (size_t)c;
  return (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
}

mfs_status mfs_delaunay_2d(size_t n, const double *x, size_t *ntri, int **tri)
{
  *ntri = 0;
  *tri = NULL;
  if (n < 3 || n > (size_t)INT_MAX / 2)
    return MFS_EINVAL;
  /* Qhull reports on an error stream: kept in memory and discarded */
  char *msg = NULL;
  size_t msglen = 0;
  FILE *err = open_memstream(&msg, &msglen);
  if (!err)
    return MFS_ENOMEM;
  coordT *pts = mfs_malloc(2 * n * sizeof *pts);
  int *t = NULL;
  mfs_status st = MFS_ENOMEM;
  qhT qh_qh, *qh = &qh_qh;
  int started = 0;
  if (!pts)
    goto done;
  memcpy(pts, x, 2 * n * sizeof *pts);
  qh_zero(qh, err);
  started = 1;
  char flags[] = "qhull d Qt Qbb Qz"; /* no Qc: a point that is no vertex fails anyway */
  int code = qh_new_qhull(qh, 2, (int)n, pts, False, flags, NULL, err);
  st = code == qh_ERRmem ? MFS_ENOMEM : MFS_EDOMAIN; /* Qhull's own memory (not hooked) */
  if (code != 0)
    goto done;
  size_t nf = 0;
  facetT *facet;
  vertexT *vertex, **vertexp;
  FORALLfacets
    nf += !facet->upperdelaunay;
  st = MFS_ENOMEM;
  t = mfs_malloc((nf ? nf : 1) * 3 * sizeof *t);
  if (!t)
    goto done;
  size_t k = 0;
  double asum = 0.0;
  FORALLfacets {
    if (facet->upperdelaunay)
      continue;
    int v[3], m = 0, bad = 0;
    FOREACHvertex_(facet->vertices) {
      int id = qh_pointid(qh, vertex->point);
      if (m < 3)
        v[m] = id;
      m++;
      bad |= id < 0 || (size_t)id >= n; /* the point at infinity of 'Qz' */
    }
    if (m != 3 || bad)
      continue;
    double A = tri_area2(x, v[0], v[1], v[2]);
    if (A < 0.0) {
      int s = v[1];
      v[1] = v[2];
      v[2] = s;
      A = -A;
    }
    asum += A;
    memcpy(t + 3 * k, v, sizeof v);
    k++;
  }
  /* drop the zero-area triangles of cocircular points */
  double amin = k ? 1e-12 * asum / (double)k : 0.0;
  size_t kept = 0;
  for (size_t i = 0; i < k; i++)
    if (tri_area2(x, t[3 * i], t[3 * i + 1], t[3 * i + 2]) > amin) {
      memmove(t + 3 * kept, t + 3 * i, 3 * sizeof *t);
      kept++;
    }
  st = kept > 0 ? MFS_OK : MFS_EDOMAIN;
  *ntri = kept;
done:
  if (started) {
    int curlong, totlong;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
  }
  fclose(err);
  mfs_free_libc(msg); /* open_memstream's buffer: the C library's */
  mfs_free(pts);
  if (st == MFS_OK) {
    *tri = t;
  } else {
    mfs_free(t);
    *ntri = 0;
  }
  return st;
}

void mfs_dual_areas(size_t n, const double *x, size_t ntri, const int *tri, double *area)
{
  memset(area, 0, n * sizeof *area);
  for (size_t t = 0; t < ntri; t++) {
    const int *v = tri + 3 * t;
    double A = 0.5 * fabs(tri_area2(x, v[0], v[1], v[2]));
    double e[3][2], d2[3], dot[3];
    for (int k = 0; k < 3; k++) { /* e[k]: the edge opposite vertex k, from k+1 to k+2 */
      const double *P = x + 2 * (size_t)v[(k + 1) % 3], *Q = x + 2 * (size_t)v[(k + 2) % 3];
      e[k][0] = Q[0] - P[0];
      e[k][1] = Q[1] - P[1];
      d2[k] = e[k][0] * e[k][0] + e[k][1] * e[k][1];
    }
    /* the angle at vertex k lies between the edges e[k+1] and e[k+2] */
    for (int k = 0; k < 3; k++) {
      const double *a = e[(k + 1) % 3], *b = e[(k + 2) % 3];
      dot[k] = -(a[0] * b[0] + a[1] * b[1]); /* cos(angle) |a| |b| */
    }
    int obtuse = -1;
    for (int k = 0; k < 3; k++)
      if (dot[k] < 0.0)
        obtuse = k;
    double share[3];
    if (obtuse >= 0) {
      for (int k = 0; k < 3; k++)
        share[k] = k == obtuse ? 0.5 * A : 0.25 * A;
    } else {
      /* Voronoi share of vertex k: (|e_{k+1}|^2 cot(angle k+1) + |e_{k+2}|^2 cot(angle k+2)) / 8,
       * cot(angle) = dot / (2A) */
      for (int k = 0; k < 3; k++) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        share[k] = (d2[k1] * dot[k1] + d2[k2] * dot[k2]) / (16.0 * A);
      }
    }
    for (int k = 0; k < 3; k++)
      area[v[k]] += share[k];
  }
}

typedef struct {
  double x, y;
  int i;
} hull_pt;

static int cmp_xy(const void *pa, const void *pb)
{
  const hull_pt *a = pa, *b = pb;
  if (a->x != b->x)
    return a->x < b->x ? -1 : 1;
  return (a->y > b->y) - (a->y < b->y);
}

/* > 0 for a left turn o -> a -> b. */
static double cross(const hull_pt *o, const hull_pt *a, const hull_pt *b)
{
  return (a->x - o->x) * (b->y - o->y) - (a->y - o->y) * (b->x - o->x);
}

mfs_status mfs_convex_hull_2d(size_t n, const double *x, unsigned char *hull)
{
  memset(hull, 0, n);
  if (n < 3) {
    memset(hull, 1, n);
    return MFS_OK;
  }
  hull_pt *p = mfs_malloc(n * sizeof *p);
  size_t *chain = mfs_malloc(n * sizeof *chain);
  if (!p || !chain) {
    mfs_free(p);
    mfs_free(chain);
    return MFS_ENOMEM;
  }
  /* Akl-Toussaint: a point strictly inside the polygon of the extreme points
   * in 8 directions is no hull vertex; most points are, and are not sorted */
  const double dir[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  size_t ext[8] = {0};
  double best[8], scale = 0.0;
  for (int k = 0; k < 8; k++)
    best[k] = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    scale = fmax(scale, fabs(x[2 * i]) + fabs(x[2 * i + 1]));
    for (int k = 0; k < 8; k++) {
      double v = dir[k][0] * x[2 * i] + dir[k][1] * x[2 * i + 1];
      if (v > best[k]) {
        best[k] = v;
        ext[k] = i;
      }
    }
  }
  hull_pt poly[8];
  int np = 0;
  for (int k = 0; k < 8; k++) {
    hull_pt q = {x[2 * ext[k]], x[2 * ext[k] + 1], (int)ext[k]};
    if (np == 0 || q.i != poly[np - 1].i)
      poly[np++] = q;
  }
  if (np > 1 && poly[np - 1].i == poly[0].i)
    np--;
  double tol = 1e-12 * scale * scale;
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    hull_pt q = {x[2 * i], x[2 * i + 1], (int)i};
    int inside = np >= 3;
    for (int k = 0; k < np && inside; k++)
      inside = cross(&poly[k], &poly[(k + 1) % np], &q) > tol;
    if (!inside)
      p[m++] = q;
  }
  n = m;
  qsort(p, n, sizeof *p, cmp_xy);
  /* lower and upper chains, keeping collinear points (pop only on a right turn) */
  for (int pass = 0; pass < 2; pass++) {
    size_t k = 0;
    for (size_t s = 0; s < n; s++) {
      size_t i = pass == 0 ? s : n - 1 - s;
      while (k >= 2 && cross(&p[chain[k - 2]], &p[chain[k - 1]], &p[i]) < 0.0)
        k--;
      chain[k++] = i;
    }
    for (size_t s = 0; s < k; s++)
      hull[p[chain[s]].i] = 1;
  }
  mfs_free(p);
  mfs_free(chain);
  return MFS_OK;
}
