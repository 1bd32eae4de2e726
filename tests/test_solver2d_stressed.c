/* The initially stressed plate of mfs_solver2d (mfs_solver2d_alloc_stressed):
 *   - its nonlinear acceleration, linearized by central differences at u = 0
 *     along a Bloch mode, equals the dispersion analysis' symbol (Lagrangian
 *     with the geometric stiffness; Eulerian sph and mls against
 *     `eulerian-consistent`);
 *   - a periodic plate under tension with an Eulerian kernel grows at the
 *     dispersion module's largest Im(omega) (sph nodal at k = (pi, 0), mls
 *     nodal at k = (pi, pi)), within 2%, and that wave vector is the zone's
 *     fastest;
 *   - the same plate with a Lagrangian kernel stays bounded, conserves its
 *     energy, and oscillates at the dispersion frequency with the stress;
 *   - the unstressed Lagrangian plate is the linear one;
 *   - the error returns. */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static const double MU = 2.3, RHO = 1.7, NU = 0.27;

static mfs_model_spec spec(int n, const char *quad, const mfs_shape_type *sh, mfs_frame fr)
{
  mfs_model_spec s = mfs_model_spec_default();
  mfs_disc *d = &s.disc;
  d->dim = 2;
  d->source = (mfs_source){
    .lattice = MFS_LATTICE_SQUARE, .nx = n, .ny = n, .lx = 0.37 * n, .ly = 0.37 * n, .periodic = 1};
  d->kernel = &mfs_kernel_cubic;
  d->shape = sh;
  d->dilation = 2.0;
  d->quadrature = mfs_quad_find(quad);
  d->frame = fr;
  d->material = (mfs_material){
    .physics = MFS_PHYS_PLANE_STRAIN, .modulus = MU, .density = RHO, .poisson = NU};
  return s;
}

/* The dispersion plan of the periodic box's lattice (normalized: dx = mu = rho = 1). */
static mfs_disp_plan *disp(const mfs_model_spec *sp, mfs_frame fr, double sxx, double syy, double sxy)
{
  mfs_disp_spec ds = {.disc = sp->disc, .stress_yy = syy / MU, .stress_xy = sxy / MU};
  ds.disc.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
  ds.disc.frame = fr;
  mfs_status st;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&ds, &st);
  CHECK(pl != NULL, "disp plan: %s", mfs_strerror(st));
  (void)sxx;
  return pl;
}


/* the complex amplitude (1/N) sum_I u_I,comp e^{-ik.X_I} over the dofs of comp */
static double complex mode_amp(const mfs_solver2d *s, const double *k, int comp)
{
  double complex z = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < s->n; i++)
    if (s->comp[i] == comp) {
      z += s->u[i] * cexp(-_Complex_I * (k[0] * s->X[i] + k[1] * s->Y[i]));
      n++;
    }
  return z / (double)n;
}

/* ---- the linearization against the symbol ---- */

