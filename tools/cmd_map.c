/* mfstab map: stability over a grid of states of 2D plane strain (the
 * principal stretches of a finite material, or the in-plane stresses of the
 * linear material), for the PDE (strong ellipticity of the acoustic tensor)
 * and for each requested kernel frame (the Bloch symbols of
 * mfs_dispersion.h): paper 000 Fig. 1 for the eq. 18 material. */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "cmd_map.h"
#include "commands.h"
#include "mfs_omp.h"

static const char usage[] = "mfstab map [options] (--stretch-range FROM:TO:N | --stress-range FROM:TO:N) [-o FILE]";
static const char about[] =
  "Stability over a grid of homogeneous states of 2D plane strain, one CSV row per grid point\n"
  "and kernel frame: the PDE (strong ellipticity of the acoustic tensor with the initial-stress\n"
  "term) and the discretization (the Bloch symbol sampled on the first Brillouin zone of the\n"
  "frame's lattice: --directions angles in [0, pi) x --wavenumbers in (0, kappa_max], plus the\n"
  "same along the PDE's worst direction and kappa dx0/pi = 1e-3 and 1e-2 there).  Paper 000\n"
  "Fig. 1: --material paper000 --stretch-range 0.3:2.0:35 --frame lagrangian,eulerian.\n"
  "  --stretch-range   F = diag(lambda1, lambda2), both on the grid FROM:TO:N (finite materials)\n"
  "  --stress-range    sigma_xx/mu and sigma_yy/mu on the grid (linear material, F = I; with\n"
  "                    --stress-xy fixed)\n"
  "Normalized (_norm): omega2 = omega^2 rho0 dx0^2 / mu0 (mu0 the small-strain shear modulus),\n"
  "stresses / mu0, wave vectors k dx0 / pi (k_worst in the frame's configuration: reference for the\n"
  "Lagrangian kernel, current for the Eulerian; k_worst_current always current): the first sample\n"
  "(the zone's, then the worst direction's) within 1e-12 max|omega^2| of the least omega^2 (of the\n"
  "largest growth, within 1e-12 sqrt(max|omega^2|)), so that mirror images, equal but for rounding,\n"
  "give the same one on every machine.\n"
  "A point is stable when no sampled omega^2 has Re < -1e-10 max|omega^2| or a growth |Im sqrt(omega^2)|\n"
  "above sqrt(1e-10 max|omega^2|); zeros at non-reciprocal wave vectors are neutral (rank-deficiency).\n"
  "CSV columns: lattice,kernel,shape,quadrature,frame,mass,dilation,material,support_rule,lambda1,\n"
  "  lambda2,J,sigma_xx_norm,sigma_yy_norm,sigma_xy_norm,pde_stable,pde_margin_norm,pde_theta_deg,\n"
  "  stable,min_omega2_norm,max_growth_norm,k_worst_x_norm,k_worst_y_norm,k_worst_current_x_norm,\n"
  "  k_worst_current_y_norm,spurious_zeros[,max_growth_per_s],label\n"
  "  label: material, tensile, compressive, rank-deficiency (joined by +), stable, or singular\n"
  "  (the moment matrix is singular on the current lattice of an Eulerian kernel; stable and the\n"
  "  omega2 columns empty).  --dilation takes a comma-separated list.\n";

typedef struct {
  const char *stretch_range, *stress_range, *frames;
  double stress_xy;
  const mfs_hyper_type *material;
  int support;
  long directions, wavenumbers;
  const char *out;
  double max_evaluations;
} map_opts;

/* the default limit on a map's symbol evaluations (about 1 us each: a few minutes) */
#define MAP_MAX_EVALUATIONS 2e8

static const char *const support_names[] = {"volume", "reference", NULL};

static const void *find_material(const char *n)
{
  return mfs_hyper_find(n);
}

