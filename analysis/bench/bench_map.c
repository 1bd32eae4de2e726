/* Benchmark of the stretch map (`mfstab map`, issue 10): the paper 000 eq. 18
 * material on an N x N grid of principal stretches on [0.3, 2]^2, cubic MLS,
 * D = 2, stress-tri, 8 directions x 64 wave numbers per grid point (plus the
 * 64 + 2 samples along the PDE's worst direction, as the command samples),
 * for the Lagrangian and both Eulerian frames.  The same library calls as
 * tools/cmd_map.c, timed by phase:
 *   plan   Lagrangian: the plan and the lattice sums at the zone samples, once;
 *          Eulerian: the plan of every grid point (its current lattice)
 *   eval   the PDE check and the symbols' eigenvalues at every grid point
 * Not a test: nothing here asserts a time.  Single-threaded (one core).
 * CSV (stdout or -o FILE): frame,grid,points,plan_s,eval_s,total_s,
 *   s_per_point,after_plan_s_per_point,pde_stable,stable,stable_outside_pde,
 *   singular,peak_rss_mb
 * (stable_outside_pde is the check: the Lagrangian domain lies within the PDE's).
 * usage: bench_map [--repeat R] [-o FILE] [N ...]   (default N = 60) */
#include <complex.h>
#undef I
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

enum { NDIR = 8, NWAVE = 64 };

static void zone(const mfs_disp_plan *pl, double *kz)
{
  for (int t = 0; t < NDIR; t++) {
    double th = M_PI * t / NDIR, km = mfs_disp_kappa_max(pl, th) * M_PI;
    for (int i = 0; i < NWAVE; i++) {
      kz[2 * (t * NWAVE + i)] = km * (i + 1) / NWAVE * cos(th);
      kz[2 * (t * NWAVE + i) + 1] = km * (i + 1) / NWAVE * sin(th);
    }
  }
}

/* stable at state st: every sampled omega^2 with Re >= -tol and growth <= sqrt(tol) */
static int evaluate(const mfs_disp_plan *pl, const mfs_disp_sample *smp, const double *kz,
                    const mfs_plane_state *st, const mfs_ellipticity *pde, int lag)
{
  double complex w[(NDIR * NWAVE + NWAVE + 2) * 2];
  size_t nz = NDIR * NWAVE, nt = nz + NWAVE + 2;
  double n[2] = {cos(pde->theta), sin(pde->theta)};
  if (lag) {
    n[0] *= st->l[0];
    n[1] *= st->l[1];
  }
  double th = atan2(n[1], n[0]), km = mfs_disp_kappa_max(pl, th) * M_PI;
  for (size_t i = 0; i < nt; i++) {
    mfs_status s;
    if (i < nz) {
      s = smp ? mfs_disp_sample_omega2(smp, i, st, w + 2 * i)
              : mfs_disp_omega2_state(pl, st, kz + 2 * i, w + 2 * i);
    } else {
      size_t j = i - nz;
      double kap = j < NWAVE ? km * (j + 1) / NWAVE : (j == NWAVE ? 1e-3 : 1e-2) * M_PI;
      double k[2] = {kap * cos(th), kap * sin(th)};
      s = mfs_disp_omega2_state(pl, st, k, w + 2 * i);
    }
    if (s != MFS_OK)
      return -1;
  }
  double scale = 0.0;
  for (size_t i = 0; i < 2 * nt; i++)
    scale = fmax(scale, cabs(w[i]));
  double tol = 1e-10 * scale;
  for (size_t i = 0; i < 2 * nt; i++)
    if (creal(w[i]) < -tol || fabs(cimag(csqrt(w[i]))) > sqrt(tol))
      return 0;
  return 1;
}

