/* mfstab run: explicit time integration of a scene (tools/scene.h) with one
 * of the reference solvers (the rod, lib/time/mfs_solver.h; the TSPH bar,
 * lib/time/mfs_tsph.h; the linear plate, lib/time/mfs_solver2d.h) through their one
 * interface (lib/time/mfs_integrator.h): one time loop, one probe table, one CSV
 * writer. */
#include <complex.h>
#undef I
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"
#include "scene.h"

static const char usage[] = "mfstab run SCENE.ini [--set SECTION.KEY=VALUE ...] [-o FILE]";
/* the help in two literals (each under C's 4095 characters) */
static const char about_1d[] =
  "Explicit time integration of a 1D rod of particles (lib/time/mfs_solver.h) or a 2D plate\n"
  "(dim = 2, lib/time/mfs_solver2d.h) described by an INI scene file; writes CSV columns t_s followed\n"
  "by the probes of [output] probes, each named with its unit (v_center_m_s, u_center_m,\n"
  "kinetic_energy_j, potential_energy_j, total_energy_j, modified_energy_j, sigma_end_pa,\n"
  "sigma_center_pa, mode_amp_m, max_v_m_s, v_mid_m_s, v_err_norm; energies per unit\n"
  "cross-section in 1D, per unit thickness in 2D).\n"
  "Sections and keys (defaults in parentheses; * required):\n"
  "  [model]          nodes*, length* (m), periodic (0), max_entries (5e8 or what the memory\n"
  "                   holds: a larger plan is refused), dim (1 | 2), formulation (displacement |\n"
  "                   stress_velocity: the TSPH bar of lib/time/mfs_tsph.h, schemes tsph (default),\n"
  "                   euler, rk2, rk4; [material] yield_stress, fluidity, perzyna_exponent,\n"
  "                   hardening; [discretization] interpolation (shepard | linear),\n"
  "                   artificial_viscosity (0: alpha of q = alpha rho c dx v_x); stable\n"
  "                   step from the von Neumann limit of the scheme)\n"
  "  [material]       density* (kg/m^3), modulus* E (Pa), initial_stress S0 (0 Pa):\n"
  "                   S = E (F^2-1)/2 + S0\n"
  "  [discretization] kernel (quartic), dilation D (2), shape (mls; sph shepard kb rl),\n"
  "                   frame (lagrangian | eulerian), quadrature (nodal | stress | gaussN),\n"
  "                   equilibrate (1: the internal force at u = 0 is a constant load),\n"
  "                   skin (0.5: Eulerian neighbour-search skin in dX)\n"
  "  [initial]        center_velocity (0 m/s, the particle nearest L/2), perturbation\n"
  "                   (0: random displacement in [-p, p] dX), seed (1), pulse_amplitude,\n"
  "                   pulse_alpha, pulse_center (v = A exp(-alpha (X - c)^2))\n"
  "  [boundary]       left, right (fixed | free | velocity; default fixed), left_velocity,\n"
  "                   right_velocity (m/s), left_until, right_until (s; then 0)\n"
  "  [time]           end* (s), dt (s) or safety (0.9: dt = safety * dt_crit), scheme\n"
  "                   (leapfrog | euler | rk2 | rk4), force (0: a dt above the central-\n"
  "                   difference limit 2/sqrt(lambda_max) is refused), max_steps (10^8: a\n"
  "                   longer run is refused), step_rule (gershgorin | certified | power: the\n"
  "                   rule of dt_crit; --step-rule overrides it)\n"
  "  [output]         probes* (v_center, u_center, kinetic_energy, potential_energy,\n"
  "                   total_energy, sigma_end, sigma_center, mode_amp, max_v, v_mid, v_err), every (1),\n"
  "                   mode (1: kappa dX/pi of mode_amp = (2/n) |sum_I u_I exp(-i kappa X_I)|)\n";
