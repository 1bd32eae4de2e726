/* mfstab reproduce: regenerate every artifact of the four papers that mfstab
 * computes into a directory (default notebooks-data/) and print one row per
 * artifact: the paper's value, ours, the status and the CSV behind it (also
 * written as reproduce.csv).  The data are written by the same code paths as
 * the user commands (stencil, dispersion, map, static, run: called in
 * process), and each row is computed from the CSV that was written, read
 * back (tools/repro.h).  Paper 003 here; the scenes in repro_scenes.c, paper
 * 004 in repro_static.c. */
#include <complex.h>
#undef I
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "eigs_figures.h"
#include "repro.h"

static const char usage[] = "mfstab reproduce [--out DIR]";
static const char about[] =
  "Regenerate every artifact of the four papers that mfstab computes (paper 003: Belytschko,\n"
  "Guo, Liu, Xiao 2000; 000: Rabczuk, Belytschko, Xiao 2004; 001: Herreros, Mabssout 2011;\n"
  "004: Belytschko, Krongauz, Dolbow, Gerlach 1998) as CSV in DIR (default notebooks-data) and\n"
  "print one row per artifact: artifact (the paper first), the paper's value, mfstab's, the\n"
  "status and the CSV file behind the row; the same table goes to DIR/reproduce.csv.\n"
  "status: match (agrees with the print), errata En (two independent paths of mfstab agree\n"
  "with each other and not with the print: docs/errata.md, entry En), data (the data are\n"
  "written and the property the paper states is checked), not built (mfstab does not compute\n"
  "it), differs (a failure: exit code 1).\n";

static int failures = 0;
static cli_out table_out;
static FILE *row_txt; /* the printed table: stdout, or the second part's temporary file */

void repro_row(const char *artifact, const char *paper, double ours, const char *status,
               const char *csv)
{
  char v[32] = "-";
  if (isfinite(ours))
    snprintf(v, sizeof v, "%.6g", ours);
  fprintf(row_txt ? row_txt : stdout, "%-54s  %-16s  %-14s  %-12s  %s\n", artifact, paper, v,
          status, *csv ? csv : "-");
  FILE *f = table_out.f;
  cli_put_text(f, artifact);
  fputc(',', f);
  cli_put_text(f, paper);
  fputc(',', f);
  if (isfinite(ours)) {
    char b[40];
    cli_fmt(b, sizeof b, ours);
    fputs(b, f);
  }
  fputc(',', f);
  cli_put_text(f, status);
  fputc(',', f);
  cli_put_text(f, csv);
  fputc('\n', f);
  if (strcmp(status, "differs") == 0)
    failures++;
}

/* Run a subcommand in process with a NULL-terminated argument list, its
 * output into DIR/file. */
static void sub_named(const char *name, int (*cmd)(int, char **), const char *file, ...)
{
  char *argv[64];
  int argc = 0;
  argv[argc++] = "reproduce";
  va_list ap;
  va_start(ap, file);
  for (const char *a; (a = va_arg(ap, const char *)) != NULL && argc < 60;)
    argv[argc++] = (char *)a;
  va_end(ap);
  argv[argc++] = "-o";
  argv[argc++] = (char *)repro_path(file);
  argv[argc] = NULL;
  const char *saved = cli_command; /* messages name the command that failed */
  cli_command = name;
  cmd(argc, argv);
  cli_command = saved;
}
#define sub(cmd, ...) sub_named(#cmd + 4, cmd, __VA_ARGS__)

/* ------------------------------------------------------------------ */
/* Selecting rows of a tidy CSV                                         */

/* 1 if row r of t has, for every (column, value) pair of the NULL-ended
 * list, that value (numbers compared as numbers). */
static int vmatch(const repro_csv *t, const char *file, size_t r, va_list ap)
{
  for (const char *c; (c = va_arg(ap, const char *)) != NULL;) {
    const char *want = va_arg(ap, const char *);
    const char *have = repro_text(t, r, repro_col(t, file, c));
    char *e1, *e2;
    double a = strtod(want, &e1), b = strtod(have, &e2);
    if (*want && !*e1 && *have && !*e2 ? a != b : strcmp(want, have) != 0)
      return 0;
  }
  return 1;
}

static int match(const repro_csv *t, const char *file, size_t r, ...)
{
  va_list ap;
  va_start(ap, r);
  int m = vmatch(t, file, r, ap);
  va_end(ap);
  return m;
}

/* Statistics of omega2_norm over the rows of a dispersion CSV that match
 * the (column, value) list: least and largest value, the value at the
 * largest kappa (the zone edge of the ray), the first kappa where omega2 <
 * -tol (NAN if none), and the largest kappa > 0 with |omega2| <= zero_tol
 * (NAN if none: no zero-energy mode). */
typedef struct {
  size_t n;
  double min, max, edge, kappa_edge, onset, zero;
} curve_stat;

static curve_stat curve(const repro_csv *t, const char *file, double zero_tol, ...)
{
  curve_stat s = {0, INFINITY, -INFINITY, NAN, -INFINITY, NAN, NAN};
  size_t ck = repro_col(t, file, "kappa_norm"), cw = repro_col(t, file, "omega2_norm");
  for (size_t r = 0; r < t->nrows; r++) {
    va_list ap;
    va_start(ap, zero_tol);
    int m = vmatch(t, file, r, ap);
    va_end(ap);
    if (!m)
      continue;
    double k = repro_num(t, r, ck), w = repro_num(t, r, cw);
    s.n++;
    s.min = fmin(s.min, w);
    s.max = fmax(s.max, w);
    if (k > s.kappa_edge) {
      s.kappa_edge = k;
      s.edge = w;
    }
    if (w < -1e-12 && !(s.onset <= k))
      s.onset = k;
    if (k > 1e-12 && fabs(w) <= zero_tol && !(s.zero >= k))
      s.zero = k;
  }
  if (s.n == 0)
    cli_die(1, "%s: no rows of the selected curve", repro_path(file));
  return s;
}

/* The largest |omega2_norm| of a file: the scale of its zero test. */
static double scale_of(const repro_csv *t, const char *file)
{
  size_t cw = repro_col(t, file, "omega2_norm");
  double m = 0.0;
  for (size_t r = 0; r < t->nrows; r++)
    m = fmax(m, fabs(repro_num(t, r, cw)));
  return m;
}

static const char *ok(int c) { return c ? "match" : "differs"; }

/* ------------------------------------------------------------------ */
/* Paper 003, Tables I and II                                           */

