/* mfstab check: one command for a user's discretization (a particle file or
 * a lattice, their convention, their material, their code's step rule): is
 * it stable, which instabilities and where they start (the finite model's
 * zero-energy modes, the equivalent lattice's dispersion), which time steps
 * can be trusted (dt_crit, dt_certified, dt_gershgorin and the rules side by
 * side), and the worst modes and where they sit.  A short summary for people
 * on standard output; the same as one CSV row with -o. */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"
#include "eigs_figures.h"
#include "model_run.h"

static const char usage[] = "mfstab check [options] [-o FILE]";
static const char about[] =
  "Check a discretization before a simulation: the model of 'mfstab eigs' (a particle file\n"
  "with --particles, or a lattice box, perturbed or not), its convention (--support, or\n"
  "--smoothing-length H --convention NAME), its material (1D --young; 2D --young --poisson or\n"
  "--shear-modulus; --density) and, with --convention, the peer's own step rule (--rule-factor\n"
  "for the factor your input file sets).  It computes lambda_max (ARPACK), the zero-energy modes\n"
  "(shift-invert ARPACK), the certified step (CHOLMOD factorizations of sigma M - K), the\n"
  "Gershgorin and element bounds, the peers' rules, and the stability classification of the\n"
  "equivalent infinite lattice (the lattice itself, or the line or square lattice of a set's\n"
  "spacing, at the same support radius; --frame eulerian for the tensile instability).\n"
  "Prints a summary on standard output; -o FILE writes the same as one CSV row: the\n"
  "configuration columns of 'mfstab eigs', then verdict,lambda_max_per_s2,dt_crit_s,\n"
  "  dt_certified_s,certified_fraction,certify_margin,dt_gershgorin_s,gershgorin_ratio,dt_bound_s,bound_valid,\n"
  "  negative_phi_points,rule,dt_rule_s,dt_rule_fraction,dt_rule_unsafe,dt_rule_<peer>_s,\n"
  "  dt_rule_<peer>_unsafe,zero_modes,rigid_modes,spurious_modes,lambda_min_nonzero_per_s2,\n"
  "  spurious_participation,spurious_location,spurious_peak_particle,spurious_peak_x_m,\n"
  "  spurious_peak_y_m,max_participation,max_location,max_boundary_share,max_peak_particle,\n"
  "  max_peak_x_m,max_peak_y_m,lattice_label,lattice_spurious_zeros,lattice_zero_kappa_norm,\n"
  "  lattice_zero_theta_deg,lattice_min_omega2_norm,lattice_onset_sigma_tension_norm,\n"
  "  lattice_onset_sigma_compression_norm,nonpositive_masses,min_mass_kg,min_mass_particle\n"
  "verdict: stable, or the labels that apply joined by '+': rank-deficiency (spurious zero-energy\n"
  "modes in the finite model or on the lattice), tensile or compressive (the lattice is unstable\n"
  "under a tension, or a compression smaller than the material's own limit; onsets searched to\n"
  "sigma/C = 10 and -1), material (the lattice's label at sigma = 0), negative-mass (a lumped\n"
  "mass <= 0: explicit integration does not apply).  Kappa is kappa dx / pi, theta in degrees, sigma normalized by the modulus.\n";

typedef struct {
  int frame;
  const char *modes_prefix;
} check_opts;

static const char *const frame_names[] = {"lagrangian", "eulerian", NULL};

#define COFF(f) offsetof(check_opts, f)
static const cli_opt check_table[] = {
  {.name = "--frame", .type = CLI_CHOICE, .arg = "lagrangian|eulerian",
   .help = "the kernel frame of your code, for the lattice classification (default lagrangian)",
   .offset = COFF(frame), .choices = frame_names},
  {.name = "--write-modes", .type = CLI_TEXT, .arg = "PREFIX",
   .help = "write the spurious zero-energy modes and the highest mode to PREFIX_modes.csv\n"
           "and PREFIX_modes.vtk (ParaView)",
   .offset = COFF(modes_prefix)},
  {.type = CLI_END}};
#undef COFF
#define CHECK_NOPTS 3