static const char about_2d[] =
  "2D plate ([model] dim = 2, lumped mass: linear, Lagrangian, M u'' = -K u; plane strain with\n"
  "a stress or frame = eulerian: St Venant-Kirchhoff S = sigma0 + C:E, M u'' = f(0) - f(u)):\n"
  "  [model]          nodes_y*, length_y* (m): nodes x nodes_y particles on length x length_y;\n"
  "                   physics (antiplane: u_z | plane_strain: u_x, u_y)\n"
  "  [material]       modulus* is the shear modulus mu (Pa); poisson (0.25; plane strain only,\n"
  "                   in (-1, 0.5)); initial_stress, initial_stress_yy, initial_stress_xy (Pa)\n"
  "  [discretization] quadrature (nodal | stress-quad | stress-tri | stress-star | gaussN);\n"
  "                   frame (eulerian: see docs/commands.md), skin (0.5 dx)\n"
  "  [boundary]       edges (fixed | free; default fixed), or [model] periodic = 1\n"
  "  [initial]        component (x | y; plane strain, default x) of the seeds: pulse_amplitude,\n"
  "                   pulse_alpha, pulse_center, pulse_center_y (v = A exp(-alpha |X - c|^2));\n"
  "                   mode_x, mode_y (integers m1, m2; periodic box), mode_amplitude A (0):\n"
  "                   u = A cos(2 pi (m1 X/length + m2 Y/length_y)); center_velocity\n"
  "  [output]         probes: u_center, v_center (component `component` of the particle\n"
  "                   nearest the centre), kinetic_energy, potential_energy, total_energy,\n"
  "                   modified_energy (conserved by leapfrog; linear plate only), (frame =\n"
  "                   eulerian: no potential energy)\n"
  "                   max_v (largest particle speed), mode_amp ((2/N) |sum u e^{-i k.X}| over\n"
  "                   the N dofs of `component`, k of mode_x, mode_y)\n"
  "  refused with dim = 2: equilibrate (always applied to a stressed plate), perturbation,\n"
  "                   seed, left/right keys, formulation = stress_velocity, [output] mode, the\n"
  "                   probes sigma_end, sigma_center, v_mid, v_err\n"
  "Exit codes: 0 success, 2 bad input (file:line: [section] key = value: why), 1 numerical\n"
  "failure (e.g. a non-finite value or an inverted deformation).\n";

/* Die with the message of a library status met at time t (bad: the
 * quadrature point of a singular moment matrix). */
static _Noreturn void die_run(const scene *sc, const mfs_integrator_type *type, mfs_status st,
                              size_t bad, double t)
{
  if (st == MFS_ESINGULAR) {
    if (type == &mfs_integrator_tsph)
      scene_key_error(sc, "discretization", "dilation",
                      "a particle sees no neighbour of the other set; use a larger dilation");
    scene_key_error(sc, "discretization", "dilation",
                    "singular moment matrix at quadrature point %zu%s; use a larger dilation", bad,
                    t > 0 ? " during the run" : "");
  }
  if (st == MFS_ETOOSMALL) {
    const mfs_disc *d = &sc->spec.disc;
    if (sc->dim == 2 && !(d->source.nx > 2.0 * d->dilation))
      scene_key_error(sc, "model", "nodes", "too few nodes for the support radius");
    if (sc->dim == 2)
      scene_key_error(sc, "model", "length_y",
                      "the periodic box is not longer than two support radii (2 D dx) in y");
    scene_key_error(sc, "model", "nodes", "too few nodes for the support radius");
  }
  if (st == MFS_EINVAL)
    cli_die(2, "%s: invalid combination of keys: %s", sc->path, mfs_strerror(st));
  cli_die(1, "%s: at t = %g s: %s", sc->path, t, mfs_strerror(st));
}

/* Initial pulse v0(X) = A exp(-alpha (X - c)^2) of the scene. */
static double pulse(const scene *sc, double X)
{
  double d = X - sc->pulse_center;
  return sc->pulse_amplitude * exp(-sc->pulse_alpha * d * d);
}

