/* mfstab eigs: extreme eigenvalues, zero-energy modes and critical time
 * steps of a finite particle model (paper 003 section 5), side by side with
 * the element bound, the Gershgorin bound, the certified step, the closed
 * form, the Fourier estimate and the peers' step rules; the options shared
 * with `mfstab bound` and `mfstab check` (the model: a lattice box, a
 * perturbed lattice or a particle file, the support in the user's terms, the
 * material in SI); and the data of Figs 17 and 18. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"
#include "eigs_figures.h"
#include "model_run.h"
#include "par.h"

static const char usage[] = "mfstab eigs [options] [-o FILE]";
static const char about_model[] =
  "Largest eigenvalue lambda_max = omega_max^2 of K v = lambda M v of a finite model (ARPACK;\n"
  "lumped mass: symmetric standard problem M^-1/2 K M^-1/2; consistent mass: generalized mode,\n"
  "CHOLMOD solves with M), with --zero-modes the zero-energy modes (shift-invert ARPACK about\n"
  "sigma = -tol lambda_max), and the critical time step of the undamped central difference\n"
  "method dt = 2/omega_max (paper 003 eqs 120, 124) from (the columns NAME_s, in s):\n"
  "  dt_crit        the exact lambda_max\n"
  "  dt_certified   (--certify) a step proven stable: CHOLMOD factors sigma M - K at\n"
  "                 sigma = 4/dt^2, searched up from lambda_max (rounding margin included)\n"
  "  dt_gershgorin  max_i sum_j |K_ij| / m_i, a proven bound (lumped mass, every m_i > 0)\n"
  "  dt_bound       the element bound max_Q lambda^Q (eqs 123-133, 139-144; lumped mass, phi_I > 0)\n"
  "  dt_alpha       the closed form alpha c^2/h^2 (eq. 136 1D, eq. 146 2D; h = a = D dx)\n"
  "  dt_fourier     the largest omega^2 of plane waves on the infinite uniform lattice\n"
  "  dt_rule_p      the rule of thumb 0.3 h/c with the SPH smoothing length h = a/2 and the\n"
  "                 P-wave speed (1D: bar speed sqrt(E/rho); 2D: sqrt((lambda+2mu)/rho))\n"
  "  dt_rule_bulk   the same with the bulk speed sqrt(K/rho), K = E/(3(1-2 nu))\n"
  "  dt_rule_<peer> the peers' own step rules with their default factors (docs/conventions.md),\n"
  "                 each with dt_rule_<peer>_unsafe = 1 when it is above dt_crit\n"
  "Models: 1D bar of N nodes on [0, L] (end nodes on the ends), 2D rectangle of NX x NY nodes\n"
  "on [0, LX] x [0, LY] (square lattice, 2D anti-plane shear or plane strain); periodic:\n"
  "dx = L/N; --perturb F moves every coordinate by up to F dx (seeded); or a particle file\n"
  "(--particles FILE: CSV x[,y][,volume][,group]) with --support A or --smoothing-length H\n"
  "--convention NAME.  Material: 1D --young E (or --modulus); 2D --young E --poisson NU or\n"
  "--shear-modulus MU; --density RHO.  c = sqrt(modulus/rho), modulus E (1D) or mu (2D).\n";
/* the help in two literals (each under C's 4095 characters) */
static const char about_csv[] =
  "CSV (one row, or one per seed with --seeds); units in the names (docs/commands.md):\n"
  "  the configuration dim,nodes_x,nodes_y,length_x_m,length_y_m,dx_m,dy_m,kernel,shape,\n"
  "  quadrature,mass,dilation,support_radius_m,fixed,periodic,physics,modulus_pa,\n"
  "  density_kg_m3,poisson,wave_speed_m_s,source,perturb,seed,convention,smoothing_length_m,\n"
  "  young_modulus_pa,shear_modulus_pa, then dofs,lambda_max_per_s2,omega_max_rad_s,\n"
  "  bound_per_s2,bound_valid,negative_phi_points,bound_alpha_per_s2,alpha,\n"
  "  lambda_fourier_per_s2,kappa_fourier_norm,theta_fourier_deg,dt_crit_s,dt_bound_s,\n"
  "  dt_alpha_s,dt_fourier_s,dt_rule_p_s,dt_rule_bulk_s,bound_ratio,arpack_iterations,\n"
  "  arpack_matvecs,arpack_residual,arpack_tol,particles,nonpositive_masses,min_mass_kg,\n"
  "  min_mass_particle,min_mass_x_m,min_mass_y_m,lambda_gershgorin_per_s2,dt_gershgorin_s,\n"
  "  gershgorin_ratio,dt_rule_<peer>_s,dt_rule_<peer>_unsafe (lammps_smd, sphinxsys,\n"
  "  sphinxsys_pwave, trixiparticles, dualsphysics)\n"
  "  with --certify: sigma_certified_per_s2,dt_certified_s,certified_fraction,\n"
  "  certify_margin,certify_factorizations\n"
  "  with --zero-modes: zero_tol,zero_modes,rigid_modes,spurious_modes,\n"
  "  lambda_min_nonzero_per_s2,zero_runs\n"
  "  with --seeds N: seeds,lambda_max_min_per_s2,lambda_max_median_per_s2,\n"
  "  lambda_max_max_per_s2,zero_modes_min,zero_modes_median,zero_modes_max,\n"
  "  negative_phi_min,negative_phi_median,negative_phi_max,\n"
  "  nonpositive_mass_models (over the N seeds, on every row)\n"
  "Empty cells are undefined values: with a lumped mass m_i <= 0 (MLS on strongly disordered\n"
  "sets) every result that needs positive masses (lambda_max, the time steps from it, the\n"
  "Gershgorin bound, zero modes, certification) does not apply and is empty;\n"
  "nonpositive_masses counts those masses and min_mass_particle (0-based) names the smallest.\n"
  "bound_valid is 1 when the element bound is a proven bound: lumped mass and every phi_I > 0 at\n"
  "the quadrature points (negative_phi_points counts the points where some phi_I <= 0).\n"
  "bound_ratio = bound / lambda_max, gershgorin_ratio = lambda_gershgorin / lambda_max,\n"
  "certified_fraction = dt_certified / dt_crit.  rigid_modes counts the rigid fields (constant;\n"
  "plane strain: translations and rotation) that are null vectors of K; spurious_modes the\n"
  "other zero modes.  --write-modes PREFIX writes PREFIX_modes.csv and PREFIX_modes.vtk.\n";

/* ------------------------------------------------------------------ */
/* the options of a finite model, shared with bound and check           */

static const char *const fixed_names[] = {"none", "ends", "boundary", NULL};

static const void *find_convention(const char *n)
{
  return mfs_convention_find(n);
}

