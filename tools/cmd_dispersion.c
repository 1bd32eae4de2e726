/* mfstab dispersion: von Neumann dispersion curves omega(kappa) of a particle
 * discretization on an infinite uniform lattice (paper 003 sections 4.1-4.4),
 * from the Bloch symbols of the assembled unit-cell operators, and with
 * --classify the library's stability classification (mfs_classify.h). */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

static const char usage[] = "mfstab dispersion [options] [-o FILE]";
static const char about[] =
  "Dispersion omega(kappa) of plane waves on an infinite uniform lattice under a uniform\n"
  "initial stress, from the Fourier symbols of the assembled linearized operators\n"
  "(paper 003 eqs 64-119).  Normalized: kappa = kappa*dx/pi, omega2 = (omega*dx/c)^2 with\n"
  "c^2 = C/rho (C the tangent modulus; plane strain: the shear modulus), sigma = sigma/C.\n"
  "CSV columns: dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,theta,kappa,\n"
  "  branch,omega2,omega2_im,omega,growth   (omega = Re sqrt(omega2), growth = |Im sqrt(omega2)|)\n"
  "With --classify, one row per (dilation, sigma): min_omega2 over the sampled Brillouin zone\n"
  "and where, unstable kappa range and largest growth, spurious zero-energy modes, the onset\n"
  "stresses, and the labels material / tensile / rank-deficiency (or stable).\n"
  "--dilation takes a comma-separated list here.\n";

typedef struct {
  int frame;
  cli_list stress, theta, kappa;
  double stretch, ls_alpha, ls_length;
  long points;
  int classify;
  const char *out;
} disp_opts;

static const char *const frame_names[] = {"lagrangian", "eulerian", "eulerian-consistent", NULL};