static void table1(void)
{
  for (int c = 0; c < 4; c++) {
    const char *rule = mfs_paper_table1_rules[c];
    char file[64];
    snprintf(file, sizeof file, "table1_%s.csv", rule);
    sub(cmd_stencil, file, "--dim", "2", "--kernel", "cubic", "--dilation", "2", "--shape", "mls",
        "--quadrature", rule, NULL);
    repro_csv t;
    repro_csv_read(&t, file); /* the whole CLI path is compared */
    size_t cj = repro_col(&t, file, "j"), ck = repro_col(&t, file, "k"),
           cK = repro_col(&t, file, "K_n_m");
    int printed = 0, good = 0;
    for (size_t e = 0; e < mfs_paper_table1_len; e++) {
      double want = mfs_paper_table1[e].K[c], got = 0.0;
      for (size_t i = 0; i < t.nrows; i++)
        if (repro_num(&t, i, cj) == mfs_paper_table1[e].j &&
            repro_num(&t, i, ck) == mfs_paper_table1[e].k)
          got = repro_num(&t, i, cK);
      double unit = want != 0.0 ? 2.0 * mfs_paper_table1_tol(want) : 1e-14;
      printed += want != 0.0;
      good += fabs(got - want) / unit <= 0.5;
    }
    repro_csv_free(&t);
    char a[80], p[48];
    snprintf(a, sizeof a, "003 Table I %s: %d entries + blanks", rule, printed);
    snprintf(p, sizeof p, "%zu/%zu", mfs_paper_table1_len, mfs_paper_table1_len);
    repro_row(a, p, good, ok(good == (int)mfs_paper_table1_len), file);
  }
}

/* The 1D MLS discretization of the paper's figures. */
static mfs_disc line_disc(const char *quad, const mfs_kernel_type *k, double D, mfs_frame frame)
{
  mfs_disc d = mfs_disc_default();
  d.quadrature = mfs_quad_find(quad);
  d.kernel = k;
  d.dilation = D;
  d.frame = frame;
  return d;
}

static mfs_disp_plan *line_plan(const char *quad, const mfs_kernel_type *k, double D,
                                mfs_frame frame)
{
  mfs_disp_spec s = {.disc = line_disc(quad, k, D, frame), .stretch = 1.0};
  mfs_status st;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&s, &st);
  if (!pl)
    cli_die(1, "a 1D dispersion plan: %s", mfs_strerror(st));
  return pl;
}

static double omega2_at(const mfs_disp_plan *pl, double sbar, double kappa)
{
  double complex w;
  if (mfs_disp_omega2(pl, sbar, kappa, 0.0, &w) != MFS_OK)
    cli_die(1, "a 1D dispersion sample failed");
  return creal(w);
}

/* max over kappa of omega2 at sigma = 0, and where */
static double max_omega2(const char *quad, mfs_frame frame, const mfs_kernel_type *k, double D,
                         double *where)
{
  mfs_disp_plan *pl = line_plan(quad, k, D, frame);
  double mx = -INFINITY;
  for (int i = 0; i <= 2000; i++) {
    double w = omega2_at(pl, 0.0, i / 2000.0);
    if (w > mx) {
      mx = w;
      *where = i / 2000.0;
    }
  }
  mfs_disp_plan_free(pl);
  return mx;
}

static void table2(void)
{
  cli_out o;
  cli_out_open(&o, repro_path("table2.csv"));
  fprintf(o.f, "scheme,paper_max_omega2_norm,max_omega2_norm,kappa_at_max_norm\n");
  struct {
    const char *name, *quad;
    mfs_frame frame;
    double paper;
    const char *entry;
  } t[3] = {{"nodal integration, both kernels", "nodal", MFS_FRAME_EULERIAN, 1.0, NULL},
            {"stress points, Eulerian kernel", "stress", MFS_FRAME_EULERIAN, 4.0, "E1"},
            {"stress points, Lagrangian kernel", "stress", MFS_FRAME_LAGRANGIAN, 2.0, NULL}};
  double v[3];
  for (int i = 0; i < 3; i++) {
    double where = 0.0;
    v[i] = max_omega2(t[i].quad, t[i].frame, &mfs_kernel_quartic, 1.5, &where);
    cli_put_text(o.f, t[i].name);
    fprintf(o.f, ",%g,%.16g,%g\n", t[i].paper, v[i], where);
  }
  cli_out_commit(&o);
  for (int i = 0; i < 3; i++) {
    char a[80], p[16];
    snprintf(a, sizeof a, "003 Table II %s", t[i].name);
    snprintf(p, sizeof p, "%.1f", t[i].paper);
    int same = fabs(v[i] - t[i].paper) < 0.05;
    /* E1: the Eulerian stress-point scheme at sigma = 0 is the Lagrangian one */
    const char *st = t[i].entry ? repro_errata(!same && fabs(v[i] - v[2]) < 1e-12, t[i].entry)
                                : ok(same);
    repro_row(a, p, v[i], st, "table2.csv");
  }
}

/* ------------------------------------------------------------------ */
/* Paper 003, 1D dispersion: Figs 3, 4, 9, 10, 11                       */

/* The onset of the tensile instability of Fig. 3 (quartic MLS, nodal,
 * Eulerian, D = 1.5): the least kappa with omega2 < 0, by bisection between
 * the samples of a 1000-point scan, for the tensions the errata quote. */
static void fig03_onset(void)
{
  static const double sb[] = {0.01, 0.05, 0.1, 0.2, 0.25, 0.5, 1.0};
  static const double dil[] = {1.5, 2.5};
  cli_out o;
  cli_out_open(&o, repro_path("fig03_onset.csv"));
  fprintf(o.f, "kernel,quadrature,frame,dilation,sigma_norm,onset_kappa_norm,cutoff_omega2_norm\n");
  for (int d = 0; d < 2; d++) {
    mfs_disp_plan *pl = line_plan("nodal", &mfs_kernel_quartic, dil[d], MFS_FRAME_EULERIAN);
    for (size_t i = 0; i < sizeof sb / sizeof sb[0]; i++) {
      double lo = NAN, hi = NAN;
      for (int k = 1; k <= 1000; k++)
        if (omega2_at(pl, sb[i], k / 1000.0) < 0.0) {
          lo = (k - 1) / 1000.0;
          hi = k / 1000.0;
          break;
        }
      for (int it = 0; it < 40 && isfinite(hi); it++) {
        double mid = 0.5 * (lo + hi);
        if (omega2_at(pl, sb[i], mid) < 0.0)
          hi = mid;
        else
          lo = mid;
      }
      fprintf(o.f, "quartic,nodal,eulerian,%g,%g,", dil[d], sb[i]);
      if (isfinite(hi))
        fprintf(o.f, "%.10g", hi);
      fprintf(o.f, ",%.16g\n", omega2_at(pl, sb[i], 1.0));
    }
    mfs_disp_plan_free(pl);
  }
  cli_out_commit(&o);
}

