/* Benchmark of the dispersion analysis after the plan (issue 14 item 3; the
 * first version: the von Neumann dispersion issue).  Families:
 *   1d           quartic MLS, Eulerian nodal (paper 003 eq. 74), D = 1.5, 2.5,
 *                5 stresses x 1000 wave numbers on [0, 1]: 10000 points, 1 branch
 *   2d-antiplane cubic MLS, D = 2, stress-tri, square lattice, 8 angles on
 *                [0, 45] deg x 400 wave numbers on [0, kappa_max]: 3200 points, 1 branch
 *   2d-plane     the same in plane strain (nu = 0.25): 2 branches (2 x 2 closed form)
 *   2d-star      anti-plane, stress-star (two particles per cell): 2 branches (the same)
 *   2d-star-plane plane strain, stress-star: 4 branches (the library's 4 x 4 Hermitian
 *                kernel, Householder and Jacobi; the direct phase: LAPACKE zhegv)
 * Phases, each timed over --repeat runs (min, median, max of the wall time):
 *   direct        the symbols summed term by term, a sincos per lattice offset
 *                 (mfs_disp_symbols, the evaluator before issue 14) and the same
 *                 eigen solve (closed forms, zhegv)
 *   point         mfs_disp_omega2, one call per point
 *   ray           mfs_disp_ray, one call per (dilation, stress, angle)
 *   ray-stresses  mfs_disp_ray, one call per (dilation, angle) for all stresses
 *   threads-1, threads-2   the ray evaluation of a 20 x larger family in parallel
 *                 over chunks of 256 wave numbers (OpenMP, as mfstab dispersion),
 *                 with 1 and 2 threads; identical says the two gave the same bits
 * error: the largest |omega^2 - reference| over the family relative to the
 * largest |omega^2| (1d: the closed form eq. 74 of lib/analysis/mfs_closed.c;
 * 2d: the direct symbols); ratio: the direct phase's median over this one's.
 * CSV: family,phase,points,branches,threads,repeats,seconds_min,seconds_median,
 *   seconds_max,ns_per_point,ns_per_point_branch,ratio,identical,error,peak_rss_mb,load1,gflop
 * (ns_per_point from the median); gflop: the minimal work of the phase's
 * points, the folded sums once per wave vector (mfs_disp_plan_work: 2 flops
 * per offset and component, shared by the stresses; 10^9 flops), the limit
 * analysis/bench/limits.py states against dgemm's rate.  With --numpy-data DIR the coefficients of the
 * NumPy comparison (bench_dispersion_numpy.py) and this run's values go to DIR.
 * usage: bench_dispersion [--repeat R] [--family NAME] [--no-threads] [--numpy-data DIR] [-o FILE]
 * Not a test: nothing here asserts a time. */
#include <complex.h>
#undef I
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "mfstab.h"
#include "mfs_omp.h"
#include "bench_common.h"

