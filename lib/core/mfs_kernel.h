/* Radial kernels (weight functions) of compact support.
 *
 * A kernel is a function w(z) of z = r/a on [0, 1], a = D*dx the support
 * radius (paper 003 eq. 39 with h = a; DESIGN.md "Dilation").  The
 * normalized kernel in dimension d is W(r) = norm[d-1] / a^d * w(r/a), so
 * that the integral of W over the ball of radius a is 1.  MLS and Shepard
 * functions do not depend on the normalization; SPH does. */
#ifndef MFS_KERNEL_H
#define MFS_KERNEL_H
#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const char *name;
  /* w(z), w'(z), w''(z) for z in [0, 1]; zero for z >= 1. */
  void (*eval)(double z, double *w, double *dw, double *d2w);
  double norm[3]; /* normalization constants for d = 1, 2, 3 */
} mfs_kernel_type;

extern const mfs_kernel_type mfs_kernel_cubic;     /* cubic B-spline (DESIGN.md) */
extern const mfs_kernel_type mfs_kernel_quartic;   /* 1 - 6z^2 + 8z^3 - 3z^4 */
extern const mfs_kernel_type mfs_kernel_wendland2; /* Wendland C2: (1-z)^4 (1+4z) */
extern const mfs_kernel_type mfs_kernel_quintic;   /* quintic spline, q = 3z */

/* The quartic spline on z < 1, inline for hot loops that special-case it
 * (the table entry mfs_kernel_quartic evaluates the same expression). */
static inline void mfs_kernel_quartic_poly(double z, double *w, double *dw, double *d2w)
{
  double z2 = z * z;
  *w = 1.0 - 6.0 * z2 + 8.0 * z2 * z - 3.0 * z2 * z2;
  *dw = -12.0 * z + 24.0 * z2 - 12.0 * z2 * z;
  *d2w = -12.0 + 48.0 * z - 36.0 * z2;
}

/* NULL-terminated list of all kernels, for lookup by name. */
extern const mfs_kernel_type *const mfs_kernel_types[];

/* The kernel called `name`, or NULL. */
const mfs_kernel_type *mfs_kernel_find(const char *name);

/* The normalized radial kernel and its radial derivatives:
 * W(r), dW/dr, d2W/dr2 and (dW/dr)/r (finite at r = 0) for support
 * radius a > 0 in dimension dim (1..3).  Units: 1/length^dim etc. */
typedef struct {
  double W, dW, d2W, dW_r;
} mfs_kernel_value;

static inline mfs_kernel_value mfs_kernel_radial(const mfs_kernel_type *k, int dim, double a,
                                                 double r)
{
  mfs_kernel_value v = {0.0, 0.0, 0.0, 0.0};
  double z = r / a;
  if (z >= 1.0)
    return v;
  double w, dw, d2w;
  k->eval(z, &w, &dw, &d2w);
  double c = k->norm[dim - 1];
  for (int i = 0; i < dim; i++)
    c /= a;
  v.W = c * w;
  v.dW = c * dw / a;
  v.d2W = c * d2w / (a * a);
  /* dw/z -> w''(0) as z -> 0 for kernels with w'(0) = 0 */
  v.dW_r = (z > 0.0) ? c * (dw / z) / (a * a) : v.d2W;
  return v;
}

#ifdef __cplusplus
}
#endif

#endif