static void fig03(void)
{
  const char *f = "fig03.csv";
  sub(cmd_dispersion, f, "--kernel", "quartic", "--dilation", "1.5,2.5", "--frame", "eulerian",
      "--quadrature", "nodal", "--stress", "0,0.1,0.25,0.5,1", "--points", "201", NULL);
  fig03_onset();
  repro_csv t;
  repro_csv_read(&t, f);
  double z = fmax(fabs(curve(&t, f, 0, "dilation", "1.5", "sigma_norm", "0", NULL).edge),
                  fabs(curve(&t, f, 0, "dilation", "2.5", "sigma_norm", "0", NULL).edge));
  repro_row("003 Fig 3 sigma = 0: omega2 at the cut-off", "0", z, ok(z < 1e-12), f);
  static const char *const s[4] = {"0.1", "0.25", "0.5", "1"};
  int unstable = 0;
  for (int i = 0; i < 4; i++)
    unstable += curve(&t, f, 0, "dilation", "2.5", "sigma_norm", s[i], NULL).edge < -1e-12;
  repro_row("003 Fig 3 D = 2.5: tensions unstable at the cut-off", "4/4 (remains)", unstable,
            ok(unstable == 4), f);
  repro_csv_free(&t);
  const char *g = "fig03_onset.csv";
  repro_csv_read(&t, g);
  double on = NAN;
  for (size_t r = 0; r < t.nrows; r++)
    if (match(&t, g, r, "dilation", "1.5", "sigma_norm", "0.25", NULL))
      on = repro_num(&t, r, repro_col(&t, g, "onset_kappa_norm"));
  repro_csv_free(&t);
  repro_row("003 Fig 3 onset kappa dx/pi, sbar = 0.25, D = 1.5", "~0.6", on,
            fabs(on - 0.6) < 0.1 ? "data" : "differs", g);
}

static void fig04(void)
{
  const char *f = "fig04.csv";
  sub(cmd_dispersion, f, "--kernel", "quartic", "--dilation", "1.5,2.5", "--frame", "eulerian",
      "--quadrature", "nodal", "--stress", "-1", "--points", "201", NULL);
  repro_csv t;
  repro_csv_read(&t, f);
  size_t cw = repro_col(&t, f, "omega2_norm");
  int neg = 0;
  for (size_t r = 0; r < t.nrows; r++)
    neg += repro_num(&t, r, cw) < -1e-12;
  repro_csv_free(&t);
  /* E9: omega2 >= 0 at every wave number */
  repro_row("003 Fig 4 sbar = -1: unstable wave numbers of 402", "most", neg, repro_errata(neg == 0, "E9"),
            f);
}

static void fig09(void)
{
  const char *f = "fig09.csv";
  sub(cmd_dispersion, f, "--kernel", "quartic", "--dilation", "1.5,2.5", "--frame", "eulerian",
      "--quadrature", "stress", "--stress", "-0.5,0,0.5,1", "--points", "201", NULL);
  repro_csv t;
  repro_csv_read(&t, f);
  double m = fmin(curve(&t, f, 0, "dilation", "1.5", "sigma_norm", "0.5", NULL).min,
                  curve(&t, f, 0, "dilation", "1.5", "sigma_norm", "1", NULL).min);
  repro_row("003 Fig 9 D = 1.5, sbar > 0: least omega2", ">= 0 (stable)", m, ok(m >= -1e-12), f);
  double e = curve(&t, f, 0, "dilation", "2.5", "sigma_norm", "1", NULL).edge;
  repro_row("003 Fig 9 D = 2.5, sbar = 1: omega2 at the cut-off", "< 0 (unstable)", e,
            ok(e < -1e-12), f);
  repro_csv_free(&t);
}

static void fig10(void)
{
  const char *f = "fig10.csv", *g = "fig10_fem.csv";
  sub(cmd_dispersion, f, "--kernel", "cubic", "--dilation", "1.5,2,2.5,3,3.5", "--frame",
      "lagrangian", "--quadrature", "stress", "--points", "201", NULL);
  sub(cmd_dispersion, g, "--kernel", "cubic", "--dilation", "1", "--quadrature", "gauss2",
      "--points", "201", NULL);
  repro_csv t, fe;
  repro_csv_read(&t, f);
  repro_csv_read(&fe, g);
  static const char *const dil[5] = {"1.5", "2", "2.5", "3", "3.5"};
  double prev = INFINITY, least = INFINITY, above = -INFINITY;
  int falling = 1;
  size_t ck = repro_col(&t, f, "kappa_norm"), cw = repro_col(&t, f, "omega2_norm");
  size_t fk = repro_col(&fe, g, "kappa_norm"), fw = repro_col(&fe, g, "omega2_norm");
  for (int i = 0; i < 5; i++) {
    curve_stat c = curve(&t, f, 0, "dilation", dil[i], NULL);
    falling &= c.edge > 0.0 && c.edge < prev;
    prev = c.edge;
  }
  for (size_t r = 0; r < t.nrows; r++) {
    double k = repro_num(&t, r, ck), w = repro_num(&t, r, cw);
    if (k > 0.0)
      least = fmin(least, w);
    for (size_t s = 0; s < fe.nrows; s++)
      if (repro_num(&fe, s, fk) == k)
        above = fmax(above, w - repro_num(&fe, s, fw));
  }
  repro_csv_free(&t);
  repro_csv_free(&fe);
  repro_row("003 Fig 10 least omega2 at kappa > 0, D = 1.5..3.5", "> 0 (no zero mode)", least,
            ok(least > 1e-12), f);
  repro_row("003 Fig 10 cut-off omega2 falling with D", "yes", falling, falling ? "data" : "differs",
            f);
  repro_row("003 Fig 10 largest omega2 - linear FE's", "< 0 (lower)", above, ok(above <= 1e-12),
            "fig10.csv fig10_fem.csv");
}

static void fig11(void)
{
  static const char *const alphas[4] = {"0", "0.001", "0.01", "0.1"};
  double cut15[4], least25 = INFINITY;
  for (int i = 0; i < 4; i++) {
    char file[64];
    snprintf(file, sizeof file, "fig11_alpha%s.csv", alphas[i]);
    sub(cmd_dispersion, file, "--kernel", "quartic", "--dilation", "1.5,2.5", "--quadrature",
        "nodal", "--mass", "consistent", "--ls-alpha", alphas[i], "--ls-length", "1", "--points",
        "201", NULL);
    repro_csv t;
    repro_csv_read(&t, file);
    cut15[i] = curve(&t, file, 0, "dilation", "1.5", NULL).edge;
    least25 = fmin(least25, curve(&t, file, 0, "dilation", "2.5", NULL).min);
    repro_csv_free(&t);
  }
  int removed = fabs(cut15[0]) < 1e-12 && cut15[1] > 0 && cut15[2] > 0 && cut15[3] > 0;
  repro_row("003 Fig 11 D = 1.5: cut-off omega2, alpha_s = 0.01", "> 0 (mode removed)", cut15[2],
            ok(removed), "fig11_alpha0.01.csv");
  /* E5: the mass symbol stays positive, omega2 >= 0 for every alpha_s */
  repro_row("003 Fig 11 D = 2.5: least omega2 over alpha_s", "< 0 (too large)", least25,
            repro_errata(least25 >= -1e-12, "E5"), "fig11_alpha0.1.csv");
}

/* ------------------------------------------------------------------ */
/* Paper 003, 2D dispersion: Figs 13, 14, 15 (eq. 119)                  */

