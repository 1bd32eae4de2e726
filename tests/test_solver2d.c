/* Unit tests of the linear explicit solver (lib/mfs_solver2d.h). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static const double MU = 2.3, RHO = 1.7, NU = 0.27;

static mfs_model_spec spec2d(int nx, int ny, double lx, double ly, const char *quad,
                             mfs_physics_kind phys)
{
  mfs_model_spec s = mfs_model_spec_default();
  mfs_disc *d = &s.disc;
  d->dim = 2;
  d->source = (mfs_source){
    .lattice = MFS_LATTICE_SQUARE, .nx = nx, .ny = ny, .lx = lx, .ly = ly, .periodic = 1};
  d->kernel = &mfs_kernel_cubic;
  d->shape = &mfs_shape_mls;
  d->dilation = 2.0;
  d->quadrature = mfs_quad_find(quad);
  d->material =
    (mfs_material){.physics = phys, .modulus = MU, .density = RHO, .poisson = NU};
  return s;
}

static mfs_solver2d *alloc_ok(const mfs_model_spec *sp, const char *what)
{
  mfs_status st;
  mfs_solver2d *s = mfs_solver2d_alloc(sp, &st, NULL);
  CHECK(s != NULL, "%s: alloc: %s", what, mfs_strerror(st));
  return s;
}

static double max_abs(const double *x, size_t n)
{
  double m = 0.0;
  for (size_t i = 0; i < n; i++)
    m = fmax(m, fabs(x[i]));
  return m;
}

/* The Bloch symbol of the periodic box's configuration at the lattice wave
 * vector k = 2 pi (m1/lx, m2/ly): omega^2 (in c^2/dx^2, c^2 = mu/rho) of
 * branch `branch` (ascending) and its polarization e (ndof components). */
static int bloch_symbol(const mfs_model_spec *sp, int m1, int m2, int branch, double *omega2,
                        double *e)
{
  const mfs_source *src = &sp->disc.source;
  mfs_disp_spec ds = {.disc = sp->disc, .stretch = 1.0};
  ds.disc.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE,
                                .spacing = 1.0,
                                .gamma = (src->ly / src->ny) / (src->lx / src->nx)};
  ds.disc.frame = MFS_FRAME_LAGRANGIAN;
  mfs_status st;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&ds, &st);
  CHECK(pl != NULL, "disp plan: %s", mfs_strerror(st));
  if (!pl)
    return st;
  int nb = mfs_disp_branches(pl);
  double k[2] = {2 * M_PI * m1 / src->nx, 2 * M_PI * m2 / src->ny / ds.disc.source.gamma};
  double complex K[4], M[4], w2[2];
  st = mfs_disp_symbols(pl, 0.0, k, K, M);
  CHECK(st == MFS_OK && nb <= 2, "symbols: %s, %d branches", mfs_strerror(st), nb);
  /* lumped mass: M(k) = diag(1) in the normalized units, K(k) real symmetric
   * (the lattice is symmetric under inversion) */
  double imag = 0.0;
  for (int i = 0; i < nb * nb; i++)
    imag = fmax(imag, fabs(cimag(K[i])) + fabs(cimag(M[i])));
  CHECK(imag < 1e-12, "symbols real: imaginary part %.3g", imag);
  if (nb == 1) {
    *omega2 = creal(K[0]) / creal(M[0]);
    e[0] = 1.0;
  } else {
    double a = creal(K[0]) / creal(M[0]), b = creal(K[1]) / creal(M[0]),
           d = creal(K[3]) / creal(M[3]);
    double h = 0.5 * (a - d), r = hypot(h, b);
    double lam = 0.5 * (a + d) + (branch ? r : -r);
    /* eigenvector (b, lam - a) or (lam - d, b), the better conditioned */
    double e0 = b, e1 = lam - a;
    if (hypot(lam - d, b) > hypot(e0, e1)) {
      e0 = lam - d;
      e1 = b;
    }
    double ne = hypot(e0, e1);
    e[0] = e0 / ne;
    e[1] = e1 / ne;
    *omega2 = lam;
  }
  /* the same from the branch solver */
  st = mfs_disp_omega2(pl, 0.0, hypot(k[0], k[1]) / M_PI, atan2(k[1], k[0]), w2);
  CHECK(st == MFS_OK, "omega2: %s", mfs_strerror(st));
  CHECK_NEAR(creal(w2[branch]), *omega2, 1e-12 * fmax(1.0, *omega2),
             "mfs_disp_omega2 vs symbol, k = (%d, %d) branch %d", m1, m2, branch);
  mfs_disp_plan_free(pl);
  return MFS_OK;
}

