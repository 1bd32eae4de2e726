/* mfstab dispersion: von Neumann dispersion curves omega(kappa) of a particle
 * discretization on an infinite uniform lattice (paper 003 sections 4.1-4.4;
 * 2D plane strain under a homogeneous initial stress or a finite stretch,
 * docs/finite-deformation.md), from the Bloch symbols of the assembled
 * unit-cell operators, and with --classify the library's stability
 * classification (mfs_classify.h). */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"
#include "mfs_omp.h"

static const char usage[] = "mfstab dispersion [options] [-o FILE]";
static const char about[] =
  "Dispersion omega(kappa) of plane waves on an infinite uniform lattice under a uniform\n"
  "initial stress (paper 003 eqs 64-119), or in 2D plane strain under a homogeneous initial\n"
  "stress (--stress, --stress-yy, --stress-xy) or a finite stretch of a hyperelastic material\n"
  "(--material, --stretch, --stretch-y), from the Fourier symbols of the assembled linearized\n"
  "operators.  Normalized (_norm): kappa = kappa*dx/pi, omega2 = (omega*dx/c)^2 with c^2 = C/rho,\n"
  "sigma = sigma/C, C the modulus (1D: E; 2D: the shear modulus; a finite material: its\n"
  "small-strain shear modulus mu0, reference spacing and density).  With --modulus, --density\n"
  "and --spacing (paper000: --spacing alone) the CSV adds SI columns.\n"
  "Anti-plane shear: the kernel frame does not enter (in-plane positions do not move) and\n"
  "--stress is the equibiaxial in-plane stress sigma I, so --frame and --stress-yy/-xy are refused.\n"
  "CSV columns: dim,lattice,kernel,shape,quadrature,frame,mass,dilation,physics,material,\n"
  "  stretch_x,stretch_y,sigma_yy_norm,sigma_xy_norm,sigma_norm,theta_deg,kappa_norm,\n"
  "  kx_current_norm,ky_current_norm,branch,omega2_norm,omega2_im_norm,omega_norm,growth_norm\n"
  "  [,k_per_m,omega_rad_s,growth_per_s,sigma_pa]   (omega = Re sqrt(omega2), growth =\n"
  "  |Im sqrt(omega2)|; kappa and theta in the frame's configuration: reference for the\n"
  "  Lagrangian kernel, current for the Eulerian; kx/ky_current the current wave vector)\n"
  "With --classify, one row per (dilation, sigma): min_omega2 over the sampled Brillouin zone\n"
  "and where, unstable kappa range and largest growth, spurious zero-energy modes, the onset\n"
  "stresses, the continuum's check (pde_stable: 1 unless pde_margin_norm, the least eigenvalue\n"
  "of the acoustic tensor / C, is below -1e-12; pde_theta_deg its direction), sigma_nn_norm along the worst mode, the long-wave deviation of the\n"
  "acoustic branches from the acoustic tensor, and the labels material / tensile / compressive /\n"
  "rank-deficiency (or stable).  --dilation takes a comma-separated list here.\n";

typedef struct {
  int frame;
  cli_list stress, theta, kappa;
  double stress_yy, stress_xy;
  double stretch, stretch_y, ls_alpha, ls_length;
  const mfs_hyper_type *material;
  int support;
  long points;
  int classify;
  const char *out;
} disp_opts;

static const char *const frame_names[] = {"lagrangian", "eulerian", "eulerian-consistent", NULL};
static const char *const support_names[] = {"volume", "reference", NULL};

static const void *find_material(const char *n)
{
  return mfs_hyper_find(n);
}