#define MOFF(f) offsetof(model_opts, f)
const cli_opt model_opts_table[] = {
  {.name = "--nodes", .type = CLI_TEXT, .arg = "N|NX,NY",
   .help = "nodes (default 41 in 1D, 21,21 in 2D; N alone in 2D: N x N)", .offset = MOFF(nodes)},
  {.name = "--length", .type = CLI_TEXT, .arg = "L|LX,LY",
   .help = "domain size (default 1, 1 x 1)", .offset = MOFF(length)},
  {.name = "--fixed", .type = CLI_CHOICE, .arg = "none|ends|boundary",
   .help = "remove the dofs of the end (1D) or boundary (2D; a particle file: its convex "
           "hull) nodes",
   .offset = MOFF(fixed), .choices = fixed_names},
  {.name = "--periodic", .type = CLI_FLAG, .help = "periodic model (dx = L/N); excludes --fixed",
   .offset = MOFF(periodic)},
  {.name = "--fourier-points", .type = CLI_INT, .arg = "K",
   .help = "sampling of the Fourier maximum: points per ray (201)",
   .offset = MOFF(fourier_points), .bounds = CLI_GE | CLI_LE, .lo = 2, .hi = 100000},
  {.name = "--fourier-angles", .type = CLI_INT, .arg = "K",
   .help = "... and angles in [0, 90] degrees (7)", .offset = MOFF(fourier_angles),
   .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 1000},
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE", .help = "output file (default: standard output)",
   .offset = MOFF(out)},
  {.name = "--particles", .type = CLI_TEXT, .arg = "FILE",
   .help = "a particle file: CSV with a header x (1D) or x,y (2D), optional volume (m or m^2; "
           "without it the dual volumes of the Delaunay triangulation) and group",
   .offset = MOFF(particles)},
  {.name = "--fix", .type = CLI_TEXT, .arg = "GROUP[,GROUP]",
   .help = "fix the particles of these groups of the particle file", .offset = MOFF(fix)},
  {.name = "--support", .type = CLI_REAL, .arg = "A",
   .help = "the support radius a in metres (instead of --dilation; needed for a particle "
           "file without --smoothing-length)",
   .offset = MOFF(support), .bounds = CLI_GE | CLI_LE, .lo = 1e-30, .hi = 1e30},
  {.name = "--smoothing-length", .type = CLI_REAL, .arg = "H",
   .help = "a peer code's smoothing length h in metres, mapped by --convention", .offset =
   MOFF(smoothing_length), .bounds = CLI_GE | CLI_LE, .lo = 1e-30, .hi = 1e30},
  {.name = "--convention", .type = CLI_TABLE, .arg = "NAME",
   .help = "the peer code whose h and kernel --smoothing-length gives (docs/conventions.md)",
   .offset = MOFF(convention), .find = find_convention,
   .list = (const void *const *)mfs_conventions},
  {.name = "--perturb", .type = CLI_REAL, .arg = "F",
   .help = "move each coordinate of the lattice by a uniform random amount in [-F, F] dx "
           "(boundary particles along their boundary), 0 <= F < 0.5",
   .offset = MOFF(perturb), .bounds = CLI_GE | CLI_LT, .lo = 0, .hi = 0.5},
  {.name = "--seed", .type = CLI_INT, .arg = "S", .help = "seed of --perturb (default 1)",
   .offset = MOFF(seed), .bounds = CLI_GE | CLI_LE, .lo = 0, .hi = 4294967295.0},
  {.name = "--young", .type = CLI_REAL, .arg = "E",
   .help = "Young's modulus (Pa); in 2D with --poisson NU", .offset = MOFF(young),
   .bounds = CLI_GT, .lo = 0},
  {.name = "--shear-modulus", .type = CLI_REAL, .arg = "MU", .help = "the shear modulus (Pa; 2D)",
   .offset = MOFF(shear_modulus), .bounds = CLI_GT, .lo = 0},
  {.name = "--rule-factor", .type = CLI_REAL, .arg = "F",
   .help = "the safety factor of the --convention peer's step rule (default: the peer's)",
   .offset = MOFF(rule_factor), .bounds = CLI_GT, .lo = 0},
  {.name = "--certify", .type = CLI_FLAG,
   .help = "dt_certified: factor sigma M - K (CHOLMOD) to prove a step stable (check: always)",
   .offset = MOFF(certify)},
  {.type = CLI_END}};
#undef MOFF
_Static_assert(sizeof model_opts_table / sizeof model_opts_table[0] == MODEL_NOPTS, "MODEL_NOPTS");

/* "N" or "NX,NY": returns the count of numbers (1 or 2), or dies. */
static int parse_nodes(const char *val, long *nx, long *ny)
{
  const char *comma = strchr(val, ',');
  char a[64], b[64];
  int k = 1;
  if (strlen(val) >= sizeof a)
    goto bad;
  if (comma) {
    if (strchr(comma + 1, ','))
      goto bad;
    size_t la = (size_t)(comma - val);
    memcpy(a, val, la);
    a[la] = '\0';
    strcpy(b, comma + 1);
    k = 2;
  } else {
    strcpy(a, val);
  }
  if (!cli_parse_long(a, nx) || (k == 2 && !cli_parse_long(b, ny)))
    goto bad;
  if (k == 1)
    *ny = *nx;
  if (*nx < 2 || *ny < 2 || *nx > 100000000L || *ny > 100000000L)
    cli_die(2, "--nodes %s: out of range; every count must be 2 to 100000000", val);
  return k;
bad:
  cli_die(2, "--nodes '%s': expected N (1D) or NX,NY (2D) with integers >= 2", val);
}

/* The material of the options: E in 1D, the shear modulus mu in 2D (from
 * --shear-modulus, or --young with --poisson), and E and nu for the peers'
 * rules.  --modulus (E in 1D) is refused in 2D, where it was the shear modulus. */
static void resolve_material(model_cmd *c, mfs_disc *disc, const cli_group *dg,
                             const cli_group *pg, const cli_group *mg)
{
  int dim = disc->dim;
  int gm = cli_seen(dg, "--modulus"), gy = cli_seen(mg, "--young"),
      gs = cli_seen(mg, "--shear-modulus"), gp = cli_seen(pg, "--poisson");
  double nu = c->d.poisson;
  if (gm + gy + gs > 1)
    cli_die(2, "%s with %s: give the modulus once (1D: --young E; 2D: --young E --poisson NU, or "
               "--shear-modulus MU)",
            gm ? "--modulus" : "--young", gs ? "--shear-modulus" : "--young");
  if (dim == 1) {
    if (gs)
      cli_die(2, "--shear-modulus: a 1D bar has Young's modulus; give --young E");
    disc->material.modulus = gy ? c->m.young : c->d.modulus;
    c->young = disc->material.modulus;
    c->shear = NAN;
  } else {
    if (gm)
      cli_die(2, "--modulus %g: ambiguous in 2D; give --young E --poisson NU, or --shear-modulus MU",
              c->d.modulus);
    if (gy && !gp)
      cli_die(2, "--young %g: in 2D give --poisson NU too (the shear modulus is E/(2(1+nu)))",
              c->m.young);
    double mu = gy ? c->m.young / (2.0 * (1.0 + nu)) : (gs ? c->m.shear_modulus : 1.0);
    disc->material.modulus = mu;
    c->shear = mu;
    c->young = gy ? c->m.young : 2.0 * mu * (1.0 + nu);
  }
  c->poisson = nu;
}