/* Test 1.  Periodic box, Bloch mode u = e cos(k.X), v = 0: an eigenvector
 * of M^-1 K with eigenvalue omega^2 = the Bloch symbol, so the leapfrog
 * (central difference) gives exactly u_n = cos(n theta) u_0 with
 * cos(theta) = 1 - dt^2 omega^2 / 2, and the RK schemes u_n = Re(R(i omega
 * dt)^n) u_0 with R their stability polynomial. */
static void test_bloch(const mfs_model_spec *sp, int m1, int m2, int branch,
                       mfs_scheme scheme, double dtfrac, long nsteps)
{
  char what[96];
  snprintf(what, sizeof what, "bloch %s %s k=(%d,%d) branch %d %s",
           sp->disc.material.physics == MFS_PHYS_SCALAR ? "anti-plane" : "plane-strain",
           sp->disc.quadrature->name, m1,
           m2, branch, mfs_scheme_name(scheme));
  double w2n, e[2];
  if (bloch_symbol(sp, m1, m2, branch, &w2n, e) != MFS_OK)
    return;
  mfs_solver2d *s = alloc_ok(sp, what);
  if (!s)
    return;
  size_t n = s->n;
  double dx = s->model->dx, omega2 = w2n * MU / RHO / (dx * dx);
  double kx = 2 * M_PI * m1 / sp->disc.source.lx, ky = 2 * M_PI * m2 / sp->disc.source.ly;
  double *u0 = malloc(n * sizeof *u0);
  for (size_t i = 0; i < n; i++)
    u0[i] = 0.731 * e[s->comp[i]] * cos(kx * s->X[i] + ky * s->Y[i]);
  double amp = max_abs(u0, n);
  CHECK(mfs_solver2d_set_state(s, u0, NULL) == MFS_OK, "%s: set_state", what);
  /* static identity: a = -omega^2 u0 */
  double res = 0.0;
  for (size_t i = 0; i < n; i++)
    res = fmax(res, fabs(s->a[i] + omega2 * u0[i]));
  CHECK(res < 1e-11 * omega2 * amp, "%s: |M^-1 K u + omega^2 u| = %.3g (omega^2 %.6g)", what,
        res, omega2);
  CHECK(mfs_solver2d_set_dt(s, dtfrac * s->dt_crit, 0) == MFS_OK, "%s: set_dt", what);
  double dt = s->dt, th = acos(1.0 - 0.5 * dt * dt * omega2);
  double complex z = I * sqrt(omega2) * dt;
  double complex R = scheme == MFS_SCHEME_EULER ? 1 + z
                     : scheme == MFS_SCHEME_RK2 ? 1 + z + z * z / 2
                                                : 1 + z + z * z / 2 + z * z * z / 6 + z * z * z * z / 24;
  double complex Rn = 1.0;
  double err = 0.0;
  mfs_status st = MFS_OK;
  for (long it = 1; it <= nsteps && st == MFS_OK; it++) {
    st = mfs_solver2d_step(s, scheme);
    Rn *= R;
    if (it % 50 && it != nsteps)
      continue;
    double f = scheme == MFS_SCHEME_LEAPFROG ? cos((double)it * th) : creal(Rn);
    for (size_t i = 0; i < n; i++)
      err = fmax(err, fabs(s->u[i] - f * u0[i]) / amp);
  }
  CHECK(st == MFS_OK, "%s: step: %s", what, mfs_strerror(st));
  CHECK(err < 1e-9, "%s: max |u - u_exact| / max|u0| = %.3g", what, err);
  printf("%s: omega^2 dx^2/c^2 = %.10f, dt = %.3f dt_crit, %ld steps (t omega = %.1f), "
         "static residual %.2g, max rel error %.2g\n",
         what, w2n, dtfrac, nsteps, s->t * sqrt(omega2), res / (omega2 * amp), err);
  free(u0);
  mfs_solver2d_free(s);
}

