/* mfstab dispersion: von Neumann dispersion curves omega(kappa) of a particle
 * discretization on an infinite uniform lattice (paper 003 sections 4.1-4.4),
 * from the Bloch symbols of the assembled unit-cell operators, and with
 * --classify a per-configuration stability classification. */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

static const char help[] =
  "usage: mfstab dispersion [options] [-o FILE]\n"
  "Dispersion omega(kappa) of plane waves on an infinite uniform lattice under a uniform\n"
  "initial stress, from the Fourier symbols of the assembled linearized operators\n"
  "(paper 003 eqs 64-119).  Normalized: kappa = kappa*dx/pi, omega2 = (omega*dx/c)^2 with\n"
  "c^2 = C/rho (C the tangent modulus; plane strain: the shear modulus), sigma = sigma/C.\n"
  "CSV columns: dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,theta,kappa,\n"
  "  branch,omega2,omega2_im,omega,growth   (omega = Re sqrt(omega2), growth = |Im sqrt(omega2)|)\n"
  "With --classify, one row per (dilation, sigma): min_omega2 over the sampled Brillouin zone\n"
  "and where, unstable kappa range and largest growth, spurious zero-energy modes, the onset\n"
  "stresses, and the labels material / tensile / rank-deficiency (or stable).\n"
  "options:\n"
  "%s"
  "  --frame eulerian|eulerian-consistent|lagrangian   kernel frame (default lagrangian):\n"
  "                          eulerian linearizes the kernel motion as the paper does (eq. 71);\n"
  "                          eulerian-consistent exactly, for shape functions re-solved in\n"
  "                          current coordinates (1D; mls, shepard, sph)\n"
  "  --physics antiplane|plane-strain   2D problem (default antiplane); --poisson NU (0.25)\n"
  "  --dilation LIST         comma-separated dilations\n"
  "  --stress LIST           comma-separated normalized stresses sigma/C (default 0)\n"
  "  --stretch F             pre-stretch of the 1D Eulerian analysis (default 1)\n"
  "  --ls-alpha A --ls-length L   least-squares stabilization beta = A (L dx)^2 (eq. 104)\n"
  "  --theta LIST            propagation angles in degrees (2D only; default 0)\n"
  "  --points N              kappa uniform on [0, kappa_max(theta)] (default 101)\n"
  "  --kappa LIST            exact kappa values (kappa*dx/pi) instead of --points\n"
  "  --classify              write the classification instead of the curves\n"
  "  -o FILE                 output file (default: standard output)\n";

typedef struct {
  double complex *w; /* nk * nb values of omega^2 */
  double *kap;
  int nk, nb;
} sweep;

static const char *frame_name(mfs_frame f)
{
  return f == MFS_FRAME_EULERIAN ? "eulerian"
         : f == MFS_FRAME_EULERIAN_CONSISTENT ? "eulerian-consistent"
                                               : "lagrangian";
}

/* omega^2 along one ray; dies on a numerical failure. */
static void run_sweep(const mfs_disp_plan *pl, double sbar, double theta, const double *kap,
                      int nk, sweep *s)
{
  s->nb = mfs_disp_branches(pl);
  s->nk = nk;
  for (int i = 0; i < nk; i++) {
    int st = mfs_disp_omega2(pl, sbar, kap[i], theta, s->w + (size_t)i * s->nb);
    if (st != MFS_OK)
      cli_die(1, "omega^2 at kappa %g, sigma %g: %s (singular mass symbol?)", kap[i], sbar,
              mfs_strerror(st));
  }
}

