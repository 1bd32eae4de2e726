/* Explicit time integrators for the second-order system u'' = a(u), shared
 * by the rod solver (mfs_solver.h) and the linear-model solver
 * (mfs_solver2d.h): central difference (leapfrog, kick-drift-kick with
 * velocities at whole steps: one acceleration per step), forward Euler,
 * RK2 (midpoint) and classical RK4 on y' = (v, a(u)).  The caller owns the
 * state and the scratch arrays and supplies the acceleration and, if its
 * boundary conditions need it, a routine that imposes them on a stage. */
#ifndef MFS_EXPLICIT_H
#define MFS_EXPLICIT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  MFS_SCHEME_LEAPFROG,
  MFS_SCHEME_EULER,
  MFS_SCHEME_RK2,
  MFS_SCHEME_RK4
} mfs_scheme;

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
int mfs_explicit_step(mfs_scheme scheme, size_t n, double *u, double *v, double *a, double t,
                      double dt, const mfs_explicit_work *w, mfs_accel_fn accel,
                      mfs_impose_fn impose, void *ctx);

#ifdef __cplusplus
}
#endif

#endif