/* d'Alembert solution of the linear rod u_tt = c^2 u_xx on [0, L] with free
 * ends (u_x = 0, so v_x = 0), u(x, 0) = 0, v(x, 0) = v0(x):
 *   v(x, t) = (V(x - c t) + V(x + c t)) / 2,
 * V the even, 2L-periodic extension of v0 (the image sources of the
 * Neumann ends: a free end reflects velocity with the same sign). */
static double free_rod_velocity(const scene *sc, double c, double X, double t)
{
  double L = sc->spec.disc.source.lx, r = 0.0;
  for (int k = 0; k < 2; k++) {
    double y = fmod(X + (k ? c * t : -c * t), 2.0 * L);
    if (y < 0)
      y += 2.0 * L;
    if (y > L)
      y = 2.0 * L - y;
    r += 0.5 * pulse(sc, y);
  }
  return r;
}

/* ---- the probes: one table for every solver ---- */

typedef struct {
  const scene *sc;
  const mfs_integrator *in;
  size_t center;           /* dof of `component` nearest the centre */
  size_t qend, qcen;       /* stress points nearest the end and the centre (1D) */
  double kin, pot, mod;    /* energies of this row */
  const double *ec, *es;   /* 2D mode_amp: cos and -sin of k.X on the dofs of `component` */
  size_t nmode;
} probe_ctx;

typedef double (*probe_fn)(const probe_ctx *c, const mfs_state *st);

static double p_v_center(const probe_ctx *c, const mfs_state *st) { return st->v[c->center]; }
static double p_u_center(const probe_ctx *c, const mfs_state *st) { return st->u[c->center]; }
static double p_kinetic(const probe_ctx *c, const mfs_state *st) { (void)st; return c->kin; }
static double p_potential(const probe_ctx *c, const mfs_state *st) { (void)st; return c->pot; }
static double p_total(const probe_ctx *c, const mfs_state *st) { (void)st; return c->kin + c->pot; }
static double p_modified(const probe_ctx *c, const mfs_state *st) { (void)st; return c->mod; }
static double p_sigma_end(const probe_ctx *c, const mfs_state *st) { return st->sigma[c->qend]; }
static double p_sigma_center(const probe_ctx *c, const mfs_state *st) { return st->sigma[c->qcen]; }

/* (2/n) |sum_I u_I exp(-i kappa X_I)|: 1D kappa dX = pi mode; 2D the Bloch
 * wave vector of [initial] mode_x, mode_y on the dofs of `component`. */
static double p_mode_amp(const probe_ctx *c, const mfs_state *st)
{
  if (st->dim == 1) {
    double complex z = 0;
    for (size_t I = 0; I < st->n; I++)
      z += st->u[I] * cexp(-1.0 * _Complex_I * M_PI * c->sc->mode * (double)I);
    return 2.0 * cabs(z) / (double)st->n;
  }
  double re = 0.0, im = 0.0;
  for (size_t i = 0; i < st->n; i++) {
    re += st->u[i] * c->ec[i];
    im += st->u[i] * c->es[i];
  }
  return 2.0 * hypot(re, im) / (double)c->nmode;
}

/* The largest particle speed. */
static double p_max_v(const probe_ctx *c, const mfs_state *st)
{
  (void)c;
  double val = 0.0;
  size_t nd = (size_t)st->ncomp;
  for (size_t i = 0; i + nd <= st->n; i += nd)
    val = fmax(val, nd == 2 ? hypot(st->v[i], st->v[i + 1]) : fabs(st->v[i]));
  return val;
}

/* The velocity at L/2 (linear interpolation between particles). */
static double p_v_mid(const probe_ctx *c, const mfs_state *st)
{
  if (c->sc->spec.disc.source.periodic)
    return st->v[c->center];
  return mfs_lerp_uniform(st->v, st->n, st->dx, 0.5 * c->sc->spec.disc.source.lx);
}

/* Relative discrete L2 error of the particle velocities against the exact
 * free-rod solution (paper 000 eq. 75): ||v_h - v|| / ||v||. */
