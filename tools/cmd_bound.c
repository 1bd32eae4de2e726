/* mfstab bound: the cheap bounds of a finite model and the critical time
 * steps they give, without computing eigenvalues: the element bound (paper
 * 003 eqs 123-133, 139-144), the Gershgorin bound (streamed row by row, K is
 * never stored), the closed forms, the Fourier estimate, the peers' step
 * rules; with --certify a step proven stable by a factorization of
 * sigma M - K searched from a short Lanczos run.  For models too large for
 * `mfstab eigs`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"
#include "eigs_figures.h"
#include "model_run.h"
#include "par.h"

static const char usage[] = "mfstab bound [options] [-o FILE]";
static const char about[] =
  "Element eigenvalue bound lambda_max <= max_Q lambda^Q of a finite model with lumped mass\n"
  "(paper 003 eqs 121-133; 2D: the exact largest eigenvalue of the 2 x 2 matrix\n"
  "c^2 sum_I g_I g_I^T / phi_I, eqs 139-144 without assuming eq. 141), streamed over the\n"
  "quadrature points of a lattice (O(N)); the Gershgorin bound max_i sum_j |K_ij| / m_i\n"
  "(lumped mass, every m_i > 0), streamed row by row from the shape table; and the critical\n"
  "time steps dt = 2/sqrt(lambda) of the central difference method from them, from the\n"
  "closed form alpha c^2/h^2 (eq. 136 1D, eq. 146 2D), from the Fourier maximum of the\n"
  "uniform lattice, the rules of thumb 0.3 h/c (h = a/2; P-wave and bulk speeds) and the\n"
  "peers' step rules (docs/conventions.md).  --certify: dt_certified, a step proven stable by\n"
  "a CHOLMOD factorization of sigma M - K, searched up from a short Lanczos estimate\n"
  "(relative accuracy 1e-4; the model is assembled for it).\n"
  "The element bound is proven only where every phi_I > 0 at the quadrature points and the mass\n"
  "is lumped (bound_valid = 1); negative_phi_points counts the points where some phi_I <= 0.\n"
  "Models and options as 'mfstab eigs' (no eigenvalue options).\n"
  "CSV (one row): the configuration columns of 'mfstab eigs', then particles,quadrature_points,\n"
  "  evaluated_points,bound_per_s2,bound_valid,negative_phi_points,x_at_bound_m,y_at_bound_m,\n"
  "  bound_alpha_per_s2,alpha,lambda_fourier_per_s2,kappa_fourier_norm,theta_fourier_deg,\n"
  "  dt_bound_s,dt_alpha_s,dt_fourier_s,dt_rule_p_s,\n"
  "  dt_rule_bulk_s,nonpositive_masses,min_mass_kg,min_mass_particle,lambda_gershgorin_per_s2,\n"
  "  dt_gershgorin_s,x_at_gershgorin_m,y_at_gershgorin_m,dt_rule_<peer>_s,dt_rule_<peer>_unsafe\n"
  "  (unsafe: 1 above 2/sqrt(lambda_lanczos_per_s2) >= dt_crit_s, 0 at most dt_certified_s, else\n"
  "  empty; empty without --certify)\n"
  "  with --certify: lambda_lanczos_per_s2,sigma_certified_per_s2,dt_certified_s,certify_margin,\n"
  "  certify_factorizations\n"
  "Under mpirun -np N the Gershgorin and element bounds run over the ranks (docs/parallel.md);\n"
  "--certify needs one process.\n";

/* The plan of the model (geometry, neighbour lists, shape table), for the
 * Gershgorin rows and, on a set or a perturbed lattice, the element bound. */
typedef struct {
  mfs_particles *p;
  mfs_quad *q;
  mfs_plan *pl;
  unsigned char *fixed;
} model_plan;

static void plan_build(const model_cmd *c, model_plan *mp)
{
  memset(mp, 0, sizeof *mp);
  const mfs_model_spec *s = &c->s;
  mfs_status st = mfs_disc_geometry(&s->disc, &mp->p, &mp->q);
  size_t bad = 0;
  if (st != MFS_OK)
    model_die_status(c, st, 0, "geometry");
  mp->pl = mfs_plan_alloc(&s->disc, mp->p, mp->q, &st);
  if (!mp->pl)
    model_die_status(c, st, 0, "neighbour lists");
  st = mfs_plan_tabulate(mp->pl, 1, &bad);
  if (st != MFS_OK)
    model_die_status(c, st, bad, "at a quadrature point of the model");
  if (s->fixed != MFS_FIX_NONE) {
    mp->fixed = mfs_malloc(mp->p->n);
    if (!mp->fixed)
      cli_die(1, "out of memory");
    for (size_t I = 0; I < mp->p->n; I++)
      mp->fixed[I] = s->fixed == MFS_FIX_MASK ? s->fix_mask[I] != 0 : mp->p->flags[I] != 0;
  }
}

