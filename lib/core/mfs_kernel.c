#include "mfs_kernel.h"

#include <math.h>
#include <string.h>

/* Normalization constants: 1 / (S_d int_0^1 w(z) z^(d-1) dz), S = 2, 2 pi,
 * 4 pi, integrated exactly (piecewise polynomials); tests/test_kernel.c checks
 * them by adaptive quadrature. */

static void cubic_eval(double z, double *w, double *dw, double *d2w)
{
  if (z <= 0.5) {
    *w = 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
    *dw = -8.0 * z + 12.0 * z * z;
    *d2w = -8.0 + 24.0 * z;
  } else if (z < 1.0) {
    double u = 1.0 - z;
    *w = 4.0 / 3.0 * u * u * u;
    *dw = -4.0 * u * u;
    *d2w = 8.0 * u;
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

static void quartic_eval(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    mfs_kernel_quartic_poly(z, w, dw, d2w);
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

static void wendland2_eval(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    double u = 1.0 - z, u2 = u * u;
    *w = u2 * u2 * (1.0 + 4.0 * z);
    *dw = -20.0 * z * u2 * u;
    *d2w = -20.0 * u2 * (1.0 - 4.0 * z);
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

static void quintic_eval(double z, double *w, double *dw, double *d2w)
{
  /* Morris' quintic spline in q = 3z: sum of c_i (s_i - q)^5_+ */
  static const double s[3] = {3.0, 2.0, 1.0}, c[3] = {1.0, -6.0, 15.0};
  double q = 3.0 * z, W = 0.0, dW = 0.0, d2W = 0.0;
  for (int i = 0; i < 3; i++) {
    double u = s[i] - q;
    if (u <= 0.0)
      continue;
    double u2 = u * u;
    W += c[i] * u2 * u2 * u;
    dW -= 5.0 * c[i] * u2 * u2;
    d2W += 20.0 * c[i] * u2 * u;
  }
  *w = W;
  *dw = 3.0 * dW;
  *d2w = 9.0 * d2W;
}

const mfs_kernel_type mfs_kernel_cubic = {
  "cubic", cubic_eval, {2.0, 60.0 / (7.0 * M_PI), 12.0 / M_PI}};
const mfs_kernel_type mfs_kernel_quartic = {
  "quartic", quartic_eval, {5.0 / 4.0, 5.0 / M_PI, 105.0 / (16.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_wendland2 = {
  "wendland2", wendland2_eval, {3.0 / 2.0, 7.0 / M_PI, 21.0 / (2.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_quintic = {
  "quintic", quintic_eval, {1.0 / 40.0, 63.0 / (478.0 * M_PI), 9.0 / (40.0 * M_PI)}};

const mfs_kernel_type *const mfs_kernel_types[] = {
  &mfs_kernel_cubic, &mfs_kernel_quartic, &mfs_kernel_wendland2, &mfs_kernel_quintic, NULL};

const mfs_kernel_type *mfs_kernel_find(const char *name)
{
  for (int i = 0; mfs_kernel_types[i]; i++)
    if (strcmp(mfs_kernel_types[i]->name, name) == 0)
      return mfs_kernel_types[i];
  return NULL;
}
