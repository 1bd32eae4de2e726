/* mfstab eigs: extreme eigenvalues, zero-energy modes and critical time
 * steps of a finite particle model (paper 003 section 5), side by side with
 * the element bound, the closed form and the Fourier estimate; and the
 * options shared with `mfstab bound`, and the data of Figs 17 and 18. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "eigs_figures.h"

static const char usage[] = "mfstab eigs [options] [-o FILE]";
static const char about[] =
  "Largest eigenvalue lambda_max = omega_max^2 of K v = lambda M v of a finite model (ARPACK;\n"
  "lumped mass: symmetric standard problem M^-1/2 K M^-1/2; consistent mass: generalized mode,\n"
  "CHOLMOD solves with M), with --zero-modes the zero-energy modes (shift-invert ARPACK about\n"
  "sigma = -tol lambda_max), and the critical time step of the undamped central difference\n"
  "method dt = 2/omega_max (paper 003 eqs 120, 124) from:\n"
  "  dt_crit      the exact lambda_max\n"
  "  dt_bound     the element bound max_Q lambda^Q (eqs 123-133, 139-144; lumped mass, phi_I > 0)\n"
  "  dt_alpha     the closed form alpha c^2/h^2 (eq. 136 1D, eq. 146 2D; h = a = D dx)\n"
  "  dt_fourier   the largest omega^2 of plane waves on the infinite uniform lattice\n"
  "  dt_rule_p    the rule of thumb 0.3 h/c with the SPH smoothing length h = a/2 and the\n"
  "               P-wave speed (1D: bar speed sqrt(E/rho); 2D: sqrt((lambda+2mu)/rho))\n"
  "  dt_rule_bulk the same with the bulk speed sqrt(K/rho), K = E/(3(1-2 nu))\n"
  "Models: 1D bar of N nodes on [0, L] (end nodes on the ends), 2D rectangle of NX x NY nodes\n"
  "on [0, LX] x [0, LY] (square lattice, 2D anti-plane shear or plane strain); periodic:\n"
  "dx = L/N.  The modulus is E in 1D and the shear modulus mu in 2D; c = sqrt(modulus/rho).\n"
  "CSV (one row): dim,nodes_x,nodes_y,length_x,length_y,dx,dy,kernel,shape,quadrature,mass,\n"
  "  dilation,support_radius,fixed,periodic,physics,modulus,density,poisson,wave_speed,dofs,\n"
  "  lambda_max,omega_max,bound,bound_valid,negative_phi_points,bound_alpha,alpha,\n"
  "  lambda_fourier,kappa_fourier,theta_fourier,dt_crit,dt_bound,dt_alpha,dt_fourier,dt_rule_p,\n"
  "  dt_rule_bulk,bound_ratio,arpack_iterations,arpack_matvecs,arpack_residual\n"
  "  and with --zero-modes: zero_tol,zero_modes,rigid_modes,spurious_modes,lambda_min_nonzero,\n"
  "  zero_runs\n"
  "bound_valid is 1 when the element bound is a proven bound: lumped mass and every phi_I > 0 at\n"
  "the quadrature points (negative_phi_points counts the points where some phi_I <= 0).\n"
  "bound_ratio = bound / lambda_max.  rigid_modes counts the rigid fields (constant; plane strain:\n"
  "translations and rotation) that are null vectors of K; spurious_modes the other zero modes.\n";

/* ------------------------------------------------------------------ */
/* the options of a finite model, shared with bound                     */

static const char *const fixed_names[] = {"none", "ends", "boundary", NULL};