static void tests_bloch(void)
{
  mfs_model_spec ap = spec2d(16, 16, 1.9, 1.9, "gauss2", MFS_PHYS_SCALAR);
  test_bloch(&ap, 3, 0, 0, MFS_SCHEME_LEAPFROG, 0.3, 3000);
  test_bloch(&ap, 2, 2, 0, MFS_SCHEME_LEAPFROG, 0.3, 3000); /* 45 degrees */
  test_bloch(&ap, 5, 3, 0, MFS_SCHEME_LEAPFROG, 0.9, 3000);
  mfs_model_spec ps = spec2d(16, 16, 1.9, 1.9, "gauss2", MFS_PHYS_PLANE_STRAIN);
  test_bloch(&ps, 3, 0, 0, MFS_SCHEME_LEAPFROG, 0.3, 2000); /* S: u_y */
  test_bloch(&ps, 3, 0, 1, MFS_SCHEME_LEAPFROG, 0.3, 2000); /* P: u_x */
  test_bloch(&ps, 2, 2, 1, MFS_SCHEME_LEAPFROG, 0.3, 2000);
  test_bloch(&ps, 4, 1, 0, MFS_SCHEME_LEAPFROG, 0.9, 2000); /* oblique polarization */
  /* the RK schemes: the same identity with their stability polynomials */
  test_bloch(&ap, 2, 2, 0, MFS_SCHEME_RK4, 0.3, 500);
  test_bloch(&ap, 2, 2, 0, MFS_SCHEME_RK2, 0.05, 200);
  test_bloch(&ap, 2, 2, 0, MFS_SCHEME_EULER, 0.02, 200);
  /* rectangular cells: dy != dx */
  mfs_model_spec rect = spec2d(16, 12, 1.9, 1.9 * 12 / 16 * 1.3, "gauss2", MFS_PHYS_SCALAR);
  test_bloch(&rect, 3, 2, 0, MFS_SCHEME_LEAPFROG, 0.9, 1000);
}

/* Test 2.  Nodal integration: the checkerboard u = (-1)^(i+j), k = (pi/dx,
 * pi/dx), has no gradient at any particle (grad phi_J(X_I) is odd in
 * X_J - X_I), so K u = 0 and u stays put; so do k = (pi/dx, 0) and (0,
 * pi/dx).  With gauss2 they have energy and the checkerboard oscillates
 * (cubic MLS, D = 2: omega^2 = 0.044 c^2/dx^2 at (pi, pi), small but not
 * zero; 0.51 at (pi, 0)). */