/* Smallest real part of omega^2 over the sampled kappa of all rays. */
static double min_omega2(const mfs_disp_plan *pl, double sbar, const double *theta, int nth,
                         int npts, double complex *buf)
{
  double m = INFINITY;
  int nb = mfs_disp_branches(pl);
  for (int t = 0; t < nth; t++) {
    double km = mfs_disp_kappa_max(pl, theta[t]);
    for (int i = 1; i <= npts; i++) {
      double kap = km * i / npts;
      if (mfs_disp_omega2(pl, sbar, kap, theta[t], buf) != MFS_OK)
        continue;
      for (int b = 0; b < nb; b++)
        m = creal(buf[b]) < m ? creal(buf[b]) : m;
    }
  }
  return m;
}

/* Smallest |sbar| in the direction sign (+1 tension, -1 compression) at
 * which some omega^2 < -tol; NAN if none up to the limit. */
static double onset(const mfs_disp_plan *pl, int sign, const double *theta, int nth, int npts,
                    double tol, double complex *buf)
{
  double lo = 0.0, hi = sign > 0 ? 10.0 : 1.0 + 1e-9;
  if (min_omega2(pl, sign * hi, theta, nth, npts, buf) >= -tol)
    return NAN;
  if (min_omega2(pl, 0.0, theta, nth, npts, buf) < -tol)
    return 0.0;
  for (int it = 0; it < 50; it++) {
    double mid = 0.5 * (lo + hi);
    if (min_omega2(pl, sign * mid, theta, nth, npts, buf) < -tol)
      hi = mid;
    else
      lo = mid;
  }
  return sign * hi;
}

static void put_num(FILE *f, double v)
{
  char b[40];
  if (isnan(v)) {
    fputs("", f);
    return;
  }
  cli_fmt(b, sizeof b, v);
  fputs(b, f);
}

