/* Explicit integrators for u'' = a(u) (see mfs_explicit.h). */
#include "mfs_explicit.h"

#include <math.h>
#include <string.h>

#include "mfs_bound.h"
#include "mfs_lanczos.h"
#include "mfs_status.h"

static int leapfrog(size_t n, double *u, double *v, double *a, double t1, double dt,
                    mfs_accel_fn accel, mfs_impose_fn impose, void *ctx)
{
  for (size_t i = 0; i < n; i++) {
    v[i] += 0.5 * dt * a[i];
    u[i] += dt * v[i];
  }
  if (impose)
    impose(ctx, u, NULL, t1);
  int st = accel(ctx, u, a);
  if (st != MFS_OK)
    return st;
  for (size_t i = 0; i < n; i++)
    v[i] += 0.5 * dt * a[i];
  if (impose)
    impose(ctx, NULL, v, t1);
  return MFS_OK;
}

/* Runge-Kutta with a_{k,k-1} = c_k the only nonzero stage coefficients:
 * Euler (1 stage), midpoint (2), classical (4). */
static int runge_kutta(int stages, size_t n, double *u, double *v, double *a, double t, double dt,
                       const mfs_explicit_work *w, mfs_accel_fn accel, mfs_impose_fn impose,
                       void *ctx)
{
  static const double b1[1] = {1}, b2[2] = {0, 1}, b4[4] = {1 / 6., 1 / 3., 1 / 3., 1 / 6.};
  const double *b = stages == 1 ? b1 : stages == 2 ? b2 : b4;
  memcpy(w->u0, u, n * sizeof *u);
  memcpy(w->v0, v, n * sizeof *v);
  memcpy(w->ku, v, n * sizeof *v);
  memcpy(w->kv, a, n * sizeof *a);
  for (int k = 1; k < stages; k++) {
    double ck = stages == 4 && k == 3 ? 1.0 : 0.5;
    double *ku = w->ku + k * n, *kv = w->kv + k * n;
    const double *kup = ku - n, *kvp = kv - n;
    for (size_t i = 0; i < n; i++) {
      w->tu[i] = w->u0[i] + ck * dt * kup[i];
      ku[i] = w->v0[i] + ck * dt * kvp[i];
    }
    if (impose)
      impose(ctx, w->tu, ku, t + ck * dt);
    int st = accel(ctx, w->tu, kv);
    if (st != MFS_OK)
      return st;
  }
  for (size_t i = 0; i < n; i++) {
    double du = 0.0, dv = 0.0;
    for (int k = 0; k < stages; k++) {
      du += b[k] * w->ku[k * n + i];
      dv += b[k] * w->kv[k * n + i];
    }
    u[i] = w->u0[i] + dt * du;
    v[i] = w->v0[i] + dt * dv;
  }
  if (impose)
    impose(ctx, u, v, t + dt);
  return accel(ctx, u, a);
}

mfs_status mfs_explicit_step(mfs_scheme scheme, size_t n, double *u, double *v, double *a,
                             double t, double dt, const mfs_explicit_work *w, mfs_accel_fn accel,
                      mfs_impose_fn impose, void *ctx)
{
  mfs_status st;
  switch (scheme) {
  case MFS_SCHEME_LEAPFROG: st = leapfrog(n, u, v, a, t + dt, dt, accel, impose, ctx); break;
  case MFS_SCHEME_EULER: st = runge_kutta(1, n, u, v, a, t, dt, w, accel, impose, ctx); break;
  case MFS_SCHEME_RK2: st = runge_kutta(2, n, u, v, a, t, dt, w, accel, impose, ctx); break;
  case MFS_SCHEME_RK4: st = runge_kutta(4, n, u, v, a, t, dt, w, accel, impose, ctx); break;
  default: return MFS_EINVAL;
  }
  if (st != MFS_OK)
    return st;
  for (size_t i = 0; i < n; i++)
    if (!isfinite(u[i]) || !isfinite(v[i]))
      return MFS_EDOMAIN;
  return MFS_OK;
}

static const char *const scheme_names[] = {"leapfrog", "euler", "rk2", "rk4"};

const char *mfs_scheme_name(mfs_scheme s)
{
  return (unsigned)s < 4 ? scheme_names[s] : "?";
}