static void test_zero_mode(const char *quad, int zero)
{
  mfs_model_spec sp = spec2d(16, 16, 1.9, 1.9, quad, MFS_PHYS_SCALAR);
  double w2[3], e[2];
  const int mk[3][2] = {{8, 8}, {8, 0}, {0, 8}}; /* (pi, pi), (pi, 0), (0, pi) */
  for (int c = 0; c < 3; c++) {
    bloch_symbol(&sp, mk[c][0], mk[c][1], 0, &w2[c], e);
    if (zero)
      CHECK(fabs(w2[c]) < 1e-12, "%s: omega^2 at k = (%d, %d) pi/8 dx: %.3g, want 0", quad,
            mk[c][0], mk[c][1], w2[c]);
    else
      CHECK(w2[c] > 0.01, "%s: omega^2 at k = (%d, %d) pi/8 dx: %.3g, want > 0.01", quad,
            mk[c][0], mk[c][1], w2[c]);
  }
  mfs_solver2d *s = alloc_ok(&sp, quad);
  if (!s)
    return;
  size_t n = s->n;
  double *u0 = malloc(n * sizeof *u0);
  for (size_t i = 0; i < n; i++) {
    long ij = lround(s->X[i] / s->model->dx) + lround(s->Y[i] / s->model->dy);
    u0[i] = ij % 2 ? -0.613 : 0.613;
  }
  mfs_solver2d_set_state(s, u0, NULL);
  double amax = max_abs(s->a, n), du = 0.0;
  for (int it = 0; it < 1000; it++) {
    CHECK(mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG) == MFS_OK, "%s: step", quad);
    for (size_t i = 0; i < n; i++)
      du = fmax(du, fabs(s->u[i] - u0[i]));
  }
  if (zero)
    CHECK(du < 1e-10, "%s: checkerboard moved by %.3g in 1000 steps", quad, du);
  else
    CHECK(du > 0.1, "%s: checkerboard moved by only %.3g in 1000 steps", quad, du);
  printf("zero mode %s: omega^2 dx^2/c^2 at (pi,pi) %.3g, (pi,0) %.3g, (0,pi) %.3g; "
         "|a(0)| %.3g (lambda_max |u| = %.3g); max |u - u0| over 1000 steps at 0.9 dt_crit "
         "= %.3g of 0.613\n",
         quad, w2[0], w2[1], w2[2], amax, s->lambda * 0.613, du);
  free(u0);
  mfs_solver2d_free(s);
}

/* Remove from v its M-orthogonal projection on the admissible rigid fields
 * (free plate: two translations and the rotation), so that the run does not
 * drift away: K u = -M a is then computed from a bounded u. */
static void remove_rigid(const mfs_solver2d *s, double *v)
{
  size_t n = s->n;
  double *r = malloc(3 * n * sizeof *r);
  int nr = mfs_model_rigid_fields(s->model, r);
  for (int k = 0; k < nr; k++) { /* Gram-Schmidt in the M inner product */
    double *rk = r + k * n;
    for (int l = 0; l < k; l++) {
      double d = 0.0;
      for (size_t i = 0; i < n; i++)
        d += s->m[i] * rk[i] * r[l * n + i];
      for (size_t i = 0; i < n; i++)
        rk[i] -= d * r[l * n + i];
    }
    double nn = 0.0, d = 0.0;
    for (size_t i = 0; i < n; i++) {
      nn += s->m[i] * rk[i] * rk[i];
      d += s->m[i] * rk[i] * v[i];
    }
    for (size_t i = 0; i < n; i++) {
      rk[i] /= sqrt(nn);
      v[i] -= d / nn * rk[i] * sqrt(nn);
    }
  }
  free(r);
}

/* Test 3.  Energy of a stable leapfrog run (velocities at whole steps).
 * The modified energy H = E - dt^2/8 a^T M a, i.e. the kinetic energy
 * 1/2 v_{n-1/2}^T M v_{n+1/2} of the half-step velocities plus the
 * potential, is exactly conserved; the physical energy E = H + dt^2/8 a^T M a
 * >= H oscillates above it by O((omega dt)^2) of the pulse's frequencies,
 * without drift. */
