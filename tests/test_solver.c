/* Unit tests of the reference explicit solver (lib/mfs_solver.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfs_solver.h"
#include "mfstab.h"

static mfs_solver_spec base(void)
{
  mfs_disc d = mfs_disc_default();
  d.source = (mfs_source){.lattice = MFS_LATTICE_LINE, .nx = 13, .lx = 2.385};
  d.material = (mfs_material){.physics = MFS_PHYS_SCALAR, .density = 1.7, .modulus = 3.1};
  d.kernel = &mfs_kernel_quartic;
  d.shape = &mfs_shape_mls;
  d.dilation = 2.3;
  d.frame = MFS_FRAME_LAGRANGIAN;
  d.quadrature = &mfs_quad_nodal;
  mfs_solver_spec s = {.disc = d,
                       .bc = {MFS_BC_FIXED, MFS_BC_FIXED},
                       .bc_until = {INFINITY, INFINITY},
                       .equilibrate = 1};
  return s;
}

/* Energy of a stable Lagrangian run of 1e5 steps stays bounded (leapfrog:
 * a shadow energy is conserved, so the oscillation does not drift). */
static void test_energy(const char *quad, double S0)
{
  mfs_solver_spec sp = base();
  sp.disc.quadrature = mfs_quad_find(quad);
  sp.disc.material.initial_stress = S0;
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s != NULL, "alloc %s: %s", quad, mfs_strerror(st));
  if (!s)
    return;
  double *v = calloc(s->n, sizeof *v);
  for (size_t I = 1; I + 1 < s->n; I++)
    v[I] = 0.01 * sin(2.7 * (double)I) + 0.02 * cos(0.9 * (double)I);
  CHECK(mfs_solver_set_state(s, NULL, v) == MFS_OK, "set_state");
  free(v);
  /* the leapfrog (shadow-)energy oscillation is O((omega dt)^2); dt_crit (the
   * Gershgorin rule) is at most the true limit 2/omega_max, and at 0.15 of it
   * the oscillation stays below 2% (about 4% at a quarter of the limit) */
  mfs_solver_set_dt(s, 0.15 * s->dt_crit, 0);
  double k, p;
  mfs_solver_energy(s, &k, &p);
  double e0 = k + p, emin = e0, emax = e0;
  for (long i = 0; i < 100000; i++) {
    st = mfs_solver_step(s, MFS_SCHEME_LEAPFROG);
    if (st != MFS_OK)
      break;
    if (i % 100 == 99) {
      mfs_solver_energy(s, &k, &p);
      emin = fmin(emin, k + p);
      emax = fmax(emax, k + p);
    }
  }
  CHECK(st == MFS_OK, "1e5 steps %s: %s", quad, mfs_strerror(st));
  CHECK((emax - emin) / e0 < 0.02, "energy oscillation %s S0=%g: %.3g of %.6g", quad, S0,
        (emax - emin) / e0, e0);
  mfs_solver_energy(s, &k, &p);
  CHECK_NEAR(k + p, e0, 0.02 * e0, "final energy, %s S0=%g", quad, S0);
  mfs_solver_free(s);
}

/* The Lagrangian internal force at small u equals K u with K assembled by the
 * core (scalar stiffness, C = E + S0): f = f0 - m a. */