static double p_v_err(const probe_ctx *c, const mfs_state *st)
{
  const mfs_material *m = &c->sc->spec.disc.material;
  double cw = sqrt(m->modulus / m->density), e = 0.0, r = 0.0;
  for (size_t I = 0; I < st->n; I++) {
    double ve = free_rod_velocity(c->sc, cw, st->X[I], st->t);
    e += (st->v[I] - ve) * (st->v[I] - ve);
    r += ve * ve;
  }
  return sqrt(e / r);
}

static const probe_fn probes[PROBE_COUNT] = {
  [PROBE_V_CENTER] = p_v_center,   [PROBE_U_CENTER] = p_u_center,
  [PROBE_KINETIC] = p_kinetic,     [PROBE_POTENTIAL] = p_potential,
  [PROBE_TOTAL] = p_total,         [PROBE_SIGMA_END] = p_sigma_end,
  [PROBE_SIGMA_CENTER] = p_sigma_center, [PROBE_MODE_AMP] = p_mode_amp,
  [PROBE_MAX_V] = p_max_v,         [PROBE_V_MID] = p_v_mid,
  [PROBE_V_ERR] = p_v_err,         [PROBE_MODIFIED] = p_modified};

/* The CSV column of each probe: its scene name with its SI unit, or _norm
 * (docs/commands.md, "Units of the CSV columns").  Energies are per unit
 * cross-section (1D) or thickness (2D). */
static const char *const probe_columns[PROBE_COUNT] = {
  [PROBE_V_CENTER] = "v_center_m_s",          [PROBE_U_CENTER] = "u_center_m",
  [PROBE_KINETIC] = "kinetic_energy_j",       [PROBE_POTENTIAL] = "potential_energy_j",
  [PROBE_TOTAL] = "total_energy_j",           [PROBE_SIGMA_END] = "sigma_end_pa",
  [PROBE_SIGMA_CENTER] = "sigma_center_pa",   [PROBE_MODE_AMP] = "mode_amp_m",
  [PROBE_MAX_V] = "max_v_m_s",                [PROBE_V_MID] = "v_mid_m_s",
  [PROBE_V_ERR] = "v_err_norm",               [PROBE_MODIFIED] = "modified_energy_j"};

static void progress(int tty, long k, long nsteps, int *shown)
{
  if (!tty)
    return;
  int pc = (int)(100 * (k + 1) / nsteps);
  if (pc != *shown) {
    *shown = pc;
    fprintf(stderr, "\r[%-50.*s] %3d%%", pc / 2,
            "##################################################", pc);
    if (k + 1 == nsteps)
      fputc('\n', stderr);
  }
}

/* ---- building the run ---- */

/* The solver of the scene, through its interface (scene.h). */
mfs_integrator scene_build(scene *sc)
{
  mfs_integrator in = {.scheme = sc->scheme};
  mfs_status st;
  size_t bad = 0;
  /* a limit on the work before anything is built */
  mfs_disc d = sc->dim == 2 ? scene_model_spec(sc).disc : sc->spec.disc;
  double n = (double)d.source.nx * (sc->dim == 2 ? (double)sc->ny : 1.0);
  double entries = mfs_disc_plan_entries(&d, n, NULL);
  double lim = sc->max_entries > 0.0 ? sc->max_entries : CLI_MAX_ENTRIES;
  if (!(entries <= lim))
    scene_key_error(sc, "discretization", "dilation",
                    "about %.3g neighbour entries in the plan, more than [model] max_entries = "
                    "%.3g%s; lower the dilation or the nodes, or raise max_entries",
                    entries, lim, sc->max_entries > 0.0 ? "" : " (the default)");
  double bytes = mfs_disc_model_bytes(&d, n), mem = cli_available_memory();
  if (sc->max_entries == 0.0 && mem > 0.0 && bytes > mem)
    scene_key_error(sc, "discretization", "dilation",
                    "the model needs about %.3g GB, and %.3g GB of memory are available; lower "
                    "the dilation or the nodes, or set [model] max_entries to try anyway",
                    bytes / 1e9, mem / 1e9);
  if (sc->dim == 2) {
    mfs_model_spec ms = scene_model_spec(sc);
    in.type = &mfs_integrator_plate;
    const double sigma0[3] = {sc->spec.disc.material.initial_stress, sc->stress_yy, sc->stress_xy};
    in.solver = mfs_solver2d_alloc_stressed(&ms, sigma0, sc->spec.skin, &st, &bad);
  } else if (sc->stress_velocity) {
    mfs_tsph_spec ts = scene_tsph_spec(sc);
    in.type = &mfs_integrator_tsph;
    in.solver = mfs_tsph_alloc(&ts, &st);
  } else {
    in.type = &mfs_integrator_rod;
    in.solver = mfs_solver_alloc(&sc->spec, &st, &bad);
  }
  if (!in.solver)
    die_run(sc, in.type, st, bad, 0.0);
  return in;
}