static void run(FILE *out, int N, mfs_frame fr, int repeat)
{
  mfs_disc d = mfs_disc_default();
  d.dim = 2;
  d.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
  d.quadrature = &mfs_quad_stress_tri;
  d.material.physics = MFS_PHYS_PLANE_STRAIN;
  d.frame = fr;
  mfs_hyper mat = mfs_hyper_paper000_constants();
  int lag = fr == MFS_FRAME_LAGRANGIAN;
  double best_plan = INFINITY, best_eval = INFINITY;
  int npde = 0, nst = 0, nout = 0, nsing = 0;
  double *kz = malloc(2 * NDIR * NWAVE * sizeof *kz);
  for (int r = 0; r < repeat; r++) {
    double tplan = 0.0, teval = 0.0;
    npde = nst = nout = nsing = 0;
    mfs_disp_plan *pl = NULL;
    mfs_disp_sample *smp = NULL;
    if (lag) {
      double t0 = now();
      mfs_disp_spec sp = {.disc = d, .material = mat};
      mfs_status st;
      pl = mfs_disp_plan_alloc(&sp, &st);
      if (!pl) {
        fprintf(stderr, "bench_map: plan: %s\n", mfs_strerror(st));
        exit(1);
      }
      zone(pl, kz);
      smp = mfs_disp_sample_alloc(pl, NDIR * NWAVE, kz, &st);
      tplan += now() - t0;
    }
    for (int i = 0; i < N; i++)
      for (int j = 0; j < N; j++) {
        double l1 = 0.3 + 1.7 * i / (N - 1), l2 = 0.3 + 1.7 * j / (N - 1);
        double t1 = now();
        mfs_plane_state ps;
        mfs_plane_state_stretch(&mat, l1, l2, &ps);
        mfs_ellipticity e;
        mfs_ellipticity_check(ps.a, 0, &e);
        teval += now() - t1;
        npde += mfs_pde_stable(&e);
        mfs_disp_plan *own = NULL;
        if (!lag) {
          double t0 = now();
          mfs_disp_spec sp = {.disc = d, .material = mat, .stretch = l1, .stretch_y = l2};
          mfs_status st;
          own = mfs_disp_plan_alloc(&sp, &st);
          if (own)
            zone(own, kz);
          tplan += now() - t0;
          if (!own) {
            nsing++;
            continue;
          }
        }
        double t0 = now();
        int s = evaluate(own ? own : pl, own ? NULL : smp, kz, &ps, &e, lag);
        teval += now() - t0;
        nst += s == 1;
        nout += s == 1 && !mfs_pde_stable(&e);
        mfs_disp_plan_free(own);
      }
    mfs_disp_sample_free(smp);
    mfs_disp_plan_free(pl);
    best_plan = fmin(best_plan, tplan);
    best_eval = fmin(best_eval, teval);
  }
  free(kz);
  double pts = (double)N * N;
  fprintf(out, "%s,%dx%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%d,%d,%.1f\n", mfs_frame_name(fr), N, N,
          N * N, best_plan, best_eval, best_plan + best_eval, (best_plan + best_eval) / pts,
          (lag ? best_eval : best_plan + best_eval) / pts, npde, nst, nout, nsing, rss_mb());
  fflush(out);
}

int main(int argc, char **argv)
{
  int repeat = 1, sizes[16], ns = 0;
  FILE *out = stdout;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-o") && i + 1 < argc) {
      out = fopen(argv[++i], "w");
      if (!out) {
        perror(argv[i]);
        return 2;
      }
    } else if (ns < 16 && atoi(argv[i]) >= 2)
      sizes[ns++] = atoi(argv[i]);
    else {
      fprintf(stderr, "usage: bench_map [--repeat R] [-o FILE] [N ...]\n");
      return 2;
    }
  }
  if (!ns)
    sizes[ns++] = 60;
  if (repeat < 1)
    repeat = 1;
  fprintf(out, "frame,grid,points,plan_s,eval_s,total_s,s_per_point,after_plan_s_per_point,"
               "pde_stable,stable,stable_outside_pde,singular,peak_rss_mb\n");
  const mfs_frame frames[3] = {MFS_FRAME_LAGRANGIAN, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT};
  for (int s = 0; s < ns; s++)
    for (int f = 0; f < 3; f++)
      run(out, sizes[s], frames[f], repeat);
  if (out != stdout)
    fclose(out);
  return 0;
}
