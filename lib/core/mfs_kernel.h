/* Radial kernels (weight functions) of compact support.
 *
 * A kernel is a function w(z) of z = r/a on [0, 1], a = D*dx the support
 * radius (paper 003 eq. 39 with h = a; docs/user-guide.md "Conventions").  The
 * normalized kernel in dimension d is W(r) = norm[d-1] / a^d * w(r/a), so
 * that the integral of W over the ball of radius a is 1.  MLS and Shepard
 * functions do not depend on the normalization; SPH does. */
#ifndef MFS_KERNEL_H
#define MFS_KERNEL_H
#ifdef __cplusplus
extern "C" {
#endif

/* The built-in kernels, one X(name) each.  Their formulas are the static
 * inline functions mfs_kernel_<name>_w below (w, w', w'' at z in [0, 1],
 * zero beyond), which the table entries mfs_kernel_<name> call, and which
 * hot loops can specialize on (mfs_shape.c).  Adding a kernel: a line here,
 * its inline formula, its table in mfs_kernel.c. */
#define MFS_KERNEL_LIST(X)                                                                   \
  X(cubic) X(quartic) X(wendland2) X(quintic) X(spiky) X(poly6) X(wendland4) X(wendland6) X(m5)

enum {
  MFS_KERNEL_ID_NONE = 0, /* a kernel defined elsewhere */
#define MFS_X_ID(name) MFS_KERNEL_ID_##name,
  MFS_KERNEL_LIST(MFS_X_ID)
#undef MFS_X_ID
  MFS_KERNEL_NIDS
};

typedef struct {
  const char *name;
  /* w(z), w'(z), w''(z) for z in [0, 1]; zero for z >= 1. */
  void (*eval)(double z, double *w, double *dw, double *d2w);
  double norm[3]; /* normalization constants for d = 1, 2, 3 */
  int id;         /* MFS_KERNEL_ID_<name> of a built-in kernel, 0 for another */
  int cusp;       /* w'(0) != 0 (spiky): W has a cone at r = 0, its gradient there is
                     taken as 0 (the peers leave the self pair out) and its second
                     derivatives there are undefined: no Eulerian frame, no least
                     squares (mfs_disc_check) */
} mfs_kernel_type;

extern const mfs_kernel_type mfs_kernel_cubic;     /* cubic B-spline (docs/user-guide.md, Conventions) */
extern const mfs_kernel_type mfs_kernel_quartic;   /* 1 - 6z^2 + 8z^3 - 3z^4 */
extern const mfs_kernel_type mfs_kernel_wendland2; /* Wendland C2: (1-z)^4 (1+4z) */
extern const mfs_kernel_type mfs_kernel_quintic;   /* quintic spline, q = 3z */
/* Kernels of the peer codes users bring (docs/conventions.md): */
extern const mfs_kernel_type mfs_kernel_spiky;     /* (1-z)^3: LAMMPS MACHDYN, TrixiParticles */
extern const mfs_kernel_type mfs_kernel_poly6;     /* (1-z^2)^3: TrixiParticles Poly6Kernel */
extern const mfs_kernel_type mfs_kernel_wendland4; /* Wendland C4 (d <= 3): (1-z)^6 (1+6z+35/3 z^2) */
extern const mfs_kernel_type mfs_kernel_wendland6; /* Wendland C6 (d <= 3): (1-z)^8 (1+8z+25z^2+32z^3) */
extern const mfs_kernel_type mfs_kernel_m5;        /* Schoenberg's M5 quartic B-spline, q = 5z/2 */

/* The quartic spline on z < 1. */
static inline void mfs_kernel_quartic_poly(double z, double *w, double *dw, double *d2w)
{
  double z2 = z * z;
  *w = 1.0 - 6.0 * z2 + 8.0 * z2 * z - 3.0 * z2 * z2;
  *dw = -12.0 * z + 24.0 * z2 - 12.0 * z2 * z;
  *d2w = -12.0 + 48.0 * z - 36.0 * z2;
}

static inline void mfs_kernel_cubic_w(double z, double *w, double *dw, double *d2w)
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

static inline void mfs_kernel_quartic_w(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0)
    mfs_kernel_quartic_poly(z, w, dw, d2w);
  else
    *w = *dw = *d2w = 0.0;
}

