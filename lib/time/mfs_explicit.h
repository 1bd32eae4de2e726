/* Explicit time integrators for the second-order system u'' = a(u), shared
 * by the rod solver (mfs_solver.h) and the linear-model solver
 * (mfs_solver2d.h): central difference (leapfrog, kick-drift-kick with
 * velocities at whole steps: one acceleration per step), forward Euler,
 * RK2 (midpoint) and classical RK4 on y' = (v, a(u)).  The caller owns the
 * state and the scratch arrays and supplies the acceleration and, if its
 * boundary conditions need it, a routine that imposes them on a stage. */
#ifndef MFS_EXPLICIT_H
#define MFS_EXPLICIT_H

#include <math.h>
#include <stddef.h>

#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  MFS_SCHEME_LEAPFROG,
  MFS_SCHEME_EULER,
  MFS_SCHEME_RK2,
  MFS_SCHEME_RK4
} mfs_scheme;

/* Name of a scheme ("leapfrog", "euler", "rk2", "rk4"); parse: MFS_EINVAL if unknown. */
const char *mfs_scheme_name(mfs_scheme s);
mfs_status mfs_scheme_parse(const char *name, mfs_scheme *s);

/* End conditions of the 1D solvers: free, fixed, or a prescribed velocity. */
typedef enum { MFS_BC_FREE, MFS_BC_FIXED, MFS_BC_VELOCITY } mfs_bc;

/* The value at X of the field v sampled at the n points i dx, i = 0..n-1,
 * by linear interpolation (the end values outside). */
static inline double mfs_lerp_uniform(const double *v, size_t n, double dx, double X)
{
  double q = X / dx;
  if (!(q > 0.0))
    return v[0];
  if (q >= (double)(n - 1))
    return v[n - 1];
  size_t i = (size_t)q;
  double f = q - (double)i;
  return (1.0 - f) * v[i] + f * v[i + 1];
}

/* *dt = value if it is a step against the stable step dt_crit: MFS_EINVAL
 * (and *dt unchanged) if value <= 0, not finite, or above dt_crit without
 * force; else MFS_OK. */
static inline mfs_status mfs_explicit_set_dt(double *dt, double value, double dt_crit, int force)
{
  if (!(value > 0.0) || !isfinite(value) || (value > dt_crit && !force))
    return MFS_EINVAL;
  *dt = value;
  return MFS_OK;
}

/* a = a(u); MFS_OK or the caller's error status. */
typedef int (*mfs_accel_fn)(void *ctx, const double *u, double *a);
/* Impose the conditions at time t on u and on v (either may be NULL). */
typedef void (*mfs_impose_fn)(void *ctx, double *u, double *v, double t);

/* Caller-owned scratch: u0, v0, tu of n values, ku, kv of 4n. */
typedef struct {
  double *u0, *v0, *ku, *kv, *tu;
} mfs_explicit_work;

/* One step from t to t + dt of (u, v) with a = a(u) on entry; on return a
 * = a(u) at the new state.  impose may be NULL.  MFS_EINVAL for an unknown
 * scheme, MFS_EDOMAIN for a non-finite u or v after the step, else the
 * status of accel. */
mfs_status mfs_explicit_step(mfs_scheme scheme, size_t n, double *u, double *v, double *a,
                             double t, double dt, const mfs_explicit_work *w, mfs_accel_fn accel,
                             mfs_impose_fn impose, void *ctx);

#ifdef __cplusplus
}
#endif

#endif