/* The step: [time] dt checked against the solver's stable step, or safety
 * times it. */
static void choose_dt(const scene *sc, mfs_integrator *in)
{
  if (in->type->choose_step && sc->step_rule != MFS_DT_GERSHGORIN) { /* alloc chose by Gershgorin */
    mfs_status st = in->type->choose_step(in->solver, sc->step_rule);
    if (st != MFS_OK)
      die_run(sc, in->type, st, 0, 0.0);
  }
  double dts = in->type->stable_dt(in->solver);
  const char *rule = in->type->step_rule;
  char why[96];
  if (in->type == &mfs_integrator_tsph)
    snprintf(why, sizeof why, "of %s (lib/time/mfs_tsph.h)", mfs_tsph_scheme_name(sc->tscheme));
  else
    snprintf(why, sizeof why, "(2/sqrt(lambda_max), eqs 120, 132)");
  if (!(dts > 0.0) && !(sc->have_dt && sc->force)) {
    in->type->free(in->solver);
    scene_key_error(sc, "time", "scheme",
                    "%s is unstable for every dt on this central operator (von Neumann); "
                    "set [discretization] artificial_viscosity > 0, or [time] dt and force = 1",
                    mfs_tsph_scheme_name(sc->tscheme));
  }
  if (sc->have_dt) {
    if (in->type->set_dt(in->solver, sc->dt, sc->force) != MFS_OK) {
      in->type->free(in->solver);
      scene_key_error(sc, "time", "dt",
                      "above the %s stability limit %.6g s %s; lower it or set [time] force = 1",
                      rule, dts, why);
    }
  } else if (in->type->set_dt(in->solver, sc->safety * dts, 1) != MFS_OK) {
    die_run(sc, in->type, MFS_EINVAL, 0, 0.0);
  }
}

/* The run's header: one line on stderr with the step, the rule that chose
 * its limit and what that rule guarantees (docs/commands.md, "mfstab run"). */