static void disp2d(const char *file, const char *quad, const char *lattice, const char *theta,
                   const char *mass)
{
  sub(cmd_dispersion, file, "--dim", "2", "--lattice", lattice, "--kernel", "cubic", "--dilation",
      "2", "--quadrature", quad, "--theta", theta, "--points", "201", "--mass", mass, NULL);
}

/* Directions of a file with a zero-energy mode (kappa > 0, |omega2| <= 1e-9
 * of the file's scale), as a bit set of the thetas; branch: "" any. */
static unsigned zero_dirs(const repro_csv *t, const char *file, const char *const *theta, int nt,
                          const char *branch)
{
  double tol = 1e-9 * scale_of(t, file);
  unsigned z = 0;
  for (int i = 0; i < nt; i++) {
    curve_stat c = *branch ? curve(t, file, tol, "theta_deg", theta[i], "branch", branch, NULL)
                           : curve(t, file, tol, "theta_deg", theta[i], NULL);
    if (isfinite(c.zero))
      z |= 1u << i;
  }
  return z;
}

static const char *const th4[4] = {"0", "15", "30", "45"};

/* zero_dirs of a file over the four directions th4, any branch. */
static unsigned zero_dirs_th4(const char *file)
{
  repro_csv t;
  repro_csv_read(&t, file);
  unsigned z = zero_dirs(&t, file, th4, 4, "");
  repro_csv_free(&t);
  return z;
}

static void fig13_14(void)
{
  disp2d("fig13.csv", "nodal", "square", "0,15,30,45", "lumped");
  disp2d("fig14a.csv", "gauss1", "square", "0,15,30,45", "lumped");
  disp2d("fig14b.csv", "gauss2", "square", "0,15,30,45", "lumped");
  repro_csv t;
  const char *f = "fig13.csv";
  repro_csv_read(&t, f);
  double tol = 1e-9 * scale_of(&t, f);
  curve_stat c0 = curve(&t, f, tol, "theta_deg", "0", NULL),
             c45 = curve(&t, f, tol, "theta_deg", "45", NULL);
  repro_csv_free(&t);
  repro_row("003 Fig 13 nodal: zero mode at theta = 0, kappa dx/pi", "1", c0.zero,
            ok(fabs(c0.zero - 1.0) < 1e-12), f);
  repro_row("003 Fig 13 nodal: zero mode at theta = 45, kappa dx/pi", "1.41421 (sqrt 2)", c45.zero,
            ok(fabs(c45.zero - sqrt(2.0)) < 1e-9), f);
  f = "fig14a.csv";
  unsigned z = zero_dirs_th4(f);
  repro_row("003 Fig 14a one-point cells: directions with a zero mode", "1 (45 deg)",
            __builtin_popcount(z), ok(z == 8u), f);
  f = "fig14b.csv";
  repro_csv_read(&t, f);
  z = zero_dirs(&t, f, th4, 4, "");
  double edge = INFINITY;
  for (int i = 0; i < 4; i++)
    edge = fmin(edge, curve(&t, f, 0, "theta_deg", th4[i], NULL).edge);
  repro_csv_free(&t);
  repro_row("003 Fig 14b 2x2 cells: least zone-edge omega2", "> 0 (no mode)", edge,
            ok(z == 0 && edge > 0), f);
}

/* Largest distance, over theta and kappa, from the omega2 of file a (one
 * branch) to the nearer of the branches of file b. */
static double curve_distance(const char *a, const char *b)
{
  repro_csv ta, tb;
  repro_csv_read(&ta, a);
  repro_csv_read(&tb, b);
  size_t at = repro_col(&ta, a, "theta_deg"), ak = repro_col(&ta, a, "kappa_norm"),
         aw = repro_col(&ta, a, "omega2_norm");
  size_t bt = repro_col(&tb, b, "theta_deg"), bk = repro_col(&tb, b, "kappa_norm"),
         bw = repro_col(&tb, b, "omega2_norm");
  double worst = 0.0;
  size_t s0 = 0;
  for (size_t r = 0; r < ta.nrows; r++) {
    double th = repro_num(&ta, r, at), k = repro_num(&ta, r, ak), w = repro_num(&ta, r, aw);
    double best = INFINITY;
    /* the rows of b are in the same (theta, kappa) order: search on from the last hit */
    size_t start = s0;
    for (size_t n = 0; n < tb.nrows; n++) {
      size_t s = (start + n) % tb.nrows;
      if (repro_num(&tb, s, bt) == th && repro_num(&tb, s, bk) == k) {
        best = fmin(best, fabs(repro_num(&tb, s, bw) - w));
        s0 = s;
      } else if (isfinite(best)) {
        break;
      }
    }
    if (!isfinite(best))
      cli_die(1, "%s has no row at theta %g, kappa %g of %s", repro_path(b), th, k, a);
    worst = fmax(worst, best);
  }
  repro_csv_free(&ta);
  repro_csv_free(&tb);
  return worst;
}

/* Eq. 119 for the star pattern: omega2 = sum_jk K_jk cos(kappa dx (j cos
 * theta + k sin theta)) / m with the stencil of node 0 (mfstab stencil) and
 * its mass m; largest distance to the nearer branch of a dispersion file. */
static double eq119_distance(const char *stencil, const char *disp, double *mass)
{
  repro_csv s, d;
  repro_csv_read(&s, stencil);
  repro_csv_read(&d, disp);
  size_t sj = repro_col(&s, stencil, "j"), sk = repro_col(&s, stencil, "k"),
         sK = repro_col(&s, stencil, "K_n_m"), sM = repro_col(&s, stencil, "M_kg");
  size_t dt = repro_col(&d, disp, "theta_deg"), dk = repro_col(&d, disp, "kappa_norm"),
         dw = repro_col(&d, disp, "omega2_norm");
  double m = 0.0;
  for (size_t r = 0; r < s.nrows; r++)
    if (repro_num(&s, r, sj) == 0 && repro_num(&s, r, sk) == 0)
      m = repro_num(&s, r, sM);
  *mass = m;
  double worst = 0.0, best = INFINITY, th0 = NAN, k0 = NAN, w119 = 0.0;
  for (size_t r = 0; r <= d.nrows; r++) {
    double th = r < d.nrows ? repro_num(&d, r, dt) : NAN, k = r < d.nrows ? repro_num(&d, r, dk) : NAN;
    if (!(th == th0 && k == k0)) { /* a new wave vector: close the last one */
      if (isfinite(best))
        worst = fmax(worst, best);
      if (r == d.nrows)
        break;
      th0 = th;
      k0 = k;
      best = INFINITY;
      double c = cos(th * M_PI / 180.0), sn = sin(th * M_PI / 180.0);
      w119 = 0.0;
      for (size_t e = 0; e < s.nrows; e++)
        w119 += repro_num(&s, e, sK) *
                cos(M_PI * k * (repro_num(&s, e, sj) * c + repro_num(&s, e, sk) * sn));
      w119 /= m;
    }
    best = fmin(best, fabs(repro_num(&d, r, dw) - w119));
  }
  repro_csv_free(&s);
  repro_csv_free(&d);
  return worst;
}

