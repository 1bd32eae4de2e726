/* mfstab run: explicit time integration of a scene (tools/scene.h) with the
 * reference solver (lib/mfs_solver.h), the TSPH bar (lib/mfs_tsph.h) or, in
 * 2D, the linear plate (lib/mfs_solver2d.h); writes a CSV time series of the
 * probes the scene names. */
#include <complex.h>
#undef I
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "scene.h"

static const char help[] =
  "usage: mfstab run SCENE.ini [--set SECTION.KEY=VALUE ...] [-o FILE]\n"
  "Explicit time integration of a 1D rod of particles (lib/mfs_solver.h) or a 2D plate\n"
  "(dim = 2, lib/mfs_solver2d.h) described by an INI scene file; writes CSV columns t followed\n"
  "by the probes of [output] probes.\n"
  "Sections and keys (defaults in parentheses; * required):\n"
  "  [model]          nodes*, length* (m), periodic (0), dim (1 | 2), formulation (displacement |\n"
  "                   stress_velocity: the TSPH bar of lib/mfs_tsph.h, schemes tsph (default),\n"
  "                   euler, rk2, rk4; [material] yield_stress, fluidity, perzyna_exponent,\n"
  "                   hardening; [discretization] interpolation (shepard | linear),\n"
  "                   artificial_viscosity (0: alpha of q = alpha rho c dx v_x); stable\n"
  "                   step from the von Neumann limit of the scheme)\n"
  "  [material]       density* (kg/m^3), modulus* E (Pa), initial_stress S0 (0 Pa)\n"
  "                   S = E (F^2-1)/2 + S0, P = F S\n"
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
  "                   difference limit 2/sqrt(lambda_max) is refused)\n"
  "  [output]         probes* (v_center, u_center, kinetic_energy, potential_energy,\n"
  "                   total_energy, sigma_end, sigma_center, mode_amp, max_v, v_mid, v_err), every (1),\n"
  "                   mode (1: kappa dX/pi of mode_amp = (2/n) |sum_I u_I exp(-i kappa X_I)|)\n"
  "2D plate ([model] dim = 2: linear, Lagrangian, lumped mass, M u'' = -K u):\n"
  "  [model]          nodes_y*, length_y* (m): nodes x nodes_y particles on length x length_y;\n"
  "                   physics (antiplane: u_z | plane_strain: u_x, u_y)\n"
  "  [material]       modulus* is the shear modulus mu (Pa); poisson (0.25; plane strain only,\n"
  "                   in (-1, 0.5))\n"
  "  [discretization] quadrature (nodal | stress-quad | stress-tri | stress-star | gaussN)\n"
  "  [boundary]       edges (fixed | free; default fixed), or [model] periodic = 1\n"
  "  [initial]        component (x | y; plane strain, default x) of the seeds: pulse_amplitude,\n"
  "                   pulse_alpha, pulse_center, pulse_center_y (v = A exp(-alpha |X - c|^2));\n"
  "                   mode_x, mode_y (integers m1, m2; periodic box), mode_amplitude A (0):\n"
  "                   u = A cos(2 pi (m1 X/length + m2 Y/length_y)); center_velocity\n"
  "  [output]         probes: u_center, v_center (component `component` of the particle\n"
  "                   nearest the centre), kinetic_energy, potential_energy, total_energy,\n"
  "                   modified_energy (kinetic + potential - dt^2/8 a'Ma, conserved by leapfrog),\n"
  "                   max_v (largest particle speed), mode_amp ((2/N) |sum u e^{-i k.X}| over\n"
  "                   the N dofs of `component`, k of mode_x, mode_y)\n"
  "  refused with dim = 2: frame = eulerian, initial_stress, equilibrate, skin, perturbation,\n"
  "                   seed, left/right keys, formulation = stress_velocity, [output] mode, the\n"
  "                   probes sigma_end, sigma_center, v_mid, v_err\n"
  "options:\n"
  "  --set SECTION.KEY=VALUE   override a key of the scene (repeatable)\n"
  "  -o FILE                   output file (default: standard output)\n"
  "Exit codes: 0 success, 2 bad input (file:line: [section] key = value: why), 1 numerical\n"
  "failure (e.g. a non-finite value or an inverted deformation).\n";

