#include "mfs_voronoi.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_neighbor.h"
#include "mfs_status.h"

#define MAXV 64

/* Keep the part of polygon P (n vertices, relative to the point) with
 * y.d <= |d|^2/2.  Returns the new vertex count, -1 if it would exceed MAXV. */
static int clip(double *P, int n, const double *d, double *tmp)
{
  double c = 0.5 * (d[0] * d[0] + d[1] * d[1]);
  int m = 0;
  for (int k = 0; k < n; k++) {
    if (m >= MAXV - 2)
      return -1;
    const double *a = P + 2 * k, *b = P + 2 * ((k + 1) % n);
    double fa = a[0] * d[0] + a[1] * d[1] - c, fb = b[0] * d[0] + b[1] * d[1] - c;
    if (fa <= 0.0) {
      tmp[2 * m] = a[0];
      tmp[2 * m + 1] = a[1];
      m++;
    }
    if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
      double t = fa / (fa - fb);
      tmp[2 * m] = a[0] + t * (b[0] - a[0]);
      tmp[2 * m + 1] = a[1] + t * (b[1] - a[1]);
      m++;
    }
  }
  memcpy(P, tmp, 2 * m * sizeof *P);
  return m;
}

static double poly_area(const double *P, int n, double *rmax)
{
  double s = 0.0, r = 0.0;
  for (int k = 0; k < n; k++) {
    int l = (k + 1) % n;
    s += P[2 * k] * P[2 * l + 1] - P[2 * l] * P[2 * k + 1];
    double rr = hypot(P[2 * k], P[2 * k + 1]);
    r = rr > r ? rr : r;
  }
  *rmax = r;
  return 0.5 * s;
}

mfs_status mfs_voronoi_areas(size_t n, const double *x, const mfs_box *box, double *area)
{
  if (box->dim != 2)
    return MFS_EINVAL;
  double Lx = box->hi[0] - box->lo[0], Ly = box->hi[1] - box->lo[1];
  if (!box->periodic)
    for (size_t i = 0; i < n; i++)
      if (x[2 * i] < box->lo[0] || x[2 * i] > box->hi[0] || x[2 * i + 1] < box->lo[1] ||
          x[2 * i + 1] > box->hi[1])
        return MFS_EINVAL;
  unsigned char *done = mfs_calloc(n ? n : 1, 1);
  if (!done)
    return MFS_ENOMEM;
  double R = 3.0 * sqrt(Lx * Ly / (double)(n ? n : 1));
  double Rmax = box->periodic ? 0.499 * (Lx < Ly ? Lx : Ly) : 2.0 * hypot(Lx, Ly);
  size_t left = n;
  mfs_status st = MFS_OK;
  while (left > 0) {
    if (R > Rmax)
      R = Rmax;
    mfs_status gst;
    mfs_grid *g = mfs_grid_alloc(2, n, x, box, R, &gst);
    mfs_nlist *nl = g ? mfs_nlist_build(g, n, x, R, &gst) : NULL;
    if (!nl) {
      mfs_grid_free(g);
      st = gst;
      break;
    }
    for (size_t i = 0; i < n; i++) {
      if (done[i])
        continue;
      const double *xi = x + 2 * i;
      double P[2 * MAXV], tmp[2 * MAXV];
      int nv = 4;
      /* start: the box (finite) or the periodic cell centred at the point */
      double x0 = box->periodic ? -0.5 * Lx : box->lo[0] - xi[0];
      double x1 = box->periodic ? 0.5 * Lx : box->hi[0] - xi[0];
      double y0 = box->periodic ? -0.5 * Ly : box->lo[1] - xi[1];
      double y1 = box->periodic ? 0.5 * Ly : box->hi[1] - xi[1];
      double init[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
      memcpy(P, init, sizeof init);
      for (size_t e = nl->ptr[i]; e < nl->ptr[i + 1] && nv != 0; e++) {
        int j = nl->idx[e];
        if ((size_t)j == i)
          continue;
        double d[2];
        mfs_box_delta(box, xi, x + 2 * (size_t)j, d);
        if (d[0] == 0.0 && d[1] == 0.0)
          continue;
        nv = clip(P, nv, d, tmp);
        if (nv < 0)
          break;
      }
      if (nv < 0) { /* a cell with more than MAXV vertices: not a sane point set */
        st = MFS_EDOMAIN;
        break;
      }
      double rmax;
      double A = poly_area(P, nv, &rmax);
      if (2.0 * rmax <= R || R >= Rmax) {
        area[i] = A;
        done[i] = 1;
        left--;
      }
    }
    mfs_nlist_free(nl);
    mfs_grid_free(g);
    if (st != MFS_OK)
      break;
    R *= 2.0;
  }
  mfs_free(done);
  return st;
}