static void test_linear_force(void)
{
  mfs_solver_spec sp = base();
  sp.disc.material.initial_stress = 0.37;
  sp.bc[0] = sp.bc[1] = MFS_BC_FREE;
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s != NULL, "alloc: %s", mfs_strerror(st));
  if (!s)
    return;
  mfs_lattice_spec ls = {.dim = 1, .lattice = MFS_LATTICE_LINE, .nx = sp.disc.source.nx, .ny = 1,
                         .dx = s->dX, .gamma = 1};
  mfs_particles *p = mfs_lattice_alloc(&ls, &st);
  mfs_quad *q = mfs_quad_alloc(&mfs_quad_nodal, p, &st);
  mfs_plan *pl = mfs_plan_alloc(&sp.disc, p, q, &st);
  mfs_material mat = {.physics = MFS_PHYS_SCALAR,
                      .modulus = sp.disc.material.modulus + sp.disc.material.initial_stress,
                      .density = sp.disc.material.density};
  mfs_csr *K = NULL;
  CHECK(pl && mfs_plan_tabulate(pl, 1, NULL) == MFS_OK &&
          mfs_assemble_stiffness(pl, &mat, &K) == MFS_OK,
        "assemble");
  double *u = calloc(s->n, sizeof *u);
  double eps = 1e-7;
  for (size_t I = 0; I < s->n; I++)
    u[I] = eps * sin(1.3 * (double)I + 0.2);
  mfs_solver_set_state(s, u, NULL);
  double maxerr = 0, maxf = 0;
  for (size_t I = 0; I < s->n && K; I++) {
    double ku = 0;
    for (size_t e = K->ptr[I]; e < K->ptr[I + 1]; e++)
      ku += K->val[e] * u[K->idx[e]];
    double f = -s->m[I] * s->a[I];
    maxerr = fmax(maxerr, fabs(f - ku));
    maxf = fmax(maxf, fabs(ku));
  }
  CHECK(maxerr < 1e-5 * maxf, "f_int(u) vs K u: max diff %.3g of %.3g", maxerr, maxf);
  /* masses: rho V_I, summing to rho L */
  double msum = 0;
  for (size_t I = 0; I < s->n; I++)
    msum += s->m[I];
  CHECK_NEAR(msum, sp.disc.material.density * sp.disc.source.lx, 1e-12, "total mass");
  free(u);
  mfs_csr_free(K);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  mfs_solver_free(s);
}

/* Stable step: the power estimate is an eigenvalue (<= the bound where the
 * bound is guaranteed); steps above dt_crit are refused unless forced; an
 * unstable forced step diverges, a step just below does not. */
static void test_dt(void)
{
  mfs_solver_spec sp = base();
  sp.disc.shape = &mfs_shape_sph; /* phi > 0: eq. 132 is a guaranteed bound */
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s != NULL, "alloc sph: %s", mfs_strerror(st));
  if (!s)
    return;
  CHECK(s->negative_phi == 0, "sph: negative phi at %zu points", s->negative_phi);
  CHECK(s->lambda_power <= s->lambda_bound * (1 + 1e-9), "power %.6g <= bound %.6g",
        s->lambda_power, s->lambda_bound);
  CHECK_NEAR(s->dt, 0.9 * s->dt_crit, 1e-15, "default dt");
  CHECK(mfs_solver_set_dt(s, 1.01 * s->dt_crit, 0) == MFS_EINVAL, "dt above the limit refused");
  CHECK(mfs_solver_set_dt(s, -1.0, 1) == MFS_EINVAL, "negative dt refused");
  CHECK(mfs_solver_set_dt(s, 1.01 * s->dt_crit, 1) == MFS_OK, "forced dt accepted");
  mfs_solver_free(s);
  /* exact limit: with the power estimate alone (mls, equal to lambda_max) */
  sp = base();
  s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s && mfs_solver_choose_step(s, MFS_DT_POWER) == MFS_OK, "power rule");
  double lam = s->lambda_power, dtc = 2.0 / sqrt(lam);
  double *u = calloc(s->n, sizeof *u);
  for (int pass = 0; pass < 2; pass++) {
    for (size_t I = 1; I + 1 < s->n; I++)
      u[I] = 1e-9 * ((I * 7919) % 13 - 6.0);
    mfs_solver_reset(s);
    mfs_solver_set_state(s, u, NULL);
    mfs_solver_set_dt(s, (pass ? 1.02 : 0.98) * dtc, 1);
    double umax = 0;
    for (int i = 0; i < 4000 && st == MFS_OK; i++) {
      st = mfs_solver_step(s, MFS_SCHEME_LEAPFROG);
      for (size_t I = 0; I < s->n; I++)
        umax = fmax(umax, fabs(s->u[I]));
    }
    if (pass == 0)
      CHECK(umax < 1e-7, "dt = 0.98 dt_crit (power): bounded, max |u| %.3g", umax);
    else
      CHECK(umax > 1e-6 || st != MFS_OK, "dt = 1.02 dt_crit (power): grows, max |u| %.3g", umax);
    st = MFS_OK;
  }
  free(u);
  mfs_solver_free(s);
}