_Noreturn void model_die_status(const model_cmd *c, mfs_status st, size_t bad, const char *what)
{
  const mfs_disc *d = &c->s.disc;
  if (c->have_file && st == MFS_ESINGULAR) {
    const particle_file *pf = &c->pf;
    /* the failing quadrature point: its position from the rule on the set */
    mfs_particles *p = NULL;
    mfs_quad *q = NULL;
    double x[2] = {0.0, 0.0};
    int node = -1;
    if (mfs_disc_geometry(d, &p, &q) == MFS_OK && bad < q->n) {
      memcpy(x, q->x + bad * (size_t)q->dim, (size_t)q->dim * sizeof *x);
      node = q->node[bad];
    }
    mfs_quad_free(q);
    mfs_particles_free(p);
    size_t I = node >= 0 ? (size_t)node : particle_file_nearest(pf, x);
    double a = mfs_disc_support(d);
    size_t cnt = 0; /* particles within the support of the point: one scan for one message */
    for (size_t J = 0; J < pf->n; J++) {
      double r2 = 0.0;
      for (int k = 0; k < pf->dim; k++) {
        double t = pf->x[J * pf->dim + k] - x[k];
        r2 += t * t;
      }
      cnt += r2 < a * a;
    }
    char where[160];
    if (pf->dim == 1)
      snprintf(where, sizeof where, "x = %g", x[0]);
    else
      snprintf(where, sizeof where, "(%g, %g)", x[0], x[1]);
    cli_die(2,
            "%s:%zu: %s %s has %zu particle%s within %s %g: too few for the %s shape functions "
            "(%s); raise %s",
            pf->path, particle_file_line(pf, I),
            node >= 0 ? "the particle at" : "the quadrature point near this particle, at", where,
            cnt, cnt == 1 ? "" : "s", c->support_option, a, d->shape->name,
            pf->dim == 1 ? "at least 2" : "at least 3 not on a line", c->support_option);
  }
  if (st == MFS_EDOMAIN && c->have_file)
    cli_die(2, "%s: no Delaunay triangulation of the particles (all on a line?); give volumes "
               "and --quadrature nodal",
            c->pf.path);
  if (st == MFS_ESINGULAR && strcmp(c->support_option, "--dilation") != 0)
    cli_die(2, "%s %g: too small for the %s moment matrix with kernel %s (singular %s); use a "
               "larger support",
            c->support_option, mfs_disc_support(d), d->shape->name, d->kernel->name, what);
  cli_die_status(st, &c->d, d->dilation, what);
}

/* A particle file as the model. */
static void finish_file(model_cmd *c, mfs_disc *disc, const cli_group *dg, const cli_group *mg)
{
  model_opts *o = &c->m;
  const char *clash[] = {"--nodes", "--length", "--periodic", "--perturb", "--seed"};
  for (int i = 0; i < 5; i++)
    if (cli_seen(mg, clash[i]))
      cli_die(2, "%s with --particles: the particle file is the model", clash[i]);
  if (cli_seen(dg, "--spacing") || cli_seen(dg, "--gamma") || cli_seen(dg, "--lattice"))
    cli_die(2, "%s with --particles: the particle file is the model",
            cli_seen(dg, "--spacing") ? "--spacing" : cli_seen(dg, "--gamma") ? "--gamma" : "--lattice");
  if (cli_seen(mg, "--fix") && cli_seen(mg, "--fixed"))
    cli_die(2, "--fix with --fixed: fix groups (--fix) or the boundary (--fixed), not both");
  particle_file_read(&c->pf, o->particles, 1e-10);
  particle_file_volumes(&c->pf);
  c->have_file = 1;
  if (cli_seen(dg, "--dim") && c->d.dim != c->pf.dim)
    cli_die(2, "--dim %ld: %s holds a %dD set (header %s)", c->d.dim, o->particles, c->pf.dim,
            c->pf.dim == 1 ? "x" : "x,y");
  disc->dim = c->pf.dim;
  disc->source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &c->pf.set};
  if (!mfs_quad_applies(disc->quadrature, disc->dim, MFS_LATTICE_POINTS)) {
    char names[256];
    cli_die(2, "--quadrature %s: not defined on a particle set in %dD; allowed: %s",
            disc->quadrature->name, disc->dim,
            cli_quad_names(disc->dim, MFS_LATTICE_POINTS, names, sizeof names));
  }
  if (c->d.physics == 1 && disc->dim != 2)
    cli_die(2, "--physics plane-strain needs a 2D particle file (x,y)");
  if (!(disc->support > 0.0))
    cli_die(2, "--particles %s: give the support radius: --support A (m), or --smoothing-length H "
               "--convention NAME",
            o->particles);
  disc->dilation = disc->support / mfs_disc_dx(disc);
  /* the work: the particles within the support of each other, counted (a
   * cluster of 2 10^4 particles in a 90 000-particle file took 12 GB and
   * minutes before this), times the quadrature's points per particle; the
   * count stops past the limit */
  {
    double n = (double)c->pf.n, points = 0.0, pairs = 0.0;
    mfs_disc_plan_entries(disc, n, &points);
    double per = points > 0.0 ? points / n : 1.0;
    double lim = c->d.max_entries > 0.0 ? c->d.max_entries : CLI_MAX_ENTRIES;
    mfs_status st = mfs_point_set_neighbours(&c->pf.set, disc->support, lim / per, &pairs);
    if (st != MFS_OK)
      cli_die(st == MFS_ENOMEM ? 1 : 2, "%s: counting the neighbours: %s", o->particles,
              mfs_strerror(st));
    char what[160];
    int more = pairs > lim / per; /* the count stopped there */
    snprintf(what, sizeof what, "--particles %s, support radius %g m: %s%.3g particle pairs "
             "within it, %.3g quadrature point%s per particle", o->particles, disc->support,
             more ? "more than " : "", more ? lim / per : pairs, per, per == 1.0 ? "" : "s");
    cli_check_entries(&c->d, disc, n, pairs * per, what, "the support radius");
  }
  mfs_fix_kind fx = (mfs_fix_kind)o->fixed;
  if (o->fix) {
    c->fix_mask = particle_file_fix_mask(&c->pf, o->fix);
    fx = MFS_FIX_MASK;
    size_t nf = 0;
    for (size_t I = 0; I < c->pf.n; I++)
      nf += c->fix_mask[I];
    if (nf == c->pf.n)
      cli_die(2, "%s: --fix %s fixes every particle; nothing is left to move", o->particles, o->fix);
  }
  if (fx == MFS_FIX_ENDS && disc->dim == 2)
    cli_die(2, "--fixed ends: a 2D model fixes its boundary; with --dim 2 allowed: none, boundary");
  c->s = (mfs_model_spec){.disc = *disc, .fixed = fx, .fix_mask = c->fix_mask};
  const char *field;
  mfs_status st = mfs_model_spec_check(&c->s, &field);
  if (st != MFS_OK)
    cli_die(2, "invalid combination of options (%s; see 'mfstab %s --help')", field, cli_command);
}