static void step_line(const scene *sc, const mfs_integrator *in, double dt)
{
  double dtc = in->type->stable_dt(in->solver);
  char head[160];
  if (sc->have_dt)
    snprintf(head, sizeof head, "mfstab run: dt = %.6g s ([time] dt; %.4f of dt_crit = %.6g s)", dt,
             dt / dtc, dtc);
  else
    snprintf(head, sizeof head, "mfstab run: dt = %.6g s = %g of dt_crit = %.6g s", dt, sc->safety,
             dtc);
  if (!in->type->step_info) {
    fprintf(stderr, "%s (the von Neumann limit of %s, lib/time/mfs_tsph.h)\n", head,
            mfs_tsph_scheme_name(sc->tscheme));
    return;
  }
  const mfs_dt_info *i = in->type->step_info(in->solver);
  char rule[400];
  if (i->used == MFS_DT_GERSHGORIN)
    snprintf(rule, sizeof rule,
             "gershgorin: lambda = max_i sum_j |K_ij|/m_i = %.6g 1/s^2, a proven upper bound of "
             "lambda_max of the linearized model at the initial state",
             i->lambda);
  else if (i->used == MFS_DT_CERTIFIED)
    snprintf(rule, sizeof rule,
             "certified: sigma M - K positive definite, lambda_max <= %.6g 1/s^2 (proven; from "
             "a %s estimate %.10g 1/s^2 at tol %g, %d factorizations)",
             i->lambda, i->estimator ? i->estimator : "Lanczos", i->lambda_arpack, i->arpack_tol,
             i->factorizations);
  else if (i->proven)
    snprintf(rule, sizeof rule,
             "power: the element bound lambda = %.6g 1/s^2 (eq. 132, proven), below 1.05 times "
             "the power-iteration estimate %.6g 1/s^2",
             i->lambda, i->lambda_power);
  else
    snprintf(rule, sizeof rule,
             "power: lambda = %.6g 1/s^2 from %d power iterations (estimate %.6g 1/s^2, from "
             "below, times 1.05%s): not proven",
             i->lambda, i->power_iterations, i->lambda_power,
             sc->dim == 2 && i->lambda != mfs_step_lambda(i->lambda_power, NAN, 1)
                 ? " and 1 + |sigma0|/mu"
                 : "");
  fprintf(stderr, "%s (%s)", head, rule);
  if (i->fallback)
    fprintf(stderr, "; %s does not apply here (%s), so %s", mfs_dt_rule_name(i->requested),
            i->fallback, mfs_dt_rule_name(i->used));
  fputc('\n', stderr);
}

/* The initial state: random perturbation (1D), Bloch mode (2D), velocity
 * pulse, centre kick; set on the dofs of `component`. */
static void initial_state(const scene *sc, mfs_integrator *in, size_t center)
{
  mfs_state s;
  in->type->state(in->solver, &s);
  size_t n = s.n;
  int comp = sc->component, disp = s.u != NULL;
  double *u0 = mfs_calloc(n, sizeof *u0), *v0 = mfs_calloc(n, sizeof *v0);
  if (!u0 || !v0)
    cli_die(1, "out of memory");
  if (sc->perturbation > 0.0) {
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r)
      cli_die(1, "out of memory");
    gsl_rng_set(r, sc->seed);
    for (size_t I = 0; I < n; I++)
      u0[I] = sc->perturbation * s.dx * (2.0 * gsl_rng_uniform(r) - 1.0);
    gsl_rng_free(r);
  }
  const mfs_source *src = &sc->spec.disc.source;
  double lx = src->lx, ly = sc->ly;
  double kx = 2.0 * M_PI * sc->mode_x / lx, ky = s.dim == 2 ? 2.0 * M_PI * sc->mode_y / ly : 0.0;
  for (size_t i = 0; i < n; i++) {
    if (s.comp && s.comp[i] != comp)
      continue;
    if (s.dim == 1) {
      if (sc->pulse_amplitude != 0.0)
        v0[i] = pulse(sc, s.X[i]);
      continue;
    }
    if (sc->mode_amplitude != 0.0)
      u0[i] = sc->mode_amplitude * cos(kx * s.X[i] + ky * s.Y[i]);
    if (sc->pulse_amplitude != 0.0) {
      double dx = s.X[i] - sc->pulse_center, dy = s.Y[i] - sc->pulse_center_y;
      if (src->periodic) { /* the nearest image */
        dx -= lx * round(dx / lx);
        dy -= ly * round(dy / ly);
      }
      v0[i] = sc->pulse_amplitude * exp(-sc->pulse_alpha * (dx * dx + dy * dy));
    }
  }
  v0[center] += sc->center_velocity;
  mfs_status st = in->type->set_state(in->solver, disp ? u0 : NULL, v0);
  if (st != MFS_OK)
    die_run(sc, in->type, st, 0, 0.0);
  mfs_free(u0);
  mfs_free(v0);
}