#ifdef BENCH_DISPERSION_MODULE /* built as a module too (bench_dispersion_ns below): */
#pragma GCC diagnostic ignored "-Wunused-function" /* the CSV driver is the executable's */
#endif

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double rss_mb(void)
{
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

/* A family: plans (one per dilation), stresses, rays. */
typedef struct {
  const char *name;
  int nplan, nsig, nth, nk;
  mfs_disp_plan *pl[2];
  double sig[5], th[8], *kap; /* kap[t nk + i] */
  int nb;
} family;

static double *kappas(const family *f, int nk)
{
  double *k = malloc((size_t)f->nth * nk * sizeof *k);
  for (int t = 0; t < f->nth; t++) {
    double km = f->pl[0] ? mfs_disp_kappa_max(f->pl[0], f->th[t]) : 1.0;
    for (int i = 0; i < nk; i++)
      k[t * nk + i] = km * i / (nk - 1);
  }
  return k;
}

static mfs_disp_plan *plan(mfs_disp_spec s)
{
  mfs_status st;
  mfs_disp_plan *p = mfs_disp_plan_alloc(&s, &st);
  if (!p) {
    fprintf(stderr, "bench_dispersion: plan: %s\n", mfs_strerror(st));
    exit(1);
  }
  return p;
}

static family make(const char *name)
{
  family f = {.name = name, .nplan = 1, .nsig = 1, .nth = 8, .nk = 400};
  if (!strcmp(name, "1d")) {
    const double sig[5] = {-0.5, 0.0, 0.25, 0.5, 1.0}, dil[2] = {1.5, 2.5};
    f.nplan = 2, f.nsig = 5, f.nth = 1, f.nk = 1000;
    memcpy(f.sig, sig, sizeof sig);
    for (int d = 0; d < 2; d++) {
      mfs_disp_spec s = {.disc = mfs_disc_default(), .stretch = 1.0};
      s.disc.kernel = &mfs_kernel_quartic;
      s.disc.dilation = dil[d];
      s.disc.frame = MFS_FRAME_EULERIAN;
      f.pl[d] = plan(s);
    }
  } else {
    mfs_disc d = mfs_disc_default();
    d.dim = 2;
    d.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
    d.quadrature = strstr(name, "star") ? &mfs_quad_stress_star : &mfs_quad_stress_tri;
    if (!strcmp(name + strlen(name) - 6, "-plane"))
      d.material.physics = MFS_PHYS_PLANE_STRAIN;
    f.pl[0] = plan((mfs_disp_spec){.disc = d, .stretch = 1.0});
    for (int t = 0; t < 8; t++)
      f.th[t] = t * M_PI / 4 / 7;
  }
  f.nb = mfs_disp_branches(f.pl[0]);
  f.kap = kappas(&f, f.nk);
  return f;
}

static void unmake(family *f)
{
  for (int d = 0; d < f->nplan; d++)
    mfs_disp_plan_free(f->pl[d]);
  free(f->kap);
}

static int cmp_re(const void *a, const void *b)
{
  double x = creal(*(const double complex *)a), y = creal(*(const double complex *)b);
  return (x > y) - (x < y);
}

/* The evaluator before issue 14: the direct symbols and the eigen solve it
 * used (one branch K / M, the lumped 2 x 2 in closed form, else zhegv or zggev). */
static void direct(const mfs_disp_plan *pl, double sbar, double kap, double th, double complex *w)
{
  const int n = mfs_disp_branches(pl), herm = mfs_disp_plan_spec(pl)->disc.frame ==
                                                     MFS_FRAME_LAGRANGIAN;
  double k[2] = {kap * M_PI * cos(th), kap * M_PI * sin(th)};
  if (mfs_disp_plan_spec(pl)->disc.dim == 1)
    k[0] = kap * M_PI, k[1] = 0.0;
  double complex K[16], M[16];
  mfs_disp_symbols(pl, sbar, k, K, M);
  if (n == 1) {
    w[0] = herm ? creal(K[0]) / creal(M[0]) : K[0] / M[0];
  } else if (n == 2 && M[1] == 0.0 && M[2] == 0.0 && M[0] == M[3]) {
    double a = creal(K[0]) / creal(M[0]), d = creal(K[3]) / creal(M[0]);
    double b = cabs(K[1]) / creal(M[0]), r = hypot(0.5 * (a - d), b);
    w[0] = 0.5 * (a + d) - r;
    w[1] = 0.5 * (a + d) + r;
  } else {
    double complex work[64];
    double rwork[32], wr[4];
    LAPACKE_zhegv_work(LAPACK_COL_MAJOR, 1, 'N', 'L', n, K, n, M, n, wr, work, 64, rwork);
    for (int i = 0; i < n; i++)
      w[i] = wr[i];
    qsort(w, (size_t)n, sizeof *w, cmp_re);
  }
}

enum { CHUNK = 256 };

/* One run of a phase over the family into w[((d nsig + s) nth + t) nk + i] nb. */
static void run_phase(const family *f, const char *phase, int nk, const double *kap,
                      double complex *w)
{
  const size_t nb = (size_t)f->nb, ray = (size_t)nk * nb;
  for (int d = 0; d < f->nplan; d++) {
    const mfs_disp_plan *pl = f->pl[d];
    double complex *wd = w + (size_t)d * f->nsig * f->nth * ray;
    if (!strcmp(phase, "threads")) { /* as mfstab dispersion: chunks of every angle */
      const long nch = (nk + CHUNK - 1) / CHUNK, ntask = f->nth * nch;
      MFS_OMP("omp parallel for schedule(dynamic)")
      for (long task = 0; task < ntask; task++) {
        int t = (int)(task / nch), c0 = (int)(task % nch) * CHUNK;
        int len = nk - c0 < CHUNK ? nk - c0 : CHUNK;
        mfs_disp_ray(pl, f->sig, (size_t)f->nsig, f->th[t], kap + t * nk + c0, (size_t)len,
                     wd + (t * (size_t)nk + c0) * nb, f->nth * ray);
      }
      continue;
    }
    for (int t = 0; t < f->nth; t++) {
      const double *kt = kap + (size_t)t * nk;
      if (!strcmp(phase, "ray-stresses")) {
        mfs_disp_ray(pl, f->sig, (size_t)f->nsig, f->th[t], kt, (size_t)nk, wd + t * ray,
                     f->nth * ray);
        continue;
      }
      for (int s = 0; s < f->nsig; s++) {
        double complex *ws = wd + ((size_t)s * f->nth + t) * ray;
        if (!strcmp(phase, "ray"))
          mfs_disp_ray(pl, f->sig + s, 1, f->th[t], kt, (size_t)nk, ws, 0);
        else if (!strcmp(phase, "point"))
          for (int i = 0; i < nk; i++)
            mfs_disp_omega2(pl, f->sig[s], kt[i], f->th[t], ws + i * nb);
        else
          for (int i = 0; i < nk; i++)
            direct(pl, f->sig[s], kt[i], f->th[t], ws + i * nb);
      }
    }
  }
}

/* phi', phi'' of the interior MLS function of particle 0 at x (dx = 1), for eq. 74 */
static void mls_at(double D, double x, double *d1, double *d2)
{
  mfs_shape_ctx c = {&mfs_kernel_quartic, 1, D, 0.0};
  double d[64], out[64 * 3], work[1024], rc;
  int nn = 0, self0 = -1;
  for (int j = (int)floor(x - D) - 1; j <= (int)ceil(x + D) + 1; j++)
    if (fabs(j - x) < D) {
      if (j == 0)
        self0 = nn;
      d[nn++] = j - x;
    }
  mfs_shape_mls.eval(&c, nn, d, NULL, -1, 2, out, work, &rc);
  *d1 = self0 >= 0 ? out[self0 * 3 + 1] : 0.0;
  *d2 = self0 >= 0 ? out[self0 * 3 + 2] : 0.0;
}

/* The error against the reference: the closed form (1d), the direct symbols (2d). */
static double family_error(const family *f, const double complex *w)
{
  const size_t nb = (size_t)f->nb, ray = (size_t)f->nk * nb;
  double scale = 0.0, err = 0.0;
  for (int d = 0; d < f->nplan; d++)
    for (int s = 0; s < f->nsig; s++)
      for (int t = 0; t < f->nth; t++) {
        const double complex *ws = w + (((size_t)d * f->nsig + s) * f->nth + t) * ray;
        const double *kt = f->kap + (size_t)t * f->nk;
        double *ref = malloc(ray * sizeof *ref);
        if (!strcmp(f->name, "1d")) {
          mfs_cf_spec cs = {.disc = mfs_disp_plan_spec(f->pl[d])->disc, .sbar = f->sig[s]};
          mfs_status st;
          mfs_cf_plan *cf = mfs_cf_plan_alloc(&cs, &st);
          mfs_cf_omega2(cf, MFS_CF_EULER_NODAL, (size_t)f->nk, kt, ref);
          mfs_cf_plan_free(cf);
        } else {
          for (int i = 0; i < f->nk; i++) {
            double complex r[4];
            direct(f->pl[d], f->sig[s], kt[i], f->th[t], r);
            for (size_t b = 0; b < nb; b++)
              ref[i * nb + b] = creal(r[b]);
          }
        }
        for (size_t i = 0; i < ray; i++) {
          scale = fmax(scale, fabs(ref[i]));
          err = fmax(err, fabs(creal(ws[i]) - ref[i]));
        }
        free(ref);
      }
  return err / fmax(scale, 1e-300);
}

/* The coefficients and values the NumPy comparison reads. */
static void numpy_data(const family *f, const char *dir, const double complex *w)
{
  char path[4096];
  snprintf(path, sizeof path, "%s/%s_coef.csv", dir, f->name);
  FILE *c = fopen(path, "w");
  snprintf(path, sizeof path, "%s/%s_values.csv", dir, f->name);
  FILE *v = fopen(path, "w");
  if (!c || !v) {
    fprintf(stderr, "bench_dispersion: cannot write into %s\n", dir);
    exit(1);
  }
  if (!strcmp(f->name, "1d")) { /* eq. 74: phi'(j), phi''(j) of each dilation */
    fprintf(c, "dilation,j,dphi,d2phi\n");
    for (int d = 0; d < f->nplan; d++) {
      double D = mfs_disp_plan_spec(f->pl[d])->disc.dilation;
      int J = (int)ceil(D);
      for (int j = -J; j <= J; j++) {
        double d1, d2;
        mls_at(D, j, &d1, &d2);
        fprintf(c, "%.17g,%d,%.17g,%.17g\n", D, j, d1, d2);
      }
    }
  } else { /* eq. 118: the stencil K_jk and M_00 */
    mfs_stencil_entry *e;
    size_t ne, bad;
    mfs_stencil(&mfs_disp_plan_spec(f->pl[0])->disc, &e, &ne, &bad);
    fprintf(c, "j,k,K,M\n");
    for (size_t q = 0; q < ne; q++)
      fprintf(c, "%d,%d,%.17g,%.17g\n", e[q].j, e[q].k, e[q].K, e[q].M);
    mfs_free(e);
  }
  fprintf(v, "dilation,sigma,theta,kappa,omega2\n");
  for (int d = 0; d < f->nplan; d++)
    for (int s = 0; s < f->nsig; s++)
      for (int t = 0; t < f->nth; t++)
        for (int i = 0; i < f->nk; i++)
          fprintf(v, "%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  mfs_disp_plan_spec(f->pl[d])->disc.dilation, f->sig[s], f->th[t],
                  f->kap[t * f->nk + i],
                  creal(w[((((size_t)d * f->nsig + s) * f->nth + t) * f->nk + i) * f->nb]));
  fclose(c);
  fclose(v);
}

static void set_threads(int n)
{
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

static void bench(FILE *out, const char *name, int repeat, int threads, const char *npdir)
{
  family f = make(name);
  const size_t nval = (size_t)f.nplan * f.nsig * f.nth * f.nk * f.nb;
  const int npts = f.nplan * f.nsig * f.nth * f.nk;
  double complex *w = malloc(nval * sizeof *w);
  const char *phases[] = {"direct", "point", "ray", "ray-stresses"};
  /* the minimal work: the folded sums once per wave vector (shared by the
   * stresses), 2 flops per offset and component (mfs_disp_plan_work) */
  double gflop = 0.0;
  for (int q = 0; q < f.nplan; q++) {
    size_t no;
    int nc;
    mfs_disp_plan_work(f.pl[q], &no, &nc);
    gflop += 1e-9 * 2.0 * (double)no * nc * f.nth * f.nk;
  }
  double tdirect = NAN, *ts = malloc((size_t)repeat * sizeof *ts);
  for (int p = 0; p < 4; p++) {
    if (f.nsig == 1 && p == 3)
      continue; /* one stress: ray-stresses is ray */
    for (int r = 0; r < repeat; r++) {
      double t0 = now();
      run_phase(&f, phases[p], f.nk, f.kap, w);
      ts[r] = now() - t0;
    }
    qsort(ts, (size_t)repeat, sizeof *ts, bench_cmp_double);
    double med = ts[repeat / 2];
    if (p == 0)
      tdirect = med;
    double err = family_error(&f, w);
    fprintf(out, "%s,%s,%d,%d,1,%d,%.6g,%.6g,%.6g,%.4g,%.4g,%.4g,,%.3g,%.1f,%.2f,%.6g\n", name,
            phases[p], npts, f.nb, repeat, ts[0], med, ts[repeat - 1], 1e9 * med / npts,
            1e9 * med / npts / f.nb, tdirect / med, err, rss_mb(), bench_load1(), gflop);
    fflush(out);
  }
  if (npdir)
    numpy_data(&f, npdir, w);
  /* threads: a family 20 x larger (wave numbers), 1 and 2 threads, the same bits? */
  const int nk10 = 20 * f.nk;
  double *k10 = kappas(&f, nk10);
  const size_t n10 = (size_t)f.nplan * f.nsig * f.nth * nk10 * f.nb;
  double complex *w10[2] = {malloc(n10 * sizeof **w10), malloc(n10 * sizeof **w10)};
  double t1 = NAN;
  for (int nt = 1; nt <= 2 && threads; nt++) {
    set_threads(nt);
    for (int r = 0; r < repeat; r++) {
      double t0 = now();
      run_phase(&f, "threads", nk10, k10, w10[nt - 1]);
      ts[r] = now() - t0;
    }
    qsort(ts, (size_t)repeat, sizeof *ts, bench_cmp_double);
    double med = ts[repeat / 2];
    if (nt == 1)
      t1 = med;
    int same = nt == 1 || memcmp(w10[0], w10[1], n10 * sizeof **w10) == 0;
    fprintf(out, "%s,threads-%d,%d,%d,%d,%d,%.6g,%.6g,%.6g,%.4g,%.4g,%.4g,%s,,%.1f,%.2f,%.6g\n", name,
            nt, npts * 20, f.nb, nt, repeat, ts[0], med, ts[repeat - 1], 1e9 * med / (npts * 20.0),
            1e9 * med / (npts * 20.0) / f.nb, t1 / med, nt == 1 ? "" : same ? "1" : "0", rss_mb(),
            bench_load1(), 20.0 * gflop);
    fflush(out);
  }
  set_threads(2);
  free(w10[0]);
  free(w10[1]);
  free(k10);
  free(ts);
  free(w);
  unmake(&f);
}

#ifdef BENCH_DISPERSION_MODULE
/* For bench_dispersion_numpy.py, which loads this file built as a module
 * (ctypes) and times the C rays in its own process, right beside NumPy's
 * evaluation: the machine runs each process at one of two speed levels
 * (docs/benchmarks.md), so only one process gives both sides the same.
 * Returns the median over repeat runs of phase ("ray" or "ray-stresses") of
 * family name, in ns per point; NAN for another phase. */
double bench_dispersion_ns(const char *name, const char *phase, int repeat)
{
  if (strcmp(phase, "ray") && strcmp(phase, "ray-stresses"))
    return NAN;
  family f = make(name);
  const int npts = f.nplan * f.nsig * f.nth * f.nk;
  double complex *w = malloc((size_t)npts * f.nb * sizeof *w);
  double *ts = malloc((size_t)(repeat > 0 ? repeat : 1) * sizeof *ts);
  double med = NAN;
  if (w && ts && repeat > 0) {
    run_phase(&f, phase, f.nk, f.kap, w); /* untimed: the output's first touch, warm caches */
    for (int r = 0; r < repeat; r++) {
      double t0 = now();
      run_phase(&f, phase, f.nk, f.kap, w);
      ts[r] = now() - t0;
    }
    qsort(ts, (size_t)repeat, sizeof *ts, bench_cmp_double);
    med = 1e9 * ts[repeat / 2] / npts;
  }
  free(ts);
  free(w);
  unmake(&f);
  return med;
}
#else
int main(int argc, char **argv)
{
  int repeat = 7, threads = 1;
  const char *fam = NULL, *npdir = NULL;
  FILE *out = stdout;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--family") && i + 1 < argc)
      fam = argv[++i];
    else if (!strcmp(argv[i], "--no-threads"))
      threads = 0;
    else if (!strcmp(argv[i], "--numpy-data") && i + 1 < argc)
      npdir = argv[++i];
    else if (!strcmp(argv[i], "-o") && i + 1 < argc) {
      out = fopen(argv[++i], "w");
      if (!out) {
        perror(argv[i]);
        return 2;
      }
    } else {
      fprintf(stderr, "usage: bench_dispersion [--repeat R] [--family NAME] [--no-threads] "
                      "[--numpy-data DIR] [-o FILE]\n");
      return 2;
    }
  }
  if (repeat < 1)
    repeat = 1;
  const char *fams[] = {"1d", "2d-antiplane", "2d-plane", "2d-star", "2d-star-plane"};
  fprintf(out, "family,phase,points,branches,threads,repeats,seconds_min,seconds_median,"
               "seconds_max,ns_per_point,ns_per_point_branch,ratio,identical,error,peak_rss_mb,"
               "load1,gflop\n");
  for (int k = 0; k < 5; k++)
    if (!fam || !strcmp(fam, fams[k]))
      bench(out, fams[k], repeat, threads, npdir);
  if (out != stdout)
    fclose(out);
  return 0;
}
#endif