static void linearization(void)
{
  typedef struct {
    const char *quad;
    const mfs_shape_type *sh;
    mfs_frame fr, dfr;
  } lcase;
  const lcase cases[] = {
    {"nodal", &mfs_shape_sph, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN},
    {"nodal", &mfs_shape_mls, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT},
    {"stress-tri", &mfs_shape_mls, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT},
    {"stress-quad", &mfs_shape_sph, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT},
    {"stress-tri", &mfs_shape_mls, MFS_FRAME_LAGRANGIAN, MFS_FRAME_LAGRANGIAN},
    {"gauss2", &mfs_shape_kb, MFS_FRAME_LAGRANGIAN, MFS_FRAME_LAGRANGIAN},
  };
  const double sig[3] = {0.31 * MU, -0.17 * MU, 0.11 * MU};
  double worst = 0.0;
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    mfs_model_spec sp = spec(12, cases[c].quad, cases[c].sh, cases[c].fr);
    mfs_status st;
    mfs_solver2d *s = mfs_solver2d_alloc_stressed(&sp, sig, 0.0, &st, NULL);
    CHECK(s != NULL, "stressed alloc %s: %s", cases[c].quad, mfs_strerror(st));
    mfs_disp_plan *pl = disp(&sp, cases[c].dfr, sig[0], sig[1], sig[2]);
    if (!s || !pl) {
      mfs_solver2d_free(s);
      mfs_disp_plan_free(pl);
      continue;
    }
    size_t n = s->n;
    double dx = s->model->dx, scale = MU / (RHO * dx * dx);
    double *u = malloc(n * sizeof *u), *ap = malloc(n * sizeof *ap), *am = malloc(n * sizeof *am);
    const int kk[][2] = {{1, 0}, {3, 2}, {6, 6}};
    double sc = 0.0, err = 0.0;
    for (int t = 0; t < 3; t++) {
      double k[2] = {2 * M_PI * kk[t][0] / 12, 2 * M_PI * kk[t][1] / 12}; /* in 1/dx */
      double kx[2] = {k[0] / dx, k[1] / dx};
      double complex K[4], M[4];
      mfs_disp_symbols(pl, sig[0] / MU, k, K, M);
      for (int g = 0; g < 2; g++) {
        double complex col[2] = {0, 0}; /* -(a(eps v) - a(-eps v)) / (2 eps) at particle 0 */
        for (int part = 0; part < 2; part++) {
          for (size_t i = 0; i < n; i++) {
            double ph = kx[0] * s->X[i] + kx[1] * s->Y[i];
            u[i] = s->comp[i] == g ? (part ? sin(ph) : cos(ph)) : 0.0;
          }
          double eps = 1e-7 * dx;
          for (size_t i = 0; i < n; i++)
            u[i] *= eps;
          mfs_solver2d_set_state(s, u, NULL);
          memcpy(ap, s->a, n * sizeof *ap);
          for (size_t i = 0; i < n; i++)
            u[i] = -u[i];
          mfs_solver2d_set_state(s, u, NULL);
          memcpy(am, s->a, n * sizeof *am);
          for (int i = 0; i < 2; i++) /* particle 0 at the origin: dofs 0, 1 */
            col[i] += (part ? _Complex_I : 1.0) * -(ap[i] - am[i]) / (2 * eps);
        }
        for (int i = 0; i < 2; i++) {
          double complex want = K[i * 2 + g] / M[0] * scale;
          sc = fmax(sc, cabs(want));
          err = fmax(err, cabs(col[i] - want));
        }
      }
    }
    double rel = err / sc;
    CHECK(rel < 1e-6, "%s %s %s: nonlinear force linearized vs the %s symbol: %g", cases[c].sh->name,
          cases[c].quad, mfs_frame_name(cases[c].fr), mfs_frame_name(cases[c].dfr), rel);
    worst = fmax(worst, rel);
    free(u);
    free(ap);
    free(am);
    mfs_solver2d_free(s);
    mfs_disp_plan_free(pl);
  }
  printf("linearization: worst %.2g\n", worst);
}

/* ---- growth and boundedness ---- */

/* Run the plate from the Bloch mode (m1, m2) on component comp for `steps` steps of dt;
 * the least-squares slope of ln |mode amplitude| over the second half (growing), or the
 * largest |amplitude| / initial (bounded), and the zero crossings' frequency. */
typedef struct {
  double slope, grow, freq;
} run_result;

static run_result run_mode(mfs_solver2d *s, int m1, int m2, int comp, double amp, double dt,
                           long steps, int ncell)
{
  size_t n = s->n;
  double dx = s->model->dx, k[2] = {2 * M_PI * m1 / (ncell * dx), 2 * M_PI * m2 / (ncell * dx)};
  double *u = malloc(n * sizeof *u);
  for (size_t i = 0; i < n; i++)
    u[i] = s->comp[i] == comp ? amp * cos(k[0] * s->X[i] + k[1] * s->Y[i]) : 0.0;
  mfs_solver2d_set_state(s, u, NULL);
  mfs_solver2d_set_dt(s, dt, 1);
  double a0 = cabs(mode_amp(s, k, comp)), mx = a0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  double prev = creal(mode_amp(s, k, comp)), t0 = NAN, t1 = NAN;
  int nz = 0, nfit = 0;
  for (long it = 1; it <= steps; it++) {
    mfs_status st = mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG);
    CHECK(st == MFS_OK, "step %ld: %s", it, mfs_strerror(st));
    if (st != MFS_OK)
      break;
    double complex z = mode_amp(s, k, comp);
    double A = cabs(z);
    mx = fmax(mx, A);
    if (it > steps / 2) {
      double x = s->t, y = log(A);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
      nfit++;
    }
    double re = creal(z);
    if ((re < 0) != (prev < 0)) { /* a zero crossing, linear interpolation */
      double tc = s->t - dt * re / (re - prev);
      if (!nz)
        t0 = tc;
      t1 = tc;
      nz++;
    }
    prev = re;
  }
  free(u);
  run_result r = {.slope = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx), .grow = mx / a0,
                  .freq = nz > 1 ? M_PI * (nz - 1) / (t1 - t0) : NAN};
  return r;
}