/* The point of xq (nq first coordinates) nearest x, the first of ties. */
static size_t nearest_point(const double *xq, size_t nq, double x)
{
  size_t best = 0;
  for (size_t Q = 0; Q < nq; Q++)
    if (fabs(xq[Q] - x) < fabs(xq[best] - x))
      best = Q;
  return best;
}

typedef struct {
  const char *scene;
  cli_texts sets;
  const char *out;
  int step_rule;
} run_opts;

static const char *const step_rule_names[] = {
  [MFS_DT_GERSHGORIN] = "gershgorin", [MFS_DT_CERTIFIED] = "certified", [MFS_DT_POWER] = "power",
  NULL};

static const cli_opt opts[] = {
  {.name = NULL, .type = CLI_TEXT, .arg = "SCENE.ini", .offset = offsetof(run_opts, scene)},
  {.name = "--set", .type = CLI_TEXTS, .arg = "SECTION.KEY=VALUE",
   .help = "override a key of the scene (repeatable)", .offset = offsetof(run_opts, sets)},
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE", .help = "output file (default: standard output)",
   .offset = offsetof(run_opts, out)},
  {.name = "--step-rule", .type = CLI_CHOICE, .arg = "gershgorin|certified|power",
   .help = "the rule of the stable step dt_crit (default gershgorin, or the scene's [time]\n"
           "step_rule): gershgorin max_i sum_j |K_ij|/m_i (proven, one pass over the\n"
           "nonzeros); certified: sigma M - K factored (proven, within 1e-6 of lambda_max);\n"
           "power: 300 power iterations times 1.05 (not proven; the rule before 0.6)",
   .offset = offsetof(run_opts, step_rule), .choices = step_rule_names},
  {.type = CLI_END}};