void model_finish(model_cmd *c, const cli_group *dg, const cli_group *pg, const cli_group *mg)
{
  cli_disc *d = &c->d;
  model_opts *o = &c->m;
  if (d->dilation.n > 1)
    cli_die(2, "--dilation: one value, not a list");
  /* the support in the user's terms */
  int gd = cli_seen(dg, "--dilation"), gsup = cli_seen(mg, "--support"),
      gh = cli_seen(mg, "--smoothing-length"), gc = cli_seen(mg, "--convention");
  if (gd + gsup + gh > 1)
    cli_die(2, "%s with %s: give the support once (--dilation D, --support A, or "
               "--smoothing-length H --convention NAME)",
            gd ? "--dilation" : "--support", gh ? "--smoothing-length" : "--support");
  if (gh && !gc)
    cli_die(2, "--smoothing-length %g: say whose h it is with --convention NAME", o->smoothing_length);
  if (gc && !gh)
    cli_die(2, "--convention %s: give the peer's h with --smoothing-length H", o->convention->name);
  if (cli_seen(mg, "--rule-factor") && !gc)
    cli_die(2, "--rule-factor %g: the factor of a --convention's step rule; give --convention",
            o->rule_factor);
  if (gc && !o->convention->rule && cli_seen(mg, "--rule-factor"))
    cli_die(2, "--rule-factor: %s has no step rule for solids (docs/conventions.md)",
            o->convention->peer);
  c->support_option = gsup ? "--support" : (gh ? "--smoothing-length" : "--dilation");
  if (gc) {
    const mfs_convention *cv = o->convention;
    if (cli_seen(dg, "--kernel") && d->kernel != cv->kernel)
      cli_die(2, "--kernel %s with --convention %s: the preset's kernel is %s", d->kernel->name,
              cv->name, cv->kernel->name);
    d->kernel = cv->kernel;
  }
  if (cli_seen(mg, "--seed") && !cli_seen(mg, "--perturb"))
    cli_die(2, "--seed %ld: the seed of --perturb; give --perturb F", o->seed);
  mfs_disc disc;
  if (o->particles) {
    if (cli_seen(dg, "--lattice"))
      cli_die(2, "--lattice with --particles: the particle file is the model");
    cli_disc dd = *d; /* the cross-option checks of a lattice do not apply */
    dd.dim = 1;
    dd.lattice = -1;
    dd.quadrature = &mfs_quad_nodal;
    dd.physics = 0;
    disc = cli_disc_build(&dd, dg->seen);
    disc.quadrature = d->quadrature;
    disc.material.physics = d->physics == 1 ? MFS_PHYS_PLANE_STRAIN : MFS_PHYS_SCALAR;
  } else {
    if (o->fix)
      cli_die(2, "--fix %s: fixes groups of a particle file (--particles); a lattice model uses "
                 "--fixed",
              o->fix);
    disc = cli_disc_build(d, dg->seen);
  }
  disc.support = 0.0;
  if (gsup)
    disc.support = o->support;
  if (gh)
    disc.support = mfs_convention_support(o->convention, o->smoothing_length);
  if (o->particles) {
    finish_file(c, &disc, dg, mg);
    if (gc && !mfs_convention_applies(o->convention, c->s.disc.dim))
      cli_die(2, "--convention %s: %s defines this kernel only in %s; the file is %dD",
              o->convention->name, o->convention->peer,
              (o->convention->dims & 4u) ? "2D" : "1D", c->s.disc.dim);
    resolve_material(c, &c->s.disc, dg, pg, mg);
    return;
  }
  int dim = disc.dim;
  if (gc && !mfs_convention_applies(o->convention, dim))
    cli_die(2, "--convention %s: %s defines this kernel only in %s; with --dim %d use another "
               "preset or --support",
            o->convention->name, o->convention->peer, (o->convention->dims & 4u) ? "2D" : "1D",
            dim);
  if (cli_seen(dg, "--spacing") || cli_seen(dg, "--gamma"))
    cli_die(2, "%s: not an option of a finite model; the spacing follows from --nodes and --length",
            cli_seen(dg, "--spacing") ? "--spacing" : "--gamma");
  if (d->lattice == MFS_LATTICE_HEX)
    cli_die(2, "--lattice hex: finite models are built on lattices line (1D) and square (2D)");
  long nx = dim == 1 ? 41 : 21, ny = dim == 1 ? 1 : 21;
  const char *nodes = o->nodes ? o->nodes : "default";
  if (o->nodes) {
    int k = parse_nodes(o->nodes, &nx, &ny);
    if (k == 2 && dim == 1)
      cli_die(2, "--nodes %s: two counts need --dim 2; in 1D give N", o->nodes);
    if (dim == 1)
      ny = 1;
  }
  if ((double)nx * (double)ny > 1e8)
    cli_die(2, "--nodes %s: more than 10^8 nodes", nodes);
  double lx = 1.0, ly = dim == 1 ? 0.0 : 1.0;
  if (o->length) {
    double v[3];
    size_t k = 0;
    char *copy = mfs_strdup(o->length);
    if (!copy)
      cli_die(1, "out of memory");
    for (char *s = strtok(copy, ","); s; s = strtok(NULL, ",")) {
      if (k == 3 || !cli_parse_double(s, &v[k]) || !(v[k] > 0.0))
        cli_die(2, "--length %s: expected L (1D) or LX,LY (2D), lengths > 0", o->length);
      k++;
    }
    mfs_free(copy);
    if (k == 0)
      cli_die(2, "--length '%s': expected L (1D) or LX,LY (2D), lengths > 0", o->length);
    if (k > (size_t)dim)
      cli_die(2, "--length %s: %zu lengths for --dim %d", o->length, k, dim);
    lx = v[0];
    if (dim == 2)
      ly = k == 2 ? v[1] : v[0];
  }
  mfs_fix_kind fx = (mfs_fix_kind)o->fixed;
  if (o->periodic && fx != MFS_FIX_NONE)
    cli_die(2, "--periodic with --fixed %s: a periodic model has no boundary; use --fixed none",
            fixed_names[fx]);
  if (dim == 2 && fx == MFS_FIX_ENDS)
    cli_die(2, "--fixed ends: a 2D model fixes its boundary; with --dim 2 allowed: none, boundary");
  if (fx != MFS_FIX_NONE && (nx < 3 || (dim == 2 && ny < 3)))
    cli_die(2, "--fixed %s: needs at least 3 nodes per direction (--nodes %s)", fixed_names[fx],
            nodes);
  double dx = o->periodic ? lx / nx : lx / (nx - 1);
  double dy = dim == 1 ? dx : (o->periodic ? ly / ny : ly / (ny - 1));
  if (disc.support > 0.0) { /* a lattice: the support as a dilation of its spacing */
    disc.dilation = disc.support / dx;
    disc.support = 0.0;
  }
  double a = disc.dilation * dx;
  const char *sopt = c->support_option;
  if (o->periodic) {
    if (!(nx * dx > 2.0 * a) || (dim == 2 && !(ny * dy > 2.0 * a)))
      cli_die(2,
              "--nodes %s: too few for %s %g in a periodic model: the box must be longer "
              "than two support radii (2 D = %g spacings)",
              nodes, sopt, strcmp(sopt, "--dilation") ? a : disc.dilation, 2.0 * disc.dilation);
  } else if ((nx - 1) * dx < a * (1.0 - 1e-12) || (dim == 2 && (ny - 1) * dy < a * (1.0 - 1e-12))) {
    cli_die(2,
            "--nodes %s: too few for %s %g: the support radius a = %g exceeds the model; "
            "use at least %.0f nodes per direction",
            nodes, sopt, strcmp(sopt, "--dilation") ? a : disc.dilation, a,
            ceil(disc.dilation) + 1.0);
  }
  disc.source = (mfs_source){.lattice = disc.source.lattice,
                             .nx = (int)nx,
                             .ny = (int)ny,
                             .lx = lx,
                             .ly = dim == 2 ? ly : 1.0,
                             .periodic = o->periodic,
                             .perturb = o->perturb,
                             .seed = (unsigned long)o->seed};
  resolve_material(c, &disc, dg, pg, mg);
  c->s = (mfs_model_spec){.disc = disc, .fixed = fx};
  char what[96];
  snprintf(what, sizeof what, "--dilation %g on %.0f nodes", disc.dilation, (double)nx * ny);
  cli_check_work(d, &disc, (double)nx * (double)ny, what);
  const char *field;
  mfs_status st = mfs_model_spec_check(&c->s, &field);
  if (st == MFS_ETOOSMALL)
    cli_die(2, "--nodes %s: too few for %s %g", nodes, sopt, disc.dilation);
  if (st != MFS_OK) {
    if (disc.quadrature->cells == MFS_CELLS_STAR && o->periodic)
      cli_die(2, "--quadrature stress-star --periodic: needs even node counts (--nodes %s)", nodes);
    if (strcmp(field, "disc.frame") == 0)
      cli_die(2, "--kernel %s: a cusp at r = 0, for the Lagrangian frame only", disc.kernel->name);
    cli_die(2, "invalid combination of options (%s; see 'mfstab %s --help')", field, cli_command);
  }
}