#define OFF(f) offsetof(disp_opts, f)
static const cli_opt opts[] = {
  {.name = "--frame", .type = CLI_CHOICE, .arg = "eulerian|eulerian-consistent|lagrangian",
   .help = "kernel frame (default lagrangian):\n"
           "eulerian linearizes the kernel motion as the paper does (eq. 71);\n"
           "eulerian-consistent exactly, for shape functions re-solved in\n"
           "current coordinates (1D; mls, shepard, sph)",
   .offset = OFF(frame), .choices = frame_names},
  {.name = "--stress", .type = CLI_REALS, .arg = "LIST",
   .help = "comma-separated normalized stresses sigma/C (default 0)", .offset = OFF(stress),
   .bounds = CLI_GE | CLI_LE, .lo = -1e6, .hi = 1e6},
  {.name = "--stretch", .type = CLI_REAL, .arg = "F",
   .help = "pre-stretch of the 1D Eulerian analysis (default 1)", .offset = OFF(stretch),
   .bounds = CLI_GE | CLI_LE, .lo = 1e-3, .hi = 1e3},
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

static void put(FILE *f, double v)
{
  cli_put_num(f, v, "a dispersion value");
}

/* The configuration columns of a row, with the trailing comma. */
static void config(FILE *f, const mfs_disc *d, const char *latn, double dil)
{
  fprintf(f, "%d,%s,%s,%s,%s,%s,%s,", d->dim, latn, d->kernel->name, d->shape->name,
          d->quadrature->name, mfs_frame_name(d->frame),
          d->consistent_mass ? "consistent" : "lumped");
  put(f, dil);
  fputc(',', f);
}

int cmd_dispersion(int argc, char **argv)
{
  cli_disc d;
  cli_disc_defaults(&d);
  disp_opts o = {.stretch = 1.0, .ls_length = 1.0, .points = 101};
  unsigned char seen_d[CLI_DISC_NOPTS], seen_p[CLI_PHYSICS_NOPTS], seen_o[16];
  cli_group g[3] = {{cli_disc_opts, &d, seen_d}, {cli_physics_opts, &d, seen_p}, {opts, &o, seen_o}};
  cli_parse(argc, argv, usage, about, g, 3);
  if (cli_seen(&g[2], "--ls-length") && !cli_seen(&g[2], "--ls-alpha"))
    cli_die(2, "--ls-length given without --ls-alpha; give both for least-squares stabilization");
  if (o.theta.n && d.dim == 1)
    cli_die(2, "--theta: propagation angles need --dim 2");
  if (cli_seen(&g[2], "--points") && o.kappa.n)
    cli_die(2, "--points and --kappa: give one of them");
  if (o.stretch != 1.0 && d.dim != 1)
    cli_die(2, "--stretch %g: a pre-stretch is analysed in 1D only", o.stretch);
  mfs_disc disc = cli_disc_build(&d, seen_d);
  disc.frame = (mfs_frame)o.frame;
  double dil1 = 2.0, zero = 0.0;
  const double *dil = d.dilation.n ? d.dilation.v : &dil1;
  size_t ndil = d.dilation.n ? d.dilation.n : 1;
  const double *sig = o.stress.n ? o.stress.v : &zero;
  size_t nsig = o.stress.n ? o.stress.n : 1;
  size_t nth = o.theta.n ? o.theta.n : 1;
  const double *th = o.theta.n ? o.theta.v : &zero;
  for (size_t i = 0; i < nsig; i++)
    if (disc.material.physics == MFS_PHYS_PLANE_STRAIN && sig[i] != 0.0)
      cli_die(2, "--stress %g: plane strain is analysed at zero initial stress only", sig[i]);
  double *thr = malloc(nth * sizeof *thr);
  mfs_disp_plan **plans = calloc(ndil, sizeof *plans);
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
                       .ls_beta = o.ls_alpha * o.ls_length * o.ls_length};
    s.disc.dilation = dil[i];
    mfs_status st;
    plans[i] = mfs_disp_plan_alloc(&s, &st);
    if (!plans[i]) {
      if (st == MFS_ENOTSUP)
        cli_die(2, "--frame %s: this combination (dimension, shape, stretch, physics) is not covered by "
                   "the analysis; see mfstab dispersion --help",
                mfs_frame_name(disc.frame));
      cli_die_status(st, &d, dil[i], "at a quadrature point of the lattice");
    }
  }
  int nk = o.kappa.n ? (int)o.kappa.n : (int)o.points;
  const int nb = mfs_disp_branches(plans[0]);
  double *kap = malloc((size_t)nk * sizeof *kap);
  double complex *w = malloc((size_t)nk * (size_t)nb * sizeof *w);
  mfs_class *cls = malloc(nsig * sizeof *cls);
  if (!kap || !w || !cls)
    cli_die(1, "out of memory");
  const char *latn = disc.source.lattice == MFS_LATTICE_LINE  ? "line"
                     : disc.source.lattice == MFS_LATTICE_HEX ? "hex"
                                                              : "square";
  cli_out out;
  cli_out_open(&out, o.out);
  FILE *f = out.f;
  if (o.classify)
    fprintf(f, "dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,min_omega2,"
               "kappa_at_min,theta_at_min,unstable,unstable_kappa_from,unstable_kappa_to,"
               "max_growth,kappa_at_max_growth,theta_at_max_growth,spurious_zeros,"
               "zero_kappa,zero_theta,onset_sigma_tension,onset_sigma_compression,label\n");
  else
    fprintf(f, "dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,theta,kappa,"
               "branch,omega2,omega2_im,omega,growth\n");
  for (size_t di = 0; di < ndil; di++) {
    const mfs_disp_plan *pl = plans[di];
    if (o.classify) {
      mfs_sampling smp = {.theta = thr, .ntheta = nth, .kappa = o.kappa.n ? o.kappa.v : NULL,
                          .nkappa = o.kappa.n, .npoints = (int)o.points};
      mfs_status st = mfs_classify(pl, &smp, sig, nsig, cls);
      if (st != MFS_OK)
        cli_die(1, "classification at D = %g: %s (singular mass symbol?)", dil[di],
                mfs_strerror(st));
      for (size_t si = 0; si < nsig; si++) {
        const mfs_class *c = cls + si;
        char label[96];
        config(f, &disc, latn, dil[di]);
        double v1[] = {c->sbar, c->min_omega2, c->kappa_at_min, th[c->theta_at_min]};
        for (int v = 0; v < 4; v++) {
          put(f, v1[v]);
          fputc(',', f);
        }
        fprintf(f, "%d,", c->unstable);
        double v2[] = {c->unstable_kappa_from, c->unstable_kappa_to, c->max_growth,
                       c->kappa_at_max_growth,
                       c->theta_at_max_growth >= 0 ? th[c->theta_at_max_growth] : NAN};
        for (int v = 0; v < 5; v++) {
          put(f, v2[v]);
          fputc(',', f);
        }
        fprintf(f, "%d,", c->spurious_zeros);
        double v3[] = {c->zero_kappa, c->zero_theta >= 0 ? th[c->zero_theta] : NAN,
                       c->onset_tension, c->onset_compression};
        for (int v = 0; v < 4; v++) {
          put(f, v3[v]);
          fputc(',', f);
        }
        fprintf(f, "%s\n", mfs_class_label(c->labels, label, sizeof label));
      }
      continue;
    }
    for (size_t si = 0; si < nsig; si++)
      for (size_t t = 0; t < nth; t++) {
        double km = mfs_disp_kappa_max(pl, thr[t]);
        for (int i = 0; i < nk; i++) {
          kap[i] = o.kappa.n ? o.kappa.v[i] : km * i / (nk - 1);
          mfs_status st = mfs_disp_omega2(pl, sig[si], kap[i], thr[t], w + (size_t)i * nb);
          if (st != MFS_OK)
            cli_die(1, "omega^2 at kappa %g, sigma %g: %s (singular mass symbol?)", kap[i], sig[si],
                    mfs_strerror(st));
        }
        for (int i = 0; i < nk; i++)
          for (int b = 0; b < nb; b++) {
            double complex w2 = w[(size_t)i * nb + b], wr = csqrt(w2);
            config(f, &disc, latn, dil[di]);
            put(f, sig[si]);
            fputc(',', f);
            put(f, th[t]);
            fputc(',', f);
            put(f, kap[i]);
            fprintf(f, ",%d,", b);
            put(f, creal(w2));
            fputc(',', f);
            put(f, cimag(w2));
            fputc(',', f);
            put(f, fabs(creal(wr)));
            fputc(',', f);
            put(f, fabs(cimag(wr)));
            fputc('\n', f);
          }
      }
  }
  cli_out_commit(&out);
  for (size_t i = 0; i < ndil; i++)
    mfs_disp_plan_free(plans[i]);
  free(plans);
  free(kap);
  free(w);
  free(cls);
  free(thr);
  free(d.dilation.v);
  free(o.stress.v);
  free(o.theta.v);
  free(o.kappa.v);
  return 0;
}