static void plan_free(model_plan *mp)
{
  mfs_plan_free(mp->pl);
  mfs_quad_free(mp->q);
  mfs_particles_free(mp->p);
  mfs_free(mp->fixed);
}

/* The element and Gershgorin bounds in one process. */
static void bound_serial(const model_cmd *c, mfs_bound_result *br, mfs_gershgorin_result *gr,
                         double *gx, size_t *mI, size_t *np, size_t *npts)
{
  const mfs_disc *d = &c->s.disc;
  size_t bad = 0;
  mfs_status st;
  model_plan mp;
  plan_build(c, &mp);
  int lattice = !mfs_disc_points(d) && !(d->source.perturb > 0.0);
  if (lattice) /* the streaming bound: equivalent points evaluated once */
    st = mfs_bound_model(&c->s, br, &bad);
  else
    st = mfs_bound_plan(mp.pl, &d->material, mp.fixed, br);
  if (st != MFS_OK)
    model_die_status(c, st, bad, "at a quadrature point of the model");
  if (!(br->lambda > 0.0))
    cli_die(1, "the element bound is %g: no quadrature point with a positive lambda^Q", br->lambda);
  if (!d->consistent_mass) {
    st = mfs_gershgorin_plan(mp.pl, &d->material, mp.fixed, gr);
    if (st != MFS_OK)
      cli_die(1, "Gershgorin bound: %s", mfs_strerror(st));
  }
  *np = mp.p->n;
  *npts = mfs_plan_npoints(mp.pl);
  int ndof = mfs_physics_ndof(d->material.physics);
  if (isfinite(gr->lambda))
    for (int k = 0; k < d->dim; k++)
      gx[k] = mp.p->x[(gr->argmax / (size_t)ndof) * (size_t)d->dim + (size_t)k];
  *mI = gr->argmin_mass / (size_t)ndof;
  plan_free(&mp);
}