static void die_status(const scene *sc, int st, size_t bad, double t)
{
  if (st == MFS_ESINGULAR)
    scene_key_error(sc, "discretization", "dilation",
                    "singular moment matrix at quadrature point %zu%s; use a larger dilation",
                    bad, t > 0 ? " during the run" : "");
  if (st == MFS_ETOOSMALL)
    scene_key_error(sc, "model", "nodes", "too few nodes for the support radius");
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
  double L = sc->spec.length, r = 0.0;
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

/* Relative discrete L2 error of the particle velocities against the exact
 * free-rod solution (paper 000 eq. 75): ||v_h - v|| / ||v||. */
static double velocity_error(const scene *sc, double c, const double *X, const double *v,
                             size_t n, double t)
{
  double e = 0.0, r = 0.0;
  for (size_t I = 0; I < n; I++) {
    double ve = free_rod_velocity(sc, c, X[I], t);
    e += (v[I] - ve) * (v[I] - ve);
    r += ve * ve;
  }
  return sqrt(e / r);
}

/* Velocity at X by linear interpolation on the uniform particles. */
static double velocity_at(const double *v, size_t n, double dX, double X)
{
  double q = X / dX;
  if (!(q > 0.0))
    return v[0];
  if (q >= (double)(n - 1))
    return v[n - 1];
  size_t I = (size_t)q;
  double f = q - (double)I;
  return (1.0 - f) * v[I] + f * v[I + 1];
}

static void put(FILE *f, double v)
{
  char b[40];
  cli_fmt(b, sizeof b, v);
  fputc(',', f);
  fputs(b, f);
}

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

/* A [time] dt above the stable step `limit` (s) of `rule`, without force. */
static _Noreturn void refuse_dt(const scene *sc, const char *rule, double limit, const char *why)
{
  scene_key_error(sc, "time", "dt",
                  "above the %s stability limit %.6g s %s; lower it or set [time] force = 1", rule,
                  limit, why);
}

static const char central_why[] = "(2/sqrt(lambda_max), eqs 120, 132)";

static void die_tsph(const scene *sc, int st, double t)
{
  if (st == MFS_ESINGULAR)
    scene_key_error(sc, "discretization", "dilation",
                    "a particle sees no neighbour of the other set; use a larger dilation");
  if (st == MFS_EINVAL)
    cli_die(2, "%s: invalid combination of keys: %s", sc->path, mfs_strerror(st));
  cli_die(1, "%s: at t = %g s: %s", sc->path, t, mfs_strerror(st));
}

/* [model] formulation = stress_velocity: the TSPH bar (lib/mfs_tsph.h). */
static int run_tsph(scene *sc, const char *outpath)
{
  int st;
  mfs_tsph_spec spec = scene_tsph_spec(sc);
  mfs_tsph *s = mfs_tsph_alloc(&spec, &st);
  if (!s)
    die_tsph(sc, st, 0.0);
  double dts = mfs_tsph_dt_stable(s);
  if (!(dts > 0.0) && !(sc->have_dt && sc->force)) {
    mfs_tsph_free(s);
    scene_key_error(sc, "time", "scheme",
                    "%s is unstable for every dt on this central operator (von Neumann); "
                    "set [discretization] artificial_viscosity > 0, or [time] dt and force = 1",
                    mfs_tsph_scheme_name(spec.scheme));
  }
  if (sc->have_dt && sc->dt > dts * (1.0 + 1e-9) && !sc->force) {
    char why[64];
    snprintf(why, sizeof why, "of %s (lib/mfs_tsph.h)", mfs_tsph_scheme_name(spec.scheme));
    mfs_tsph_free(s);
    refuse_dt(sc, "von Neumann", dts, why);
  }
  if (mfs_tsph_set_dt(s, sc->have_dt ? sc->dt : sc->safety * dts) != MFS_OK)
    die_tsph(sc, MFS_EINVAL, 0.0);
  size_t n = s->n;
  double *v0 = calloc(n, sizeof *v0);
  if (!v0)
    cli_die(1, "out of memory");
  if (sc->pulse_amplitude != 0.0)
    for (size_t I = 0; I < n; I++)
      v0[I] = pulse(sc, s->X[I]);
  size_t ic = 0, L = n - 1;
  for (size_t I = 0; I < n; I++)
    if (fabs(s->X[I] - 0.5 * spec.length) < fabs(s->X[ic] - 0.5 * spec.length))
      ic = I;
  v0[ic] += sc->center_velocity;
  if ((st = mfs_tsph_set_state(s, NULL, v0)) != MFS_OK)
    die_tsph(sc, st, 0.0);
  free(v0);
  double c = sqrt(spec.modulus / spec.density);

  cli_out out;
  cli_out_open(&out, outpath);
  fputs("t", out.f);
  for (int p = 0; p < sc->nprobes; p++)
    fprintf(out.f, ",%s", scene_probe_names[sc->probe[p]]);
  fputc('\n', out.f);
  long nsteps = (long)ceil(sc->end / s->dt * (1.0 - 1e-12));
  int tty = isatty(STDERR_FILENO), shown = -1;
  for (long k = 0;; k++) {
    if (k % sc->every == 0 || k == nsteps) {
      double kin, pot;
      mfs_tsph_energy(s, &kin, &pot);
      char b[40];
      cli_fmt(b, sizeof b, s->t);
      fputs(b, out.f);
      for (int p = 0; p < sc->nprobes; p++) {
        double val = 0.0;
        switch (sc->probe[p]) {
        case PROBE_V_CENTER: val = s->v[ic]; break;
        case PROBE_KINETIC: val = kin; break;
        case PROBE_POTENTIAL: val = pot; break;
        case PROBE_TOTAL: val = kin + pot; break;
        case PROBE_SIGMA_END: val = s->sigma[L]; break;
        case PROBE_SIGMA_CENTER: val = s->sigma[ic]; break;
        case PROBE_MAX_V:
          for (size_t I = 0; I < n; I++)
            val = fmax(val, fabs(s->v[I]));
          break;
        case PROBE_V_MID: val = mfs_tsph_velocity_at(s, 0.5 * spec.length); break;
        case PROBE_V_ERR: val = velocity_error(sc, c, s->X, s->v, n, s->t); break;
        default: break; /* refused by scene_finish */
        }
        put(out.f, val);
      }
      fputc('\n', out.f);
    }
    if (k == nsteps)
      break;
    if ((st = mfs_tsph_step(s)) != MFS_OK)
      die_tsph(sc, st, s->t);
    progress(tty, k, nsteps, &shown);
  }
  mfs_tsph_free(s);
  cli_out_commit(&out);
  return 0;
}

static void die_2d(const scene *sc, const mfs_model_spec *ms, int st, size_t bad, double t)
{
  if (st == MFS_ESINGULAR)
    scene_key_error(sc, "discretization", "dilation",
                    "singular moment matrix at quadrature point %zu; use a larger dilation", bad);
  if (st == MFS_ETOOSMALL) { /* mfs_model_spec_check: the periodic box vs 2 D dx */
    if (ms->nx <= 2.0 * ms->dilation)
      scene_key_error(sc, "model", "nodes", "too few nodes for the support radius");
    scene_key_error(sc, "model", "length_y",
                    "the periodic box is not longer than two support radii (2 D dx) in y");
  }
  if (st == MFS_EINVAL)
    cli_die(2, "%s: invalid combination of keys: %s", sc->path, mfs_strerror(st));
  cli_die(1, "%s: at t = %g s: %s", sc->path, t, mfs_strerror(st));
}

/* [model] dim = 2: the linear Lagrangian plate of lib/mfs_solver2d.h
 * (anti-plane shear or plane strain, lumped mass). */
static int run_2d(scene *sc, const char *outpath)
{
  int st;
  size_t bad = 0;
  mfs_model_spec ms = scene_model_spec(sc);
  mfs_solver2d *s = mfs_solver2d_alloc(&ms, &st, &bad);
  if (!s)
    die_2d(sc, &ms, st, bad, 0.0);
  if (sc->have_dt) {
    if (mfs_solver2d_set_dt(s, sc->dt, sc->force) != MFS_OK) {
      double dcrit = s->dt_crit;
      mfs_solver2d_free(s);
      refuse_dt(sc, "central-difference", dcrit, central_why);
    }
  } else {
    mfs_solver2d_set_dt(s, sc->safety * s->dt_crit, 1);
  }

  /* initial state on the dofs of `component`: Bloch mode, pulse, centre kick */
  size_t n = s->n;
  int comp = sc->component;
  double lx = ms.lx, ly = ms.ly;
  double kx = 2.0 * M_PI * sc->mode_x / lx, ky = 2.0 * M_PI * sc->mode_y / ly;
  double *u0 = calloc(n, sizeof *u0), *v0 = calloc(n, sizeof *v0);
  if (!u0 || !v0)
    cli_die(1, "out of memory");
  for (size_t i = 0; i < n; i++) {
    if (s->comp[i] != comp)
      continue;
    if (sc->mode_amplitude != 0.0)
      u0[i] = sc->mode_amplitude * cos(kx * s->X[i] + ky * s->Y[i]);
    if (sc->pulse_amplitude != 0.0) {
      double dx = s->X[i] - sc->pulse_center, dy = s->Y[i] - sc->pulse_center_y;
      if (ms.periodic) { /* the nearest image */
        dx -= lx * round(dx / lx);
        dy -= ly * round(dy / ly);
      }
      v0[i] = sc->pulse_amplitude * exp(-sc->pulse_alpha * (dx * dx + dy * dy));
    }
  }
  long dc = mfs_solver2d_dof(s, mfs_solver2d_nearest(s, 0.5 * lx, 0.5 * ly), comp);
  if (dc < 0) /* the centre particle is never on the boundary (nodes >= 3) */
    cli_die(1, "%s: no free particle at the centre of the box", sc->path);
  v0[dc] += sc->center_velocity;
  if ((st = mfs_solver2d_set_state(s, u0, v0)) != MFS_OK)
    die_2d(sc, &ms, st, 0, 0.0);
  free(u0);
  free(v0);

  /* what the probes need: energies; e^{-i k.X} of the mode_amp dofs */
  int need_energy = 0, need_mode = 0;
  for (int p = 0; p < sc->nprobes; p++) {
    int q = sc->probe[p];
    need_energy |= q == PROBE_KINETIC || q == PROBE_POTENTIAL || q == PROBE_TOTAL ||
                   q == PROBE_MODIFIED;
    need_mode |= q == PROBE_MODE_AMP;
  }
  double *ec = NULL, *es = NULL;
  size_t nmode = 0;
  if (need_mode) {
    ec = malloc(2 * n * sizeof *ec);
    if (!ec)
      cli_die(1, "out of memory");
    es = ec + n;
    for (size_t i = 0; i < n; i++) {
      double ph = kx * s->X[i] + ky * s->Y[i];
      int on = s->comp[i] == comp;
      ec[i] = on ? cos(ph) : 0.0;
      es[i] = on ? -sin(ph) : 0.0;
      nmode += (size_t)on;
    }
  }
  int ndof = ms.physics == MFS_PHYS_PLANE_STRAIN ? 2 : 1; /* (u_x, u_y) pairs: model->dof */

  cli_out out;
  cli_out_open(&out, outpath);
  fputs("t", out.f);
  for (int p = 0; p < sc->nprobes; p++)
    fprintf(out.f, ",%s", scene_probe_names[sc->probe[p]]);
  fputc('\n', out.f);
  long nsteps = (long)ceil(sc->end / s->dt * (1.0 - 1e-12));
  int tty = isatty(STDERR_FILENO), shown = -1;
  for (long k = 0;; k++) {
    if (k % sc->every == 0 || k == nsteps) {
      double kin = 0, pot = 0, mod = 0;
      if (need_energy)
        mfs_solver2d_energy(s, &kin, &pot, &mod);
      char b[40];
      cli_fmt(b, sizeof b, s->t);
      fputs(b, out.f);
      for (int p = 0; p < sc->nprobes; p++) {
        double val = 0.0;
        switch (sc->probe[p]) {
        case PROBE_V_CENTER: val = s->v[dc]; break;
        case PROBE_U_CENTER: val = s->u[dc]; break;
        case PROBE_KINETIC: val = kin; break;
        case PROBE_POTENTIAL: val = pot; break;
        case PROBE_TOTAL: val = kin + pot; break;
        case PROBE_MODIFIED: val = mod; break;
        case PROBE_MODE_AMP: {
          double re = 0.0, im = 0.0;
          for (size_t i = 0; i < n; i++) {
            re += s->u[i] * ec[i];
            im += s->u[i] * es[i];
          }
          val = 2.0 * hypot(re, im) / (double)nmode;
          break;
        }
        case PROBE_MAX_V: /* the largest particle speed */
          for (size_t i = 0; i + (size_t)ndof <= n; i += (size_t)ndof)
            val = fmax(val, ndof == 2 ? hypot(s->v[i], s->v[i + 1]) : fabs(s->v[i]));
          break;
        default: break; /* 1D only: refused by scene_finish */
        }
        put(out.f, val);
      }
      fputc('\n', out.f);
    }
    if (k == nsteps)
      break;
    if ((st = mfs_solver2d_step(s, sc->scheme)) != MFS_OK)
      die_2d(sc, &ms, st, 0, s->t);
    progress(tty, k, nsteps, &shown);
  }
  free(ec);
  mfs_solver2d_free(s);
  cli_out_commit(&out);
  return 0;
}

int cmd_run(int argc, char **argv)
{
  const char *path = NULL, *outpath = NULL;
  const char *sets[256];
  int nsets = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return 0;
    } else if (!strcmp(argv[i], "--set") || !strcmp(argv[i], "-o")) {
      if (i + 1 >= argc)
        cli_die(2, "%s: missing value", argv[i]);
      if (!strcmp(argv[i], "-o")) {
        outpath = argv[++i];
      } else {
        if (nsets == 256)
          cli_die(2, "--set: at most 256");
        sets[nsets++] = argv[++i];
      }
    } else if (argv[i][0] == '-' && argv[i][1]) {
      cli_die(2, "%s: unknown option; allowed: --set, -o, --help", argv[i]);
    } else if (!path) {
      path = argv[i];
    } else {
      cli_die(2, "'%s': only one scene file is allowed", argv[i]);
    }
  }
  if (!path)
    cli_die(2, "missing the scene file; usage: mfstab run SCENE.ini [--set S.K=V] [-o FILE]");
  scene sc;
  scene_load(&sc, path);
  for (int i = 0; i < nsets; i++)
    scene_set(&sc, sets[i]);
  scene_finish(&sc);
  if (sc.dim == 2)
    return run_2d(&sc, outpath);
  if (sc.stress_velocity)
    return run_tsph(&sc, outpath);

  int st;
  size_t bad = 0;
  mfs_solver *s = mfs_solver_alloc(&sc.spec, &st, &bad);
  if (!s)
    die_status(&sc, st, bad, 0.0);
  if (sc.have_dt) {
    if (mfs_solver_set_dt(s, sc.dt, sc.force) != MFS_OK) {
      double dcrit = s->dt_crit;
      mfs_solver_free(s);
      refuse_dt(&sc, "central-difference", dcrit, central_why);
    }
  } else {
    mfs_solver_set_dt(s, sc.safety * s->dt_crit, 1);
  }

  /* initial conditions */
  size_t n = s->n;
  double *u0 = calloc(n, sizeof *u0), *v0 = calloc(n, sizeof *v0);
  if (!u0 || !v0)
    cli_die(1, "out of memory");
  if (sc.perturbation > 0.0) {
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r)
      cli_die(1, "out of memory");
    gsl_rng_set(r, sc.seed);
    for (size_t I = 0; I < n; I++)
      u0[I] = sc.perturbation * s->dX * (2.0 * gsl_rng_uniform(r) - 1.0);
    gsl_rng_free(r);
  }
  if (sc.pulse_amplitude != 0.0)
    for (size_t I = 0; I < n; I++) {
      double d = s->X[I] - sc.pulse_center;
      v0[I] = sc.pulse_amplitude * exp(-sc.pulse_alpha * d * d);
    }
  size_t ic = mfs_solver_nearest(s, 0.5 * sc.spec.length);
  v0[ic] += sc.center_velocity;
  if ((st = mfs_solver_set_state(s, u0, v0)) != MFS_OK)
    die_status(&sc, st, 0, 0.0);
  free(u0);
  free(v0);

  /* what the probes need */
  int need_energy = 0, need_fields = 0;
  size_t qend = 0, qcen = 0;
  for (int p = 0; p < sc.nprobes; p++) {
    need_energy |= sc.probe[p] == PROBE_KINETIC || sc.probe[p] == PROBE_POTENTIAL ||
                   sc.probe[p] == PROBE_TOTAL;
    need_fields |= sc.probe[p] == PROBE_SIGMA_END || sc.probe[p] == PROBE_SIGMA_CENTER;
  }
  for (size_t Q = 0; Q < s->nq; Q++) {
    if (fabs(s->xq0[Q] - sc.spec.length) < fabs(s->xq0[qend] - sc.spec.length))
      qend = Q;
    if (fabs(s->xq0[Q] - 0.5 * sc.spec.length) < fabs(s->xq0[qcen] - 0.5 * sc.spec.length))
      qcen = Q;
  }

  cli_out out;
  cli_out_open(&out, outpath);
  fputs("t", out.f);
  for (int p = 0; p < sc.nprobes; p++)
    fprintf(out.f, ",%s", scene_probe_names[sc.probe[p]]);
  fputc('\n', out.f);

  long nsteps = (long)ceil(sc.end / s->dt * (1.0 - 1e-12));
  int tty = isatty(STDERR_FILENO);
  int shown = -1;
  for (long k = 0;; k++) {
    if (k % sc.every == 0 || k == nsteps) {
      double kin = 0, pot = 0;
      if (need_energy && (st = mfs_solver_energy(s, &kin, &pot)) != MFS_OK)
        die_status(&sc, st, 0, s->t);
      if (need_fields && !need_energy && (st = mfs_solver_fields(s)) != MFS_OK)
        die_status(&sc, st, 0, s->t);
      char b[40];
      cli_fmt(b, sizeof b, s->t);
      fputs(b, out.f);
      for (int p = 0; p < sc.nprobes; p++) {
        double val = 0.0;
        switch (sc.probe[p]) {
        case PROBE_V_CENTER: val = s->v[ic]; break;
        case PROBE_U_CENTER: val = s->u[ic]; break;
        case PROBE_KINETIC: val = kin; break;
        case PROBE_POTENTIAL: val = pot; break;
        case PROBE_TOTAL: val = kin + pot; break;
        case PROBE_SIGMA_END: val = s->sigma[qend]; break;
        case PROBE_SIGMA_CENTER: val = s->sigma[qcen]; break;
        case PROBE_MODE_AMP: {
          double complex z = 0;
          for (size_t I = 0; I < n; I++)
            z += s->u[I] * cexp(-1.0 * _Complex_I * M_PI * sc.mode * (double)I);
          val = 2.0 * cabs(z) / (double)n;
          break;
        }
        case PROBE_MAX_V:
          for (size_t I = 0; I < n; I++)
            val = fmax(val, fabs(s->v[I]));
          break;
        case PROBE_V_MID:
          val = sc.spec.periodic ? s->v[ic] : velocity_at(s->v, n, s->dX, 0.5 * sc.spec.length);
          break;
        case PROBE_V_ERR:
          val = velocity_error(&sc, sqrt(sc.spec.modulus / sc.spec.density), s->X, s->v, n, s->t);
          break;
        }
        put(out.f, val);
      }
      fputc('\n', out.f);
    }
    if (k == nsteps)
      break;
    if ((st = mfs_solver_step(s, sc.scheme)) != MFS_OK)
      die_status(&sc, st, 0, s->t);
    if (tty) {
      int pc = (int)(100 * (k + 1) / nsteps);
      if (pc != shown) {
        shown = pc;
        fprintf(stderr, "\r[%-50.*s] %3d%%", pc / 2,
                "##################################################", pc);
        if (k + 1 == nsteps)
          fputc('\n', stderr);
      }
    }
  }
  mfs_solver_free(s);
  cli_out_commit(&out);
  return 0;
}