void model_cmd_free(model_cmd *c)
{
  if (c->have_file)
    particle_file_free(&c->pf);
  mfs_free(c->fix_mask);
  mfs_free(c->d.dilation.v);
  c->fix_mask = NULL;
  c->have_file = 0;
}

void eigs_derive(const mfs_model_spec *s, eigs_derived *dv)
{
  const mfs_disc *d = &s->disc;
  double nu = d->material.poisson, rho = d->material.density, mu = d->material.modulus;
  double E = d->dim == 1 ? mu : 2.0 * mu * (1.0 + nu);
  double lam = 2.0 * mu * nu / (1.0 - 2.0 * nu);
  double a = mfs_disc_support(d);
  dv->c = sqrt(mu / rho);
  dv->c_p = d->dim == 1 ? dv->c : sqrt((lam + 2.0 * mu) / rho);
  dv->c_bulk = sqrt(E / (3.0 * (1.0 - 2.0 * nu)) / rho);
  dv->h_sph = 0.5 * a;
  dv->dt_rule_p = 0.3 * dv->h_sph / dv->c_p;
  dv->dt_rule_bulk = 0.3 * dv->h_sph / dv->c_bulk;
  dv->alpha = mfs_bound_alpha(d->kernel, d->dim);
  double cw = d->material.physics == MFS_PHYS_PLANE_STRAIN ? dv->c_p : dv->c;
  dv->bound_alpha = dv->alpha * cw * cw / (a * a);
}

void eigs_put(FILE *f, double v, int last)
{
  if (isnan(v)) { /* undefined: an empty cell */
    fputc(last ? '\n' : ',', f);
    return;
  }
  if (!isfinite(v))
    cli_die(1, "a result is not finite (%g); no output written", v);
  char b[40];
  cli_fmt(b, sizeof b, v);
  fputs(b, f);
  fputc(last ? '\n' : ',', f);
}

void eigs_put_estimates(FILE *f, const eigs_derived *dv, double lf, double kf, double tf)
{
  eigs_put(f, dv->bound_alpha, 0);
  eigs_put(f, dv->alpha, 0);
  eigs_put(f, lf, 0);
  eigs_put(f, kf, 0);
  eigs_put(f, tf * 180.0 / M_PI, 0);
}

void eigs_config_header(FILE *f)
{
  fputs("dim,nodes_x,nodes_y,length_x_m,length_y_m,dx_m,dy_m,kernel,shape,quadrature,mass,dilation,"
        "support_radius_m,fixed,periodic,physics,modulus_pa,density_kg_m3,poisson,wave_speed_m_s,source,perturb,"
        "seed,convention,smoothing_length_m,young_modulus_pa,shear_modulus_pa",
        f);
}

void eigs_config_row(FILE *f, const model_cmd *c, const mfs_model_spec *s, const eigs_derived *dv)
{
  const mfs_disc *d = &s->disc;
  const mfs_source *src = &d->source;
  int pts = mfs_disc_points(d);
  double dx = mfs_disc_dx(d), dy = mfs_disc_dy(d);
  double lx = src->lx, ly = d->dim == 1 ? 0.0 : src->ly;
  if (pts) { /* the bounding box */
    const mfs_point_set *ps = src->points;
    for (int k = 0; k < d->dim; k++) {
      double lo = ps->x[k], hi = ps->x[k];
      for (size_t i = 1; i < ps->n; i++) {
        double v = ps->x[i * d->dim + k];
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
      }
      if (k == 0)
        lx = hi - lo;
      else
        ly = hi - lo;
    }
  }
  fprintf(f, "%d,%d,%d,", d->dim, pts ? (int)src->points->n : src->nx,
          pts || d->dim == 1 ? 1 : src->ny);
  eigs_put(f, lx, 0);
  eigs_put(f, ly, 0);
  eigs_put(f, dx, 0);
  eigs_put(f, dy, 0);
  fprintf(f, "%s,%s,%s,%s,", d->kernel->name, d->shape->name, d->quadrature->name,
          d->consistent_mass ? "consistent" : "lumped");
  eigs_put(f, d->dilation, 0);
  eigs_put(f, mfs_disc_support(d), 0);
  const char *fixn = s->fixed == MFS_FIX_NONE   ? "none"
                     : s->fixed == MFS_FIX_MASK ? "groups"
                     : (d->dim == 1 ? "ends" : "boundary");
  fprintf(f, "%s,%d,%s,", fixn, pts ? 0 : src->periodic,
          d->material.physics == MFS_PHYS_PLANE_STRAIN ? "plane-strain"
                                                       : (d->dim == 1 ? "bar" : "antiplane"));
  eigs_put(f, d->material.modulus, 0);
  eigs_put(f, d->material.density, 0);
  eigs_put(f, d->material.poisson, 0);
  fprintf(f, "%.16g,%s,", dv->c, pts ? "particles" : (src->perturb > 0.0 ? "perturbed" : "lattice"));
  eigs_put(f, pts ? NAN : src->perturb, 0);
  if (!pts && src->perturb > 0.0)
    fprintf(f, "%lu,", src->seed);
  else
    fputc(',', f);
  fprintf(f, "%s,", c && c->m.convention ? c->m.convention->name : "");
  eigs_put(f, c && c->m.convention ? c->m.smoothing_length : NAN, 0);
  eigs_put(f, c ? c->young : NAN, 0);
  cli_put_num(f, c && d->dim == 2 ? c->shear : NAN, "shear_modulus_pa");
}

