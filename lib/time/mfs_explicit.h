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

#include "mfs_bound.h"
#include "mfs_eigen.h"
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

/* The rule that chooses the stable step dt_crit = 2 / sqrt(lambda) of the
 * central difference (eq. 120 with xi = 0) from the solver's linearized
 * operator at its initial state (u = 0; M^-1 K, lumped mass):
 *   MFS_DT_GERSHGORIN  lambda = max_i sum_j |K_ij| / m_i (mfs_bound.h): a
 *                        proven upper bound of every |eigenvalue|, one pass
 *                        over the nonzeros; needs every m_i > 0;
 *   MFS_DT_CERTIFIED   lambda = sigma (1 + margin) of a Cholesky
 *                        factorization of sigma M - K (mfs_eig_certify_search,
 *                        from a Lanczos estimate at relative tolerance
 *                        MFS_DT_ARPACK_TOL: mfs_lanczos_max with a lumped
 *                        mass, ARPACK's mfs_eig_max with a consistent one):
 *                        proven, within about 1e-6 of lambda_max, one
 *                        Lanczos run and a few factorizations;
 *   MFS_DT_POWER       the rule before these (mfs_step_lambda): 1.05 times
 *                        300 power iterations (from below; not proven), or
 *                        the element bound where it is proven and smaller.
 * Where the requested rule does not apply, the solver says so in
 * mfs_dt_info.fallback and uses the next one that does (the order
 * certified -> gershgorin -> power), never silently. */
typedef enum { MFS_DT_GERSHGORIN, MFS_DT_CERTIFIED, MFS_DT_POWER } mfs_dt_rule;

/* "gershgorin", "certified", "power"; parse: MFS_EINVAL if unknown. */
const char *mfs_dt_rule_name(mfs_dt_rule r);
mfs_status mfs_dt_rule_parse(const char *name, mfs_dt_rule *r);

/* ARPACK's relative tolerance of the estimate the certified step starts
 * from: the step needs lambda_max to about 1e-6 (the certificate then moves
 * sigma up by relative gaps from 1e-6), and for a symmetric problem the
 * Ritz value's error is of the order of the squared residual, far below the
 * tolerance (measured: tests/test_solver2d.c). */
#define MFS_DT_ARPACK_TOL 1e-8

/* What the solver's step rule found (all lambda in 1/s^2; NAN: not computed
 * or not applicable). */
typedef struct {
  mfs_dt_rule requested, used;
  double lambda;            /* the value dt_crit = 2 / sqrt(lambda) uses */
  int proven;               /* lambda is a proven upper bound of lambda_max of the
                               linearized model at the initial state */
  double lambda_gershgorin; /* max_i sum_j |K_ij| / m_i */
  double lambda_certified;  /* sigma (1 + margin) of the certificate */
  double lambda_power;      /* the power-iteration estimate (before the 1.05) */
  double lambda_arpack;     /* the Lanczos estimate the certificate started from (the name
                               from when it was always ARPACK's) */
  double arpack_tol;        /* its tolerance (0: no estimate run) */
  const char *estimator;    /* who computed it: "Lanczos" (mfs_lanczos_max, lumped mass) or
                               "ARPACK" (mfs_eig_max); NULL: none */
  int factorizations;       /* of the certificate */
  int power_iterations;     /* 0: none run */
  const char *fallback;     /* why the requested rule did not apply (static text), or NULL */
} mfs_dt_info;

/* The certified step of the pencil (K, lumped m > 0): a Lanczos estimate at
 * MFS_DT_ARPACK_TOL (info->lambda_arpack, arpack_tol, estimator: plain
 * Lanczos, mfs_lanczos_max, for a lumped mass; ARPACK otherwise), then
 * mfs_eig_certify_search from it (info->lambda_certified = sigma (1 +
 * margin), factorizations).  MFS_OK with lambda_certified finite; MFS_EDOMAIN
 * (no sigma certified, or no positive estimate); MFS_ENOMEM; other statuses of
 * mfs_lanczos_max / mfs_eig_max (the caller falls back to another rule). */
mfs_status mfs_dt_certify(const mfs_pencil *P, mfs_dt_info *info);

/* An mfs_dt_info with nothing computed for rule r. */
mfs_dt_info mfs_dt_info_init(mfs_dt_rule r);

/* The element bound's result for the power rule: with bst MFS_OK, br's lambda
 * and negative_phi into *lambda_bound and *negative_phi (else they stay as
 * they are: the power rule then goes without it).  Returns MFS_ENOMEM if bst
 * is (out of memory is not a reason to choose the step without the bound),
 * else MFS_OK. */
static inline mfs_status mfs_dt_take_bound(mfs_status bst, const mfs_bound_result *br,
                                           double *lambda_bound, size_t *negative_phi)
{
  if (bst == MFS_ENOMEM)
    return bst;
  if (bst == MFS_OK) {
    *lambda_bound = br->lambda;
    *negative_phi = br->negative_phi;
  }
  return MFS_OK;
}

/* A solver's ways to a lambda, for mfs_dt_choose. */
typedef struct {
  void *ctx;
  const char *block; /* why neither stiffness rule applies here (static text), or NULL */
  /* the certified step into in (lambda_certified): MFS_OK, MFS_ENOMEM, or
   * another status to fall back, with *why set where the reason is not
   * "no certificate" (static text) */
  mfs_status (*certify)(void *ctx, mfs_dt_info *in, const char **why);
  mfs_status (*gershgorin)(void *ctx, double *lambda);
  mfs_status (*power)(void *ctx, double *lambda, int *iterations);
  /* the power rule's lambda: mfs_step_lambda(power, lambda_bound,
   * negative_phi) times power_scale (1, or an estimate's margin); proven
   * only where it is the element bound, negative_phi is 0 and
   * power_unproven is 0 */
  double lambda_bound;
  size_t negative_phi;
  double power_scale;
  int power_unproven;
} mfs_dt_ops;

/* The step rule's lambda into *step (the solver's record; values it holds
 * are kept, not computed again): the certified step where requested and
 * possible, else the Gershgorin bound unless the power rule was requested,
 * else the power rule; step->used the rule that gave step->lambda,
 * step->fallback why the requested one did not.  *changed = 0 if the rule
 * was already the requested one (nothing done), else 1 on success.  MFS_OK;
 * MFS_EINVAL (no such rule); MFS_EDOMAIN (no lambda); the callbacks'
 * MFS_ENOMEM and errors; *step unchanged on failure. */
mfs_status mfs_dt_choose(const mfs_dt_ops *o, mfs_dt_rule rule, mfs_dt_info *step, int *changed);

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