static void fig15(void)
{
  disp2d("fig15a.csv", "stress-quad", "square", "0,15,30,45", "lumped");
  disp2d("fig15b.csv", "stress-tri", "square", "0,15,30,45", "lumped");
  disp2d("fig15c.csv", "stress-star", "square", "0,15,30,45", "lumped");
  disp2d("fig15c_volume.csv", "stress-star", "square", "0,15,30,45", "volume");
  disp2d("fig15d.csv", "stress-hex", "hex", "0,30,60,90", "lumped");
  sub(cmd_stencil, "fig15c_stencil.csv", "--dim", "2", "--kernel", "cubic", "--dilation", "2",
      "--quadrature", "stress-star", NULL);
  sub(cmd_stencil, "fig15c_stencil_volume.csv", "--dim", "2", "--kernel", "cubic", "--dilation",
      "2", "--quadrature", "stress-star", "--mass", "volume", NULL);
  repro_csv t;
  const char *f = "fig15a.csv";
  unsigned z = zero_dirs_th4(f);
  repro_row("003 Fig 15a quadrilateral centres: zero-mode directions", "1 (45 deg)",
            __builtin_popcount(z), ok(z == 8u), f);
  f = "fig15b.csv";
  z = zero_dirs_th4(f);
  repro_row("003 Fig 15b triangle centres: zero-mode directions", "0", __builtin_popcount(z),
            ok(z == 0), f);
  /* eq. 119 (one node per cell, mass = the node volume) against the Bloch
   * symbol of the assembled unit cell: the same on the triangle centres */
  sub(cmd_stencil, "fig15b_stencil.csv", "--dim", "2", "--kernel", "cubic", "--dilation", "2",
      "--quadrature", "stress-tri", NULL);
  double m_tri, m_row, m_vol;
  double d119b = eq119_distance("fig15b_stencil.csv", "fig15b.csv", &m_tri);
  repro_row("003 eq. 119 vs Bloch symbol, Fig 15b: largest distance", "0", d119b,
            ok(d119b < 1e-12 && fabs(m_tri - 1.0) < 1e-12), "fig15b.csv fig15b_stencil.csv");
  /* the star pattern (two nodes per cell): almost (b); its two nodes carry
   * different row-sum masses (E20), and eq. 119 does not describe the pair */
  repro_csv_read(&t, "fig15c.csv");
  double sc = scale_of(&t, "fig15c.csv");
  repro_csv_free(&t);
  double dev = curve_distance("fig15b.csv", "fig15c.csv");
  repro_row("003 Fig 15c star vs 15b: largest distance / max omega2", "~0 (almost same)", dev / sc,
            dev / sc < 0.05 ? "data" : "differs", "fig15b.csv fig15c.csv");
  double mv = curve_distance("fig15c.csv", "fig15c_volume.csv");
  double d119 = eq119_distance("fig15c_stencil.csv", "fig15c.csv", &m_row);
  double d119v = eq119_distance("fig15c_stencil_volume.csv", "fig15c_volume.csv", &m_vol);
  repro_row("003 Fig 15c star: omega2 moved by --mass volume", "0 (eq. 119 mass)", mv,
            repro_errata(mv > 1e-6 && fabs(m_row - 1.0) > 1e-6 && m_vol == 1.0, "E20"),
            "fig15c.csv fig15c_volume.csv");
  repro_row("003 Fig 15c star: eq. 119 (node 0) vs Bloch branches", "(eq. 119 used)", d119v,
            repro_errata(d119v > 1e-3 && d119 > 1e-3, "E20"),
            "fig15c_volume.csv fig15c_stencil_volume.csv");
  static const char *const th_hex[4] = {"0", "30", "60", "90"};
  f = "fig15d.csv";
  repro_csv_read(&t, f);
  z = zero_dirs(&t, f, th_hex, 4, "");
  double e0 = curve(&t, f, 0, "theta_deg", "0", NULL).edge,
         e90 = curve(&t, f, 0, "theta_deg", "90", NULL).edge;
  repro_csv_free(&t);
  repro_row("003 Fig 15d hexagonal: zero-mode directions", "0", __builtin_popcount(z), ok(z == 0), f);
  repro_row("003 Fig 15d hexagonal: zone-edge omega2, theta 0 - 90", "!= 0 (differ)", e0 - e90,
            ok(fabs(e0 - e90) > 1e-6), f);
}

/* The star pattern's row-sum masses of its two nodes against D (E20): the
 * stencil gives node 0's, the other is 2 - it (the masses add up to the
 * two node volumes). */
static void star_mass(void)
{
  static const char *const dil[] = {"1.5", "1.75", "2", "2.5", "3"};
  cli_out o;
  cli_out_open(&o, repro_path("star_mass.csv"));
  fprintf(o.f, "kernel,quadrature,dilation,mass_node0_norm,mass_node1_norm\n");
  double at175 = NAN;
  for (size_t i = 0; i < sizeof dil / sizeof dil[0]; i++) {
    sub(cmd_stencil, "star_mass_stencil.csv", "--dim", "2", "--kernel", "cubic", "--dilation",
        dil[i], "--quadrature", "stress-star", NULL);
    repro_csv t;
    repro_csv_read(&t, "star_mass_stencil.csv");
    double m = NAN;
    for (size_t r = 0; r < t.nrows; r++)
      if (match(&t, "star_mass_stencil.csv", r, "j", "0", "k", "0", NULL))
        m = repro_num(&t, r, repro_col(&t, "star_mass_stencil.csv", "M_kg"));
    repro_csv_free(&t);
    fprintf(o.f, "cubic,stress-star,%s,%.16g,%.16g\n", dil[i], m, 2.0 - m);
    if (strcmp(dil[i], "1.75") == 0)
      at175 = m;
  }
  cli_out_commit(&o);
  remove(repro_path("star_mass_stencil.csv"));
  repro_row("003 eq. 119 star pattern: node mass, cubic D = 1.75", "1 (node volume)", at175,
            repro_errata(fabs(at175 - 1.0) > 1e-3, "E20"), "star_mass.csv");
}

/* ------------------------------------------------------------------ */
/* Paper 003, section 5: Figs 17-18, eqs 136, 145, 147                  */

/* Fig. 17's "approaches 1.1": the ratio of eq. 137 to lambda_max of the
 * 101-node cubic bar for D beyond Fig. 17's range (1 to 10). */