#define MOFF(f) offsetof(model_opts, f)
const cli_opt model_opts_table[] = {
  {.name = "--nodes", .type = CLI_TEXT, .arg = "N|NX,NY",
   .help = "nodes (default 41 in 1D, 21,21 in 2D; N alone in 2D: N x N)", .offset = MOFF(nodes)},
  {.name = "--length", .type = CLI_TEXT, .arg = "L|LX,LY",
   .help = "domain size (default 1, 1 x 1)", .offset = MOFF(length)},
  {.name = "--fixed", .type = CLI_CHOICE, .arg = "none|ends|boundary",
   .help = "remove the dofs of the end (1D) or boundary (2D) nodes", .offset = MOFF(fixed),
   .choices = fixed_names},
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

void model_finish(model_cmd *c, const cli_group *dg, const cli_group *mg)
{
  cli_disc *d = &c->d;
  model_opts *o = &c->m;
  if (cli_seen(dg, "--spacing") || cli_seen(dg, "--gamma"))
    cli_die(2, "%s: not an option of a finite model; the spacing follows from --nodes and --length",
            cli_seen(dg, "--spacing") ? "--spacing" : "--gamma");
  if (d->lattice == MFS_LATTICE_HEX)
    cli_die(2, "--lattice hex: finite models are built on lattices line (1D) and square (2D)");
  if (d->dilation.n > 1)
    cli_die(2, "--dilation: one value, not a list");
  mfs_disc disc = cli_disc_build(d, dg->seen);
  int dim = disc.dim;
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
    char *copy = strdup(o->length);
    if (!copy)
      cli_die(1, "out of memory");
    for (char *s = strtok(copy, ","); s; s = strtok(NULL, ",")) {
      if (k == 3 || !cli_parse_double(s, &v[k]) || !(v[k] > 0.0))
        cli_die(2, "--length %s: expected L (1D) or LX,LY (2D), lengths > 0", o->length);
      k++;
    }
    free(copy);
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
  /* too few nodes for the dilation */
  double dx = o->periodic ? lx / nx : lx / (nx - 1);
  double dy = dim == 1 ? dx : (o->periodic ? ly / ny : ly / (ny - 1));
  double a = disc.dilation * dx;
  if (o->periodic) {
    if (!(nx * dx > 2.0 * a) || (dim == 2 && !(ny * dy > 2.0 * a)))
      cli_die(2,
              "--nodes %s: too few for --dilation %g in a periodic model: the box must be longer "
              "than two support radii (2 D = %g spacings)",
              nodes, disc.dilation, 2.0 * disc.dilation);
  } else if ((nx - 1) * dx < a * (1.0 - 1e-12) || (dim == 2 && (ny - 1) * dy < a * (1.0 - 1e-12))) {
    cli_die(2,
            "--nodes %s: too few for --dilation %g: the support radius a = %g exceeds the model; "
            "use at least %.0f nodes per direction",
            nodes, disc.dilation, a, ceil(disc.dilation) + 1.0);
  }
  disc.source = (mfs_source){.lattice = disc.source.lattice,
                             .nx = (int)nx,
                             .ny = (int)ny,
                             .lx = lx,
                             .ly = dim == 2 ? ly : 1.0,
                             .periodic = o->periodic};
  c->s = (mfs_model_spec){.disc = disc, .fixed = fx};
  char what[96];
  snprintf(what, sizeof what, "--dilation %g on %.0f nodes", disc.dilation, (double)nx * ny);
  cli_check_work(d, &disc, (double)nx * (double)ny, what);
  const char *field;
  mfs_status st = mfs_model_spec_check(&c->s, &field);
  if (st == MFS_ETOOSMALL)
    cli_die(2, "--nodes %s: too few for --dilation %g", nodes, disc.dilation);
  if (st != MFS_OK) {
    if (disc.quadrature->cells == MFS_CELLS_STAR && o->periodic)
      cli_die(2, "--quadrature stress-star --periodic: needs even node counts (--nodes %s)", nodes);
    cli_die(2, "invalid combination of options (%s; see 'mfstab %s --help')", field, cli_command);
  }
  (void)mg;
}

void eigs_derive(const mfs_model_spec *s, eigs_derived *dv)
{
  const mfs_disc *d = &s->disc;
  double nu = d->material.poisson, rho = d->material.density, mu = d->material.modulus;
  double E = d->dim == 1 ? mu : 2.0 * mu * (1.0 + nu);
  double lam = 2.0 * mu * nu / (1.0 - 2.0 * nu);
  double a = d->dilation * mfs_disc_dx(d);
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
  fputs("dim,nodes_x,nodes_y,length_x,length_y,dx,dy,kernel,shape,quadrature,mass,dilation,"
        "support_radius,fixed,periodic,physics,modulus,density,poisson,wave_speed",
        f);
}

void eigs_config_row(FILE *f, const mfs_model_spec *s, const eigs_derived *dv)
{
  const mfs_disc *d = &s->disc;
  const mfs_source *src = &d->source;
  double dx = mfs_disc_dx(d), dy = mfs_disc_dy(d);
  fprintf(f, "%d,%d,%d,", d->dim, src->nx, d->dim == 1 ? 1 : src->ny);
  eigs_put(f, src->lx, 0);
  eigs_put(f, d->dim == 1 ? 0.0 : src->ly, 0);
  eigs_put(f, dx, 0);
  eigs_put(f, dy, 0);
  fprintf(f, "%s,%s,%s,%s,", d->kernel->name, d->shape->name, d->quadrature->name,
          d->consistent_mass ? "consistent" : "lumped");
  eigs_put(f, d->dilation, 0);
  eigs_put(f, d->dilation * dx, 0);
  const char *fixn = s->fixed == MFS_FIX_NONE ? "none" : (d->dim == 1 ? "ends" : "boundary");
  fprintf(f, "%s,%d,%s,", fixn, src->periodic,
          d->material.physics == MFS_PHYS_PLANE_STRAIN ? "plane-strain"
                                                       : (d->dim == 1 ? "bar" : "antiplane"));
  eigs_put(f, d->material.modulus, 0);
  eigs_put(f, d->material.density, 0);
  eigs_put(f, d->material.poisson, 0);
  fprintf(f, "%.16g", dv->c);
}

/* Die with a clear line for a failed eigenvalue computation. */
static _Noreturn void die_eig(int st, const mfs_eig_info *info, const char *what)
{
  if (st == MFS_ENOCONV)
    cli_die(1,
            "%s: ARPACK %s did not converge (info %d) after %d iterations, %d Ritz values "
            "converged; raise --maxiter or --ncv, or loosen --arpack-tol",
            what, info->routine, info->info, info->iterations, info->nconv);
  if (st == MFS_EARPACK)
    cli_die(1, "%s: ARPACK %s failed with info %d", what, info->routine, info->info);
  if (st == MFS_EDOMAIN && strcmp(info->routine, "cholmod") == 0)
    cli_die(1, "%s: CHOLMOD: the matrix to factor is not positive definite (status %d)", what,
            info->cholmod_status);
  cli_die(1, "%s: %s", what, mfs_strerror(st));
}

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

typedef struct {
  int zero_modes;
  double tol;
  long nev, ncv, maxiter;
  double arpack_tol;
  const char *export_prefix;
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
  {.type = CLI_END}};
#undef EOFF

int cmd_eigs(int argc, char **argv)
{
  model_cmd c = {.m = {.fourier_points = 201, .fourier_angles = 7}};
  cli_disc_defaults(&c.d);
  eig_opts e = {.tol = 1e-8, .arpack_tol = 1e-12};
  unsigned char sd[CLI_DISC_NOPTS], sp[CLI_PHYSICS_NOPTS], sm[MODEL_NOPTS], se[8];
  cli_group g[4] = {{cli_disc_opts, &c.d, sd},
                    {cli_physics_opts, &c.d, sp},
                    {model_opts_table, &c.m, sm},
                    {eig_table, &e, se}};
  cli_parse(argc, argv, usage, about, g, 4);
  if (e.export_prefix && !*e.export_prefix)
    cli_die(2, "--export-mtx '': expected a file name prefix");
  model_finish(&c, &g[0], &g[2]);
  eigs_derived dv;
  eigs_derive(&c.s, &dv);

  mfs_status st;
  size_t bad = 0;
  double D = c.s.disc.dilation;
  mfs_model *m = mfs_model_alloc(&c.s, &st, &bad);
  if (!m)
    cli_die_status(st, &c.d, D, "at a quadrature point of the model");
  mfs_bound_result br;
  st = mfs_bound_of_model(m, &br);
  if (st != MFS_OK)
    cli_die(1, "element bound: %s", mfs_strerror(st));
  mfs_model_release_plan(m);
  if (e.export_prefix) {
    export_one(m, e.export_prefix, "K");
    export_one(m, e.export_prefix, "M");
  }
  double lf, kf, tf;
  st = mfs_bound_fourier(&c.s, (int)c.m.fourier_points, (int)c.m.fourier_angles, &lf, &kf, &tf);
  if (st != MFS_OK)
    cli_die_status(st, &c.d, D, "Fourier estimate on the uniform lattice");

  mfs_pencil P = {m->K, m->M, m->m};
  mfs_eig_opts eo = {(int)e.ncv, (int)e.maxiter, e.arpack_tol};
  mfs_eig_info info;
  double lam = 0.0;
  if (m->n < 2)
    cli_die(2, "the model has %zu free degree of freedom; use more nodes", m->n);
  st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
  if (st != MFS_OK)
    die_eig(st, &info, "lambda_max");
  if (!(lam > 0.0))
    cli_die(1, "lambda_max = %g: the stiffness has no positive eigenvalue", lam);
  int iters = info.iterations, mv = info.matvecs;
  double resid = info.residual;

  mfs_zero_modes z = {0};
  mfs_eig_info zinfo = {0};
  int rigid = 0;
  if (e.zero_modes) {
    mfs_zero_opts zo = {e.tol, (int)e.nev, 0, 0};
    st = mfs_eig_zero_modes(&P, lam, &zo, &eo, &z, &zinfo);
    if (st != MFS_OK)
      die_eig(st, &zinfo, "zero-energy modes");
    int nr = mfs_model_rigid_fields(m, NULL);
    if (nr > 0) {
      double *r = malloc((size_t)nr * m->n * sizeof *r);
      if (!r)
        cli_die(1, "out of memory");
      mfs_model_rigid_fields(m, r);
      for (int k = 0; k < nr; k++) {
        int null;
        if (mfs_eig_is_null(&P, r + (size_t)k * m->n, lam, e.tol, &null) != MFS_OK)
          cli_die(1, "zero-energy modes: out of memory");
        rigid += null;
      }
      free(r);
    }
  }

  int bvalid = !c.s.disc.consistent_mass && br.negative_phi == 0;
  cli_out out;
  cli_out_open(&out, c.m.out);
  FILE *f = out.f;
  eigs_config_header(f);
  fputs(",dofs,lambda_max,omega_max,bound,bound_valid,negative_phi_points,bound_alpha,alpha,"
        "lambda_fourier,kappa_fourier,theta_fourier,dt_crit,dt_bound,dt_alpha,dt_fourier,"
        "dt_rule_p,dt_rule_bulk,bound_ratio,arpack_iterations,arpack_matvecs,arpack_residual",
        f);
  if (e.zero_modes)
    fputs(",zero_tol,zero_modes,rigid_modes,spurious_modes,lambda_min_nonzero,zero_runs", f);
  fputc('\n', f);
  eigs_config_row(f, &c.s, &dv);
  fprintf(f, ",%zu,", m->n);
  eigs_put(f, lam, 0);
  eigs_put(f, sqrt(lam), 0);
  eigs_put(f, br.lambda, 0);
  fprintf(f, "%d,%zu,", bvalid, br.negative_phi);
  eigs_put_estimates(f, &dv, lf, kf, tf);
  eigs_put(f, mfs_dt_crit(lam), 0);
  eigs_put(f, mfs_dt_crit(br.lambda), 0);
  eigs_put(f, mfs_dt_crit(dv.bound_alpha), 0);
  eigs_put(f, mfs_dt_crit(lf), 0);
  eigs_put(f, dv.dt_rule_p, 0);
  eigs_put(f, dv.dt_rule_bulk, 0);
  eigs_put(f, br.lambda / lam, 0);
  fprintf(f, "%d,%d,", iters, mv);
  eigs_put(f, resid, !e.zero_modes);
  if (e.zero_modes) {
    eigs_put(f, e.tol, 0);
    fprintf(f, "%d,%d,%d,", z.count, rigid, z.count - rigid);
    eigs_put(f, z.lambda_min_nonzero, 0);
    fprintf(f, "%d\n", zinfo.runs);
  }
  cli_out_commit(&out);
  mfs_model_free(m);
  free(c.d.dilation.v);
  return 0;
}

/* ------------------------------------------------------------------ */
/* Figs 17 and 18                                                      */

static int fig_row(FILE *f, const char *fig, const mfs_model_spec *ms, int nodes)
{
  const mfs_disc *s = &ms->disc;
  mfs_status st;
  size_t bad;
  mfs_model *m = mfs_model_alloc(ms, &st, &bad);
  if (!m) {
    fprintf(stderr, "mfstab %s: %s D = %g: %s\n", cli_command, fig, s->dilation, mfs_strerror(st));
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
    fprintf(stderr, "mfstab %s: %s D = %g: ARPACK: %s (info %d)\n", cli_command, fig, s->dilation,
            mfs_strerror(st), info.info);
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
  const char *path = cli_out_open_fmt(&out, "%s/%s", dir, name);
  FILE *f = out.f;
  fputs("figure,kernel,shape,quadrature,mass,nodes,dilation,lambda_max_dx2,bound_dx2,"
        "alpha_dx2,paper_alpha_dx2,paper_alpha2_dx2,bound_ratio,alpha_ratio,negative_phi_points\n",
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
    cli_out_abort(&out);
    fprintf(stderr, "mfstab %s: cannot compute %s\n", cli_command, path);
    cli_out_abort(&out);
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