mfs_status mfs_scheme_parse(const char *name, mfs_scheme *s)
{
  for (int i = 0; name && i < 4; i++)
    if (strcmp(name, scheme_names[i]) == 0) {
      *s = (mfs_scheme)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

static const char *const dt_rule_names[3] = {
  [MFS_DT_GERSHGORIN] = "gershgorin", [MFS_DT_CERTIFIED] = "certified",
  [MFS_DT_POWER] = "power"};

const char *mfs_dt_rule_name(mfs_dt_rule r)
{
  return (unsigned)r < 3 ? dt_rule_names[r] : "?";
}

mfs_status mfs_dt_rule_parse(const char *name, mfs_dt_rule *r)
{
  for (int i = 0; name && i < 3; i++)
    if (strcmp(name, dt_rule_names[i]) == 0) {
      *r = (mfs_dt_rule)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

mfs_dt_info mfs_dt_info_init(mfs_dt_rule r)
{
  return (mfs_dt_info){.requested = r, .used = r, .lambda = NAN, .lambda_gershgorin = NAN,
                         .lambda_certified = NAN, .lambda_power = NAN, .lambda_arpack = NAN};
}

mfs_status mfs_dt_certify(const mfs_pencil *P, mfs_dt_info *info)
{
  double lam = NAN;
  info->arpack_tol = MFS_DT_ARPACK_TOL;
  mfs_status st;
  if (P->m && !P->M) { /* the estimate needs no eigenvector and no more than ~1e-8 */
    mfs_lanczos_opts lo = {.tol = MFS_DT_ARPACK_TOL};
    info->estimator = "Lanczos";
    st = mfs_lanczos_max(P, &lo, &lam, NULL);
  } else {
    mfs_eig_opts eo = {.tol = MFS_DT_ARPACK_TOL};
    mfs_eig_info ei;
    info->estimator = "ARPACK";
    st = mfs_eig_max(P, &eo, &lam, NULL, &ei);
  }
  if (st != MFS_OK)
    return st;
  info->lambda_arpack = lam;
  if (!(lam > 0.0) || !isfinite(lam))
    return MFS_EDOMAIN;
  mfs_certify_opts co = {.lambda_est = lam};
  mfs_certify_result cr;
  if ((st = mfs_eig_certify_search(P, &co, &cr)) != MFS_OK)
    return st;
  info->factorizations = cr.factorizations;
  if (!cr.ok)
    return MFS_EDOMAIN;
  info->lambda_certified = cr.lambda_upper;
  return MFS_OK;
}

mfs_status mfs_dt_choose(const mfs_dt_ops *o, mfs_dt_rule rule, mfs_dt_info *step, int *changed)
{
  *changed = 0;
  if ((unsigned)rule > MFS_DT_POWER)
    return MFS_EINVAL;
  if (step->requested == rule)
    return MFS_OK;
  mfs_dt_info in = mfs_dt_info_init(rule);
  in.lambda_power = step->lambda_power; /* kept once found */
  in.power_iterations = step->power_iterations;
  in.lambda_gershgorin = step->lambda_gershgorin;
  const char *why = o->block;
  mfs_status st;
  if (rule == MFS_DT_CERTIFIED && !why) {
    const char *na = NULL;
    st = o->certify(o->ctx, &in, &na);
    if (st == MFS_ENOMEM)
      return st;
    if (st == MFS_OK) {
      in.lambda = in.lambda_certified;
      in.proven = 1;
    } else {
      why = na ? na : "no certificate (ARPACK or the factorizations failed)";
    }
  }
  if (isnan(in.lambda) && rule != MFS_DT_POWER && !o->block) {
    if (isnan(in.lambda_gershgorin) &&
        (st = o->gershgorin(o->ctx, &in.lambda_gershgorin)) != MFS_OK)
      return st;
    in.used = MFS_DT_GERSHGORIN;
    if (in.lambda_gershgorin > 0.0 && isfinite(in.lambda_gershgorin)) {
      in.lambda = in.lambda_gershgorin;
      in.proven = 1;
    } else if (!why) {
      why = "the Gershgorin bound is not positive and finite";
    }
  }
  if (isnan(in.lambda)) {
    in.used = MFS_DT_POWER;
    if (isnan(in.lambda_power) &&
        (st = o->power(o->ctx, &in.lambda_power, &in.power_iterations)) != MFS_OK)
      return st;
    in.lambda = mfs_step_lambda(in.lambda_power, o->lambda_bound, o->negative_phi);
    in.proven = !o->power_unproven && in.lambda == o->lambda_bound && o->negative_phi == 0;
    in.lambda *= o->power_scale;
  }
  in.fallback = in.used != rule ? why : NULL;
  if (isnan(in.lambda))
    return MFS_EDOMAIN;
  *step = in;
  *changed = 1;
  return MFS_OK;
}