/* ------------------------------------------------------------------ */
/* the command                                                          */

typedef struct {
  int zero_modes;
  double tol;
  long nev, ncv, maxiter;
  double arpack_tol;
  const char *export_prefix, *modes_prefix;
  long seeds;
} eig_opts;

#define EOFF(f) offsetof(eig_opts, f)
static const cli_opt eig_table[] = {
  {.name = "--zero-modes", .type = CLI_FLAG,
   .help = "count the zero-energy modes (eigenvalues <= tol lambda_max)", .offset = EOFF(zero_modes)},
  {.name = "--tol", .type = CLI_REAL, .arg = "T",
   .help = "zero-mode threshold relative to lambda_max (default 1e-8)", .offset = EOFF(tol),
   .bounds = CLI_GT | CLI_LT, .lo = 0, .hi = 1},
  {.name = "--nev", .type = CLI_INT, .arg = "K", .help = "eigenvalues per shift-invert run (default 6)",
   .offset = EOFF(nev), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 1000},
  {.name = "--ncv", .type = CLI_INT, .arg = "K", .help = "ARPACK Lanczos vectors (default 20)",
   .offset = EOFF(ncv), .bounds = CLI_GE | CLI_LE, .lo = 3, .hi = 100000},
  {.name = "--maxiter", .type = CLI_INT, .arg = "K", .help = "ARPACK restarts (default 10000)",
   .offset = EOFF(maxiter), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 100000000},
  {.name = "--arpack-tol", .type = CLI_REAL, .arg = "T",
   .help = "ARPACK relative accuracy (default 1e-12; 0: machine precision)",
   .offset = EOFF(arpack_tol), .bounds = CLI_GE | CLI_LT, .lo = 0, .hi = 1},
  {.name = "--export-mtx", .type = CLI_TEXT, .arg = "PREFIX",
   .help = "write K and M to PREFIX_K.mtx, PREFIX_M.mtx (Matrix Market)",
   .offset = EOFF(export_prefix)},
  {.name = "--write-modes", .type = CLI_TEXT, .arg = "PREFIX",
   .help = "write the spurious zero-energy modes and the highest mode per particle to\n"
           "PREFIX_modes.csv and PREFIX_modes.vtk (ParaView); implies --zero-modes",
   .offset = EOFF(modes_prefix)},
  {.name = "--seeds", .type = CLI_INT, .arg = "N",
   .help = "with --perturb: N models, seeds S .. S+N-1 (one row each, with min/median/max)",
   .offset = EOFF(seeds), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 100000},
  {.type = CLI_END}};
#undef EOFF
#define EIG_NOPTS 10
_Static_assert(sizeof eig_table / sizeof eig_table[0] == EIG_NOPTS, "EIG_NOPTS");

/* Write one Matrix Market file through the atomic output. */
static void export_one(const mfs_model *m, const char *prefix, const char *which)
{
  cli_out o;
  const char *path = cli_out_open_fmt(&o, "%s_%s.mtx", prefix, which);
  mfs_status st =
    which[0] == 'K' ? mfs_model_write_mtx(m, o.f, NULL) : mfs_model_write_mtx(m, NULL, o.f);
  if (st != MFS_OK)
    cli_die(1, "--export-mtx %s: cannot write: %s", path, mfs_strerror(st));
  cli_out_commit(&o);
}