#define OFF(f) offsetof(map_opts, f)
static const cli_opt opts[] = {
  {.name = "--material", .type = CLI_TABLE, .arg = "NAME",
   .help = "the material (default paper000 with --stretch-range, linear with --stress-range;\n"
           "neo-hookean: --modulus mu and --poisson)",
   .offset = OFF(material), .find = find_material, .list = (const void *const *)mfs_hyper_types},
  {.name = "--stretch-range", .type = CLI_TEXT, .arg = "FROM:TO:N",
   .help = "grid of both principal stretches (> 0)", .offset = OFF(stretch_range)},
  {.name = "--stress-range", .type = CLI_TEXT, .arg = "FROM:TO:N",
   .help = "grid of sigma_xx/mu and sigma_yy/mu (linear material)", .offset = OFF(stress_range)},
  {.name = "--stress-xy", .type = CLI_REAL, .arg = "S",
   .help = "with --stress-range: sigma_xy/mu (default 0)", .offset = OFF(stress_xy)},
  {.name = "--frame", .type = CLI_TEXT, .arg = "LIST",
   .help = "comma-separated kernel frames: lagrangian, eulerian, eulerian-consistent (default\n"
           "lagrangian)",
   .offset = OFF(frames)},
  {.name = "--support-rule", .type = CLI_CHOICE, .arg = "volume|reference",
   .help = "Eulerian kernel radius under a stretch: D dx0 sqrt(J) (volume, default) or D dx0",
   .offset = OFF(support), .choices = support_names},
  {.name = "--directions", .type = CLI_INT, .arg = "N",
   .help = "propagation directions on [0, pi) (default 8)", .offset = OFF(directions),
   .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 10000},
  {.name = "--wavenumbers", .type = CLI_INT, .arg = "N",
   .help = "wave numbers per direction (default 64)", .offset = OFF(wavenumbers),
   .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 100000},
  {.name = "--max-evaluations", .type = CLI_REAL, .arg = "N",
   .help = "refuse a map of more than N symbol evaluations: grid points x dilations x frames x\n"
           "(directions x wavenumbers + wavenumbers + 2) (default 2e8)",
   .offset = OFF(max_evaluations), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 1e15},
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE",
   .help = "output file (default: standard output)", .offset = OFF(out)},
  {.type = CLI_END}};
#undef OFF

/* FROM:TO:N into v[0..N) (uniform); dies naming the option. */
static double *parse_range(const char *opt, const char *s, int positive, long *n)
{
  char buf[256];
  if (strlen(s) >= sizeof buf)
    cli_die(2, "%s '%.40s...': too long; expected FROM:TO:N", opt, s);
  strcpy(buf, s);
  char *a = buf, *b = strchr(a, ':'), *c = b ? strchr(b + 1, ':') : NULL;
  if (!b || !c || strchr(c + 1, ':'))
    cli_die(2, "%s '%s': expected FROM:TO:N (e.g. 0.3:2.0:35)", opt, s);
  *b++ = '\0';
  *c++ = '\0';
  double lo, hi;
  long k;
  if (!cli_parse_double(a, &lo) || !cli_parse_double(b, &hi))
    cli_die(2, "%s '%s': FROM and TO must be finite decimal numbers", opt, s);
  if (!cli_parse_long(c, &k) || k < 1 || k > 100000)
    cli_die(2, "%s '%s': N must be an integer from 1 to 100000", opt, s);
  if (k == 1 && lo != hi)
    cli_die(2, "%s '%s': N = 1 needs FROM = TO", opt, s);
  if (positive && (!(lo > 0.0) || !(hi > 0.0)))
    cli_die(2, "%s '%s': stretches must be > 0", opt, s);
  double *v = mfs_malloc((size_t)k * sizeof *v);
  if (!v)
    cli_die(1, "out of memory");
  for (long i = 0; i < k; i++)
    v[i] = k == 1 ? lo : lo + (hi - lo) * (double)i / (double)(k - 1);
  *n = k;
  return v;
}

/* The frames of a comma-separated list; dies on an unknown name. */
static int parse_frames(const char *s, mfs_frame *fr)
{
  char buf[256];
  if (strlen(s) >= sizeof buf)
    cli_die(2, "--frame '%.40s...': too long", s);
  strcpy(buf, s);
  int n = 0;
  for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
    if (n == 3 || mfs_frame_parse(t, &fr[n]) != MFS_OK)
      cli_die(2, "--frame '%s': %s; allowed: a comma-separated list of lagrangian, eulerian, "
                 "eulerian-consistent (each once)",
              s, n == 3 ? "too many" : "unknown frame");
    for (int j = 0; j < n; j++)
      if (fr[j] == fr[n])
        cli_die(2, "--frame '%s': %s given twice", s, t);
    n++;
  }
  if (!n)
    cli_die(2, "--frame '%s': empty list", s);
  return n;
}