/* The growth at the wave vector k (1/dx): the largest |Im sqrt(omega^2)| (normalized). */
static double growth_at(const mfs_disp_plan *pl, double sbar, const double *k)
{
  double complex w[4];
  mfs_disp_omega2(pl, sbar, hypot(k[0], k[1]) / M_PI, atan2(k[1], k[0]), w);
  double g = 0.0;
  for (int b = 0; b < mfs_disp_branches(pl); b++)
    g = fmax(g, fabs(cimag(csqrt(w[b]))));
  return g;
}

/* The dispersion's largest growth over the zone (19 angles x 201 wave numbers), the
 * growth at the box wave vector k (1/dx), in SI (1/s), and the largest over the box's
 * admissible wave vectors 2 pi (m1, m2) / n. */
static void growth_pred(const mfs_disp_plan *pl, double sbar, double c_dx, int n, double *gmax,
                        double *gbox, int *mb)
{
  *gbox = 0.0;
  for (int m1 = 0; m1 < n; m1++)
    for (int m2 = 0; m2 < n; m2++) {
      double kb[2] = {2 * M_PI * m1 / n, 2 * M_PI * m2 / n}, g = growth_at(pl, sbar, kb) * c_dx;
      if (g > *gbox * (1 + 1e-12)) {
        *gbox = g;
        mb[0] = m1;
        mb[1] = m2;
      }
    }
  double th[19];
  for (int t = 0; t < 19; t++)
    th[t] = M_PI / 2 * t / 18.0;
  mfs_sampling smp = {.theta = th, .ntheta = 19, .npoints = 201};
  mfs_class cl;
  CHECK(mfs_classify(pl, &smp, &sbar, 1, &cl) == MFS_OK, "classify");
  *gmax = cl.max_growth * c_dx;
}

