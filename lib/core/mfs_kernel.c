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

const mfs_kernel_type *const mfs_kernel_types[] = {
  &mfs_kernel_cubic, &mfs_kernel_quartic, &mfs_kernel_wendland2, &mfs_kernel_quintic, NULL};

const mfs_kernel_type *mfs_kernel_find(const char *name)
{
  for (int i = 0; mfs_kernel_types[i]; i++)
    if (strcmp(mfs_kernel_types[i]->name, name) == 0)
      return mfs_kernel_types[i];
  return NULL;
}