/* The grid points are evaluated in parallel (OpenMP), each on its own with a
 * workspace per thread, and written in order: the file is the same for any
 * number of threads. */

/* What the map writes for one state and frame. */
typedef struct {
  int singular, stable, zeros;
  double min_re, max_growth;
  double kw[2], kwc[2]; /* the worst mode's wave vector: frame's, current (1/dx0) */
  unsigned labels;
} map_point;

void map_worst(const double complex *w, size_t n, int nb, double scale, double *min_re,
               double *max_growth, size_t *imin, size_t *igr)
{
  double lo = INFINITY, hi = 0.0;
  for (size_t i = 0; i < n * (size_t)nb; i++) {
    lo = fmin(lo, creal(w[i]));
    hi = fmax(hi, fabs(cimag(csqrt(w[i]))));
  }
  const double tie = 1e-12 * scale, tie_g = 1e-12 * sqrt(scale);
  *imin = *igr = 0;
  for (size_t i = n; i-- > 0;) /* backwards: the first such sample is the last one kept */
    for (int b = nb; b-- > 0;) {
      double complex w2 = w[i * (size_t)nb + b];
      if (creal(w2) <= lo + tie)
        *imin = i;
      if (fabs(cimag(csqrt(w2))) >= hi - tie_g)
        *igr = i;
    }
  *min_re = lo;
  *max_growth = hi;
}

/* Sample the Bloch symbol of plan pl at state st: the zone samples kz[0..nz)
 * (through the sample object when given), and the rays along the PDE's worst
 * direction.  The classification as mfs_classify's thresholds. */
static mfs_status eval_point(const mfs_disp_plan *pl, const mfs_disp_sample *smp, const double *kz,
                             size_t nz, long nwave, const mfs_plane_state *st,
                             const mfs_ellipticity *pde, double complex *w, double *kall,
                             map_point *mp)
{
  const int nb = mfs_disp_branches(pl);
  /* the worst direction in the frame's configuration: Lagrangian N ~ F^T n */
  double n[2] = {cos(pde->theta), sin(pde->theta)};
  if (mfs_disp_plan_spec(pl)->disc.frame == MFS_FRAME_LAGRANGIAN) {
    n[0] *= st->l[0];
    n[1] *= st->l[1];
  }
  double th = atan2(n[1], n[0]), km = mfs_disp_kappa_max(pl, th) * M_PI;
  size_t nw = (size_t)nwave + 2, ntot = nz + nw;
  for (size_t i = 0; i < nz; i++) {
    kall[2 * i] = kz[2 * i];
    kall[2 * i + 1] = kz[2 * i + 1];
  }
  for (size_t i = 0; i < nw; i++) {
    double kap = i < (size_t)nwave ? km * (double)(i + 1) / (double)nwave
                                   : (i == (size_t)nwave ? 1e-3 : 1e-2) * M_PI;
    kall[2 * (nz + i)] = kap * cos(th);
    kall[2 * (nz + i) + 1] = kap * sin(th);
  }
  size_t i0 = smp ? nz : 0; /* the zone from the sample, the rest at once */
  for (size_t i = 0; i < i0; i++) {
    mfs_status s = mfs_disp_sample_omega2(smp, i, st, w + i * (size_t)nb);
    if (s != MFS_OK)
      return s;
  }
  mfs_status e = mfs_disp_omega2_states(pl, st, ntot - i0, kall + 2 * i0, w + i0 * (size_t)nb);
  if (e != MFS_OK)
    return e;
  double scale = 0.0;
  for (size_t i = 0; i < ntot * (size_t)nb; i++)
    scale = fmax(scale, cabs(w[i]));
  const double tol = 1e-10 * scale;
  *mp = (map_point){0};
  size_t imin, igr;
  map_worst(w, ntot, nb, scale, &mp->min_re, &mp->max_growth, &imin, &igr);
  for (size_t i = 0; i < ntot; i++)
    for (int b = 0; b < nb; b++)
      if (fabs(creal(w[i * (size_t)nb + b])) <= tol &&
          !mfs_disp_is_reciprocal(pl, kall + 2 * i, 1e-9))
        mp->zeros++;
  int by_min = mp->min_re < -tol, unstable = by_min || mp->max_growth > sqrt(tol);
  if (mp->max_growth <= sqrt(tol))
    mp->max_growth = 0.0;
  size_t iw = by_min || !unstable ? imin : igr;
  mp->kw[0] = kall[2 * iw];
  mp->kw[1] = kall[2 * iw + 1];
  mfs_disp_current_k(pl, mp->kw, mp->kwc);
  mp->stable = !unstable;
  double kk = hypot(mp->kwc[0], mp->kwc[1]), u[2] = {mp->kwc[0] / kk, mp->kwc[1] / kk};
  const double *s = st->sigma;
  double snn = u[0] * u[0] * s[0] + u[0] * u[1] * (s[1] + s[2]) + u[1] * u[1] * s[3];
  mp->labels = mfs_class_labels(unstable, pde, snn, 0.5 * (s[0] + s[3]), mp->zeros);
  return MFS_OK;
}