static void growth(void)
{
  typedef struct {
    const mfs_shape_type *sh;
    mfs_frame dfr;
  } gcase;
  const gcase cases[] = {{&mfs_shape_sph, MFS_FRAME_EULERIAN},
                         {&mfs_shape_mls, MFS_FRAME_EULERIAN_CONSISTENT}};
  const double sig[3] = {0.2 * MU, 0.0, 0.0};
  for (int c = 0; c < 2; c++) {
    mfs_model_spec sp = spec(16, "nodal", cases[c].sh, MFS_FRAME_EULERIAN);
    mfs_status st;
    mfs_solver2d *s = mfs_solver2d_alloc_stressed(&sp, sig, 0.0, &st, NULL);
    mfs_disp_plan *pl = disp(&sp, cases[c].dfr, sig[0], 0, 0);
    CHECK(s && pl, "growth alloc: %s", mfs_strerror(st));
    if (!s || !pl)
      continue;
    double dx = s->model->dx, c_dx = sqrt(MU / RHO) / dx;
    /* the box's fastest Bloch mode 2 pi (m1, m2) / 16 seeds the run */
    double gmax, gk;
    int mb[2] = {0, 0};
    growth_pred(pl, sig[0] / MU, c_dx, 16, &gmax, &gk, mb);
    double k[2] = {2 * M_PI * mb[0] / 16.0, 2 * M_PI * mb[1] / 16.0};
    if (cases[c].sh == &mfs_shape_sph) /* at the zone edge (pi, 0): also the zone's fastest */
      CHECK(mb[0] == 8 && mb[1] == 0 && fabs(gk / gmax - 1) < 1e-9,
            "sph: the box's fastest k = (%d, %d) 2 pi/16 is the zone's: %g vs %g", mb[0], mb[1], gk, gmax);
    /* from 1e-10 dx for ln(1e5) / g: the linear regime throughout */
    double dt = 0.02 / c_dx, tend = log(1e5) / gk;
    run_result r = run_mode(s, mb[0], mb[1], 0, 1e-10 * dx, dt, (long)(tend / dt), 16);
    /* the leapfrog's own rate for omega^2 = -g^2: ln(z)/dt with z + 1/z = 2 + g^2 dt^2 */
    double gd = gk * dt, z = 1 + gd * gd / 2 + gd * sqrt(1 + gd * gd / 4), pred = log(z) / dt;
    CHECK(fabs(r.slope / gmax - 1) < 0.02, "%s Eulerian plate: growth %g 1/s vs the dispersion's %g",
          cases[c].sh->name, r.slope, gmax);
    CHECK(fabs(r.slope / pred - 1) < 1e-4, "%s Eulerian plate: growth %g 1/s vs the leapfrog's for "
          "the box's k %g", cases[c].sh->name, r.slope, pred);
    printf("growth %s nodal Eulerian, sigma_xx = 0.2 mu: measured %.7g 1/s, dispersion max %.7g "
           "(at the box's fastest k = (%d, %d) 2 pi/16: %.7g), rel. diff %.2g; %ld searches\n",
           cases[c].sh->name, r.slope, gmax, mb[0], mb[1], gk, r.slope / gmax - 1, s->searches);
    mfs_solver2d_free(s);
    mfs_disp_plan_free(pl);

    /* the same plate, Lagrangian kernel: bounded, at the Lagrangian frequency under stress */
    sp.disc.frame = MFS_FRAME_LAGRANGIAN;
    s = mfs_solver2d_alloc_stressed(&sp, sig, 0.0, &st, NULL);
    pl = disp(&sp, MFS_FRAME_LAGRANGIAN, sig[0], 0, 0);
    if (!s || !pl) {
      CHECK(0, "Lagrangian alloc: %s", mfs_strerror(st));
      mfs_solver2d_free(s);
      mfs_disp_plan_free(pl);
      continue;
    }
    /* bounded: the Eulerian plate's unstable mode plus a random field of 1e-3 dx */
    double *u = malloc(s->n * sizeof *u), kin, pot, e0, e1, u0 = 0.0, umax = 0.0;
    unsigned long rng = 2024;
    for (size_t i = 0; i < s->n; i++) {
      rng = rng * 6364136223846793005UL + 1442695040888963407UL;
      double noise = ((double)(rng >> 11) / 9007199254740992.0 - 0.5) * 2e-3 * dx;
      u[i] = noise + (s->comp[i] == 0 ? 1e-3 * dx * cos(k[0] / dx * s->X[i] + k[1] / dx * s->Y[i]) : 0.0);
      u0 = fmax(u0, fabs(u[i]));
    }
    mfs_solver2d_set_state(s, u, NULL);
    mfs_solver2d_set_dt(s, dt, 1);
    mfs_solver2d_energy(s, &kin, &pot, NULL);
    e0 = kin + pot;
    double emax = 0.0;
    for (int it = 0; it < 4000; it++) {
      if (mfs_solver2d_step(s, MFS_SCHEME_LEAPFROG) != MFS_OK)
        break;
      for (size_t i = 0; i < s->n; i++)
        umax = fmax(umax, fabs(s->u[i]));
      mfs_solver2d_energy(s, &kin, &pot, NULL);
      emax = fmax(emax, fabs((kin + pot) / e0 - 1));
    }
    e1 = kin + pot;
    CHECK(umax < 3 * u0, "%s Lagrangian plate: max |u| %g vs initial %g over %g growth times (bounded)",
          cases[c].sh->name, umax, u0, 4000 * dt * gmax);
    CHECK(e0 > 0 && emax < 1e-2, "%s Lagrangian plate: energy %g -> %g (largest drift %g)",
          cases[c].sh->name, e0, e1, emax);
    printf("bounded %s nodal Lagrangian: max |u| / initial %.4f over %.0f Eulerian growth times, "
           "energy drift %.2g\n", cases[c].sh->name, umax / u0, 4000 * dt * gmax, emax);
    /* and a P wave k = (3, 0) 2 pi/16 at the dispersion's frequency under the stress */
    double k3[2] = {2 * M_PI * 3 / 16.0, 0.0};
    double complex w[4];
    mfs_disp_omega2(pl, sig[0] / MU, k3[0] / M_PI, 0.0, w);
    double complex K[4], M[4];
    mfs_disp_symbols(pl, sig[0] / MU, k3, K, M);
    double W = sqrt(creal(K[0]) / creal(M[0])) * c_dx; /* u_x decouples along x */
    double cth = 1 - W * W * dt * dt / 2, lf = atan2(sqrt(1 - cth * cth), cth) / dt;
    run_result rl = run_mode(s, 3, 0, 0, 1e-4 * dx, dt, 3000, 16);
    CHECK(fabs(rl.freq / lf - 1) < 1e-6, "%s Lagrangian plate: P-wave frequency %g vs dispersion %g",
          cases[c].sh->name, rl.freq, lf);
    printf("  P wave (3, 0): frequency %.9g rad/s vs the dispersion's %.9g\n", rl.freq, lf);
    free(u);
    mfs_solver2d_free(s);
    mfs_disp_plan_free(pl);
  }
}

