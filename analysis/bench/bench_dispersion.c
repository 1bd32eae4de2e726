/* Benchmark of `mfstab dispersion` (issue: von Neumann dispersion).
 *   1D family: 5 stresses x 2 dilations x 1000 kappa, Eulerian nodal, quartic MLS
 *   2D family: 8 angles x 400 kappa, stress-tri, cubic MLS, D = 2
 * Time of the evaluation after the plan is built (best of several repeats),
 * and of the plan, against a straightforward reference measured in the same
 * run: the closed form (eq. 74) evaluated naively per point, recomputing the
 * MLS shape functions phi'(j dx), phi''(j dx) at every point (1D), and eq.
 * 118 with the stencil K_jk recomputed at every point (2D).
 * CSV on stdout: family,phase,points,seconds,seconds_per_point,ratio,error,peak_rss_mb */
#include <complex.h>
#undef I
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

#include "mfstab.h"

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

/* phi', phi'' of the interior MLS function of particle 0 at x (dx = 1) */
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

/* eq. 74 at one point, everything recomputed */
static double naive74(double D, double sbar, double kap)
{
  double S = 0.0, P = 0.0, k = kap * M_PI;
  int J = (int)ceil(D);
  for (int j = -J; j <= J; j++) {
    double d1, d2;
    mls_at(D, j, &d1, &d2);
    S += d1 * sin(k * j);
    P += d2 * (1.0 - cos(k * j));
  }
  return (1.0 + sbar) * S * S - sbar * (P - S * S);
}

int main(void)
{
  const double sig[5] = {-0.5, 0.0, 0.25, 0.5, 1.0}, dil[2] = {1.5, 2.5};
  const int nk = 1000, reps = 20;
  printf("family,phase,points,seconds,seconds_per_point,ratio,error,peak_rss_mb\n");
  /* 1D */
  double t0 = now();
  mfs_disp_plan *pl[2];
  for (int d = 0; d < 2; d++) {
    mfs_disp_spec s = {.disc = mfs_disc_default(), .stretch = 1.0};
    s.disc.kernel = &mfs_kernel_quartic;
    s.disc.dilation = dil[d];
    s.disc.frame = MFS_FRAME_EULERIAN;
    mfs_status st;
    pl[d] = mfs_disp_plan_alloc(&s, &st);
    if (!pl[d])
      return 1;
  }
  double tplan = now() - t0, best = INFINITY, sink = 0.0;
  static double out[2][5][1000];
  for (int r = 0; r < reps; r++) {
    t0 = now();
    for (int d = 0; d < 2; d++)
      for (int s = 0; s < 5; s++)
        for (int i = 0; i < nk; i++) {
          double complex w;
          mfs_disp_omega2(pl[d], sig[s], (double)i / (nk - 1), 0.0, &w);
          out[d][s][i] = creal(w);
        }
    double t = now() - t0;
    best = t < best ? t : best;
  }
  int npts = 2 * 5 * nk;
  t0 = now();
  double err = 0.0;
  for (int d = 0; d < 2; d++)
    for (int s = 0; s < 5; s++)
      for (int i = 0; i < nk; i++) {
        double v = naive74(dil[d], sig[s], (double)i / (nk - 1));
        err = fmax(err, fabs(v - out[d][s][i]));
        sink += v;
      }
  double tnaive = now() - t0;
  printf("1d,plan,%d,%.6g,,,,%.1f\n", npts, tplan, rss_mb());
  printf("1d,evaluate,%d,%.6g,%.3g,,,%.1f\n", npts, best, best / npts, rss_mb());
  printf("1d,naive_closed_form,%d,%.6g,%.3g,%.1f,%.3g,%.1f\n", npts, tnaive, tnaive / npts,
         tnaive / best, err, rss_mb());
  for (int d = 0; d < 2; d++)
    mfs_disp_plan_free(pl[d]);

  /* 2D */
  const int nth = 8, nk2 = 400;
  t0 = now();
  mfs_disc d2 = mfs_disc_default();
  d2.dim = 2;
  d2.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
  d2.quadrature = &mfs_quad_stress_tri;
  mfs_disp_spec s2 = {.disc = d2, .stretch = 1.0};
  mfs_status st;
  mfs_disp_plan *p2 = mfs_disp_plan_alloc(&s2, &st);
  if (!p2)
    return 1;
  tplan = now() - t0;
  static double o2[8][400];
  best = INFINITY;
  for (int r = 0; r < reps; r++) {
    t0 = now();
    for (int t = 0; t < nth; t++) {
      double th = t * M_PI / 4 / (nth - 1), km = mfs_disp_kappa_max(p2, th);
      for (int i = 0; i < nk2; i++) {
        double complex w;
        mfs_disp_omega2(p2, 0.0, km * i / (nk2 - 1), th, &w);
        o2[t][i] = creal(w);
      }
    }
    double t = now() - t0;
    best = t < best ? t : best;
  }
  npts = nth * nk2;
  /* reference: eq. 118/119 with the stencil recomputed per point (a sample, scaled) */
  int sample = 64;
  t0 = now();
  err = 0.0;
  for (int n = 0; n < sample; n++) {
    int t = n % nth, i = (n * 37) % nk2;
    double th = t * M_PI / 4 / (nth - 1), km = mfs_disp_kappa_max(p2, th), kap = km * i / (nk2 - 1);
    mfs_stencil_entry *e;
    size_t ne, bad;
    mfs_stencil(&d2, &e, &ne, &bad);
    double num = 0.0, m = 0.0;
    for (size_t q = 0; q < ne; q++) {
      double ph = kap * M_PI * (e[q].j * cos(th) + e[q].k * sin(th));
      num += e[q].K * cos(ph);
      m += e[q].M * cos(ph);
    }
    free(e);
    err = fmax(err, fabs(num / m - o2[t][i]));
  }
  tnaive = (now() - t0) / sample * npts;
  printf("2d,plan,%d,%.6g,,,,%.1f\n", npts, tplan, rss_mb());
  printf("2d,evaluate,%d,%.6g,%.3g,,,%.1f\n", npts, best, best / npts, rss_mb());
  printf("2d,naive_stencil_per_point,%d,%.6g,%.3g,%.1f,%.3g,%.1f\n", npts, tnaive, tnaive / npts,
         tnaive / best, err, rss_mb());
  mfs_disp_plan_free(p2);
  fprintf(stderr, "checksum %g\n", sink);
  return 0;
}