/* Convergence orders of the four schemes on the same discretization, against
 * an RK4 reference with a tiny step. */
static void test_orders(void)
{
  mfs_solver_spec sp = base();
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  if (!s)
    return;
  double *v0 = calloc(s->n, sizeof *v0), *ref = calloc(s->n, sizeof *ref);
  for (size_t I = 1; I + 1 < s->n; I++)
    v0[I] = 1e-3 * sin(M_PI * (double)I / (double)(s->n - 1));
  double T = 20 * s->dt_crit;
  mfs_scheme sch[4] = {MFS_SCHEME_EULER, MFS_SCHEME_RK2, MFS_SCHEME_LEAPFROG, MFS_SCHEME_RK4};
  int order[4] = {1, 2, 2, 4};
  /* reference */
  mfs_solver_reset(s);
  mfs_solver_set_state(s, NULL, v0);
  mfs_solver_set_dt(s, T / 4000, 0);
  for (int i = 0; i < 4000; i++)
    mfs_solver_step(s, MFS_SCHEME_RK4);
  memcpy(ref, s->u, s->n * sizeof *ref);
  for (int k = 0; k < 4; k++) {
    double err[2];
    for (int h = 0; h < 2; h++) {
      int nst = (k == 0 ? 4000 : 200) << h;
      mfs_solver_reset(s);
      mfs_solver_set_state(s, NULL, v0);
      mfs_solver_set_dt(s, T / nst, 0);
      for (int i = 0; i < nst; i++)
        mfs_solver_step(s, sch[k]);
      CHECK_NEAR(s->t, T, 1e-12 * T, "%s end time", mfs_scheme_name(sch[k]));
      err[h] = 0;
      for (size_t I = 0; I < s->n; I++)
        err[h] = fmax(err[h], fabs(s->u[I] - ref[I]));
    }
    double p = log2(err[0] / err[1]);
    CHECK(fabs(p - order[k]) < 0.25, "%s observed order %.3f, want %d (errors %.3g %.3g)",
          mfs_scheme_name(sch[k]), p, order[k], err[0], err[1]);
  }
  free(v0);
  free(ref);
  mfs_solver_free(s);
}

/* Eulerian kernel at rest under uniform stress in a periodic rod: an
 * equilibrium; a uniform translation is a rigid motion (no force). */
static void test_eulerian_rigid(void)
{
  mfs_solver_spec sp = base();
  sp.disc.source.nx = 24;
  sp.disc.source.periodic = 1;
  sp.disc.frame = MFS_FRAME_EULERIAN;
  sp.disc.material.initial_stress = 0.29;
  sp.equilibrate = 0;
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s != NULL, "alloc eulerian: %s", mfs_strerror(st));
  if (!s)
    return;
  double *u = calloc(s->n, sizeof *u), amax = 0;
  for (size_t I = 0; I < s->n; I++)
    u[I] = 0.6 * s->dX; /* rigid shift across the skin: forces a new search */
  CHECK(mfs_solver_set_state(s, u, NULL) == MFS_OK, "set_state");
  for (size_t I = 0; I < s->n; I++)
    amax = fmax(amax, fabs(s->a[I]));
  CHECK(amax < 1e-10 * sp.disc.material.initial_stress / (sp.disc.material.density * s->dX), "rigid shift: max |a| %.3g",
        amax);
  CHECK(s->searches >= 2, "neighbour search repeated after a move beyond the skin (%ld)",
        s->searches);
  free(u);
  mfs_solver_free(s);
}