static void unstressed(void)
{
  mfs_model_spec sp = spec(10, "stress-tri", &mfs_shape_mls, MFS_FRAME_LAGRANGIAN);
  mfs_status st;
  mfs_solver2d *a = mfs_solver2d_alloc(&sp, &st, NULL);
  const double zero[3] = {0, 0, 0};
  mfs_solver2d *b = mfs_solver2d_alloc_stressed(&sp, zero, 0.0, &st, NULL);
  CHECK(a && b && !a->stressed && !b->stressed, "unstressed Lagrangian: the linear plate");
  mfs_solver2d_free(a);
  mfs_solver2d_free(b);
}

static void errors(void)
{
  mfs_status st;
  mfs_model_spec sp = spec(10, "nodal", &mfs_shape_mls, MFS_FRAME_EULERIAN_CONSISTENT);
  CHECK(!mfs_solver2d_alloc_stressed(&sp, NULL, 0.0, &st, NULL) && st == MFS_ENOTSUP,
        "eulerian-consistent: %s", mfs_strerror(st));
  sp.disc.frame = MFS_FRAME_EULERIAN;
  sp.disc.material.physics = MFS_PHYS_SCALAR;
  CHECK(!mfs_solver2d_alloc_stressed(&sp, NULL, 0.0, &st, NULL) && st == MFS_ENOTSUP,
        "Eulerian anti-plane: %s", mfs_strerror(st));
  sp.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  const double bad[3] = {NAN, 0, 0};
  CHECK(!mfs_solver2d_alloc_stressed(&sp, bad, 0.0, &st, NULL) && st == MFS_EINVAL, "NaN stress");
  CHECK(!mfs_solver2d_alloc_stressed(&sp, NULL, -1.0, &st, NULL) && st == MFS_EINVAL, "skin < 0");
}

/* ---- the step rules on the stressed plate ---- */

/* Lagrangian kernel: the Gershgorin bound of the tangent stiffness (the
 * default rule) lies above lambda_max of the linearized operator and within 2
 * times it, lambda_max by the Bloch symbol on the box's wave vectors (the
 * periodic box's exact spectrum, the independent path); `certified` falls
 * back to Gershgorin (no assembled tangent) and says so.  Eulerian kernel
 * with stress: the power rule, said in the fallback. */