/* The classification of the equivalent lattice at sbar = 0, with the onsets. */
typedef struct {
  int ok;
  mfs_class cl;
  double theta_deg[7];
  int ntheta;
  char label[64];
} lattice_check;

static void classify_lattice(const model_cmd *c, int frame, lattice_check *lc)
{
  memset(lc, 0, sizeof *lc);
  const mfs_disc *d = &c->s.disc;
  double dx = mfs_disc_dx(d), dy = d->dim == 1 ? dx : mfs_disc_dy(d);
  mfs_disp_spec ds = {.disc = *d, .stretch = 1.0};
  mfs_lattice_kind lat = d->source.lattice;
  if (mfs_disc_points(d))
    lat = d->dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE;
  ds.disc.source = (mfs_source){.lattice = lat, .spacing = 1.0, .gamma = d->dim == 1 ? 1.0 : dy / dx};
  ds.disc.dilation = mfs_disc_support(d) / dx;
  ds.disc.support = 0.0;
  ds.disc.frame = frame ? MFS_FRAME_EULERIAN : MFS_FRAME_LAGRANGIAN;
  mfs_status st;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&ds, &st);
  if (!pl && st == MFS_ENOMEM)
    cli_die(1, "equivalent lattice: out of memory");
  if (!pl)
    return; /* not covered (e.g. plane strain Eulerian): reported as such */
  double th[7];
  lc->ntheta = d->dim == 1 ? 1 : 7;
  for (int k = 0; k < lc->ntheta; k++) {
    lc->theta_deg[k] = lc->ntheta > 1 ? 15.0 * k : 0.0;
    th[k] = lc->theta_deg[k] * M_PI / 180.0;
  }
  mfs_sampling smp = {.theta = th, .ntheta = (size_t)lc->ntheta, .npoints = 101};
  double sbar = 0.0;
  st = mfs_classify(pl, &smp, &sbar, 1, &lc->cl);
  mfs_disp_plan_free(pl);
  if (st == MFS_ENOMEM)
    cli_die(1, "equivalent lattice: out of memory");
  if (st != MFS_OK)
    return;
  lc->ok = 1;
  mfs_class_label(lc->cl.labels, lc->label, sizeof lc->label);
}

static void put_text(FILE *f, const char *s)
{
  fputs(s ? s : "", f);
  fputc(',', f);
}

/* Where particle I is, for people: "particle 17 (plate.csv:19) at (0.1, 0.2)". */
static void where(const model_cmd *c, const mfs_particles *p, size_t I, char *buf, size_t len)
{
  char line[80] = "";
  if (c->have_file)
    snprintf(line, sizeof line, " (%s:%zu)", c->pf.path, particle_file_line(&c->pf, I));
  if (p->dim == 1)
    snprintf(buf, len, "particle %zu%s at x = %.6g", I, line, p->x[I]);
  else
    snprintf(buf, len, "particle %zu%s at (%.6g, %.6g)", I, line, p->x[2 * I], p->x[2 * I + 1]);
}