/* The step rules on the rod's scenes: the Gershgorin bound of K(Cbar) is at
 * least lambda_max and at most twice it; lambda_max by two independent paths
 * agrees (the ARPACK value of the assembled K(Cbar) of the certified rule and
 * the power iteration on finite differences of the nonlinear force, which
 * shows K(Cbar) is the force's linearization); the certificate lies above
 * both, within 1e-5; a leapfrog run at the default step (0.9 of the Gershgorin
 * dt_crit) keeps its energy bounded.  The Eulerian rod with S0 != 0 falls
 * back to the power rule and says so. */
static void test_rules(const char *what, int euler, const char *quad, double S0, int free_ends)
{
  mfs_solver_spec sp = base();
  sp.disc.source.nx = 41;
  sp.disc.quadrature = mfs_quad_find(quad);
  sp.disc.material.initial_stress = S0;
  if (euler)
    sp.disc.frame = MFS_FRAME_EULERIAN;
  if (free_ends)
    sp.bc[0] = sp.bc[1] = MFS_BC_FREE;
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s != NULL, "%s: alloc: %s", what, mfs_strerror(st));
  if (!s)
    return;
  mfs_dt_info g = s->step;
  if (euler && S0 != 0.0) {
    CHECK(g.used == MFS_DT_POWER && g.fallback && !g.proven && g.power_iterations == 300,
          "%s: Gershgorin does not apply: used %s, fallback %s", what, mfs_dt_rule_name(g.used),
          g.fallback ? g.fallback : "(none)");
    CHECK(mfs_solver_choose_step(s, MFS_DT_CERTIFIED) == MFS_OK && s->step.used == MFS_DT_POWER &&
              s->step.fallback,
          "%s: certified falls back to power", what);
    printf("%s: fallback to power: %s\n", what, g.fallback ? g.fallback : "");
    mfs_solver_free(s);
    return;
  }
  CHECK(g.used == MFS_DT_GERSHGORIN && g.proven && !g.fallback && g.power_iterations == 0,
        "%s: default rule %s (power iterations %d)", what, mfs_dt_rule_name(g.used),
        g.power_iterations);
  CHECK_NEAR(s->dt_crit, 2.0 / sqrt(g.lambda_gershgorin), 1e-15 * s->dt_crit, "%s: dt_crit", what);
  double dt0 = s->dt;
  CHECK(mfs_solver_choose_step(s, MFS_DT_POWER) == MFS_OK, "%s: power", what);
  double lp = s->step.lambda_power;
  CHECK(mfs_solver_choose_step(s, MFS_DT_CERTIFIED) == MFS_OK && s->step.used == MFS_DT_CERTIFIED,
        "%s: certified used %s", what, mfs_dt_rule_name(s->step.used));
  double la = s->step.lambda_arpack, lc = s->step.lambda_certified;
  CHECK(lp <= la * (1 + 1e-6) && lp >= la * (1 - 1e-3),
        "%s: power (force differences, from below) %.10g vs ARPACK (K(Cbar)) %.10g", what, lp, la);
  CHECK(lc >= la * (1 - 1e-12) && lc <= la * (1 + 1e-5), "%s: certified / ARPACK - 1 = %.3g", what,
        lc / la - 1.0);
  double rg = g.lambda_gershgorin / la;
  CHECK(rg >= 1.0 - 1e-12 && rg <= 2.0, "%s: Gershgorin / lambda_max = %.6f outside [1, 2]", what, rg);
  CHECK(s->step.arpack_tol == MFS_DT_ARPACK_TOL, "%s: tolerance reported %g", what,
        s->step.arpack_tol);
  int nfact = s->step.factorizations;
  /* back to the default step: a leapfrog run keeps its energy bounded (the
   * physical energy of the leapfrog oscillates by O((omega dt)^2): its
   * range over the second half of the run is no larger than over the first) */
  CHECK(mfs_solver_choose_step(s, MFS_DT_GERSHGORIN) == MFS_OK && s->dt == dt0, "%s: back", what);
  double *v = calloc(s->n, sizeof *v);
  for (size_t I = 0; I < s->n; I++)
    v[I] = 1e-3 * (sin(2.7 * (double)I) + 2.0 * cos(0.9 * (double)I));
  CHECK(mfs_solver_set_state(s, NULL, v) == MFS_OK, "%s: set_state", what);
  free(v);
  double k, p;
  mfs_solver_energy(s, &k, &p);
  const long nst = 20000;
  double e0 = k + p, osc[2] = {0.0, 0.0};
  for (long i = 0; i < nst && st == MFS_OK; i++) {
    st = mfs_solver_step(s, MFS_SCHEME_LEAPFROG);
    if (i % 10 == 9) {
      mfs_solver_energy(s, &k, &p);
      double d = fabs(k + p - e0) / e0;
      osc[2 * i >= nst] = fmax(osc[2 * i >= nst], isfinite(d) ? d : INFINITY);
    }
  }
  CHECK(st == MFS_OK, "%s: run: %s", what, mfs_strerror(st));
  CHECK(osc[1] <= 1.1 * osc[0], "%s: energy range at the default step grows: %.3g then %.3g of E0",
        what, osc[0], osc[1]);
  printf("%s: lambda_max %.8g (power %.8g), Gershgorin / lambda_max %.4f, certified / lambda_max "
         "- 1 = %.2g (%d factorizations); 2e4 leapfrog steps at 0.9 of the Gershgorin dt_crit: "
         "max |E - E0| / E0 %.3g (first half), %.3g (second half)\n",
         what, la, lp, rg, lc / la - 1.0, nfact, osc[0], osc[1]);
  mfs_solver_free(s);
}