int cmd_dispersion(int argc, char **argv)
{
  char helptext[8192];
  snprintf(helptext, sizeof helptext, help, cli_disc_help);
  cli_disc d;
  cli_disc_defaults(&d);
  const char *outpath = NULL, *opt, *val;
  double *dil = NULL, *sig = NULL, *th = NULL, *kapl = NULL;
  size_t ndil = 0, nsig = 0, nth = 0, nkap = 0;
  long npts = 101;
  int seen_points = 0, classify = 0, seen_alpha = 0, seen_len = 0;
  double stretch = 1.0, ls_alpha = 0.0, ls_len = 1.0, poisson = 0.25;
  mfs_frame frame = MFS_FRAME_LAGRANGIAN;
  mfs_physics_kind phys = MFS_PHYS_SCALAR;
  static const char *const flags[] = {"--classify", NULL};
  opt_iter it;
  opt_init(&it, argc, argv, helptext, flags);
  while (opt_next(&it, &opt, &val)) {
    if (!opt)
      opt_unknown(opt);
    if (strcmp(opt, "--dilation") == 0) {
      free(dil);
      ndil = cli_double_list(opt, val, &dil);
      for (size_t i = 0; i < ndil; i++)
        if (!(dil[i] > 0.0))
          cli_die(2, "--dilation %s: every dilation must be > 0", val);
    } else if (cli_disc_option(&d, opt, val)) {
      continue;
    } else if (strcmp(opt, "--frame") == 0) {
      if (strcmp(val, "eulerian") == 0)
        frame = MFS_FRAME_EULERIAN;
      else if (strcmp(val, "lagrangian") == 0)
        frame = MFS_FRAME_LAGRANGIAN;
      else if (strcmp(val, "eulerian-consistent") == 0)
        frame = MFS_FRAME_EULERIAN_CONSISTENT;
      else
        cli_die(2, "--frame '%s': allowed: eulerian, eulerian-consistent, lagrangian", val);
    } else if (strcmp(opt, "--physics") == 0) {
      if (strcmp(val, "antiplane") == 0)
        phys = MFS_PHYS_SCALAR;
      else if (strcmp(val, "plane-strain") == 0)
        phys = MFS_PHYS_PLANE_STRAIN;
      else
        cli_die(2, "--physics '%s': allowed: antiplane, plane-strain", val);
    } else if (strcmp(opt, "--poisson") == 0) {
      poisson = cli_double(opt, val);
      if (!(poisson > -1.0 && poisson < 0.5))
        cli_die(2, "--poisson %s: must be in (-1, 0.5)", val);
    } else if (strcmp(opt, "--stress") == 0) {
      free(sig);
      nsig = cli_double_list(opt, val, &sig);
    } else if (strcmp(opt, "--stretch") == 0) {
      stretch = cli_double(opt, val);
      if (!(stretch > 0.0))
        cli_die(2, "--stretch %s: must be > 0", val);
    } else if (strcmp(opt, "--ls-alpha") == 0) {
      ls_alpha = cli_double(opt, val);
      seen_alpha = 1;
      if (ls_alpha < 0.0)
        cli_die(2, "--ls-alpha %s: must be >= 0", val);
    } else if (strcmp(opt, "--ls-length") == 0) {
      ls_len = cli_double(opt, val);
      seen_len = 1;
      if (!(ls_len > 0.0))
        cli_die(2, "--ls-length %s: must be > 0", val);
    } else if (strcmp(opt, "--theta") == 0) {
      free(th);
      nth = cli_double_list(opt, val, &th);
    } else if (strcmp(opt, "--points") == 0) {
      npts = cli_long(opt, val, 2, 10000000);
      seen_points = 1;
    } else if (strcmp(opt, "--kappa") == 0) {
      free(kapl);
      nkap = cli_double_list(opt, val, &kapl);
      for (size_t i = 0; i < nkap; i++)
        if (kapl[i] < 0.0)
          cli_die(2, "--kappa %s: wave numbers must be >= 0", val);
    } else if (strcmp(opt, "--classify") == 0) {
      classify = 1;
    } else if (strcmp(opt, "-o") == 0) {
      outpath = val;
    } else {
      opt_unknown(opt);
    }
  }
  if (seen_len && !seen_alpha)
    cli_die(2, "--ls-length given without --ls-alpha; give both for least-squares stabilization");
  if (th && d.dim == 1)
    cli_die(2, "--theta: propagation angles need --dim 2");
  if (seen_points && kapl)
    cli_die(2, "--points and --kappa: give one of them");
  if (phys == MFS_PHYS_PLANE_STRAIN && d.dim != 2)
    cli_die(2, "--physics plane-strain needs --dim 2");
  if (stretch != 1.0 && d.dim != 1)
    cli_die(2, "--stretch %g: a pre-stretch is analysed in 1D only", stretch);
  mfs_lattice_kind lattice;
  mfs_quad_rule rule;
  cli_disc_finish(&d, &lattice, &rule);
  if (!dil) {
    ndil = 1;
    dil = malloc(sizeof *dil);
    dil[0] = d.dilation;
  }
  if (!sig) {
    nsig = 1;
    sig = calloc(1, sizeof *sig);
  }
  if (!th) {
    nth = 1;
    th = calloc(1, sizeof *th);
  }
  for (size_t i = 0; i < nsig; i++)
    if (phys == MFS_PHYS_PLANE_STRAIN && sig[i] != 0.0)
      cli_die(2, "--stress %g: plane strain is analysed at zero initial stress only", sig[i]);
  double *thr = malloc(nth * sizeof *thr);
  for (size_t t = 0; t < nth; t++)
    thr[t] = th[t] * M_PI / 180.0;

  mfs_disp_plan **plans = calloc(ndil, sizeof *plans);
  for (size_t i = 0; i < ndil; i++) {
    d.dilation = dil[i];
    mfs_disp_spec s = {d.dim,        lattice,  d.gamma, d.quadrature, d.kernel, d.shape,
                       dil[i],       frame,    phys,    poisson,      stretch,  d.consistent_mass,
                       ls_alpha * ls_len * ls_len};
    int st;
    plans[i] = mfs_disp_plan_alloc(&s, &st);
    if (!plans[i]) {
      if (st == MFS_ENOTSUP)
        cli_die(2, "--frame %s: this combination (dimension, shape, stretch, physics) is not covered by "
                   "the analysis; see mfstab dispersion --help",
                frame_name(frame));
      cli_die_status(st, &d, "at a quadrature point of the lattice");
    }
  }

  int nk = kapl ? (int)nkap : (int)npts;
  sweep sw;
  sw.kap = malloc((size_t)nk * sizeof *sw.kap);
  sw.w = malloc((size_t)nk * 4 * sizeof *sw.w);
  double complex buf[4];
  cli_out o;
  cli_out_open(&o, outpath);
  const char *latn = lattice == MFS_LATTICE_LINE ? "line" : lattice == MFS_LATTICE_HEX ? "hex" : "square";
  const char *massn = d.consistent_mass ? "consistent" : "lumped";
  if (classify)
    fprintf(o.f, "dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,min_omega2,"
                 "kappa_at_min,theta_at_min,unstable,unstable_kappa_from,unstable_kappa_to,"
                 "max_growth,kappa_at_max_growth,theta_at_max_growth,spurious_zeros,"
                 "zero_kappa,zero_theta,onset_sigma_tension,onset_sigma_compression,label\n");
  else
    fprintf(o.f, "dim,lattice,kernel,shape,quadrature,frame,mass,dilation,sigma,theta,kappa,"
                 "branch,omega2,omega2_im,omega,growth\n");
  for (size_t di = 0; di < ndil; di++) {
    const mfs_disp_plan *pl = plans[di];
    double scale = 0.0; /* largest |omega^2| at sigma = 0, for relative zero tests */
    double onset_t = NAN, onset_c = NAN;
    int zeros0 = 0;
    if (classify) {
      for (size_t t = 0; t < nth; t++) {
        double km = mfs_disp_kappa_max(pl, thr[t]);
        for (int i = 0; i <= 200; i++) {
          if (mfs_disp_omega2(pl, 0.0, km * i / 200, thr[t], buf) != MFS_OK)
            continue;
          for (int b = 0; b < mfs_disp_branches(pl); b++)
            scale = cabs(buf[b]) > scale ? cabs(buf[b]) : scale;
        }
      }
      double tol = 1e-10 * scale;
      onset_t = onset(pl, +1, thr, (int)nth, nk, tol, buf);
      onset_c = onset(pl, -1, thr, (int)nth, nk, tol, buf);
      (void)zeros0;
    }
    for (size_t si = 0; si < nsig; si++) {
      double sb = sig[si];
      double mn = INFINITY, k_mn = 0, t_mn = 0, gmax = 0, k_g = NAN, t_g = NAN;
      double uf = NAN, ut = NAN, zk = NAN, zt = NAN;
      int nzero = 0, nzero0 = 0;
      for (size_t t = 0; t < nth; t++) {
        double km = mfs_disp_kappa_max(pl, thr[t]);
        for (int i = 0; i < nk; i++)
          sw.kap[i] = kapl ? kapl[i] : km * i / (nk - 1);
        run_sweep(pl, sb, thr[t], sw.kap, nk, &sw);
        for (int i = 0; i < nk; i++)
          for (int b = 0; b < sw.nb; b++) {
            double complex w2 = sw.w[(size_t)i * sw.nb + b], w = csqrt(w2);
            double re = creal(w2), g = fabs(cimag(w));
            if (!classify) {
              fprintf(o.f, "%d,%s,%s,%s,%s,%s,%s,", d.dim, latn, d.kernel->name, d.shape->name,
                      d.quadrature, frame_name(frame), massn);
              put_num(o.f, dil[di]);
              fputc(',', o.f);
              put_num(o.f, sb);
              fputc(',', o.f);
              put_num(o.f, th[t]);
              fputc(',', o.f);
              put_num(o.f, sw.kap[i]);
              fprintf(o.f, ",%d,", b);
              put_num(o.f, re);
              fputc(',', o.f);
              put_num(o.f, cimag(w2));
              fputc(',', o.f);
              put_num(o.f, fabs(creal(w)));
              fputc(',', o.f);
              put_num(o.f, g);
              fputc('\n', o.f);
              continue;
            }
            if (re < mn) {
              mn = re;
              k_mn = sw.kap[i];
              t_mn = th[t];
            }
            double tol = 1e-10 * scale;
            if (re < -tol || g > sqrt(tol)) {
              uf = isnan(uf) || sw.kap[i] < uf ? sw.kap[i] : uf;
              ut = isnan(ut) || sw.kap[i] > ut ? sw.kap[i] : ut;
              if (g > gmax) {
                gmax = g;
                k_g = sw.kap[i];
                t_g = th[t];
              }
            }
            double kv[2] = {sw.kap[i] * M_PI * cos(thr[t]), sw.kap[i] * M_PI * sin(thr[t])};
            if (d.dim == 1)
              kv[1] = 0.0;
            if (fabs(re) <= tol && !mfs_disp_is_reciprocal(pl, kv, 1e-9)) {
              nzero++;
              zk = sw.kap[i];
              zt = th[t];
            }
          }
        if (classify && sb != 0.0) { /* rank deficiency: zeros at sigma = 0 */
          run_sweep(pl, 0.0, thr[t], sw.kap, nk, &sw);
          for (int i = 0; i < nk; i++)
            for (int b = 0; b < sw.nb; b++) {
              double kv[2] = {sw.kap[i] * M_PI * cos(thr[t]), sw.kap[i] * M_PI * sin(thr[t])};
              if (d.dim == 1)
                kv[1] = 0.0;
              if (fabs(creal(sw.w[(size_t)i * sw.nb + b])) <= 1e-10 * scale &&
                  !mfs_disp_is_reciprocal(pl, kv, 1e-9))
                nzero0++;
            }
        }
      }
      if (!classify)
        continue;
      if (sb == 0.0)
        nzero0 = nzero;
      double tol = 1e-10 * scale;
      int unstable = mn < -tol || gmax > 0.0;
      double cbar = (d.dim == 1 && frame == MFS_FRAME_LAGRANGIAN) ? stretch * stretch + sb : 1.0 + sb;
      char label[96] = "";
      if (cbar <= 0.0)
        strcat(label, "material");
      if (unstable && cbar > 0.0)
        strcat(label, label[0] ? "+tensile" : "tensile");
      if (nzero0 > 0)
        strcat(label, label[0] ? "+rank-deficiency" : "rank-deficiency");
      if (!label[0])
        strcpy(label, "stable");
      fprintf(o.f, "%d,%s,%s,%s,%s,%s,%s,", d.dim, latn, d.kernel->name, d.shape->name,
              d.quadrature, frame_name(frame), massn);
      double vals[] = {dil[di], sb, mn, k_mn, t_mn};
      for (int v = 0; v < 5; v++) {
        put_num(o.f, vals[v]);
        fputc(',', o.f);
      }
      fprintf(o.f, "%d,", unstable);
      double vals2[] = {uf, ut, gmax, k_g, t_g};
      for (int v = 0; v < 5; v++) {
        put_num(o.f, vals2[v]);
        fputc(',', o.f);
      }
      fprintf(o.f, "%d,", nzero);
      double vals3[] = {zk, zt, onset_t, onset_c};
      for (int v = 0; v < 4; v++) {
        put_num(o.f, vals3[v]);
        fputc(',', o.f);
      }
      fprintf(o.f, "%s\n", label);
    }
  }
  cli_out_commit(&o);
  for (size_t i = 0; i < ndil; i++)
    mfs_disp_plan_free(plans[i]);
  free(plans);
  free(sw.kap);
  free(sw.w);
  free(dil);
  free(sig);
  free(th);
  free(thr);
  free(kapl);
  return 0;
}