int cmd_check(int argc, char **argv)
{
  model_cmd c = {.m = {.fourier_points = 201, .fourier_angles = 7, .seed = 1}};
  cli_disc_defaults(&c.d);
  check_opts co = {0};
  unsigned char sd[CLI_DISC_NOPTS], sp[CLI_PHYSICS_NOPTS], sm[MODEL_NOPTS], sc[CHECK_NOPTS];
  cli_group g[4] = {{cli_disc_opts, &c.d, sd},
                    {cli_physics_opts, &c.d, sp},
                    {model_opts_table, &c.m, sm},
                    {check_table, &co, sc}};
  cli_parse(argc, argv, usage, about, g, 4);
  if (c.m.out && strcmp(c.m.out, "-") == 0)
    cli_die(2, "-o -: the summary goes to standard output; give -o FILE for the CSV");
  if (co.modes_prefix && !*co.modes_prefix)
    cli_die(2, "--write-modes '': expected a file name prefix");
  model_finish(&c, &g[0], &g[1], &g[2]);
  if (co.frame && c.s.disc.kernel->cusp)
    cli_die(2, "--frame eulerian with kernel %s: a cusp at r = 0 has no second derivatives",
            c.s.disc.kernel->name);

  cli_out_hold(); /* the CSV and the modes: all written, or none */
  /* lambda_max only for the step: to MFS_DT_ARPACK_TOL (1e-8; its error is far below 1e-6, and
   * the certificate bounds it from above); the zero modes at 1e-12 as in eigs */
  run_opts ro = {.zero_modes = 1, .tol = 1e-8, .arpack_tol = 1e-12, .lambda_tol = MFS_DT_ARPACK_TOL,
                 .certify = 1, .keep = 1};
  run_result r;
  model_run(&c, &ro, &r);
  lattice_check lc;
  classify_lattice(&c, co.frame, &lc);
  const mfs_model *m = r.m;
  const mfs_particles *p = m->p;
  const mfs_disc *d = &c.s.disc;

  /* modes */
  unsigned char *layer = model_boundary_layer(m);
  int nsp = 0;
  double *spm = model_spurious_modes(m, &r, &nsp);
  mode_info worst = {.participation = NAN, .boundary_share = NAN, .location = ""};
  int iw = -1;
  for (int k = 0; k < nsp; k++) { /* the most extended spurious mode is the worst */
    mode_info mi;
    mode_describe(m, layer, spm + (size_t)k * m->n, &mi);
    if (iw < 0 || mi.participation > worst.participation) {
      worst = mi;
      iw = k;
    }
  }
  mode_info top = {.participation = NAN, .boundary_share = NAN, .location = ""};
  if (r.have_lambda)
    mode_describe(m, layer, r.vmax, &top);
  if (co.modes_prefix)
    write_modes(&c, &r, co.modes_prefix);

  /* verdict */
  char verdict[128] = "";
  int rank = (r.have_zero && r.z.count > r.rigid) ||
             (lc.ok && (lc.cl.labels & MFS_LABEL_RANK_DEFICIENCY));
  /* under stress: an onset in tension, or in compression before the material's own
   * (C + sigma <= 0 at sigma/C = -1), is an instability of the discretization */
  int tens = lc.ok && ((lc.cl.labels & MFS_LABEL_TENSILE) || !isnan(lc.cl.onset_tension));
  int comp = lc.ok && !isnan(lc.cl.onset_compression) &&
             fabs(lc.cl.onset_compression + 1.0) >= 1e-6;
  int mat = lc.ok && (lc.cl.labels & MFS_LABEL_MATERIAL);
  const char *parts[5] = {rank ? "rank-deficiency" : NULL, tens ? "tensile" : NULL,
                          comp ? "compressive" : NULL, mat ? "material" : NULL,
                          r.nonpositive ? "negative-mass" : NULL};
  for (int k = 0; k < 5; k++)
    if (parts[k]) {
      if (verdict[0])
        strcat(verdict, "+");
      strcat(verdict, parts[k]);
    }
  if (!verdict[0])
    strcpy(verdict, "stable");

  double lam = r.have_lambda ? r.lambda : NAN, dtc = r.have_lambda ? mfs_dt_crit(lam) : NAN;
  double dtcert = r.have_cert && r.cr.ok ? mfs_dt_crit(r.cr.lambda_upper) : NAN;
  double dtg = mfs_dt_crit(r.g.lambda), dtb = r.br.lambda > 0.0 ? mfs_dt_crit(r.br.lambda) : NAN;
  const mfs_convention *cv = c.m.convention;
  int ur = -1; /* the user's rule: the convention peer's first rule */
  for (int k = 0; cv && cv->rule && mfs_step_rules[k]; k++)
    if (mfs_step_rules[k] == cv->rule)
      ur = k;
  double dtu = ur >= 0 ? r.dt_rule[ur] : NAN;

  /* the CSV opened first: its allocations fail before a line of the summary is out */
  cli_out out = {0};
  if (c.m.out)
    cli_out_open(&out, c.m.out);

  /* ---- the summary ---- */
  FILE *o = stdout;
  char w1[256], w2[256];
  const char *phys = d->material.physics == MFS_PHYS_PLANE_STRAIN ? "plane strain"
                     : d->dim == 1                                ? "bar"
                                                                  : "anti-plane shear";
  size_t nfix = 0;
  for (size_t I = 0; I < p->n; I++)
    nfix += m->fixed[I] != 0;
  fprintf(o, "mfstab check: %s, %dD %s, %zu particles (%zu fixed), %s %s, %s quadrature, %s mass\n",
          c.have_file ? c.pf.path : (d->source.perturb > 0.0 ? "perturbed lattice" : "lattice"),
          d->dim, phys, p->n, nfix, d->kernel->name, d->shape->name, d->quadrature->name,
          d->consistent_mass ? "consistent" : "lumped");
  fprintf(o, "  support radius a = %.6g m", mfs_disc_support(d));
  if (cv)
    fprintf(o, " (%s: h = %.6g m, %s -> mfstab %s, a = %g h)", cv->name, c.m.smoothing_length,
            cv->peer_kernel, cv->kernel->name, cv->support_per_h);
  fprintf(o, "; spacing %.6g m, a = %.4g dx\n", mfs_disc_dx(d), d->dilation);
  fprintf(o, "  material: E = %.6g Pa, nu = %.4g, rho = %.6g kg/m^3", c.young, c.poisson,
          d->material.density);
  if (d->dim == 2)
    fprintf(o, ", shear modulus %.6g Pa", c.shear);
  fprintf(o, "; wave speed c = %.6g m/s\n", r.dv.c);
  fprintf(o, "\nverdict: %s\n", verdict);
  int fin_sp = r.have_zero ? r.z.count - r.rigid : 0;
  if (rank && !r.have_zero)
    fprintf(o, "  rank-deficiency: the equivalent lattice has spurious zero-energy modes (the "
               "finite model's are not computed)\n");
  else if (rank && fin_sp == 0)
    fprintf(o, "  rank-deficiency: the equivalent lattice has spurious zero-energy modes; this "
               "finite model, by its boundary conditions, has none below 1e-8 lambda_max (the "
               "lowest nonzero is %.3g lambda_max)\n",
            r.z.lambda_min_nonzero / lam);
  else if (rank)
    fprintf(o, "  rank-deficiency: %d spurious zero-energy mode%s of the finite model%s\n", fin_sp,
            fin_sp == 1 ? "" : "s",
            lc.ok && (lc.cl.labels & MFS_LABEL_RANK_DEFICIENCY) ? " and of the equivalent lattice"
                                                                : "");
  if (r.nonpositive) {
    where(&c, p, r.min_mass_particle, w1, sizeof w1);
    fprintf(o, "  %zu lumped mass%s <= 0, the smallest %.4g at %s: explicit integration "
               "with this mass does not apply, nor lambda_max, dt_crit, dt_certified, "
               "dt_gershgorin or the zero modes\n",
            r.nonpositive, r.nonpositive == 1 ? "" : "es", r.min_mass, w1);
  }
  if (r.have_zero) {
    fprintf(o, "  finite model: %d zero-energy mode%s (%d rigid, %d spurious)", r.z.count,
            r.z.count == 1 ? "" : "s", r.rigid, r.z.count - r.rigid);
    if (iw >= 0) {
      where(&c, p, worst.peak_particle, w1, sizeof w1);
      fprintf(o, "; the most extended spurious mode involves %.0f%% of the particles, %s, "
                 "largest at %s",
              100.0 * worst.participation, worst.location, w1);
    }
    fputc('\n', o);
  }
  if (lc.ok) {
    fprintf(o, "  equivalent lattice (%s, dx = %.6g m, D = %.4g, %s frame): %s",
            mfs_disc_points(d) ? (d->dim == 1 ? "line" : "square") : "the model's",
            mfs_disc_dx(d), d->dilation, co.frame ? "Eulerian" : "Lagrangian", lc.label);
    if (lc.cl.spurious_zeros > 0)
      fprintf(o, "; spurious zeros at kappa dx/pi = %.4g, theta = %g deg", lc.cl.zero_kappa,
              lc.cl.zero_theta >= 0 ? lc.theta_deg[lc.cl.zero_theta] : 0.0);
    if (!isnan(lc.cl.onset_tension))
      fprintf(o, "; unstable in tension from sigma/C = %.4g", lc.cl.onset_tension);
    if (!isnan(lc.cl.onset_compression))
      fprintf(o, "; in compression from sigma/C = %.4g%s", lc.cl.onset_compression,
              fabs(lc.cl.onset_compression + 1.0) < 1e-6 ? " (C + sigma <= 0: the material's own)"
                                                          : "");
    fputc('\n', o);
  } else {
    fprintf(o, "  equivalent lattice: not classified (the dispersion analysis does not cover "
               "this combination)\n");
  }
  fprintf(o, "\ntime steps of the central difference method (s):\n");
  if (r.have_lambda)
    fprintf(o, "  dt_crit        %-12.6g 2/sqrt(lambda_max), lambda_max = %.6g 1/s^2 (ARPACK, arpack_tol %g)\n",
            dtc, lam, ro.lambda_tol);
  else
    fprintf(o, "  dt_crit        does not apply (lumped masses <= 0)\n");
  if (!isnan(dtcert))
    fprintf(o, "  dt_certified   %-12.6g proven: sigma M - K factored at sigma = 4/dt^2 (%.7f dt_crit)\n",
            dtcert, dtcert / dtc);
  fprintf(o, "  dt_gershgorin  ");
  if (isnan(dtg))
    fprintf(o, "%-12s %s\n", "-", d->consistent_mass ? "does not apply (consistent mass)"
                                                      : "does not apply (lumped masses <= 0)");
  else
    fprintf(o, "%-12.6g proven bound max_i sum_j |K_ij|/m_i (%.4f dt_crit)\n", dtg, dtg / dtc);
  fprintf(o, "  dt_bound       %-12.6g element bound (eq. 132), %s\n", dtb,
          r.bound_valid ? "proven" : (d->consistent_mass ? "not proven (consistent mass)"
                                                         : "NOT proven: some phi_I <= 0"));
  if (ur >= 0) {
    const mfs_step_rule *rule = mfs_step_rules[ur];
    double fct = c.m.rule_factor > 0.0 ? c.m.rule_factor : rule->factor;
    fprintf(o, "  your rule      %-12.6g %s, factor %g: %s", dtu, rule->peer, fct,
            isnan(dtc) ? "dt_crit unknown" : (dtu > dtc ? "UNSAFE (above dt_crit)" : "safe"));
    if (!isnan(dtc))
      fprintf(o, " (%.4f dt_crit)", dtu / dtc);
    fputc('\n', o);
  } else if (cv) {
    fprintf(o, "  your rule      %s has no step rule for solids (docs/conventions.md)\n", cv->peer);
  }
  fprintf(o, "  peers' rules at their default factors:\n");
  for (int k = 0; mfs_step_rules[k]; k++) {
    if (k == ur && !(c.m.rule_factor > 0.0))
      continue;
    double v = r.dt_rule[k];
    if (k == ur) { /* the peer's default factor */
      mfs_rule_args ra = {.dim = d->dim, .h = mfs_rule_h(mfs_step_rules[k], cv, mfs_disc_support(d)),
                          .young = c.young, .poisson = c.poisson, .density = d->material.density};
      v = mfs_rule_dt(mfs_step_rules[k], &ra, 0.0);
    }
    fprintf(o, "    %-16s %-12.6g %s\n", mfs_step_rules[k]->name, v,
            isnan(dtc) ? "" : (v > dtc ? "UNSAFE" : "safe"));
  }
  if (r.have_lambda) {
    where(&c, p, top.peak_particle, w2, sizeof w2);
    fprintf(o, "\nthe highest mode (it sets dt_crit): %s, %.0f%% of its energy within a of the "
               "boundary, involves %.0f%% of the particles, largest at %s\n",
            top.location, 100.0 * top.boundary_share, 100.0 * top.participation, w2);
  }
  if (co.modes_prefix && r.have_lambda)
    fprintf(o, "modes written to %s_modes.csv and %s_modes.vtk\n", co.modes_prefix, co.modes_prefix);

  /* ---- the CSV ---- */
  if (c.m.out) {
    FILE *f = out.f;
    eigs_config_header(f);
    fputs(",verdict,lambda_max_per_s2,dt_crit_s,dt_certified_s,certified_fraction,certify_margin,"
          "dt_gershgorin_s,gershgorin_ratio,dt_bound_s,bound_valid,negative_phi_points,rule,dt_rule_s,"
          "dt_rule_fraction,dt_rule_unsafe",
          f);
    rules_header(f);
    fputs(",zero_modes,rigid_modes,spurious_modes,lambda_min_nonzero_per_s2,spurious_participation,"
          "spurious_location,spurious_peak_particle,spurious_peak_x_m,spurious_peak_y_m,"
          "max_participation,max_location,max_boundary_share,max_peak_particle,max_peak_x_m,"
          "max_peak_y_m,lattice_label,lattice_spurious_zeros,lattice_zero_kappa_norm,lattice_zero_theta_deg,"
          "lattice_min_omega2_norm,lattice_onset_sigma_tension_norm,lattice_onset_sigma_compression_norm,"
          "nonpositive_masses,min_mass_kg,min_mass_particle,arpack_tol\n",
          f);
    eigs_config_row(f, &c, &c.s, &r.dv);
    fputc(',', f);
    put_text(f, verdict);
    eigs_put(f, lam, 0);
    eigs_put(f, dtc, 0);
    eigs_put(f, dtcert, 0);
    eigs_put(f, dtcert / dtc, 0);
    eigs_put(f, r.have_cert && r.cr.ok ? r.cr.margin : NAN, 0);
    eigs_put(f, dtg, 0);
    eigs_put(f, r.g.lambda / lam, 0);
    eigs_put(f, dtb, 0);
    fprintf(f, "%d,%zu,", r.bound_valid, r.br.negative_phi);
    put_text(f, ur >= 0 ? mfs_step_rules[ur]->name : "");
    eigs_put(f, dtu, 0);
    eigs_put(f, dtu / dtc, 0);
    if (!isnan(dtu) && !isnan(dtc))
      fprintf(f, "%d", dtu > dtc);
    fputc(',', f);
    rules_row(f, r.dt_rule, dtc, dtc, 0);
    if (r.have_zero) {
      fprintf(f, "%d,%d,%d,", r.z.count, r.rigid, r.z.count - r.rigid);
      eigs_put(f, r.z.lambda_min_nonzero, 0);
    } else {
      fputs(",,,,", f);
    }
    eigs_put(f, worst.participation, 0);
    put_text(f, iw >= 0 ? worst.location : "");
    if (iw >= 0) {
      fprintf(f, "%zu,", worst.peak_particle);
      eigs_put(f, p->x[worst.peak_particle * (size_t)p->dim], 0);
      eigs_put(f, p->dim == 2 ? p->x[worst.peak_particle * 2 + 1] : NAN, 0);
    } else {
      fputs(",,,", f);
    }
    eigs_put(f, top.participation, 0);
    put_text(f, r.have_lambda ? top.location : "");
    eigs_put(f, top.boundary_share, 0);
    if (r.have_lambda) {
      fprintf(f, "%zu,", top.peak_particle);
      eigs_put(f, p->x[top.peak_particle * (size_t)p->dim], 0);
      eigs_put(f, p->dim == 2 ? p->x[top.peak_particle * 2 + 1] : NAN, 0);
    } else {
      fputs(",,,", f);
    }
    put_text(f, lc.ok ? lc.label : "");
    if (lc.ok) {
      fprintf(f, "%d,", lc.cl.spurious_zeros);
      eigs_put(f, lc.cl.zero_kappa, 0);
      eigs_put(f, lc.cl.zero_theta >= 0 ? lc.theta_deg[lc.cl.zero_theta] : NAN, 0);
      eigs_put(f, lc.cl.min_omega2, 0);
      eigs_put(f, lc.cl.onset_tension, 0);
      eigs_put(f, lc.cl.onset_compression, 0);
    } else {
      fputs(",,,,,,", f);
    }
    fprintf(f, "%zu,", r.nonpositive);
    eigs_put(f, r.min_mass, 0);
    if (!d->consistent_mass)
      fprintf(f, "%zu", r.min_mass_particle);
    fputc(',', f);
    eigs_put(f, r.have_lambda ? ro.lambda_tol : NAN, 1);
    cli_out_commit(&out);
  }
  cli_out_release();
  mfs_free(spm);
  mfs_free(layer);
  run_result_free(&r);
  model_cmd_free(&c);
  return 0;
}