static void test_energy(mfs_fix_kind fixed, const char *quad, double dtfrac, double osc_tol)
{
  mfs_model_spec sp = spec2d(12, 10, 2.385, 1.9, quad, MFS_PHYS_PLANE_STRAIN);
  sp.disc.source.periodic = 0;
  sp.fixed = fixed;
  char what[64];
  snprintf(what, sizeof what, "%s plate %s %.1f dt_crit",
           fixed == MFS_FIX_NONE ? "free" : "fixed", quad, dtfrac);
  mfs_solver2d *s = alloc_ok(&sp, what);
  if (!s)
    return;
  size_t n = s->n;
  double *v = malloc(n * sizeof *v), x0 = 0.41 * sp.disc.source.lx, y0 = 0.57 * sp.disc.source.ly, w = 0.35 * sp.disc.source.lx;
  for (size_t i = 0; i < n; i++) {
    double r2 = (s->X[i] - x0) * (s->X[i] - x0) + (s->Y[i] - y0) * (s->Y[i] - y0);
    v[i] = (s->comp[i] ? 0.35 : 0.83) * exp(-r2 / (w * w));
  }
  remove_rigid(s, v);
  mfs_solver2d_set_state(s, NULL, v);
  free(v);
  mfs_solver2d_set_dt(s, dtfrac * s->dt_crit, 0);
  enum { NSTEP = 10000, NAVG = 1000 };
  double k, p, h0, e0;
  mfs_solver2d_energy(s, &k, &p, &h0);
  e0 = k + p;
  double emin = e0, emax = e0, hmin = h0, hmax = h0, first = 0.0, last = 0.0;
  mfs_status st = MFS_OK;
  for (int it = 1; it <= NSTEP && st == MFS_OK; it++) {
    st = mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG);
    double h;
    mfs_solver2d_energy(s, &k, &p, &h);
    emin = fmin(emin, k + p);
    emax = fmax(emax, k + p);
    hmin = fmin(hmin, h);
    hmax = fmax(hmax, h);
    if (it <= NAVG)
      first += (k + p) / NAVG;
    if (it > NSTEP - NAVG)
      last += (k + p) / NAVG;
  }
  CHECK(st == MFS_OK, "%s: step: %s", what, mfs_strerror(st));
  CHECK((hmax - hmin) / h0 < 1e-12, "%s: modified energy oscillation %.3g of %.6g", what,
        (hmax - hmin) / h0, h0);
  CHECK(emin >= hmin, "%s: physical energy %.17g below the modified %.17g", what, emin, hmin);
  CHECK((emax - emin) / e0 < osc_tol, "%s: physical energy oscillation %.3g of %.6g > %g", what,
        (emax - emin) / e0, e0, osc_tol);
  CHECK(fabs(last - first) / e0 < 1e-3, "%s: physical energy drift (mean of last - first 1000) %.3g",
        what, (last - first) / e0);
  printf("energy %s (n = %zu, lambda from %s): 1e4 steps, modified energy oscillation %.2g, "
         "physical energy oscillation %.3g (< %g), drift %.2g\n",
         what, n, mfs_dt_rule_name(s->step.used), (hmax - hmin) / h0,
         (emax - emin) / e0, osc_tol, (last - first) / e0);
  mfs_solver2d_free(s);
}

/* Test 4.  dt_crit against the exact lambda_max (dense eigenvalues), and
 * the time-domain limit: seeded with the top eigenvector, the leapfrog
 * grows at 1.1 dt_crit and not at 0.99 of the exact limit. */