/* The zone samples of a plan: ndir angles in [0, pi) x nwave wave numbers in (0, kappa_max]. */
static void zone(const mfs_disp_plan *pl, long ndir, long nwave, double *kz)
{
  for (long t = 0; t < ndir; t++) {
    double th = M_PI * (double)t / (double)ndir, km = mfs_disp_kappa_max(pl, th) * M_PI;
    for (long i = 0; i < nwave; i++) {
      double kap = km * (double)(i + 1) / (double)nwave;
      kz[2 * (t * nwave + i)] = kap * cos(th);
      kz[2 * (t * nwave + i) + 1] = kap * sin(th);
    }
  }
}

static void putc_num(FILE *f, double v)
{
  cli_put_num(f, v, "a map value");
  fputc(',', f);
}

static void plan_free_cb(void *p)
{
  mfs_disp_plan_free(p);
}

static void sample_free_cb(void *p)
{
  mfs_disp_sample_free(p);
}

/* The workspaces of cmd_map, freed together (by cli_die too). */
typedef struct {
  double *kz, *kall;
  double complex *w;
  map_point *mps;
  mfs_plane_state *pss;
  mfs_ellipticity *pdes;
  mfs_status *pst;
} map_work;

static void map_work_free(void *p)
{
  map_work *mw = p;
  mfs_free(mw->kz);
  mfs_free(mw->kall);
  mfs_free(mw->w);
  mfs_free(mw->mps);
  mfs_free(mw->pss);
  mfs_free(mw->pdes);
  mfs_free(mw->pst);
}

/* Every cli_die of cmd_map frees what it holds (cli_on_die): nothing is left
 * for the sanitizer's leak check, whatever the stack still points to. */