scene_result scene_run(scene *sc, int write_csv, const char *csv_path, scene_row_fn row, void *ctx,
                        int keep_failure)
{
  scene_result res = {0};
  cli_out out = {0};
  FILE *csv = NULL;
  mfs_integrator in = scene_build(sc);
  choose_dt(sc, &in);
  const mfs_integrator_type *T = in.type;
  const mfs_source *src = &sc->spec.disc.source;
  size_t center = T->nearest(in.solver, 0.5 * src->lx, 0.5 * sc->ly, sc->component);
  if (center == (size_t)-1) /* the centre particle is never on the boundary (nodes >= 3) */
    cli_die(1, "%s: no free particle at the centre of the box", sc->path);
  initial_state(sc, &in, center);

  mfs_state s;
  T->state(in.solver, &s);
  probe_ctx pc = {.sc = sc, .in = &in, .center = center};
  int need_energy = 0, need_fields = 0, need_mode = 0;
  for (int p = 0; p < sc->nprobes; p++) {
    int q = sc->probe[p];
    need_energy |= q == PROBE_KINETIC || q == PROBE_POTENTIAL || q == PROBE_TOTAL ||
                   q == PROBE_MODIFIED;
    need_fields |= q == PROBE_SIGMA_END || q == PROBE_SIGMA_CENTER;
    need_mode |= q == PROBE_MODE_AMP;
  }
  if (s.nq > 0) {
    pc.qend = nearest_point(s.xq, s.nq, src->lx);
    pc.qcen = nearest_point(s.xq, s.nq, 0.5 * src->lx);
  }
  double *ec = NULL;
  if (need_mode && s.dim == 2) {
    ec = mfs_malloc(2 * s.n * sizeof *ec);
    if (!ec)
      cli_die(1, "out of memory");
    double kx = 2.0 * M_PI * sc->mode_x / src->lx, ky = 2.0 * M_PI * sc->mode_y / sc->ly;
    for (size_t i = 0; i < s.n; i++) {
      double ph = kx * s.X[i] + ky * s.Y[i];
      int on = s.comp[i] == sc->component;
      ec[i] = on ? cos(ph) : 0.0;
      ec[s.n + i] = on ? -sin(ph) : 0.0;
      pc.nmode += (size_t)on;
    }
    pc.ec = ec;
    pc.es = ec + s.n;
  }

  double steps = ceil(sc->end / s.dt * (1.0 - 1e-12));
  if (!(steps <= (double)sc->max_steps)) {
    T->free(in.solver);
    scene_key_error(sc, "time", "end",
                    "%.4g steps of %.4g s; more than [time] max_steps = %ld: raise it to run "
                    "that long",
                    steps, s.dt, sc->max_steps);
  }
  long nsteps = (long)steps;
  if (sc->print_step)
    step_line(sc, &in, s.dt);
  if (write_csv) {
    cli_out_open(&out, csv_path);
    csv = out.f;
    fputs("t_s", csv);
    for (int p = 0; p < sc->nprobes; p++)
      fprintf(csv, ",%s", probe_columns[sc->probe[p]]);
    fputc('\n', csv);
  }
  int tty = csv && isatty(STDERR_FILENO), shown = -1;
  mfs_status st;
  double val[SCENE_MAX_PROBES];
  for (long k = 0;; k++) {
    if (k % sc->every == 0 || k == nsteps) {
      if (need_energy && (st = T->energy(in.solver, &pc.kin, &pc.pot, &pc.mod)) != MFS_OK)
        die_run(sc, T, st, 0, s.t);
      if (need_fields && !need_energy && T->fields && (st = T->fields(in.solver)) != MFS_OK)
        die_run(sc, T, st, 0, s.t);
      T->state(in.solver, &s);
      int bad = -1;
      for (int p = 0; p < sc->nprobes; p++) {
        val[p] = probes[sc->probe[p]](&pc, &s);
        if (!isfinite(val[p]) && bad < 0)
          bad = p;
      }
      if (bad >= 0 && keep_failure) {
        res.failed = 1;
        break;
      }
      if (bad >= 0)
        cli_die(1, "%s: at t = %g s: probe %s is not finite (%g); no output written", sc->path,
                s.t, scene_probe_names[sc->probe[bad]], val[bad]);
      if (csv) {
        char b[40];
        cli_fmt(b, sizeof b, s.t);
        fputs(b, csv);
        for (int p = 0; p < sc->nprobes; p++) {
          cli_fmt(b, sizeof b, val[p]);
          fputc(',', csv);
          fputs(b, csv);
        }
        fputc('\n', csv);
      }
      if (row && row(ctx, &s, val))
        break;
    }
    if (k == nsteps)
      break;
    if ((st = T->step(in.solver, in.scheme)) != MFS_OK) {
      T->state(in.solver, &s);
      if (keep_failure && st == MFS_EDOMAIN) {
        res.failed = 1;
        break;
      }
      die_run(sc, T, st, 0, s.t);
    }
    res.steps = k + 1;
    if (tty)
      progress(tty, k, nsteps, &shown);
  }
  T->state(in.solver, &s);
  res.t = s.t;
  mfs_free(ec);
  T->free(in.solver);
  if (csv)
    cli_out_commit(&out);
  return res;
}

int cmd_run(int argc, char **argv)
{
  static run_opts o; /* static: the texts table is large */
  memset(&o, 0, sizeof o);
  unsigned char seen[5];
  cli_group g = {opts, &o, seen};
  static char about[sizeof about_1d + sizeof about_2d];
  snprintf(about, sizeof about, "%s%s", about_1d, about_2d);
  cli_parse(argc, argv, usage, about, &g, 1);
  if (!o.scene)
    cli_die(2, "missing the scene file; usage: mfstab run SCENE.ini [--set S.K=V] [-o FILE]");
  scene sc;
  scene_load(&sc, o.scene);
  for (int i = 0; i < o.sets.n; i++)
    scene_set(&sc, o.sets.v[i]);
  if (seen[3]) {
    char set[64];
    snprintf(set, sizeof set, "time.step_rule=%s", step_rule_names[o.step_rule]);
    scene_set(&sc, set);
  }
  scene_finish(&sc);
  sc.print_step = 1;
  scene_run(&sc, 1, o.out, NULL, NULL, 0);
  return 0;
}