static double fig17_ratio(void)
{
  cli_out o;
  cli_out_open(&o, repro_path("fig17_ratio.csv"));
  fprintf(o.f, "kernel,shape,quadrature,mass,nodes,dilation,lambda_max_dx2_norm,paper_alpha_dx2_norm,"
               "alpha_ratio\n");
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.kernel = &mfs_kernel_cubic;
  s.disc.quadrature = &mfs_quad_gauss[1];
  s.disc.source.nx = 101;
  double first = NAN;
  for (int i = 0; i <= 18; i++) {
    s.disc.dilation = 1.0 + 0.5 * i;
    mfs_status st;
    size_t bad;
    mfs_model *m = mfs_model_alloc(&s, &st, &bad);
    if (!m)
      cli_die(1, "Fig 17, D = %g: %s", s.disc.dilation, mfs_strerror(st));
    mfs_pencil P = {m->K, m->M, m->m};
    mfs_eig_opts eo = {0, 0, 1e-13};
    mfs_eig_info info;
    double lam;
    st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
    if (st != MFS_OK || !(lam > 0.0))
      cli_die(1, "Fig 17, D = %g: ARPACK: %s", s.disc.dilation, mfs_strerror(st));
    double l = lam * m->dx * m->dx, a = MFS_PAPER_ALPHA / (s.disc.dilation * s.disc.dilation);
    mfs_model_free(m);
    fprintf(o.f, "cubic,mls,gauss2,lumped,101,%g,%.16g,%.16g,%.16g\n", s.disc.dilation, l, a, a / l);
    if (!isfinite(first) && a / l <= 1.1)
      first = s.disc.dilation;
  }
  cli_out_commit(&o);
  return first;
}

static void figure17(void)
{
  if (eigs_figure17(repro_outdir) != 0)
    cli_die(1, "%s", eigs_figure17_error());
  const char *f = "fig17_cubic.csv";
  repro_csv t;
  double l1 = NAN, low137 = INFINITY, low124 = INFINITY, r4 = NAN;
  for (int k = 0; k < 2; k++) {
    f = k ? "fig17_quartic.csv" : "fig17_cubic.csv";
    repro_csv_read(&t, f);
    size_t cn = repro_col(&t, f, "nodes"), cd = repro_col(&t, f, "dilation"),
           cl = repro_col(&t, f, "lambda_max_dx2_norm"), cb = repro_col(&t, f, "bound_dx2_norm"),
           ca = repro_col(&t, f, "paper_alpha_dx2_norm");
    for (size_t r = 0; r < t.nrows; r++) {
      double n = repro_num(&t, r, cn), D = repro_num(&t, r, cd), l = repro_num(&t, r, cl);
      low137 = fmin(low137, repro_num(&t, r, ca) / l);
      low124 = fmin(low124, repro_num(&t, r, cb) / l);
      if (k == 0 && n == 41 && D == 1.0)
        l1 = l;
      if (k == 0 && n == 101 && D == 4.0)
        r4 = repro_num(&t, r, ca) / l;
    }
    repro_csv_free(&t);
  }
  repro_row("003 Fig 17 lambda_max dx^2, D = 1 (linear FE, eq. 138)", "4", l1,
            ok(fabs(l1 - 4.0) < 1e-9), "fig17_cubic.csv");
  repro_row("003 Fig 17 least eq. 137 / lambda_max, D = 1..4", ">= 1 (bounded)", low137,
            ok(low137 >= 1.0), "fig17_cubic.csv fig17_quartic.csv");
  repro_row("003 Fig 17 least element bound (eq. 124) / lambda_max", ">= 1", low124,
            ok(low124 >= 1.0 - 1e-12), "fig17_cubic.csv fig17_quartic.csv");
  double at = fig17_ratio();
  /* E21: "approaches 1.1 as the domain of influence increases": 1.25 at the
   * figure's D = 4, 1.1 reached only near D = 8 */
  repro_row("003 Fig 17 eq. 137 / lambda_max, 101 nodes, D = 4", "~1.1", r4,
            repro_errata(r4 > 1.15 && isfinite(at) && at > 4.0, "E21"), "fig17_cubic.csv");
  repro_row("003 Fig 17 least D with eq. 137 / lambda_max <= 1.1", "(D <= 4)", at,
            repro_errata(isfinite(at) && at > 4.0, "E21"), "fig17_ratio.csv");

  /* Fig. 18 (E6): the closed forms stay above our lambda_max */
  f = "fig18_cubic.csv";
  repro_csv_read(&t, f);
  size_t cd = repro_col(&t, f, "dilation"), cl = repro_col(&t, f, "lambda_max_dx2_norm"),
         c1 = repro_col(&t, f, "paper_alpha_dx2_norm"), c2 = repro_col(&t, f, "paper_alpha2_dx2_norm");
  double low146 = INFINITY, r148 = NAN, l5 = NAN;
  for (size_t r = 0; r < t.nrows; r++) {
    double D = repro_num(&t, r, cd), l = repro_num(&t, r, cl);
    if (D > 3.5)
      low146 = fmin(low146, repro_num(&t, r, c1) / l);
    if (D == 5.0) {
      r148 = repro_num(&t, r, c2) / l;
      l5 = l;
    }
  }
  repro_csv_free(&t);
  repro_row("003 Fig 18 least eq. 146 / lambda_max, D > 3.5", "< 1 (below)", low146,
            repro_errata(low146 > 1.0, "E6"), f);
  repro_row("003 Fig 18 eq. 148 / lambda_max at D = 5", "< 1 (below)", r148, repro_errata(r148 > 1.0, "E6"),
            f);
  repro_row("003 Fig 18 lambda_max dx^2 at D = 5", "> 0.6", l5, repro_errata(l5 < 0.6, "E6"), f);
}

/* Eqs 136, 145, 147: the constants of the closed-form bounds, and the
 * interior element eigenvalue of the periodic 2D lattice that eq. 147's
 * empirical alpha_2 stands for (cubic and quartic, 2 x 2 Gauss cells). */
static void eq_constants(void)
{
  cli_out o;
  cli_out_open(&o, repro_path("eq_constants.csv"));
  fprintf(o.f, "equation,kernel,dim,dilation,printed,alpha,alpha_continuum,h2_lambdaQ_max_norm\n");
  double a1 = mfs_bound_alpha(&mfs_kernel_cubic, 1), a2 = mfs_bound_alpha(&mfs_kernel_cubic, 2);
  fprintf(o.f, "136,cubic,1,,%g,%.16g,%.16g,\n", MFS_PAPER_ALPHA, a1,
          mfs_bound_alpha_continuum(&mfs_kernel_cubic, 1));
  fprintf(o.f, "145,cubic,2,,%g,%.16g,%.16g,\n", MFS_PAPER_ALPHA1, a2,
          mfs_bound_alpha_continuum(&mfs_kernel_cubic, 2));
  double hi[2] = {-INFINITY, -INFINITY}, lo[2] = {INFINITY, INFINITY};
  const mfs_kernel_type *kk[2] = {&mfs_kernel_cubic, &mfs_kernel_quartic};
  for (int k = 0; k < 2; k++)
    for (int i = 0; i <= 7; i++) {
      mfs_model_spec s = mfs_model_spec_default();
      s.disc.dim = 2;
      s.disc.kernel = kk[k];
      s.disc.quadrature = &mfs_quad_gauss[1];
      s.disc.source.lattice = MFS_LATTICE_SQUARE;
      s.disc.source.nx = s.disc.source.ny = 20;
      s.disc.source.lx = s.disc.source.ly = 1.0;
      s.disc.source.periodic = 1;
      s.disc.dilation = 1.5 + 0.5 * i;
      mfs_bound_result br;
      size_t bad;
      mfs_status st = mfs_bound_model(&s, &br, &bad);
      if (st != MFS_OK || br.negative_phi)
        cli_die(1, "eq. 147, D = %g: %s", s.disc.dilation, mfs_strerror(st));
      double h = s.disc.dilation / 20.0, v = br.lambda * h * h;
      hi[k] = fmax(hi[k], v);
      lo[k] = fmin(lo[k], v);
      fprintf(o.f, "147,%s,2,%g,%g,%.16g,,%.16g\n", kk[k]->name, s.disc.dilation, MFS_PAPER_ALPHA2,
              mfs_bound_alpha(kk[k], 2), v);
    }
  cli_out_commit(&o);
  repro_row("003 eq. 136 alpha (cubic, 1D)", "12.42", a1, ok(fabs(a1 - 12.42) < 0.005),
            "eq_constants.csv");
  repro_row("003 eq. 145 alpha_1 (cubic, 2D)", "13.30", a2,
            repro_errata(fabs(a2 - 13.30) > 0.005 && fabs(a2 - 13.38) < 0.005, "E6"), "eq_constants.csv");
  repro_row("003 eq. 147 alpha_2: lattice h^2 max lambda^Q, cubic", "15.00", hi[0],
            repro_errata(hi[0] < 14.5 && lo[0] > 13.0, "E6"), "eq_constants.csv");
}