int cmd_map(int argc, char **argv)
{
  cli_disc d;
  cli_disc_defaults(&d);
  d.dim = 2;
  d.physics = 1; /* plane strain */
  map_opts o = {.directions = 8, .wavenumbers = 64};
  unsigned char seen_d[CLI_DISC_NOPTS], seen_p[CLI_PHYSICS_NOPTS], seen_o[16];
  cli_group g[3] = {{cli_disc_opts, &d, seen_d}, {cli_physics_opts, &d, seen_p}, {opts, &o, seen_o}};
  cli_parse(argc, argv, usage, about, g, 3);
  cli_on_die(mfs_free, d.dilation.v);
  if (d.dim != 2 || d.physics != 1)
    cli_die(2, "--%s: mfstab map analyses 2D plane strain (--dim 2 --physics plane-strain)",
            d.dim != 2 ? "dim" : "physics");
  if (!o.stretch_range == !o.stress_range)
    cli_die(2, "--stretch-range, --stress-range: give exactly one of them");
  int stretch_map = o.stretch_range != NULL;
  if (!o.material)
    o.material = stretch_map ? &mfs_hyper_paper000 : &mfs_hyper_linear;
  if (stretch_map && !o.material->finite)
    cli_die(2, "--material %s: a stretch map needs a finite material (neo-hookean, paper000); the "
               "linear material is mapped over --stress-range",
            o.material->name);
  if (!stretch_map && o.material->finite)
    cli_die(2, "--material %s: a finite material's stress follows from the stretch; use "
               "--stretch-range",
            o.material->name);
  if (stretch_map && cli_seen(&g[2], "--stress-xy"))
    cli_die(2, "--stress-xy %g: used with --stress-range only", o.stress_xy);
  if (o.material == &mfs_hyper_paper000) {
    const char *own[] = {"--modulus", "--density", "--poisson"};
    for (int i = 0; i < 3; i++)
      if (cli_seen(i < 2 ? &g[0] : &g[1], own[i]))
        cli_die(2, "%s: the paper000 material has its own constants (paper 000 eq. 18: c1, c2, "
                   "lambda, rho = 125.4 kg/m^3)",
                own[i]);
  }
  mfs_frame frames[3] = {MFS_FRAME_LAGRANGIAN};
  int nfr = o.frames ? parse_frames(o.frames, frames) : 1;
  int euler = 0;
  for (int i = 0; i < nfr; i++)
    euler |= frames[i] != MFS_FRAME_LAGRANGIAN;
  if (cli_seen(&g[2], "--support-rule") && (!euler || !stretch_map))
    cli_die(2, "--support-rule %s: the radius of an Eulerian kernel under a stretch (a stretch map "
               "with --frame eulerian or eulerian-consistent)",
            support_names[o.support]);
  long ng;
  double *grid = parse_range(stretch_map ? "--stretch-range" : "--stress-range",
                             stretch_map ? o.stretch_range : o.stress_range, stretch_map, &ng);
  cli_on_die(mfs_free, grid);
  /* SI: the material's modulus and density with --spacing */
  int sm = cli_seen(&g[0], "--modulus"), sd = cli_seen(&g[0], "--density"),
      ss = cli_seen(&g[0], "--spacing");
  mfs_hyper mat = o.material == &mfs_hyper_paper000
                    ? mfs_hyper_paper000_constants()
                    : mfs_hyper_isotropic(o.material, d.modulus, d.poisson, d.density);
  int si = ss && (o.material == &mfs_hyper_paper000 || (sm && sd));
  if ((sm || sd || ss) && !si)
    cli_die(2, "%s: SI columns need %s together (the map itself is normalized)",
            ss ? "--spacing" : sm ? "--modulus" : "--density",
            o.material == &mfs_hyper_paper000 ? "--spacing" : "--modulus, --density and --spacing");
  double csi = sqrt(mat.type->mu0(mat.c) / mat.density) / d.spacing;
  mfs_disc disc = cli_disc_build(&d, seen_d);
  if (cli_seen(&g[0], "--gamma") && disc.source.lattice == MFS_LATTICE_HEX)
    cli_die(2, "--gamma %g: dy/dx of the square lattice; the hexagonal lattice has none", d.gamma);
  double dil1 = 2.0;
  const double *dil = d.dilation.n ? d.dilation.v : &dil1;
  size_t ndil = d.dilation.n ? d.dilation.n : 1;

  /* workspaces per thread: zone samples (a per-state plan's own), all samples, omega^2 */
  size_t nz = (size_t)(o.directions * o.wavenumbers), nw = (size_t)o.wavenumbers + 2;
  size_t npt = (size_t)ng * (size_t)ng;
  double evals = (double)npt * (double)ndil * (double)nfr * ((double)nz + (double)nw);
  double elim = o.max_evaluations > 0.0 ? o.max_evaluations : MAP_MAX_EVALUATIONS;
  if (!(evals <= elim))
    cli_die(2,
            "%s %s: about %.3g symbol evaluations (%.3g grid points x %zu dilation%s x %d frame%s "
            "x %.3g wave vectors), more than --max-evaluations %.3g%s; a coarser grid, fewer "
            "--directions or --wavenumbers, or raise --max-evaluations",
            stretch_map ? "--stretch-range" : "--stress-range",
            stretch_map ? o.stretch_range : o.stress_range, evals, (double)npt, ndil,
            ndil == 1 ? "" : "s", nfr, nfr == 1 ? "" : "s", (double)(nz + nw), elim,
            o.max_evaluations > 0.0 ? "" : " (the default)");
  int nthr = mfs_omp_threads();
  map_work mw = {
    .kz = mfs_malloc(2 * nz * (size_t)nthr * sizeof *mw.kz),
    .kall = mfs_malloc(2 * (nz + nw) * (size_t)nthr * sizeof *mw.kall),
    .w = mfs_malloc((nz + nw) * 4 * (size_t)nthr * sizeof *mw.w),
    .mps = mfs_malloc(npt * sizeof *mw.mps),
    .pss = mfs_malloc(npt * sizeof *mw.pss),
    .pdes = mfs_malloc(npt * sizeof *mw.pdes),
    .pst = mfs_malloc(2 * npt * sizeof *mw.pst),
  };
  cli_on_die(map_work_free, &mw);
  if (!mw.kz || !mw.kall || !mw.w || !mw.mps || !mw.pss || !mw.pdes || !mw.pst)
    cli_die(1, "out of memory");
  double *kz = mw.kz, *kall = mw.kall;
  double complex *w = mw.w;
  map_point *mps = mw.mps;
  mfs_plane_state *pss = mw.pss;
  mfs_ellipticity *pdes = mw.pdes;
  mfs_status *pst = mw.pst;
  const char *latn = disc.source.lattice == MFS_LATTICE_HEX ? "hex" : "square";
  cli_out out;
  cli_out_open(&out, o.out);
  FILE *f = out.f;
  fprintf(f, "lattice,kernel,shape,quadrature,frame,mass,dilation,material,support_rule,lambda1,"
             "lambda2,J,sigma_xx_norm,sigma_yy_norm,sigma_xy_norm,pde_stable,pde_margin_norm,"
             "pde_theta_deg,stable,min_omega2_norm,max_growth_norm,k_worst_x_norm,k_worst_y_norm,"
             "k_worst_current_x_norm,k_worst_current_y_norm,spurious_zeros,%slabel\n",
          si ? "max_growth_per_s," : "");
  for (size_t di = 0; di < ndil; di++)
    for (int fi = 0; fi < nfr; fi++) {
      mfs_disc dd = disc;
      dd.dilation = dil[di];
      dd.frame = frames[fi];
      int eul = frames[fi] != MFS_FRAME_LAGRANGIAN;
      /* one plan for every state, except Eulerian kernels under a stretch (the current lattice) */
      int per_state = eul && stretch_map;
      mfs_disp_plan *pl = NULL;
      mfs_disp_sample *smp = NULL;
      mfs_disp_spec base = {.disc = dd, .support = (mfs_support_rule)o.support};
      if (stretch_map)
        base.material = mat;
      else
        base.stress_xy = o.stress_xy;
      if (!per_state) {
        mfs_status st;
        pl = mfs_disp_plan_alloc(&base, &st);
        cli_on_die(plan_free_cb, pl);
        if (!pl) {
          if (st == MFS_ENOTSUP)
            cli_die(2, "--frame %s: not covered for --shape %s (position derivatives: mls, shepard, "
                       "sph)",
                    mfs_frame_name(dd.frame), dd.shape->name);
          cli_die_status(st, &d, dil[di], "at a quadrature point of the lattice");
        }
        zone(pl, o.directions, o.wavenumbers, kz);
        smp = mfs_disp_sample_alloc(pl, nz, kz, &st);
        cli_on_die(sample_free_cb, smp);
        if (!smp)
          cli_die(1, "map: %s", mfs_strerror(st));
      }
      /* the states and the PDE, in order (a bad state names itself) */
      for (size_t q = 0; q < npt; q++) {
        double x = grid[q / (size_t)ng], y = grid[q % (size_t)ng];
        mfs_status st = stretch_map
                          ? mfs_plane_state_stretch(&mat, x, y, pss + q)
                          : mfs_plane_state_linear(disc.material.poisson, x, y, o.stress_xy, pss + q);
        if (st != MFS_OK)
          cli_die(2, "%s: (%g, %g) is not a valid state of the %s material",
                  stretch_map ? "--stretch-range" : "--stress-range", x, y, mat.type->name);
        if (mfs_ellipticity_check(pss[q].a, 0, pdes + q) != MFS_OK)
          cli_die(1, "the acoustic tensor at (%g, %g) is not finite", x, y);
      }
      /* the discretization at every grid point, in parallel: each point on its own */
      const long ntask = (long)npt;
      MFS_OMP("omp parallel for schedule(dynamic) if (ntask > 1)")
      for (long q = 0; q < ntask; q++) {
        int th = mfs_omp_thread();
        double *kzt = per_state ? kz + 2 * nz * (size_t)th : kz;
        map_point mp = {0};
        mfs_disp_plan *own = NULL;
        mfs_status st = MFS_OK;
        if (per_state) {
          mfs_disp_spec sp = base;
          sp.stretch = grid[q / ng];
          sp.stretch_y = grid[q % ng];
          own = mfs_disp_plan_alloc(&sp, &st);
          mp.singular = own == NULL && st == MFS_ESINGULAR;
          if (own)
            zone(own, o.directions, o.wavenumbers, kzt);
        }
        pst[2 * q] = own || !per_state || mp.singular ? MFS_OK : st;
        pst[2 * q + 1] = MFS_OK;
        if (!mp.singular && (own || !per_state))
          pst[2 * q + 1] = eval_point(own ? own : pl, own ? NULL : smp, kzt, nz, o.wavenumbers,
                                      pss + q, pdes + q, w + (nz + nw) * 4 * (size_t)th,
                                      kall + 2 * (nz + nw) * (size_t)th, &mp);
        mfs_disp_plan_free(own);
        mps[q] = mp;
      }
      for (size_t q = 0; q < npt; q++) { /* the first failure, in order */
        double x = grid[q / (size_t)ng], y = grid[q % (size_t)ng];
        mfs_status st = pst[2 * q];
        if (st != MFS_OK)
          cli_die(st == MFS_ENOTSUP || st == MFS_EINVAL ? 2 : 1,
                  "--frame %s at stretches (%g, %g): %s", mfs_frame_name(dd.frame), x, y,
                  st == MFS_ENOTSUP ? "not covered for this shape" : mfs_strerror(st));
        if (pst[2 * q + 1] != MFS_OK)
          cli_die(1, "omega^2 at (%g, %g): %s", x, y, mfs_strerror(pst[2 * q + 1]));
      }
      for (size_t q = 0; q < npt; q++) {
        const mfs_plane_state ps = pss[q];
        const mfs_ellipticity pde = pdes[q];
        const map_point mp = mps[q];
        fprintf(f, "%s,%s,%s,%s,%s,%s,", latn, dd.kernel->name, dd.shape->name,
                dd.quadrature->name, mfs_frame_name(dd.frame),
                dd.consistent_mass ? "consistent" : "lumped");
        putc_num(f, dil[di]);
        fprintf(f, "%s,%s,", mat.type->name,
                eul && stretch_map ? support_names[o.support] : "");
        double v[] = {ps.l[0], ps.l[1], ps.J, ps.sigma[0], ps.sigma[3], ps.sigma[1]};
        for (int k = 0; k < 6; k++)
          putc_num(f, v[k]);
        fprintf(f, "%d,", mfs_pde_stable(&pde));
        putc_num(f, pde.q_min);
        putc_num(f, pde.theta * 180.0 / M_PI);
        if (mp.singular) {
          fprintf(f, ",,,,,,,,%ssingular\n", si ? "," : "");
          continue;
        }
        fprintf(f, "%d,", mp.stable);
        double v2[] = {mp.min_re, mp.max_growth, mp.kw[0] / M_PI, mp.kw[1] / M_PI,
                       mp.kwc[0] / M_PI, mp.kwc[1] / M_PI};
        for (int k = 0; k < 6; k++)
          putc_num(f, v2[k]);
        fprintf(f, "%d,", mp.zeros);
        if (si)
          putc_num(f, mp.max_growth * csi);
        char lab[96];
        fprintf(f, "%s\n", mfs_class_label(mp.labels, lab, sizeof lab));
      }
      if (!per_state) {
        cli_on_die_pop();
        cli_on_die_pop();
      }
      mfs_disp_sample_free(smp);
      mfs_disp_plan_free(pl);
    }
  cli_out_commit(&out);
  cli_on_die_pop(); /* the workspaces */
  cli_on_die_pop(); /* grid */
  cli_on_die_pop(); /* the dilations */
  map_work_free(&mw);
  mfs_free(grid);
  mfs_free(d.dilation.v);
  return 0;
}
