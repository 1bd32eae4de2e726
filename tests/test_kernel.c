/* Kernels: every kernel of mfs_kernel_types is normalized in 1D, 2D and 3D
 * (checked by GSL adaptive quadrature, an independent path from the exact
 * constants in mfs_kernel.c), vanishes at the edge of its support, is flat at
 * the centre, and its derivatives agree with finite differences of the kernel
 * itself; mfs_kernel_radial is consistent with eval; lookup by name. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stddef.h>

#include "check.h"
#include "mfstab.h"

typedef struct {
  const mfs_kernel_type *k;
  int dim;
  double a;
} radial_arg;

/* S_d r^(d-1) W(r): the integrand of the integral of W over the ball */
static double ball_integrand(double r, void *arg)
{
  const radial_arg *p = arg;
  static const double S[3] = {2.0, 2.0 * M_PI, 4.0 * M_PI};
  mfs_kernel_value v = mfs_kernel_radial(p->k, p->dim, p->a, r);
  return S[p->dim - 1] * pow(r, p->dim - 1) * v.W;
}

static void check_normalization(const mfs_kernel_type *k)
{
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  const double radii[2] = {2.385 * 0.7313, 0.04217};
  for (int ia = 0; ia < 2; ia++)
    for (int dim = 1; dim <= 3; dim++) {
      radial_arg arg = {k, dim, radii[ia]};
      gsl_function F = {ball_integrand, &arg};
      double I = 0.0, err = 0.0;
      int st = gsl_integration_qag(&F, 0.0, radii[ia], 1e-14, 1e-13, 1000, GSL_INTEG_GAUSS61, ws,
                                   &I, &err);
      CHECK(st == GSL_SUCCESS, "%s d=%d: qag status %d", k->name, dim, st);
      CHECK_NEAR(I, 1.0, 1e-10, "%s d=%d a=%g: integral of W over the ball", k->name, dim,
                 radii[ia]);
    }
  gsl_integration_workspace_free(ws);
}

static double w_of(const mfs_kernel_type *k, double z, int which)
{
  double w, dw, d2w;
  k->eval(z, &w, &dw, &d2w);
  return which == 0 ? w : (which == 1 ? dw : d2w);
}

static void check_shape_of_w(const mfs_kernel_type *k)
{
  double w, dw, d2w;
  k->eval(1.0, &w, &dw, &d2w);
  CHECK(w == 0.0, "%s: w(1) = %.3g, want 0", k->name, w);
  CHECK_NEAR(dw, 0.0, 1e-14, "%s: w'(1) (kernels are C1 at the support edge)", k->name);
  k->eval(1.0 + 0.2731, &w, &dw, &d2w);
  CHECK(w == 0.0 && dw == 0.0 && d2w == 0.0, "%s: w, w', w'' at z = 1.2731 not zero", k->name);
  k->eval(0.0, &w, &dw, &d2w);
  if (k->cusp) { /* a cone at the centre: w'(0) < 0 */
    CHECK(w > 0.0 && dw < 0.0, "%s (cusp): w(0) = %g > 0 and w'(0) = %g < 0", k->name, w, dw);
  } else {
    CHECK(dw == 0.0, "%s: w'(0) = %.3g, want 0", k->name, dw);
    CHECK(w > 0.0 && d2w < 0.0, "%s: w(0) = %g > 0 and w''(0) = %g < 0 (a peak at 0)", k->name,
          w, d2w);
  }

  /* scale of the derivatives, for relative tolerances */
  double scale = 0.0;
  for (int i = 0; i <= 1000; i++) {
    double t = fabs(w_of(k, i / 1000.0, 2));
    scale = t > scale ? t : scale;
  }
  /* points inside the pieces, including just off the cubic's breakpoint 1/2
   * and the quintic's 1/3, 2/3 (|z - breakpoint| > h: central differences of
   * w' across a jump of w''' would only be first-order accurate) */
  const double zs[] = {0.0137, 0.1931, 0.3329, 0.3341, 0.4127, 0.4993, 0.5007,
                       0.6123, 0.6661, 0.6673, 0.7713, 0.9419, 0.9953};
  const double h = 1e-5;
  for (size_t i = 0; i < sizeof zs / sizeof zs[0]; i++) {
    double z = zs[i];
    double fd1 = (w_of(k, z + h, 0) - w_of(k, z - h, 0)) / (2.0 * h);
    double fd2 = (w_of(k, z + h, 1) - w_of(k, z - h, 1)) / (2.0 * h);
    CHECK_NEAR(w_of(k, z, 1), fd1, 1e-8 * scale, "%s: w'(%g) vs central difference of w", k->name,
               z);
    CHECK_NEAR(w_of(k, z, 2), fd2, 1e-8 * scale, "%s: w''(%g) vs central difference of w'",
               k->name, z);
    /* decreasing on (0, 1) */
    CHECK(w_of(k, z, 1) < 0.0, "%s: w'(%g) = %g not negative", k->name, z, w_of(k, z, 1));
  }
  /* continuity of w, w', w'' across the breakpoints (C2 splines: the cubic's 1/2,
   * the quintic's 1/3 and 2/3, the M5 spline's 1/5 and 3/5) */
  const double bps[] = {1.0 / 3.0, 0.5, 2.0 / 3.0, 0.2, 0.6};
  for (size_t i = 0; i < sizeof bps / sizeof bps[0]; i++)
    for (int which = 0; which < 3; which++) {
      double lo = w_of(k, bps[i] * (1 - 1e-12), which), hi = w_of(k, bps[i] * (1 + 1e-12), which);
      CHECK_NEAR(lo, hi, 1e-9 * scale, "%s: derivative %d continuous at z = %g", k->name, which,
                 bps[i]);
    }
}