static int cmp_dbl(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* min, median, max of v[0..n) over the defined (not NAN) values; NAN if none. */
static void stats3(const double *v, size_t n, double *out)
{
  double *t = mfs_malloc((n ? n : 1) * sizeof *t);
  if (!t)
    cli_die(1, "out of memory");
  size_t k = 0;
  for (size_t i = 0; i < n; i++)
    if (!isnan(v[i]))
      t[k++] = v[i];
  if (k == 0) {
    out[0] = out[1] = out[2] = NAN;
  } else {
    qsort(t, k, sizeof *t, cmp_dbl);
    out[0] = t[0];
    out[1] = k % 2 ? t[k / 2] : 0.5 * (t[k / 2 - 1] + t[k / 2]);
    out[2] = t[k - 1];
  }
  mfs_free(t);
}

/* The result columns of one model. */
static void eigs_row(FILE *f, const model_cmd *c, const run_result *r, const eig_opts *e,
                     int certify, const double *sweep)
{
  eigs_config_row(f, c, &c->s, &r->dv);
  double lam = r->have_lambda ? r->lambda : NAN;
  fprintf(f, ",%zu,", r->dofs);
  eigs_put(f, lam, 0);
  eigs_put(f, sqrt(lam), 0);
  eigs_put(f, r->br.lambda, 0);
  fprintf(f, "%d,%zu,", r->bound_valid, r->br.negative_phi);
  eigs_put_estimates(f, &r->dv, r->lf, r->kf, r->tf);
  double dtc = r->have_lambda ? mfs_dt_crit(lam) : NAN;
  eigs_put(f, dtc, 0);
  eigs_put(f, r->br.lambda > 0.0 ? mfs_dt_crit(r->br.lambda) : NAN, 0);
  eigs_put(f, mfs_dt_crit(r->dv.bound_alpha), 0);
  eigs_put(f, mfs_dt_crit(r->lf), 0);
  eigs_put(f, r->dv.dt_rule_p, 0);
  eigs_put(f, r->dv.dt_rule_bulk, 0);
  eigs_put(f, r->br.lambda / lam, 0);
  if (r->have_lambda)
    fprintf(f, "%d,%d,", r->iters, r->matvecs);
  else
    fputs(",,", f);
  eigs_put(f, r->have_lambda ? r->resid : NAN, 0);
  /* the tolerance ARPACK stopped at (0: its machine precision, dlamch('E')) */
  eigs_put(f, r->have_lambda ? (e->arpack_tol > 0.0 ? e->arpack_tol : 0.5 * DBL_EPSILON) : NAN, 0);
  fprintf(f, "%zu,%zu,", r->particles, r->nonpositive);
  eigs_put(f, r->min_mass, 0);
  size_t I = r->min_mass_particle;
  int cm = c->s.disc.consistent_mass;
  if (cm)
    fputs(",,,", f);
  else {
    fprintf(f, "%zu,", I);
    eigs_put(f, r->min_mass_x[0], 0);
    eigs_put(f, r->min_mass_x[1], 0);
  }
  eigs_put(f, r->g.lambda, 0);
  eigs_put(f, mfs_dt_crit(r->g.lambda), 0);
  eigs_put(f, r->g.lambda / lam, 0);
  int last_rules = !certify && !e->zero_modes && !sweep;
  rules_row(f, r->dt_rule, dtc, dtc, last_rules);
  if (certify) {
    int ok = r->have_cert && r->cr.ok;
    eigs_put(f, ok ? r->cr.lambda_upper : NAN, 0);
    double dtcert = ok ? mfs_dt_crit(r->cr.lambda_upper) : NAN;
    eigs_put(f, dtcert, 0);
    eigs_put(f, dtcert / dtc, 0);
    eigs_put(f, ok ? r->cr.margin : NAN, 0);
    if (r->have_cert)
      fprintf(f, "%d", r->cr.factorizations);
    fputc(!e->zero_modes && !sweep ? '\n' : ',', f);
  }
  if (e->zero_modes) {
    eigs_put(f, e->tol, 0);
    if (r->have_zero) {
      fprintf(f, "%d,%d,%d,", r->z.count, r->rigid, r->z.count - r->rigid);
      eigs_put(f, r->z.lambda_min_nonzero, 0);
      fprintf(f, "%d", r->zero_runs);
    } else {
      fputs(",,,,", f);
    }
    fputc(sweep ? ',' : '\n', f);
  }
  if (sweep) {
    fprintf(f, "%.0f,", sweep[0]);
    for (int k = 1; k <= 9; k++)
      eigs_put(f, sweep[k], 0);
    fprintf(f, "%.0f\n", sweep[10]);
  }
}

static _Noreturn void note_usage(void)
{
  cli_die(2, "--seeds: sweeps the seeds of --perturb; give --perturb F (0 < F < 0.5)");
}

int cmd_eigs(int argc, char **argv)
{
  model_cmd c = {.m = {.fourier_points = 201, .fourier_angles = 7, .seed = 1}};
  cli_disc_defaults(&c.d);
  eig_opts e = {.tol = 1e-8, .arpack_tol = 1e-12};
  unsigned char sd[CLI_DISC_NOPTS], sp[CLI_PHYSICS_NOPTS], sm[MODEL_NOPTS], se[EIG_NOPTS];
  cli_group g[4] = {{cli_disc_opts, &c.d, sd},
                    {cli_physics_opts, &c.d, sp},
                    {model_opts_table, &c.m, sm},
                    {eig_table, &e, se}};
  static char about[sizeof about_model + sizeof about_csv];
  snprintf(about, sizeof about, "%s%s", about_model, about_csv);
  cli_parse(argc, argv, usage, about, g, 4);
  if (e.export_prefix && !*e.export_prefix)
    cli_die(2, "--export-mtx '': expected a file name prefix");
  if (e.modes_prefix && !*e.modes_prefix)
    cli_die(2, "--write-modes '': expected a file name prefix");
  if (e.modes_prefix)
    e.zero_modes = 1;
  long nseeds = cli_seen(&g[3], "--seeds") ? e.seeds : 0;
  if (nseeds && !(c.m.perturb > 0.0))
    note_usage();
  if (nseeds && (e.export_prefix || e.modes_prefix))
    cli_die(2, "%s with --seeds: writes one model; drop --seeds",
            e.export_prefix ? "--export-mtx" : "--write-modes");
  model_finish(&c, &g[0], &g[1], &g[2]);
  cli_out_hold(); /* the CSV, the modes and the matrices: all written, or none */

  run_opts ro = {.zero_modes = e.zero_modes, .tol = e.tol, .nev = e.nev, .ncv = e.ncv,
                 .maxiter = e.maxiter, .arpack_tol = e.arpack_tol, .certify = c.m.certify,
                 .keep = 1};
  if (par_active()) { /* mpirun: distributed, unless an option needs one process */
    const char *one = e.modes_prefix            ? "--write-modes"
                      : e.zero_modes            ? "--zero-modes"
                      : c.m.certify             ? "--certify"
                      : e.export_prefix         ? "--export-mtx"
                      : nseeds                  ? "--seeds"
                      : c.s.disc.consistent_mass ? "--mass consistent"
                                                : NULL;
    if (one)
      par_need_one(one);
    ro.distributed = !one;
  }
  size_t nrun = nseeds ? (size_t)nseeds : 1;
  run_result *rr = mfs_calloc(nrun, sizeof *rr);
  double *lv = mfs_malloc(nrun * sizeof *lv), *zv = mfs_malloc(nrun * sizeof *zv),
         *nv = mfs_malloc(nrun * sizeof *nv);
  if (!rr || !lv || !zv || !nv)
    cli_die(1, "out of memory");
  unsigned long seed0 = c.s.disc.source.seed;
  double nbad = 0.0;
  for (size_t k = 0; k < nrun; k++) {
    c.s.disc.source.seed = seed0 + k;
    model_run(&c, &ro, &rr[k]);
    if (!nseeds && e.export_prefix) {
      export_one(rr[k].m, e.export_prefix, "K");
      export_one(rr[k].m, e.export_prefix, "M");
    }
    lv[k] = rr[k].have_lambda ? rr[k].lambda : NAN;
    zv[k] = rr[k].have_zero ? rr[k].z.count : NAN;
    nv[k] = (double)rr[k].br.negative_phi;
    nbad += rr[k].nonpositive > 0;
    if (nseeds) { /* keep only what the row needs */
      mfs_free(rr[k].vmax);
      rr[k].vmax = NULL;
      mfs_free(rr[k].z.modes);
      rr[k].z.modes = NULL;
    }
  }
  double sweep[11];
  if (nseeds) {
    sweep[0] = (double)nseeds;
    stats3(lv, nrun, sweep + 1);
    stats3(zv, nrun, sweep + 4);
    stats3(nv, nrun, sweep + 7);
    sweep[10] = nbad;
  }
  if (e.modes_prefix)
    write_modes(&c, &rr[0], e.modes_prefix);

  cli_out out;
  cli_out_open(&out, par_out_path(c.m.out));
  FILE *f = out.f;
  eigs_config_header(f);
  fputs(",dofs,lambda_max_per_s2,omega_max_rad_s,bound_per_s2,bound_valid,negative_phi_points,bound_alpha_per_s2,alpha,"
        "lambda_fourier_per_s2,kappa_fourier_norm,theta_fourier_deg,dt_crit_s,dt_bound_s,dt_alpha_s,dt_fourier_s,"
        "dt_rule_p_s,dt_rule_bulk_s,bound_ratio,arpack_iterations,arpack_matvecs,arpack_residual,"
        "arpack_tol,particles,nonpositive_masses,min_mass_kg,min_mass_particle,min_mass_x_m,min_mass_y_m,"
        "lambda_gershgorin_per_s2,dt_gershgorin_s,gershgorin_ratio",
        f);
  rules_header(f);
  if (c.m.certify)
    fputs(",sigma_certified_per_s2,dt_certified_s,certified_fraction,certify_margin,"
          "certify_factorizations",
          f);
  if (e.zero_modes)
    fputs(",zero_tol,zero_modes,rigid_modes,spurious_modes,lambda_min_nonzero_per_s2,zero_runs", f);
  if (nseeds)
    fputs(",seeds,lambda_max_min_per_s2,lambda_max_median_per_s2,lambda_max_max_per_s2,zero_modes_min,"
          "zero_modes_median,zero_modes_max,negative_phi_min,negative_phi_median,"
          "negative_phi_max,nonpositive_mass_models",
          f);
  fputc('\n', f);
  for (size_t k = 0; k < nrun; k++) {
    c.s.disc.source.seed = seed0 + k;
    eigs_row(f, &c, &rr[k], &e, c.m.certify, nseeds ? sweep : NULL);
  }
  cli_out_commit(&out);
  cli_out_release();
  for (size_t k = 0; k < nrun; k++) {
    if (rr[k].nonpositive > 0 && !nseeds) {
      size_t I = rr[k].min_mass_particle;
      const double *xI = rr[k].min_mass_x;
      char where[96];
      if (c.s.disc.dim == 1)
        snprintf(where, sizeof where, "x = %g", xI[0]);
      else
        snprintf(where, sizeof where, "(%g, %g)", xI[0], xI[1]);
      char line[64] = "";
      if (c.have_file)
        snprintf(line, sizeof line, ", %s:%zu", c.pf.path, particle_file_line(&c.pf, I));
      fprintf(stderr,
              "mfstab eigs: note: %zu lumped mass%s <= 0 (the smallest %g at particle %zu, %s%s): "
              "the results that need positive masses do not apply (empty cells)\n",
              rr[k].nonpositive, rr[k].nonpositive == 1 ? "" : "es", rr[k].min_mass, I, where,
              line);
    }
    run_result_free(&rr[k]);
  }
  mfs_free(rr);
  mfs_free(lv);
  mfs_free(zv);
  mfs_free(nv);
  model_cmd_free(&c);
  return 0;
}

/* ------------------------------------------------------------------ */
/* Figs 17 and 18                                                      */

static char fig_error[160]; /* why eigs_figure17 failed */

const char *eigs_figure17_error(void) { return fig_error; }

static int fig_row(FILE *f, const char *fig, const mfs_model_spec *ms, int nodes)
{
  const mfs_disc *s = &ms->disc;
  mfs_status st;
  size_t bad;
  mfs_model *m = mfs_model_alloc(ms, &st, &bad);
  if (!m) {
    snprintf(fig_error, sizeof fig_error, "Fig. %s, D = %g: %s", fig, s->dilation,
             mfs_strerror(st));
    return 1;
  }
  mfs_bound_result br;
  mfs_bound_of_model(m, &br);
  mfs_pencil P = {m->K, m->M, m->m};
  mfs_eig_opts eo = {0, 0, 1e-13};
  mfs_eig_info info;
  double lam;
  st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
  if (st != MFS_OK || !(lam > 0.0)) {
    snprintf(fig_error, sizeof fig_error, "Fig. %s, D = %g: ARPACK: %s (info %d)", fig,
             s->dilation, mfs_strerror(st), info.info);
    mfs_model_free(m);
    return 1;
  }
  double dx2 = m->dx * m->dx, D2 = s->dilation * s->dilation;
  double alpha = mfs_bound_alpha(s->kernel, s->dim);
  double paper1 = s->dim == 1 ? MFS_PAPER_ALPHA : MFS_PAPER_ALPHA1;
  fprintf(f, "%s,%s,%s,%s,lumped,%d,%.16g,%.16g,%.16g,%.16g,%.16g,", fig, s->kernel->name,
          s->shape->name, s->quadrature->name, nodes, s->dilation, lam * dx2, br.lambda * dx2,
          alpha / D2, paper1 / D2);
  if (s->dim == 2) /* eq. 148 is 2D only: an empty field in 1D */
    fprintf(f, "%.16g", MFS_PAPER_ALPHA2 / D2);
  fprintf(f, ",%.16g,%.16g,%zu\n", br.lambda / lam, alpha / D2 / (lam * dx2), br.negative_phi);
  mfs_model_free(m);
  return 0;
}

static int fig_file(const char *dir, const char *name, const mfs_kernel_type *k, int dim)
{
  cli_out out;
  cli_out_open_fmt(&out, "%s/%s", dir, name);
  FILE *f = out.f;
  fputs("figure,kernel,shape,quadrature,mass,nodes,dilation,lambda_max_dx2_norm,bound_dx2_norm,"
        "alpha_dx2_norm,paper_alpha_dx2_norm,paper_alpha2_dx2_norm,bound_ratio,alpha_ratio,negative_phi_points\n",
        f);
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.kernel = k;
  s.disc.quadrature = &mfs_quad_gauss[1];
  int bad = 0;
  if (dim == 1) {
    static const int nn[2] = {41, 101};
    for (int a = 0; a < 2 && !bad; a++)
      for (int i = 0; i <= 12 && !bad; i++) {
        s.disc.source.nx = nn[a];
        s.disc.dilation = 1.0 + 0.25 * i;
        bad = fig_row(f, "17", &s, nn[a]);
      }
  } else {
    s.disc.dim = 2;
    s.disc.source.lattice = MFS_LATTICE_SQUARE;
    s.disc.source.nx = s.disc.source.ny = 21;
    for (int i = 0; i <= 14 && !bad; i++) {
      s.disc.dilation = 1.5 + 0.25 * i;
      bad = fig_row(f, "18", &s, 21 * 21);
    }
  }
  if (bad) {
    cli_out_abort(&out); /* fig_error says why */
  } else {
    cli_out_commit(&out);
  }
  return bad;
}

int eigs_figure17(const char *dir)
{
  int bad = 0;
  bad |= fig_file(dir, "fig17_cubic.csv", &mfs_kernel_cubic, 1);
  bad |= fig_file(dir, "fig17_quartic.csv", &mfs_kernel_quartic, 1);
  bad |= fig_file(dir, "fig18_cubic.csv", &mfs_kernel_cubic, 2);
  bad |= fig_file(dir, "fig18_quartic.csv", &mfs_kernel_quartic, 2);
  return bad ? 1 : 0;
}