#define OFF(f) offsetof(disp_opts, f)
static const cli_opt opts[] = {
  {.name = "--frame", .type = CLI_CHOICE, .arg = "eulerian|eulerian-consistent|lagrangian",
   .help = "kernel frame (default lagrangian):\n"
           "eulerian linearizes the kernel motion as the paper does (eq. 71; 2D: phi_I a fixed\n"
           "function of x - x_I); eulerian-consistent exactly, for shape functions re-solved in\n"
           "current coordinates (mls, shepard, sph); 1D and 2D plane strain",
   .offset = OFF(frame), .choices = frame_names},
  {.name = "--stress", .type = CLI_REALS, .arg = "LIST",
   .help = "comma-separated normalized stresses sigma/C (default 0): 1D the bar's stress,\n"
           "plane strain sigma_xx, anti-plane the equibiaxial in-plane stress",
   .offset = OFF(stress), .bounds = CLI_GE | CLI_LE, .lo = -1e6, .hi = 1e6},
  {.name = "--stress-yy", .type = CLI_REAL, .arg = "S",
   .help = "plane strain: sigma_yy / C (default 0)", .offset = OFF(stress_yy),
   .bounds = CLI_GE | CLI_LE, .lo = -1e6, .hi = 1e6},
  {.name = "--stress-xy", .type = CLI_REAL, .arg = "S",
   .help = "plane strain: sigma_xy / C (default 0)", .offset = OFF(stress_xy),
   .bounds = CLI_GE | CLI_LE, .lo = -1e6, .hi = 1e6},
  {.name = "--material", .type = CLI_TABLE, .arg = "NAME",
   .help = "plane strain: the material (default linear, under --stress*; neo-hookean: --modulus\n"
           "mu and --poisson; paper000: paper 000 eq. 18, its own constants); finite materials\n"
           "take --stretch and --stretch-y",
   .offset = OFF(material), .find = find_material, .list = (const void *const *)mfs_hyper_types},
  {.name = "--stretch", .type = CLI_REAL, .arg = "F",
   .help = "1D: pre-stretch of the Eulerian analysis; plane strain with a finite material:\n"
           "the principal stretch lambda1 of F = diag(lambda1, lambda2) (default 1)",
   .offset = OFF(stretch), .bounds = CLI_GE | CLI_LE, .lo = 1e-3, .hi = 1e3},
  {.name = "--stretch-y", .type = CLI_REAL, .arg = "F",
   .help = "plane strain with a finite material: lambda2 (default 1)", .offset = OFF(stretch_y),
   .bounds = CLI_GE | CLI_LE, .lo = 1e-3, .hi = 1e3},
  {.name = "--support-rule", .type = CLI_CHOICE, .arg = "volume|reference",
   .help = "Eulerian kernel radius under a stretch: a = D dx0 sqrt(J) (volume, default) or\n"
           "a = D dx0 (reference)",
   .offset = OFF(support), .choices = support_names},
  {.name = "--ls-alpha", .type = CLI_REAL, .arg = "A",
   .help = "least-squares stabilization beta = A (L dx)^2 (eq. 104)", .offset = OFF(ls_alpha),
   .bounds = CLI_GE | CLI_LE, .lo = 0, .hi = 1e6},
  {.name = "--ls-length", .type = CLI_REAL, .arg = "L",
   .help = "the length L of --ls-alpha, in dx (default 1)", .offset = OFF(ls_length),
   .bounds = CLI_GT | CLI_LE, .lo = 0, .hi = 1e3},
  {.name = "--theta", .type = CLI_REALS, .arg = "LIST",
   .help = "propagation angles in degrees (2D only; default 0)", .offset = OFF(theta),
   .bounds = CLI_GE | CLI_LE, .lo = -360, .hi = 360},
  {.name = "--points", .type = CLI_INT, .arg = "N",
   .help = "kappa uniform on [0, kappa_max(theta)] (default 101)", .offset = OFF(points),
   .bounds = CLI_GE | CLI_LE, .lo = 2, .hi = 10000000},
  {.name = "--kappa", .type = CLI_REALS, .arg = "LIST",
   .help = "exact kappa values (kappa*dx/pi) instead of --points", .offset = OFF(kappa),
   .bounds = CLI_GE | CLI_LE, .lo = 0, .hi = 1e6},
  {.name = "--classify", .type = CLI_FLAG,
   .help = "write the classification instead of the curves", .offset = OFF(classify)},
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE",
   .help = "output file (default: standard output)", .offset = OFF(out)},
  {.type = CLI_END}};