static void check_radial(const mfs_kernel_type *k)
{
  const double a = 2.385 * 0.7313;
  const double rs[] = {0.0, 1e-9, 0.1873, 0.5 * a - 1e-3, 0.5 * a + 1e-3, 0.9137 * a, a,
                       1.07 * a};
  for (int dim = 1; dim <= 3; dim++) {
    double c = k->norm[dim - 1] / pow(a, dim);
    for (size_t i = 0; i < sizeof rs / sizeof rs[0]; i++) {
      double r = rs[i];
      mfs_kernel_value v = mfs_kernel_radial(k, dim, a, r);
      if (r >= a) {
        CHECK(v.W == 0.0 && v.dW == 0.0 && v.d2W == 0.0 && v.dW_r == 0.0,
              "%s d=%d: kernel at r = %g >= a not zero", k->name, dim, r);
        continue;
      }
      double w, dw, d2w;
      k->eval(r / a, &w, &dw, &d2w);
      CHECK_NEAR(v.W, c * w, 1e-14 * c * fabs(w), "%s d=%d r=%g: W = norm/a^d w", k->name, dim,
                 r);
      CHECK_NEAR(v.dW, c * dw / a, 1e-14 * c * (fabs(dw) + 1.0) / a, "%s d=%d r=%g: dW/dr",
                 k->name, dim, r);
      CHECK_NEAR(v.d2W, c * d2w / (a * a), 1e-14 * c * fabs(d2w) / (a * a),
                 "%s d=%d r=%g: d2W/dr2", k->name, dim, r);
      if (r == 0.0 && k->cusp)
        CHECK(v.dW_r == 0.0, "%s d=%d (cusp): dW_r(0) = %g, want 0", k->name, dim, v.dW_r);
      else if (r == 0.0)
        CHECK(v.dW_r == v.d2W, "%s d=%d: dW_r(0) = %g, want d2W(0) = %g", k->name, dim, v.dW_r,
              v.d2W);
      else
        CHECK_NEAR(v.dW_r, v.dW / r, 1e-13 * fabs(v.dW / r), "%s d=%d r=%g: dW_r = dW/r",
                   k->name, dim, r);
    }
    /* dW/r tends to d2W at 0 (w'(0) = 0): the r = 0 value is the limit */
    if (k->cusp)
      continue;
    mfs_kernel_value v0 = mfs_kernel_radial(k, dim, a, 0.0);
    mfs_kernel_value v1 = mfs_kernel_radial(k, dim, a, 1e-7 * a);
    CHECK_NEAR(v1.dW_r, v0.d2W, 1e-5 * fabs(v0.d2W), "%s d=%d: dW/r -> d2W as r -> 0", k->name,
               dim);
  }
}

int main(void)
{
  gsl_set_error_handler_off();
  int nk = 0;
  for (int i = 0; mfs_kernel_types[i]; i++) {
    const mfs_kernel_type *k = mfs_kernel_types[i];
    nk++;
    check_normalization(k);
    check_shape_of_w(k);
    check_radial(k);
    CHECK(mfs_kernel_find(k->name) == k, "mfs_kernel_find(\"%s\")", k->name);
  }
  CHECK(nk == 9, "%d kernels in mfs_kernel_types, want 9", nk);
  CHECK(mfs_kernel_find("cubic") == &mfs_kernel_cubic, "find cubic");
  CHECK(mfs_kernel_find("quartic") == &mfs_kernel_quartic, "find quartic");
  CHECK(mfs_kernel_find("wendland2") == &mfs_kernel_wendland2, "find wendland2");
  CHECK(mfs_kernel_find("quintic") == &mfs_kernel_quintic, "find quintic");
  CHECK(mfs_kernel_find("spiky") == &mfs_kernel_spiky && mfs_kernel_spiky.cusp,
        "find spiky (a cusp)");
  CHECK(mfs_kernel_find("m5") == &mfs_kernel_m5, "find m5");
  CHECK(mfs_kernel_find("gaussian") == NULL, "unknown kernel name gives NULL");
  CHECK(mfs_kernel_find("") == NULL, "empty kernel name gives NULL");
  CHECK(mfs_kernel_find("Cubic") == NULL, "names are case-sensitive");
  return check_summary("test_kernel");
}