static void step_rules(void)
{
  typedef struct {
    const char *quad;
    const mfs_shape_type *sh;
    mfs_frame fr;
  } rcase;
  const rcase cases[] = {
    {"stress-tri", &mfs_shape_mls, MFS_FRAME_LAGRANGIAN},
    {"gauss2", &mfs_shape_kb, MFS_FRAME_LAGRANGIAN},
    {"nodal", &mfs_shape_mls, MFS_FRAME_LAGRANGIAN},
    {"nodal", &mfs_shape_mls, MFS_FRAME_EULERIAN},
  };
  const double sig[3] = {0.31 * MU, -0.17 * MU, 0.11 * MU};
  const int N = 12;
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    mfs_model_spec sp = spec(N, cases[c].quad, cases[c].sh, cases[c].fr);
    mfs_status st;
    mfs_solver2d *s = mfs_solver2d_alloc_stressed(&sp, sig, 0.0, &st, NULL);
    CHECK(s != NULL, "rules alloc %s: %s", cases[c].quad, mfs_strerror(st));
    if (!s)
      continue;
    const mfs_dt_info g = s->step;
    if (cases[c].fr != MFS_FRAME_LAGRANGIAN) {
      CHECK(g.used == MFS_DT_POWER && g.fallback && !g.proven, "eulerian %s: used %s, fallback %s",
            cases[c].quad, mfs_dt_rule_name(g.used), g.fallback ? g.fallback : "(none)");
      printf("step rules eulerian %s %s: %s\n", cases[c].sh->name, cases[c].quad,
             g.fallback ? g.fallback : "");
      mfs_solver2d_free(s);
      continue;
    }
    mfs_disp_plan *pl = disp(&sp, cases[c].fr, sig[0], sig[1], sig[2]);
    if (!pl) {
      mfs_solver2d_free(s);
      continue;
    }
    double dx = s->model->dx, scale = MU / (RHO * dx * dx), lmax = 0.0;
    for (int a = 0; a < N; a++)
      for (int b = 0; b < N; b++) {
        double k[2] = {2 * M_PI * a / N, 2 * M_PI * b / N};
        double complex K[4], M[4];
        mfs_disp_symbols(pl, sig[0] / MU, k, K, M);
        double p = 0.5 * creal(K[0] + K[3]), q = 0.5 * creal(K[0] - K[3]);
        double top = p + sqrt(q * q + creal(K[1] * conj(K[1])));
        double bot = p - sqrt(q * q + creal(K[1] * conj(K[1])));
        lmax = fmax(lmax, fmax(fabs(top), fabs(bot)) / creal(M[0]) * scale);
      }
    double r = g.lambda_gershgorin / lmax;
    CHECK(g.used == MFS_DT_GERSHGORIN && g.proven && !g.fallback, "%s %s: default rule %s",
          cases[c].sh->name, cases[c].quad, mfs_dt_rule_name(g.used));
    CHECK(r >= 1.0 - 1e-12 && r <= 2.0, "%s %s: Gershgorin / lambda_max (symbol) = %.6f outside [1, 2]",
          cases[c].sh->name, cases[c].quad, r);
    double lold = (1.0 + (0.5 * fabs(sig[0] + sig[1]) + hypot(0.5 * (sig[0] - sig[1]), sig[2])) / MU);
    CHECK(mfs_solver2d_choose_step(s, MFS_DT_CERTIFIED) == MFS_OK &&
              s->step.used == MFS_DT_GERSHGORIN && s->step.fallback,
          "%s %s: certified falls back to Gershgorin", cases[c].sh->name, cases[c].quad);
    CHECK(mfs_solver2d_choose_step(s, MFS_DT_POWER) == MFS_OK && s->step.used == MFS_DT_POWER,
          "%s %s: power", cases[c].sh->name, cases[c].quad);
    printf("step rules lagrangian %s %s: lambda_max (symbol) %.8g, Gershgorin %.8g (ratio %.4f), "
           "power rule (unstressed 1.05 power x %.4f) %.8g (ratio %.4f)\n",
           cases[c].sh->name, cases[c].quad, lmax, g.lambda_gershgorin, r, lold, s->step.lambda,
           s->step.lambda / lmax);
    mfs_disp_plan_free(pl);
    mfs_solver2d_free(s);
  }
}

int main(void)
{
  linearization();
  step_rules();
  growth();
  unstressed();
  errors();
  return check_summary("test_solver2d_stressed");
}