#undef OFF

/* The curves are evaluated in parallel (OpenMP) over chunks of CURVE_CHUNK
 * wave numbers of every angle, all stresses at once (mfs_disp_ray); every
 * point is computed on its own, so the file is the same for any number of
 * threads.  Then written in order. */

enum { CURVE_CHUNK = 256 };

/* omega^2 of plan pl at the stresses sig[0..nsig), angles thr[0..nth) and
 * wave numbers kap[t nk + i] into w[((s nth + t) nk + i) nb + b]; cst holds a
 * status per chunk.  A failure names the first failing point (in the order
 * of the file) and exits 1. */
static void curves(const mfs_disp_plan *pl, const double *sig, size_t nsig, const double *thr,
                   size_t nth, const double *kap, size_t nk, double complex *w, mfs_status *cst)
{
  const size_t nb = (size_t)mfs_disp_branches(pl), nch = (nk + CURVE_CHUNK - 1) / CURVE_CHUNK;
  const long ntask = (long)(nth * nch);
  MFS_OMP("omp parallel for schedule(dynamic) if (ntask > 1)")
  for (long task = 0; task < ntask; task++) {
    size_t t = (size_t)task / nch, c0 = ((size_t)task % nch) * CURVE_CHUNK;
    size_t len = nk - c0 < CURVE_CHUNK ? nk - c0 : CURVE_CHUNK;
    cst[task] = mfs_disp_ray(pl, sig, nsig, thr[t], kap + t * nk + c0, len,
                             w + (t * nk + c0) * nb, nth * nk * nb);
  }
  for (long task = 0; task < ntask; task++) {
    if (cst[task] == MFS_OK)
      continue;
    for (size_t s = 0; s < nsig; s++)
      for (size_t t = 0; t < nth; t++)
        for (size_t i = 0; i < nk; i++) {
          double complex om[4];
          mfs_status st = mfs_disp_omega2(pl, sig[s], kap[t * nk + i], thr[t], om);
          if (st != MFS_OK)
            cli_die(1, "omega^2 at kappa %g, sigma %g: %s (singular mass symbol?)", kap[t * nk + i],
                    sig[s], mfs_strerror(st));
        }
    cli_die(1, "omega^2: %s", mfs_strerror(cst[task]));
  }
}

static void put(FILE *f, double v)
{
  cli_put_num(f, v, "a dispersion value");
}

static void putc_num(FILE *f, double v)
{
  put(f, v);
  fputc(',', f);
}

/* The SI scales of the normalized values: 1/dx for kappa*pi, c/dx for omega
 * and growth, C for stresses; enabled by --modulus, --density and --spacing
 * (a finite material brings its modulus mu0 and density). */
typedef struct {
  int on;
  double dx, c, C;
} si_scale;

static const char *physics_name(const mfs_disc *d)
{
  if (d->material.physics == MFS_PHYS_PLANE_STRAIN)
    return "plane-strain";
  return d->dim == 1 ? "bar" : "antiplane";
}

/* The configuration columns of a row, with the trailing comma. */
static void config(FILE *f, const mfs_disc *d, const char *latn, double dil, const char *mat,
                   const mfs_disp_spec *sp, const mfs_plane_state *ps)
{
  fprintf(f, "%d,%s,%s,%s,%s,%s,%s,", d->dim, latn, d->kernel->name, d->shape->name,
          d->quadrature->name, mfs_frame_name(d->frame),
          d->consistent_mass ? "consistent" : d->node_volume_mass ? "volume" : "lumped");
  putc_num(f, dil);
  fprintf(f, "%s,%s,", physics_name(d), mat);
  int plane = d->material.physics == MFS_PHYS_PLANE_STRAIN;
  putc_num(f, d->dim == 1 || plane ? (sp->stretch > 0 ? sp->stretch : 1.0) : NAN);
  putc_num(f, plane ? (sp->stretch_y > 0 ? sp->stretch_y : 1.0) : NAN);
  putc_num(f, ps ? ps->sigma[3] : NAN);
  putc_num(f, ps ? ps->sigma[1] : NAN);
}