/* ------------------------------------------------------------------ */
/* The data behind the numbers docs/errata.md quotes (no rows of their  */
/* own; tests/test_errata.py compares the quotes with these files)      */

static void errata_data(void)
{
  /* E2: the long-wave limit omega2 / (pi kappa)^2 of eq. 74 under tension (the continuum:
   * 1 + sbar), and the growth rates of the paper's and the consistent linearization */
  sub(cmd_dispersion, "errata_e2_longwave.csv", "--kernel", "quartic", "--quadrature", "nodal",
      "--frame", "eulerian", "--dilation", "1.5,2,2.5", "--stress", "0.3", "--kappa", "0.001",
      NULL);
  sub(cmd_dispersion, "errata_e2_eulerian.csv", "--kernel", "quartic", "--quadrature", "nodal",
      "--frame", "eulerian", "--dilation", "1.5,2.5", "--stress", "0.1,0.5,1", "--points", "201",
      NULL);
  sub(cmd_dispersion, "errata_e2_consistent.csv", "--kernel", "quartic", "--quadrature", "nodal",
      "--frame", "eulerian-consistent", "--dilation", "1.5,2.5", "--stress", "0.1,0.5,1",
      "--points", "201", NULL);
  /* E4: the stretched Eulerian stress-point model's long-wave limit, 1 + sbar F */
  sub(cmd_dispersion, "errata_e4_longwave.csv", "--kernel", "cubic", "--quadrature", "stress",
      "--frame", "eulerian", "--dilation", "2", "--stress", "0.3", "--stretch", "1.2", "--kappa",
      "0.001", NULL);
  /* notes: SPH is not linearly complete (cubic, D = 1.5, Lagrangian nodal) */
  sub(cmd_dispersion, "errata_sph_longwave.csv", "--kernel", "cubic", "--shape", "sph",
      "--quadrature", "nodal", "--dilation", "1.5", "--stress", "0,0.3", "--kappa", "0.001", NULL);
  /* notes: the free bar's lambda_max against the lattice's Fourier maximum */
  sub(cmd_eigs, "errata_free_bar.csv", "--kernel", "cubic", "--dilation", "2", "--quadrature",
      "gauss2", NULL);
  /* E3: eq. 93 as derived (paths a and b) and as printed; quartic, D = 2.5, F = 1.15 */
  static const double kap[3] = {0.25, 0.5, 0.75};
  double pb[3], pp[3];
  mfs_cf_spec cs = {.disc = line_disc("stress", &mfs_kernel_quartic, 2.5, MFS_FRAME_EULERIAN),
                    .sbar = 0.3517, .stretch = 1.15};
  mfs_status st;
  mfs_cf_plan *cp = mfs_cf_plan_alloc(&cs, &st);
  if (!cp || mfs_cf_omega2(cp, MFS_CF_EULER_STRESS, 3, kap, pb) != MFS_OK ||
      mfs_cf_omega2(cp, MFS_CF_EULER_STRESS_PRINTED, 3, kap, pp) != MFS_OK)
    cli_die(1, "the closed forms of eq. 93 failed");
  mfs_cf_plan_free(cp);
  mfs_disp_spec ds = {.disc = cs.disc, .stretch = 1.15};
  mfs_disp_plan *dp = mfs_disp_plan_alloc(&ds, &st);
  if (!dp)
    cli_die(1, "eq. 93: %s", mfs_strerror(st));
  cli_out o;
  cli_out_open(&o, repro_path("errata_e3.csv"));
  fputs("kernel,dilation,stretch,sigma_norm,kappa_norm,omega2_bloch_norm,omega2_derived_norm,"
        "omega2_printed_norm\n",
        o.f);
  for (int i = 0; i < 3; i++)
    fprintf(o.f, "quartic,2.5,1.15,0.3517,%g,%.16g,%.16g,%.16g\n", kap[i],
            omega2_at(dp, 0.3517, kap[i]), pb[i], pp[i]);
  mfs_disp_plan_free(dp);
  cli_out_commit(&o);
}

/* ------------------------------------------------------------------ */
/* Paper 000, Fig. 1                                                    */

/* Counts of a map CSV for one frame: grid points, PDE-stable ones, stable
 * ones within and outside the PDE domain. */
static void map_counts(const char *file, const char *frame, int *n, int *pde, int *in, int *out)
{
  repro_csv t;
  repro_csv_read(&t, file);
  size_t cf = repro_col(&t, file, "frame"), cp = repro_col(&t, file, "pde_stable"),
         cs = repro_col(&t, file, "stable");
  *n = *pde = *in = *out = 0;
  for (size_t r = 0; r < t.nrows; r++) {
    if (strcmp(repro_text(&t, r, cf), frame) != 0)
      continue;
    int p = strcmp(repro_text(&t, r, cp), "1") == 0, st = strcmp(repro_text(&t, r, cs), "1") == 0;
    (*n)++;
    *pde += p;
    *in += p && st;
    *out += !p && st;
  }
  repro_csv_free(&t);
}

/* Paper 000 Fig. 1: stable domains of the eq. 18 material in the plane of the
 * principal stretches, PDE and MLS with stress points, both kernel frames.
 * The paper gives neither the dilation nor the stress-point layout: D = 2 and
 * quadrilateral centres (the layout of its rubber ring, 540 particles and 480
 * stress points), with triangle centres as a second layout; the Eulerian
 * kernel's radius follows the particle volume.  docs/commands.md (map).
 * The rows use a 10 x 10 grid on [0.3, 2]^2, which decides them in a
 * fraction of the time; analysis/figures.sh writes the 35 x 35 maps of the
 * figures (fig01_000_*.csv) and the zoom. */
