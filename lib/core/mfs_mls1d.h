/* Internal (not installed): the fused 1D linear MLS gather and evaluation,
 * one definition inlined where it is instantiated per kernel: the shape
 * table's gather_1d (mfs_shape.c) and the Eulerian rod's force loop
 * (lib/time/mfs_solver.c), where the call per point measured 5-15% of the
 * step (analysis/bench/compare_builds.sh).  Arguments and results are those
 * of mfs_shape_gather_1d_fn (mfs_shape.h), the kernel kw its inline formula
 * (mfs_kernel_<name>_w) or its table's eval. */
#ifndef MFS_MLS1D_H
#define MFS_MLS1D_H

#include <math.h>
#include <stddef.h>

#include "mfs_kernel.h"
#include "mfs_particles.h"
#include "mfs_shape.h"
#include "mfs_status.h"

/* The arithmetic of mls_fast_order1 (mfs_shape.c) in 1D, in one pass over the candidates
 * (mfs_shape_gather_1d_fn's arguments).  With field, values = 0 leaves the values
 * out[2 J] unwritten (the Eulerian force needs only phi'; a constant, so the store
 * goes away where it is inlined). */
typedef void (*mfs_mls1d_kernel_fn)(double z, double *w, double *dw, double *d2w);

static inline int mfs_mls1d_gather(mfs_mls1d_kernel_fn kw, const mfs_shape_ctx *c, const mfs_box *box,
                                   double x, const double *xp, const int *cand, size_t nc,
                                   int *idx, double *out, double *work, int *nn, double *rcond,
                                   const double *field, double *grad, int values)
{
  const double a = c->a, ia = 1.0 / a, cn = c->kernel->norm[0] * ia;
  double a00 = 0, a01 = 0, a11 = 0, b00 = 0, b01 = 0, b11 = 0;
  int k = 0;
  for (size_t e = 0; e < nc; e++) {
    int J = cand[e];
    double dd = mfs_box_delta1(box, x, xp[J]);
    if (fabs(dd) >= a)
      continue;
    double px = dd * ia, z = fabs(px), wv = 0.0, dw = 0.0, d2w = 0.0;
    if (z < 1.0)
      kw(z, &wv, &dw, &d2w);
    double W = cn * wv;
    double t = z > 0.0 ? -cn * dw / z * ia : -cn * d2w * ia;
    double gx = t * px;
    a00 += W;
    a01 += W * px;
    a11 += W * px * px;
    b00 += gx;
    b01 += gx * px;
    b11 += gx * px * px;
    work[3 * k] = W;
    work[3 * k + 1] = gx;
    work[3 * k + 2] = px;
    idx[k++] = J;
  }
  *nn = k;
  *rcond = 0.0;
  double det = a00 * a11 - a01 * a01;
  if (!(det > 0.0))
    return MFS_ESINGULAR;
  double i00 = a11 / det, i01 = -a01 / det, i11 = a00 / det;
  double na0 = fabs(a00) + fabs(a01), na1 = fabs(a01) + fabs(a11); /* no libm call */
  double ni0 = fabs(i00) + fabs(i01), ni1 = fabs(i01) + fabs(i11);
  double na = na0 > na1 ? na0 : na1, ni = ni0 > ni1 ? ni0 : ni1;
  *rcond = 1.0 / (na * ni);
  if (!(*rcond >= c->rcond_min) || *rcond == 0.0)
    return MFS_ESINGULAR;
  double g0 = i00, g1 = i01; /* dg = A^-1 (e1/a - dA g) */
  double r0 = -(b00 * g0 + b01 * g1);
  double r1 = ia - (b01 * g0 + b11 * g1);
  double dg0 = i00 * r0 + i01 * r1, dg1 = i01 * r0 + i11 * r1;
  if (field) { /* the field's gradient in the same pass */
    double gr = 0.0;
    for (int J = 0; J < k; J++) {
      const double *w = work + 3 * J;
      double gp = g0 + g1 * w[2], dgp = dg0 + dg1 * w[2];
      double dphi = dgp * w[0] + gp * w[1];
      if (values)
        out[2 * J] = gp * w[0];
      out[2 * J + 1] = dphi;
      gr += dphi * field[idx[J]];
    }
    *grad = gr;
    return MFS_OK;
  }
  for (int J = 0; J < k; J++) {
    const double *w = work + 3 * J;
    double gp = g0 + g1 * w[2], dgp = dg0 + dg1 * w[2];
    out[2 * J] = gp * w[0];
    out[2 * J + 1] = dgp * w[0] + gp * w[1];
  }
  return MFS_OK;
}

#endif