static inline void mfs_kernel_wendland2_w(double z, double *w, double *dw, double *d2w)
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

/* Morris' quintic spline in q = 3z: sum of c_i (s_i - q)^5_+ */
static inline void mfs_kernel_quintic_w(double z, double *w, double *dw, double *d2w)
{
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

/* The spiky kernel of Desbrun and Gascuel (1996), (1-z)^3: a cone at z = 0. */
static inline void mfs_kernel_spiky_w(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    double u = 1.0 - z;
    *w = u * u * u;
    *dw = -3.0 * u * u;
    *d2w = 6.0 * u;
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

/* Mueller's poly6 kernel, (1-z^2)^3. */
static inline void mfs_kernel_poly6_w(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    double u = 1.0 - z * z;
    *w = u * u * u;
    *dw = -6.0 * z * u * u;
    *d2w = -6.0 * u * (1.0 - 5.0 * z * z);
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

/* Wendland's C4 function for d <= 3, psi_{3,2} up to a constant. */
static inline void mfs_kernel_wendland4_w(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    double u = 1.0 - z, u2 = u * u, u4 = u2 * u2;
    *w = u4 * u2 * (1.0 + 6.0 * z + 35.0 / 3.0 * z * z);
    *dw = -56.0 / 3.0 * z * u4 * u * (1.0 + 5.0 * z);
    *d2w = -56.0 / 3.0 * u4 * (1.0 + 4.0 * z - 35.0 * z * z);
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

/* Wendland's C6 function for d <= 3, psi_{3,3} up to a constant. */
static inline void mfs_kernel_wendland6_w(double z, double *w, double *dw, double *d2w)
{
  if (z < 1.0) {
    double u = 1.0 - z, u2 = u * u, u6 = u2 * u2 * u2;
    *w = u6 * u2 * (1.0 + 8.0 * z + 25.0 * z * z + 32.0 * z * z * z);
    *dw = -22.0 * z * u6 * u * (1.0 + 7.0 * z + 16.0 * z * z);
    *d2w = -22.0 * u6 * (1.0 + 6.0 * z - 15.0 * z * z - 160.0 * z * z * z);
  } else {
    *w = *dw = *d2w = 0.0;
  }
}

/* Schoenberg's M5 quartic B-spline in z = r/a, (1-z)^4 - 5 (3/5-z)^4_+ + 10 (1/5-z)^4_+
 * (TrixiParticles' SchoenbergQuarticSplineKernel with a = 5h/2); not Lucy's quartic. */
static inline void mfs_kernel_m5_w(double z, double *w, double *dw, double *d2w)
{
  static const double s[3] = {1.0, 0.6, 0.2}, c[3] = {1.0, -5.0, 10.0};
  if (z < 0.2) { /* expanded (46/125 - 12/5 z^2 + 6 z^4): w'(0) = 0 exactly */
    double z2 = z * z;
    *w = 46.0 / 125.0 - 2.4 * z2 + 6.0 * z2 * z2;
    *dw = -4.8 * z + 24.0 * z2 * z;
    *d2w = -4.8 + 72.0 * z2;
    return;
  }
  double W = 0.0, dW = 0.0, d2W = 0.0;
  for (int i = 0; i < 3; i++) {
    double u = s[i] - z;
    if (u <= 0.0)
      continue;
    W += c[i] * u * u * u * u;
    dW -= 4.0 * c[i] * u * u * u;
    d2W += 12.0 * c[i] * u * u;
  }
  *w = W;
  *dw = dW;
  *d2w = d2W;
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
  /* dw/z -> w''(0) as z -> 0 for kernels with w'(0) = 0; a cusp has no
   * gradient at its centre, taken as 0 (mfs_kernel_type.cusp) */
  v.dW_r = (z > 0.0) ? c * (dw / z) / (a * a) : (k->cusp ? 0.0 : v.d2W);
  return v;
}

#ifdef __cplusplus
}
#endif

#endif