static void test_dt(mfs_physics_kind phys, const char *quad)
{
  mfs_model_spec sp = spec2d(10, 9, 1.7, 1.53, quad, phys);
  char what[64];
  snprintf(what, sizeof what, "dt %s %s", phys == MFS_PHYS_SCALAR ? "anti-plane" : "plane-strain",
           quad);
  mfs_solver2d *s = alloc_ok(&sp, what);
  if (!s)
    return;
  size_t n = s->n;
  mfs_pencil P = {s->model->K, NULL, s->model->m};
  double *wd = malloc(n * sizeof *wd), *top = malloc(n * sizeof *top), lam_top;
  CHECK(mfs_eig_dense(&P, wd) == MFS_OK, "%s: dense", what);
  double lmax = wd[n - 1], dt_exact = 2.0 / sqrt(lmax);
  CHECK(mfs_eig_max(&P, NULL, &lam_top, top, NULL) == MFS_OK, "%s: eig_max", what);
  CHECK_NEAR(lam_top / lmax, 1.0, 1e-10, "%s: ARPACK vs dense lambda_max", what);
  /* the default rule: the Gershgorin bound, proven, above lambda_max and at most 2 times it */
  const mfs_dt_info *g = &s->step;
  double rg = g->lambda_gershgorin / lmax;
  CHECK(g->used == MFS_DT_GERSHGORIN && g->proven && !g->fallback, "%s: default rule %s", what,
        mfs_dt_rule_name(g->used));
  CHECK(rg >= 1.0 - 1e-12 && rg <= 2.0, "%s: Gershgorin / lambda_max = %.6f outside [1, 2]", what,
        rg);
  CHECK_NEAR(s->dt_crit, 2.0 / sqrt(g->lambda_gershgorin), 1e-15 * s->dt_crit, "%s: dt_crit", what);
  /* certified: proven and within 1e-5 of lambda_max; its ARPACK estimate at
   * MFS_DT_ARPACK_TOL against the dense value (the stopping rule of the step) */
  CHECK(mfs_solver2d_choose_step(s, MFS_DT_CERTIFIED) == MFS_OK, "%s: certified", what);
  double rc = s->step.lambda_certified / lmax, ea = fabs(s->step.lambda_arpack / lmax - 1.0);
  CHECK(s->step.used == MFS_DT_CERTIFIED && s->step.proven, "%s: certified used %s", what,
        mfs_dt_rule_name(s->step.used));
  CHECK(rc >= 1.0 - 1e-12 && rc <= 1.0 + 1e-5, "%s: certified / lambda_max - 1 = %.3g", what,
        rc - 1.0);
  CHECK(ea <= 1e-8, "%s: ARPACK at tol %g: relative error %.3g", what, s->step.arpack_tol, ea);
  printf("%s: Gershgorin / lambda_max %.4f, certified / lambda_max - 1 = %.2g (%d factorizations), "
         "ARPACK at tol %g: relative error %.2g\n",
         what, rg, rc - 1.0, s->step.factorizations, s->step.arpack_tol, ea);
  /* the power rule (kept for comparison): safe, and within the 1.05 safety */
  CHECK(mfs_solver2d_choose_step(s, MFS_DT_POWER) == MFS_OK, "%s: power", what);
  CHECK(s->lambda_power <= lmax * (1 + 1e-12), "%s: power estimate %.10g above lambda_max %.10g",
        what, s->lambda_power, lmax);
  CHECK(s->dt_crit <= dt_exact, "%s: dt_crit %.8g above the limit %.8g", what, s->dt_crit,
        dt_exact);
  CHECK(s->dt_crit >= dt_exact / sqrt(1.05) * (1 - 1e-12), "%s: dt_crit %.8g below %.8g / sqrt(1.05)",
        what, s->dt_crit, dt_exact);
  CHECK_NEAR(s->dt, 0.9 * s->dt_crit, 1e-15 * s->dt, "%s: default dt", what);
  CHECK(mfs_solver2d_set_dt(s, 1.01 * s->dt_crit, 0) == MFS_EINVAL, "%s: 1.01 dt_crit accepted",
        what);
  CHECK(mfs_solver2d_set_dt(s, s->dt_crit, 0) == MFS_OK, "%s: dt_crit refused", what);
  double amp = max_abs(top, n);
  double growth[2];
  const double dts[2] = {1.1 * s->dt_crit, 0.99 * dt_exact};
  for (int c = 0; c < 2; c++) {
    CHECK(mfs_solver2d_set_dt(s, dts[c], 1) == MFS_OK, "%s: forced dt", what);
    mfs_solver2d_reset(s);
    mfs_solver2d_set_state(s, top, NULL);
    double g = 0.0;
    mfs_status st = MFS_OK;
    for (int it = 0; it < 400 && st == MFS_OK; it++) {
      st = mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG);
      g = fmax(g, max_abs(s->u, n) / amp);
    }
    CHECK(st == MFS_OK, "%s: step: %s", what, mfs_strerror(st));
    growth[c] = g;
  }
  CHECK(growth[0] > 1e10, "%s: at 1.1 dt_crit max|u|/|u0| = %.3g in 400 steps", what, growth[0]);
  CHECK(growth[1] <= 1.0 + 1e-6, "%s: at 0.99 of the exact limit max|u|/|u0| = %.9g", what,
        growth[1]);
  printf("%s (n = %zu): lambda_max exact %.10g, power %.10g (1 - ratio %.2g), bound %.6g "
         "(negative phi at %zu points), dt_crit / exact limit %.6f; "
         "max|u|/|u0| in 400 steps: %.3g at 1.1 dt_crit, %.9f at 0.99 exact\n",
         what, n, lmax, s->lambda_power, 1.0 - s->lambda_power / lmax, s->lambda_bound,
         s->negative_phi, s->dt_crit / dt_exact, growth[0], growth[1]);
  free(wd);
  free(top);
  mfs_solver2d_free(s);
}