int cmd_bound(int argc, char **argv)
{
  model_cmd c = {.m = {.fourier_points = 201, .fourier_angles = 7, .seed = 1}};
  cli_disc_defaults(&c.d);
  unsigned char sd[CLI_DISC_NOPTS], sp[CLI_PHYSICS_NOPTS], sm[MODEL_NOPTS];
  cli_group g[3] = {
    {cli_disc_opts, &c.d, sd}, {cli_physics_opts, &c.d, sp}, {model_opts_table, &c.m, sm}};
  cli_parse(argc, argv, usage, about, g, 3);
  model_finish(&c, &g[0], &g[1], &g[2]);
  eigs_derived dv;
  eigs_derive(&c.s, &dv);
  const mfs_disc *d = &c.s.disc;
  mfs_bound_result br;
  size_t bad = 0, np, npts, mI;
  mfs_status st;
  double gx[2] = {NAN, NAN};
  mfs_gershgorin_result gr = {.lambda = NAN, .min_mass = NAN};
  if (par_active() && c.m.certify)
    par_need_one("--certify");
  if (par_active() && !c.m.certify) /* mpirun: over the ranks (tools/model_prun.c) */
    bound_prun(&c, &br, &gr, gx, &mI, &np, &npts);
  else
    bound_serial(&c, &br, &gr, gx, &mI, &np, &npts);
  double lf, kf, tf;
  st = mfs_bound_fourier(&c.s, (int)c.m.fourier_points, (int)c.m.fourier_angles, &lf, &kf, &tf);
  if (st != MFS_OK)
    model_die_status(&c, st, 0, "Fourier estimate on the uniform lattice");
  int bvalid = !d->consistent_mass && br.negative_phi == 0;
  double rules[RUN_MAX_RULES];
  model_rules(&c, rules);

  /* --certify: a short Lanczos run on the assembled model, then the factorizations */
  mfs_certify_result cr = {0};
  double lan = NAN;
  int have_cert = 0;
  if (c.m.certify && gr.nonpositive == 0) {
    mfs_model *m = mfs_model_alloc(&c.s, &st, &bad);
    if (!m)
      model_die_status(&c, st, bad, "at a quadrature point of the model");
    mfs_model_release_plan(m);
    mfs_pencil P = {m->K, m->M, m->m};
    /* a lower bound of lambda_max: plain Lanczos with a lumped mass (mfs_lanczos.h; no
     * eigenvector needed, 1e-4 is enough), ARPACK at 1e-3 with a consistent one (a
     * Ritz value within 1e-5 of lambda_max on the models of
     * analysis/bench/bench_check.sh); both below the first gap 4e-4, and a failed
     * factorization retries at 4 times the gap (certified_fraction still >= 0.999) */
    if (P.m) {
      mfs_lanczos_opts lo = {.tol = 1e-4};
      st = mfs_lanczos_max(&P, &lo, &lan, NULL);
    } else {
      mfs_eig_opts eo = {0, 0, 1e-3};
      mfs_eig_info info;
      st = mfs_eig_max(&P, &eo, &lan, NULL, &info);
    }
    if (st != MFS_OK || !(lan > 0.0))
      cli_die(1, "certification: the Lanczos estimate failed (%s)", mfs_strerror(st));
    double *x = mfs_model_coords(m); /* the factorization ordered by the particles' positions */
    if (!x)
      cli_die(1, "certification: out of memory");
    mfs_certify_opts co = {.lambda_est = lan, .gap = 4e-4, .growth = 4.0, .coord = x,
                           .coord_dim = m->p->dim};
    st = mfs_eig_certify_search(&P, &co, &cr);
    mfs_free(x);
    if (st != MFS_OK)
      cli_die(1, "certification: %s", mfs_strerror(st));
    have_cert = cr.ok;
    mfs_model_free(m);
  }
  double dtcert = have_cert ? mfs_dt_crit(cr.lambda_upper) : NAN;

  cli_out out;
  cli_out_open(&out, par_out_path(c.m.out));
  FILE *f = out.f;
  eigs_config_header(f);
  fputs(",particles,quadrature_points,evaluated_points,bound_per_s2,bound_valid,negative_phi_points,"
        "x_at_bound_m,y_at_bound_m,bound_alpha_per_s2,alpha,lambda_fourier_per_s2,kappa_fourier_norm,theta_fourier_deg,"
        "dt_bound_s,dt_alpha_s,dt_fourier_s,dt_rule_p_s,dt_rule_bulk_s,nonpositive_masses,min_mass_kg,"
        "min_mass_particle,lambda_gershgorin_per_s2,dt_gershgorin_s,x_at_gershgorin_m,y_at_gershgorin_m",
        f);
  rules_header(f);
  if (c.m.certify)
    fputs(",lambda_lanczos_per_s2,sigma_certified_per_s2,dt_certified_s,certify_margin,certify_factorizations", f);
  fputc('\n', f);
  eigs_config_row(f, &c, &c.s, &dv);
  fprintf(f, ",%zu,%zu,%zu,", np, npts, br.evaluated);
  eigs_put(f, br.lambda, 0);
  fprintf(f, "%d,%zu,", bvalid, br.negative_phi);
  eigs_put(f, br.xmax[0], 0);
  eigs_put(f, br.xmax[1], 0);
  eigs_put_estimates(f, &dv, lf, kf, tf);
  eigs_put(f, mfs_dt_crit(br.lambda), 0);
  eigs_put(f, mfs_dt_crit(dv.bound_alpha), 0);
  eigs_put(f, mfs_dt_crit(lf), 0);
  eigs_put(f, dv.dt_rule_p, 0);
  eigs_put(f, dv.dt_rule_bulk, 0);
  if (d->consistent_mass)
    fputs(",,,", f);
  else
    fprintf(f, "%zu,", gr.nonpositive);
  if (!d->consistent_mass) {
    eigs_put(f, gr.min_mass, 0);
    fprintf(f, "%zu,", mI);
  }
  eigs_put(f, gr.lambda, 0);
  eigs_put(f, mfs_dt_crit(gr.lambda), 0);
  eigs_put(f, gx[0], 0);
  cli_put_num(f, d->dim == 2 ? gx[1] : (isfinite(gx[0]) ? 0.0 : NAN), "y_at_gershgorin");
  fputc(',', f);
  rules_row(f, rules, dtcert, isnan(lan) ? NAN : mfs_dt_crit(lan), !c.m.certify);
  if (c.m.certify) {
    eigs_put(f, lan, 0);
    eigs_put(f, have_cert ? cr.lambda_upper : NAN, 0);
    eigs_put(f, dtcert, 0);
    eigs_put(f, have_cert ? cr.margin : NAN, 0);
    if (!isnan(lan))
      fprintf(f, "%d", cr.factorizations);
    fputc('\n', f);
  }
  cli_out_commit(&out);
  if (gr.nonpositive > 0)
    fprintf(stderr,
            "mfstab bound: note: %zu lumped mass%s <= 0 (the smallest %g at particle %zu): the "
            "Gershgorin bound and the certification do not apply (empty cells)\n",
            gr.nonpositive, gr.nonpositive == 1 ? "" : "es", gr.min_mass, mI);
  model_cmd_free(&c);
  return 0;
}
