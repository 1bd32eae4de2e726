#include "mfs_kernel.h"

#include <math.h>
#include <string.h>

/* Normalization constants: 1 / (S_d int_0^1 w(z) z^(d-1) dz), S = 2, 2 pi,
 * 4 pi, integrated exactly (piecewise polynomials); tests/test_kernel.c checks
 * them by adaptive quadrature. */

#define MFS_X_EVAL(name)                                                                     \
  static void name##_eval(double z, double *w, double *dw, double *d2w)                        \
  {                                                                                            \
    mfs_kernel_##name##_w(z, w, dw, d2w);                                                      \
  }
MFS_KERNEL_LIST(MFS_X_EVAL)
#undef MFS_X_EVAL

const mfs_kernel_type mfs_kernel_cubic = {
  .name = "cubic", .eval = cubic_eval, .id = MFS_KERNEL_ID_cubic, .norm = {2.0, 60.0 / (7.0 * M_PI), 12.0 / M_PI}};
const mfs_kernel_type mfs_kernel_quartic = {
  .name = "quartic", .eval = quartic_eval, .id = MFS_KERNEL_ID_quartic, .norm = {5.0 / 4.0, 5.0 / M_PI, 105.0 / (16.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_wendland2 = {
  .name = "wendland2", .eval = wendland2_eval, .id = MFS_KERNEL_ID_wendland2, .norm = {3.0 / 2.0, 7.0 / M_PI, 21.0 / (2.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_quintic = {
  .name = "quintic", .eval = quintic_eval, .id = MFS_KERNEL_ID_quintic,
  .norm = {1.0 / 40.0, 63.0 / (478.0 * M_PI), 9.0 / (40.0 * M_PI)}};

/* The peers' kernels (docs/conventions.md cites each definition). */
const mfs_kernel_type mfs_kernel_spiky = {
  .name = "spiky", .eval = spiky_eval, .id = MFS_KERNEL_ID_spiky, .cusp = 1,
  .norm = {2.0, 10.0 / M_PI, 15.0 / M_PI}};
const mfs_kernel_type mfs_kernel_poly6 = {
  .name = "poly6", .eval = poly6_eval, .id = MFS_KERNEL_ID_poly6,
  .norm = {35.0 / 32.0, 4.0 / M_PI, 315.0 / (64.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_wendland4 = {
  .name = "wendland4", .eval = wendland4_eval, .id = MFS_KERNEL_ID_wendland4,
  .norm = {27.0 / 16.0, 9.0 / M_PI, 495.0 / (32.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_wendland6 = {
  .name = "wendland6", .eval = wendland6_eval, .id = MFS_KERNEL_ID_wendland6,
  .norm = {15.0 / 8.0, 78.0 / (7.0 * M_PI), 1365.0 / (64.0 * M_PI)}};
const mfs_kernel_type mfs_kernel_m5 = {
  .name = "m5", .eval = m5_eval, .id = MFS_KERNEL_ID_m5,
  .norm = {3125.0 / 768.0, 46875.0 / (2398.0 * M_PI), 15625.0 / (512.0 * M_PI)}};

const mfs_kernel_type *const mfs_kernel_types[] = {
  &mfs_kernel_cubic, &mfs_kernel_quartic, &mfs_kernel_wendland2, &mfs_kernel_quintic,
  &mfs_kernel_spiky, &mfs_kernel_poly6,   &mfs_kernel_wendland4, &mfs_kernel_wendland6,
  &mfs_kernel_m5,    NULL};

const mfs_kernel_type *mfs_kernel_find(const char *name)
{
  for (int i = 0; mfs_kernel_types[i]; i++)
    if (strcmp(mfs_kernel_types[i]->name, name) == 0)
      return mfs_kernel_types[i];
  return NULL;
}