/* Test 5.  Error returns, helpers, 1D models. */
static void test_errors(void)
{
  mfs_status st;
  size_t bad;
  CHECK(mfs_solver2d_alloc(NULL, &st, &bad) == NULL && st == MFS_EINVAL, "NULL spec: %s",
        mfs_strerror(st));
  mfs_model_spec sp = spec2d(10, 9, 1.7, 1.53, "gauss2", MFS_PHYS_PLANE_STRAIN);
  sp.disc.consistent_mass = 1;
  CHECK(mfs_solver2d_alloc(&sp, &st, &bad) == NULL && st == MFS_EINVAL, "consistent mass: %s",
        mfs_strerror(st));
  sp.disc.consistent_mass = 0;
  sp.disc.source.nx = 1;
  CHECK(mfs_solver2d_alloc(&sp, &st, &bad) == NULL && st == MFS_EINVAL, "nx = 1: %s",
        mfs_strerror(st));
  sp.disc.source.nx = 4;
  CHECK(mfs_solver2d_alloc(&sp, &st, &bad) == NULL && st == MFS_ETOOSMALL, "periodic nx = 4: %s",
        mfs_strerror(st));
  sp.disc.source.nx = 10;
  sp.disc.quadrature = mfs_quad_find("gauss0");
  CHECK(mfs_solver2d_alloc(&sp, &st, &bad) == NULL && st == MFS_EINVAL, "quadrature: %s",
        mfs_strerror(st));
  sp.disc.quadrature = mfs_quad_find("gauss2");
  sp.disc.dilation = 0.6; /* too few neighbours: singular moment matrix */
  CHECK(mfs_solver2d_alloc(&sp, &st, &bad) == NULL && st == MFS_ESINGULAR, "D = 0.6: %s",
        mfs_strerror(st));
  sp.disc.dilation = 2.0;

  mfs_solver2d *s = alloc_ok(&sp, "errors");
  if (!s)
    return;
  size_t n = s->n;
  double *u = calloc(n, sizeof *u);
  u[7] = 0.3;
  CHECK(mfs_solver2d_set_state(s, u, NULL) == MFS_OK, "set_state");
  u[3] = NAN;
  CHECK(mfs_solver2d_set_state(s, u, NULL) == MFS_EDOMAIN, "NaN u accepted");
  CHECK(mfs_solver2d_set_state(s, NULL, u) == MFS_EDOMAIN, "NaN v accepted");
  CHECK(s->u[7] == 0.3 && s->u[3] == 0.0, "state changed by a refused set_state");
  CHECK(mfs_solver2d_set_dt(s, 0.0, 1) == MFS_EINVAL, "dt = 0");
  CHECK(mfs_solver2d_set_dt(s, -1.0, 1) == MFS_EINVAL, "dt < 0");
  CHECK(mfs_solver2d_set_dt(s, INFINITY, 1) == MFS_EINVAL, "dt = inf");
  CHECK(mfs_solver2d_step(s, (mfs_scheme)7) == MFS_EINVAL, "unknown scheme");
  /* a forced, far too large step overflows: MFS_EDOMAIN */
  CHECK(mfs_solver2d_set_dt(s, 50.0 * s->dt_crit, 1) == MFS_OK, "forced dt");
  st = MFS_OK;
  int it = 0;
  for (; it < 2000 && st == MFS_OK; it++)
    st = mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG);
  CHECK(st == MFS_EDOMAIN, "overflowing run: %s after %d steps", mfs_strerror(st), it);
  mfs_solver2d_reset(s);
  CHECK(s->t == 0.0 && s->steps == 0 && max_abs(s->u, 3 * n) == 0.0, "reset");

  /* helpers: the nearest particle of each dof's position and back */
  int okn = 1;
  for (size_t i = 0; i < n; i++) {
    size_t P = mfs_solver2d_nearest(s, s->X[i] + 0.3 * s->model->dx, s->Y[i] - 0.4 * s->model->dy);
    okn &= mfs_solver2d_dof(s, P, s->comp[i]) == (long)i;
  }
  CHECK(okn, "nearest / dof round trip");
  CHECK(mfs_solver2d_nearest(s, sp.disc.source.lx - 0.2 * s->model->dx, -0.4 * s->model->dy) == 0,
        "periodic wrap");
  CHECK(mfs_solver2d_nearest(s, 3.1 * s->model->dx, 2.2 * s->model->dy + sp.disc.source.ly) == 2 * 10 + 3,
        "periodic wrap y");
  CHECK(mfs_solver2d_dof(s, 5, 2) == -1 && mfs_solver2d_dof(s, 90, 0) == -1, "dof out of range");
  free(u);
  mfs_solver2d_free(s);

  /* fixed boundary: boundary particles have no dof */
  sp.disc.source.periodic = 0;
  sp.fixed = MFS_FIX_BOUNDARY;
  s = alloc_ok(&sp, "fixed");
  if (s) {
    CHECK(s->n == 2 * 8 * 7, "fixed: %zu dofs", s->n);
    size_t corner = mfs_solver2d_nearest(s, -5.0, 9.0), inner = mfs_solver2d_nearest(s, 0.2, 0.2);
    CHECK(corner == 8 * 10 && mfs_solver2d_dof(s, corner, 0) == -1, "fixed corner %zu", corner);
    long d = mfs_solver2d_dof(s, inner, 1);
    CHECK(inner == 11 && d == 1 && s->comp[d] == 1 && s->X[d] == s->model->dx, "inner dof %ld",
          d);
    mfs_solver2d_free(s);
  }

  /* 1D models are accepted: Y = 0, the 1D Bloch identity */
  mfs_model_spec s1 = mfs_model_spec_default();
  s1.disc.source.nx = 23;
  s1.disc.source.lx = 2.385;
  s1.disc.source.periodic = 1;
  s1.disc.material.modulus = 3.1;
  s1.disc.material.density = 0.7;
  s = alloc_ok(&s1, "1D");
  if (s) {
    double kx = 2 * M_PI * 4 / s1.disc.source.lx, *u1 = malloc(s->n * sizeof *u1);
    for (size_t i = 0; i < s->n; i++)
      u1[i] = cos(kx * s->X[i]);
    mfs_solver2d_set_state(s, u1, NULL);
    double w2 = -s->a[0] / u1[0], th = acos(1 - 0.5 * s->dt * s->dt * w2), err = 0.0;
    for (int k = 1; k <= 500; k++) {
      mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG);
      for (size_t i = 0; i < s->n; i++)
        err = fmax(err, fabs(s->u[i] - cos(k * th) * u1[i]));
    }
    CHECK(max_abs(s->Y, s->n) == 0.0 && mfs_solver2d_nearest(s, 0.9 * s1.disc.source.lx / 23, 7.0) == 1,
          "1D helpers");
    CHECK(err < 1e-10, "1D Bloch mode: error %.3g", err);
    free(u1);
    mfs_solver2d_free(s);
  }
}

int main(void)
{
  tests_bloch();
  test_zero_mode("nodal", 1);
  test_zero_mode("gauss2", 0);
  test_energy(MFS_FIX_NONE, "gauss2", 0.9, 0.12);
  test_energy(MFS_FIX_BOUNDARY, "gauss2", 0.9, 0.12);
  test_energy(MFS_FIX_NONE, "nodal", 0.9, 0.12);
  test_energy(MFS_FIX_NONE, "gauss2", 0.3, 0.02);
  test_energy(MFS_FIX_BOUNDARY, "gauss2", 0.3, 0.02);
  test_dt(MFS_PHYS_SCALAR, "gauss2");
  test_dt(MFS_PHYS_PLANE_STRAIN, "gauss2");
  test_dt(MFS_PHYS_SCALAR, "nodal");
  test_errors();
  return check_summary("test_solver2d");
}