static void test_errors(void)
{
  mfs_status st;
  mfs_solver_spec sp = base();
  sp.disc.material.density = -1;
  CHECK(mfs_solver_alloc(&sp, &st, NULL) == NULL && st == MFS_EINVAL, "negative density");
  sp = base();
  sp.disc.quadrature = mfs_quad_find("stress-quad");
  CHECK(mfs_solver_alloc(&sp, &st, NULL) == NULL && st == MFS_EINVAL, "2D rule refused");
  sp = base();
  sp.disc.dilation = 0.6;
  size_t bad = 99;
  CHECK(mfs_solver_alloc(&sp, &st, &bad) == NULL && st == MFS_ESINGULAR, "D = 0.6: %s",
        mfs_strerror(st));
  sp = base();
  sp.disc.source.periodic = 1;
  sp.disc.source.nx = 4;
  CHECK(mfs_solver_alloc(&sp, &st, NULL) == NULL && st == MFS_ETOOSMALL, "too small: %s",
        mfs_strerror(st));
  mfs_scheme sc;
  CHECK(mfs_scheme_parse("rk3", &sc) == MFS_EINVAL, "unknown scheme");
  CHECK(mfs_scheme_parse("rk4", &sc) == MFS_OK && sc == MFS_SCHEME_RK4, "rk4 parsed");
  mfs_dt_rule r;
  CHECK(mfs_dt_rule_parse("gauss", &r) == MFS_EINVAL, "unknown step rule");
  CHECK(mfs_dt_rule_parse("certified", &r) == MFS_OK && r == MFS_DT_CERTIFIED, "rule parsed");
  sp = base();
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  CHECK(s && mfs_solver_choose_step(s, (mfs_dt_rule)7) == MFS_EINVAL, "rule 7 refused");
  mfs_solver_free(s);
  mfs_solver_free(NULL);
}

int main(void)
{
  test_energy("nodal", 0.0);
  test_energy("stress", 0.0);
  test_energy("gauss2", 0.8);
  test_linear_force();
  test_dt();
  test_orders();
  test_eulerian_rigid();
  test_rules("rod lagrangian nodal", 0, "nodal", 0.0, 0);
  test_rules("rod lagrangian gauss2 S0 = 0.8 free", 0, "gauss2", 0.8, 1);
  test_rules("rod lagrangian stress S0 = -0.9", 0, "stress", -0.9, 0);
  test_rules("rod eulerian nodal", 1, "nodal", 0.0, 0);
  test_rules("rod eulerian nodal S0 = 0.29", 1, "nodal", 0.29, 0);
  test_errors();
  return check_summary("test_solver");
}