static void figure1_000(void)
{
  const char *layout[2] = {"stress-quad", "stress-tri"};
  for (int q = 0; q < 2; q++) {
    char file[64];
    snprintf(file, sizeof file, "fig01_000_%s_10x10.csv", layout[q]);
    sub(cmd_map, file, "--material", "paper000", "--stretch-range", "0.3:2.0:10", "--kernel",
        "cubic", "--shape", "mls", "--dilation", "2", "--quadrature", layout[q], "--frame",
        "lagrangian,eulerian,eulerian-consistent", NULL);
    int n, pde, in, out;
    map_counts(file, "lagrangian", &n, &pde, &in, &out);
    char a[80];
    if (q == 0)
      repro_row("000 Fig 1 PDE-stable states of 10 x 10", "-", pde, pde > 0 ? "data" : "differs",
                file);
    snprintf(a, sizeof a, "000 Fig 1 Lagrangian / PDE domain, %s", layout[q]);
    double cov = pde ? (double)in / pde : 0.0;
    repro_row(a, "~1", cov, ok(cov >= 0.95 && out == 0), file);
    const char *fr[2] = {"eulerian", "eulerian-consistent"};
    for (int e = 0; e < 2; e++) {
      map_counts(file, fr[e], &n, &pde, &in, &out);
      snprintf(a, sizeof a, "000 Fig 1 %s / PDE domain, %s", e ? "consistent" : "Eulerian eq. 71",
               layout[q]);
      double fe = pde ? (double)in / pde : 0.0;
      repro_row(a, "smaller", fe, fe < 0.5 ? "data" : "differs", file);
    }
  }
}

/* ------------------------------------------------------------------ */
/* What the papers show and mfstab does not compute                     */

static void not_built(void)
{
  static const char *const what[] = {
    "003 Figs 19-20 Taylor bar impact",
    "003 Figs 21-27 fluid-structure impact",
    "000 Figs 5-7 cantilever beam convergence",
    "000 Figs 12-13, Tables 4-6 notched concrete beam",
    "000 Figs 14-16 plate under compression",
    "000 Figs 17-19 steel and rubber rings",
    "000 Fig 20 funnel flow",
    "001 Figs 7, 9 Taylor-Galerkin FEM comparison",
    "001 Figs 11-13 TSPH cantilever beam",
    "001 Figs 14-16 2D specimen",
  };
  for (size_t i = 0; i < sizeof what / sizeof what[0]; i++)
    repro_row(what[i], "-", NAN, "not built", "");
}

typedef struct {
  const char *out;
} repro_opts;

static const cli_opt opts[] = {
  {.name = "--out", .type = CLI_TEXT, .arg = "DIR",
   .help = "directory of the CSV files (default notebooks-data)", .offset = offsetof(repro_opts, out)},
  {.type = CLI_END}};

/* The rows of paper 000 Fig. 1 and paper 004 Table III (about half of the
 * CPU time) are computed by a child process on the second core while this
 * one does paper 003 and the scenes: the same code writing the same files;
 * the child's rows go to two temporary files (printed table, CSV rows) that
 * are copied in their place, so the table is the one a single process
 * prints.  The fork comes before any OpenMP region (libgomp's threads do not
 * survive a fork).  The child's messages go to a third temporary file and
 * are printed only if this process has not failed first (one line); if this
 * process dies, the child is ended with it. */
static pid_t part2 = -1;

static void part2_kill(void *arg)
{
  (void)arg;
  if (part2 > 0)
    kill(part2, SIGTERM);
}

static void part2_rows(void)
{
  figure1_000();
  repro_static_rows();
}

static void copy_rows(FILE *from, FILE *to)
{
  char b[4096];
  size_t n;
  rewind(from);
  while ((n = fread(b, 1, sizeof b, from)) > 0)
    fwrite(b, 1, n, to);
}

int cmd_reproduce(int argc, char **argv)
{
  repro_opts o = {.out = "notebooks-data"};
  unsigned char seen[2];
  cli_group g = {opts, &o, seen};
  cli_parse(argc, argv, usage, about, &g, 1);
  repro_outdir = o.out;
  struct stat sb;
  if (mkdir(repro_outdir, 0777) != 0 && errno != EEXIST)
    cli_die(2, "--out %s: cannot create the directory (%s)", repro_outdir, strerror(errno));
  if (stat(repro_outdir, &sb) != 0 || !S_ISDIR(sb.st_mode))
    cli_die(2, "--out %s: not a directory; expected a directory for the CSV files", repro_outdir);
  FILE *txt2 = tmpfile(), *csv2 = tmpfile(), *err2 = tmpfile();
  if (!txt2 || !csv2 || !err2)
    cli_die(1, "cannot create a temporary file: %s", strerror(errno));
  fflush(stdout);
  fflush(stderr);
  part2 = fork();
  if (part2 == 0) { /* the child: its rows into the temporary files */
    row_txt = txt2;
    table_out.f = csv2;
    if (dup2(fileno(err2), STDERR_FILENO) < 0)
      _exit(1);
    part2_rows();
    int bad = fflush(txt2) != 0 || fflush(csv2) != 0;
    _exit(bad ? 1 : failures ? 10 + (failures < 100 ? failures : 100) : 0); /* 10 + count */
  }
  cli_on_die(part2_kill, NULL);
  cli_out_open(&table_out, repro_path("reproduce.csv"));
  fputs("artifact,paper,mfstab,status,csv\n", table_out.f);
  printf("%-54s  %-16s  %-14s  %-12s  %s\n", "artifact", "paper", "mfstab", "status", "csv");
  table1();
  table2();
  fig03();
  fig04();
  fig09();
  fig10();
  fig11();
  fig13_14();
  fig15();
  star_mass();
  figure17();
  eq_constants();
  errata_data();
  repro_scene_rows();
  if (part2 < 0) /* no second process: the same rows here */
    part2_rows();
  else {
    int ws;
    while (waitpid(part2, &ws, 0) < 0 && errno == EINTR)
      ;
    part2 = -1;
    int code = WIFEXITED(ws) ? WEXITSTATUS(ws) : 1;
    if (code != 0 && code < 10) { /* the child's one line */
      cli_out_abort(&table_out);
      fflush(stderr);
      copy_rows(err2, stderr);
      exit(code);
    }
    if (!WIFEXITED(ws))
      cli_die(1, "the second part (paper 000 Fig. 1, paper 004 Table III) ended abnormally");
    fflush(stdout);
    copy_rows(txt2, stdout);
    copy_rows(csv2, table_out.f);
    failures += code >= 10 ? code - 10 : 0;
  }
  fclose(txt2);
  fclose(csv2);
  fclose(err2);
  not_built();
  cli_out_commit(&table_out);
  if (failures)
    cli_die(1, "%d artifact(s) differ from the paper without an errata entry", failures);
  return 0;
}