int cmd_dispersion(int argc, char **argv)
{
  cli_disc d;
  cli_disc_defaults(&d);
  disp_opts o = {.stretch = 1.0, .stretch_y = 1.0, .ls_length = 1.0, .points = 101,
                 .material = &mfs_hyper_linear};
  unsigned char seen_d[CLI_DISC_NOPTS], seen_p[CLI_PHYSICS_NOPTS], seen_o[24];
  cli_group g[3] = {{cli_disc_opts, &d, seen_d}, {cli_physics_opts, &d, seen_p}, {opts, &o, seen_o}};
  cli_parse(argc, argv, usage, about, g, 3);
  if (cli_seen(&g[2], "--ls-length") && !cli_seen(&g[2], "--ls-alpha"))
    cli_die(2, "--ls-length given without --ls-alpha; give both for least-squares stabilization");
  if (o.theta.n && d.dim == 1)
    cli_die(2, "--theta: propagation angles need --dim 2");
  if (cli_seen(&g[2], "--points") && o.kappa.n)
    cli_die(2, "--points and --kappa: give one of them");
  mfs_disc disc = cli_disc_build(&d, seen_d);
  disc.frame = (mfs_frame)o.frame;
  int plane = disc.material.physics == MFS_PHYS_PLANE_STRAIN;
  int finite = plane && o.material->finite;
  if (cli_seen(&g[0], "--gamma") && disc.source.lattice == MFS_LATTICE_HEX)
    cli_die(2, "--gamma %g: dy/dx of the square lattice; the hexagonal lattice has none", d.gamma);
  /* options the analysis would ignore are refused */
  if (disc.dim == 2 && !plane && disc.frame != MFS_FRAME_LAGRANGIAN)
    cli_die(2, "--frame %s: the kernel frame does not enter anti-plane motion (in-plane positions "
               "do not move: K = (1 + sigma) A for every frame); use --physics plane-strain",
            mfs_frame_name(disc.frame));
  if (cli_seen(&g[1], "--poisson") && (!plane || o.material == &mfs_hyper_paper000))
    cli_die(2, "--poisson %g: used by plane strain with the linear or neo-hookean material only",
            d.poisson);
  if (!plane && cli_seen(&g[2], "--material"))
    cli_die(2, "--material %s: materials are analysed in 2D plane strain only (--dim 2 --physics "
               "plane-strain)",
            o.material->name);
  const char *comp[2] = {"--stress-yy", "--stress-xy"};
  for (int c = 0; c < 2; c++)
    if (cli_seen(&g[2], comp[c]) && (!plane || finite))
      cli_die(2, "%s %g: %s", comp[c], c ? o.stress_xy : o.stress_yy,
              finite ? "a finite material's stress follows from --stretch and --stretch-y"
              : disc.dim == 1 ? "a stress component of 2D plane strain (--dim 2 --physics plane-strain)"
                              : "not analysed with --physics antiplane, where --stress is the "
                                "equibiaxial in-plane stress sigma I; use --physics plane-strain");
  if (finite && o.stress.n)
    cli_die(2, "--stress: a finite material's stress follows from --stretch and --stretch-y");
  if (disc.dim == 2 && (o.stretch != 1.0 || o.stretch_y != 1.0) && !finite)
    cli_die(2, "--stretch%s %g: a finite stretch needs --physics plane-strain and a finite --material "
               "(neo-hookean, paper000)",
            o.stretch != 1.0 ? "" : "-y", o.stretch != 1.0 ? o.stretch : o.stretch_y);
  if (disc.dim == 1 && cli_seen(&g[2], "--stretch-y"))
    cli_die(2, "--stretch-y %g: a stretch of 2D plane strain", o.stretch_y);
  if (cli_seen(&g[2], "--support-rule") && !(finite && disc.frame != MFS_FRAME_LAGRANGIAN))
    cli_die(2, "--support-rule %s: the radius of an Eulerian kernel under a finite stretch "
               "(--frame eulerian|eulerian-consistent with a finite --material)",
            support_names[o.support]);
  /* SI columns */
  si_scale si = {0};
  int sm = cli_seen(&g[0], "--modulus"), sd = cli_seen(&g[0], "--density"),
      ss = cli_seen(&g[0], "--spacing");
  mfs_hyper mat = {0};
  if (finite) {
    if (o.material == &mfs_hyper_paper000) {
      if (sm || sd)
        cli_die(2, "%s: the paper000 material has its own constants (paper 000 eq. 18: c1, c2, "
                   "lambda, rho = 125.4 kg/m^3)",
                sm ? "--modulus" : "--density");
      mat = mfs_hyper_paper000_constants();
    } else {
      mat = mfs_hyper_isotropic(o.material, d.modulus, d.poisson, d.density);
    }
    si.on = ss && (o.material == &mfs_hyper_paper000 || (sm && sd));
    si.C = mat.type->mu0(mat.c);
    si.c = sqrt(si.C / mat.density);
  } else {
    si.on = sm && sd && ss;
    si.C = d.modulus;
    si.c = sqrt(d.modulus / d.density);
  }
  si.dx = d.spacing;
  if ((sm || sd || ss) && !si.on)
    cli_die(2, "%s: SI columns need %s together (the analysis itself is normalized)",
            ss ? "--spacing" : sm ? "--modulus" : "--density",
            o.material == &mfs_hyper_paper000 ? "--spacing" : "--modulus, --density and --spacing");
  double dil1 = 2.0, zero = 0.0;
  const double *dil = d.dilation.n ? d.dilation.v : &dil1;
  size_t ndil = d.dilation.n ? d.dilation.n : 1;
  const double *sig = o.stress.n ? o.stress.v : &zero;
  size_t nsig = o.stress.n ? o.stress.n : 1;
  size_t nth = o.theta.n ? o.theta.n : 1;
  const double *th = o.theta.n ? o.theta.v : &zero;
  double *thr = mfs_malloc(nth * sizeof *thr);
  mfs_disp_plan **plans = mfs_calloc(ndil, sizeof *plans);
  if (!thr || !plans)
    cli_die(1, "out of memory");
  for (size_t t = 0; t < nth; t++)
    thr[t] = th[t] * M_PI / 180.0;
  for (size_t i = 0; i < ndil; i++) { /* the work: the periodic box of the unit cell */
    mfs_disc di = disc;
    di.dilation = dil[i];
    double side = 4.0 * ceil(2.0 * dil[i]) + 4.0;
    char what[64];
    snprintf(what, sizeof what, "--dilation %g", dil[i]);
    cli_check_work(&d, &di, disc.dim == 1 ? side : side * side, what);
  }
  for (size_t i = 0; i < ndil; i++) {
    mfs_disp_spec s = {.disc = disc,
                       .stretch = o.stretch,
                       .ls_beta = o.ls_alpha * o.ls_length * o.ls_length,
                       .stretch_y = o.stretch_y,
                       .stress_yy = o.stress_yy,
                       .stress_xy = o.stress_xy,
                       .material = mat,
                       .support = (mfs_support_rule)o.support};
    s.disc.dilation = dil[i];
    mfs_status st;
    plans[i] = mfs_disp_plan_alloc(&s, &st);
    if (!plans[i]) {
      if (st == MFS_ENOTSUP)
        cli_die(2, "--frame %s: this combination (dimension, shape %s, stretch, physics, least "
                   "squares) is not covered by the analysis; see mfstab dispersion --help",
                mfs_frame_name(disc.frame), disc.shape->name);
      if (st == MFS_ESINGULAR && finite && disc.frame != MFS_FRAME_LAGRANGIAN)
        cli_die(2, "--stretch %g --stretch-y %g: the %s moment matrix is singular on the current "
                   "lattice (support radius %s); use a larger --dilation",
                o.stretch, o.stretch_y, disc.shape->name, support_names[o.support]);
      if (st == MFS_EINVAL && finite)
        cli_die(2, "--stretch %g --stretch-y %g: not a valid state of the %s material", o.stretch,
                o.stretch_y, o.material->name);
      cli_die_status(st, &d, dil[i], "at a quadrature point of the lattice");
    }
  }
  int nk = o.kappa.n ? (int)o.kappa.n : (int)o.points;
  const int nb = mfs_disp_branches(plans[0]);
  /* the curves of one dilation: kappa per angle, omega^2 per (stress, angle, kappa) */
  double *kap = NULL;
  double complex *w = NULL;
  size_t nray = nth * (size_t)nk, nchunk = nth * (((size_t)nk + CURVE_CHUNK - 1) / CURVE_CHUNK);
  mfs_status *cst = NULL;
  if (!o.classify) {
    kap = mfs_malloc(nray * sizeof *kap);
    w = mfs_malloc(nsig * nray * (size_t)nb * sizeof *w);
    cst = mfs_malloc(nchunk * sizeof *cst);
  }
  mfs_class *cls = mfs_malloc(nsig * sizeof *cls);
  if ((!o.classify && (!kap || !w || !cst)) || !cls)
    cli_die(1, "out of memory");
  const char *latn = disc.source.lattice == MFS_LATTICE_LINE  ? "line"
                     : disc.source.lattice == MFS_LATTICE_HEX ? "hex"
                                                              : "square";
  const char *matn = plane ? o.material->name : "linear";
  static const char cfg[] = "dim,lattice,kernel,shape,quadrature,frame,mass,dilation,physics,"
                            "material,stretch_x,stretch_y,sigma_yy_norm,sigma_xy_norm,";
  cli_out out;
  cli_out_open(&out, o.out);
  FILE *f = out.f;
  if (o.classify)
    fprintf(f, "%ssigma_norm,min_omega2_norm,kappa_at_min_norm,theta_at_min_deg,unstable,"
               "unstable_kappa_from_norm,unstable_kappa_to_norm,max_growth_norm,"
               "kappa_at_max_growth_norm,theta_at_max_growth_deg,spurious_zeros,zero_kappa_norm,"
               "zero_theta_deg,onset_sigma_tension_norm,onset_sigma_compression_norm,pde_stable,"
               "pde_margin_norm,pde_theta_deg,sigma_nn_norm,longwave_deviation,%slabel\n",
            cfg, si.on ? "max_growth_per_s," : "");
  else
    fprintf(f, "%ssigma_norm,theta_deg,kappa_norm,kx_current_norm,ky_current_norm,branch,"
               "omega2_norm,omega2_im_norm,omega_norm,growth_norm%s\n",
            cfg, si.on ? ",k_per_m,omega_rad_s,growth_per_s,sigma_pa" : "");
  for (size_t di = 0; di < ndil; di++) {
    const mfs_disp_plan *pl = plans[di];
    const mfs_disp_spec *sp = mfs_disp_plan_spec(pl);
    if (o.classify) {
      mfs_sampling smp = {.theta = thr, .ntheta = nth, .kappa = o.kappa.n ? o.kappa.v : NULL,
                          .nkappa = o.kappa.n, .npoints = (int)o.points};
      mfs_status st = mfs_classify(pl, &smp, sig, nsig, cls);
      if (st != MFS_OK)
        cli_die(1, "classification at D = %g: %s (singular mass symbol?)", dil[di],
                mfs_strerror(st));
      for (size_t si_ = 0; si_ < nsig; si_++) {
        const mfs_class *c = cls + si_;
        char label[96];
        mfs_plane_state ps;
        int have = plane && mfs_disp_state(pl, c->sbar, &ps) == MFS_OK;
        config(f, &disc, latn, dil[di], matn, sp, have ? &ps : NULL);
        double v1[] = {have ? ps.sigma[0] : c->sbar, c->min_omega2, c->kappa_at_min,
                       th[c->theta_at_min]};
        for (int v = 0; v < 4; v++)
          putc_num(f, v1[v]);
        fprintf(f, "%d,", c->unstable);
        double v2[] = {c->unstable_kappa_from, c->unstable_kappa_to, c->max_growth,
                       c->kappa_at_max_growth,
                       c->theta_at_max_growth >= 0 ? th[c->theta_at_max_growth] : NAN};
        for (int v = 0; v < 5; v++)
          putc_num(f, v2[v]);
        fprintf(f, "%d,", c->spurious_zeros);
        double v3[] = {c->zero_kappa, c->zero_theta >= 0 ? th[c->zero_theta] : NAN,
                       c->onset_tension, c->onset_compression};
        for (int v = 0; v < 4; v++)
          putc_num(f, v3[v]);
        fprintf(f, "%d,", mfs_pde_stable(&c->pde));
        double v4[] = {c->pde.q_min, plane ? c->pde.theta * 180.0 / M_PI : NAN, c->sigma_nn,
                       c->longwave_deviation};
        for (int v = 0; v < 4; v++)
          putc_num(f, v4[v]);
        if (si.on)
          putc_num(f, c->max_growth * si.c / si.dx);
        fprintf(f, "%s\n", mfs_class_label(c->labels, label, sizeof label));
      }
      continue;
    }
    for (size_t t = 0; t < nth; t++) {
      double km = mfs_disp_kappa_max(pl, thr[t]);
      for (int i = 0; i < nk; i++)
        kap[t * nk + i] = o.kappa.n ? o.kappa.v[i] : km * i / (nk - 1);
    }
    curves(pl, sig, nsig, thr, nth, kap, (size_t)nk, w, cst);
    for (size_t s_ = 0; s_ < nsig; s_++) {
      mfs_plane_state ps;
      int have = plane && mfs_disp_state(pl, sig[s_], &ps) == MFS_OK;
      for (size_t t = 0; t < nth; t++) {
        const double *kp = kap + t * nk;
        const double complex *wt = w + (s_ * nth + t) * (size_t)nk * nb;
        for (int i = 0; i < nk; i++) {
          double k[2] = {kp[i] * M_PI * cos(thr[t]), kp[i] * M_PI * sin(thr[t])}, kc[2];
          if (disc.dim == 1)
            k[1] = 0.0, k[0] = kp[i] * M_PI;
          mfs_disp_current_k(pl, k, kc);
          for (int b = 0; b < nb; b++) {
            double complex w2 = wt[(size_t)i * nb + b], wr = csqrt(w2);
            double sx = have ? ps.sigma[0] : sig[s_];
            config(f, &disc, latn, dil[di], matn, sp, have ? &ps : NULL);
            putc_num(f, sx);
            putc_num(f, th[t]);
            putc_num(f, kp[i]);
            putc_num(f, kc[0] / M_PI);
            putc_num(f, disc.dim > 1 ? kc[1] / M_PI : NAN);
            fprintf(f, "%d,", b);
            putc_num(f, creal(w2));
            putc_num(f, cimag(w2));
            putc_num(f, fabs(creal(wr)));
            put(f, fabs(cimag(wr)));
            if (si.on) {
              fputc(',', f);
              putc_num(f, kp[i] * M_PI / si.dx);
              putc_num(f, fabs(creal(wr)) * si.c / si.dx);
              putc_num(f, fabs(cimag(wr)) * si.c / si.dx);
              put(f, sx * si.C);
            }
            fputc('\n', f);
          }
        }
      }
    }
  }
  cli_out_commit(&out);
  for (size_t i = 0; i < ndil; i++)
    mfs_disp_plan_free(plans[i]);
  mfs_free(plans);
  mfs_free(kap);
  mfs_free(w);
  mfs_free(cst);
  mfs_free(cls);
  mfs_free(thr);
  mfs_free(d.dilation.v);
  mfs_free(o.stress.v);
  mfs_free(o.theta.v);
  mfs_free(o.kappa.v);
  return 0;
}
