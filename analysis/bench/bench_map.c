/* Benchmark of the stretch map (`mfstab map`, issue 10; both cores, issue 14):
 * the paper 000 eq. 18 material on an N x N grid of principal stretches on
 * [0.3, 2]^2, cubic MLS, D = 2, stress-tri, 8 directions x 64 wave numbers per
 * grid point (plus the 64 + 2 samples along the PDE's worst direction, as the
 * command samples), for the Lagrangian and both Eulerian frames.  The same
 * library calls as tools/cmd_map.c, the grid points in parallel (OpenMP, a
 * workspace per thread) with 1 and 2 threads:
 *   plan   Lagrangian: the plan and the lattice sums at the zone samples, once
 *          (Eulerian: none; each grid point's own plan is in the grid time)
 *   grid   the PDE check, the per-state plans and the symbols' eigenvalues at
 *          every grid point
 * identical: 1 if the two thread counts gave the same outcome at every point.
 * Not a test: nothing here asserts a time.
 * CSV (stdout or -o FILE): frame,grid,points,threads,plan_s,grid_s,total_s,
 *   s_per_point,speedup,identical,pde_stable,stable,stable_outside_pde,singular,
 *   peak_rss_mb,load1,gflop   (the least of --repeat runs; stable_outside_pde is
 *   the check: the Lagrangian domain lies within the PDE's)
 * gflop: the minimal work of the grid (10^9 flops; analysis/bench/limits.py
 *   states it against dgemm's rate): the folded lattice sums, 2 flops per
 *   offset and component of the plan (mfs_disp_plan_work), at every wave
 *   vector whose sums are evaluated: Lagrangian, the zone samples' once (the
 *   sample object, in plan_s) and per grid point the 64 + 2 ray samples', plus
 *   per point and zone sample 2 flops per component (each enters the state's
 *   symbol with at least a multiply and an add); Eulerian, per grid point its
 *   own plan's sums at all 8 x 64 + 64 + 2 samples (a point whose plan is
 *   singular: none).  The plans, phases and eigen solves are above the bound.
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
#include "mfs_omp.h"
#include "bench_common.h"

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
  double kr[2 * (NWAVE + 2)];
  for (size_t j = 0; j < NWAVE + 2; j++) {
    double kap = j < NWAVE ? km * (j + 1) / NWAVE : (j == NWAVE ? 1e-3 : 1e-2) * M_PI;
    kr[2 * j] = kap * cos(th);
    kr[2 * j + 1] = kap * sin(th);
  }
  mfs_status s = smp ? MFS_OK : mfs_disp_omega2_states(pl, st, nz, kz, w);
  for (size_t i = 0; smp && i < nz && s == MFS_OK; i++)
    s = mfs_disp_sample_omega2(smp, i, st, w + 2 * i);
  if (s == MFS_OK)
    s = mfs_disp_omega2_states(pl, st, NWAVE + 2, kr, w + 2 * nz);
  if (s != MFS_OK)
    return -1;
  double scale = 0.0;
  for (size_t i = 0; i < 2 * nt; i++)
    scale = fmax(scale, cabs(w[i]));
  double tol = 1e-10 * scale;
  for (size_t i = 0; i < 2 * nt; i++)
    if (creal(w[i]) < -tol || fabs(cimag(csqrt(w[i]))) > sqrt(tol))
      return 0;
  return 1;
}

/* One grid with nt threads, the least time of repeat runs (returned); res[q]
 * per point: 4 pde_stable + 2 + (-2 singular, -1 failed, 0 unstable, 1 stable);
 * res1, t1: those of one thread, to compare. */
static double run(FILE *out, int N, mfs_frame fr, int repeat, int nt, int *res, const int *res1,
                  double t1)
{
  mfs_disc d = mfs_disc_default();
  d.dim = 2;
  d.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
  d.quadrature = &mfs_quad_stress_tri;
  d.material.physics = MFS_PHYS_PLANE_STRAIN;
  d.frame = fr;
  mfs_hyper mat = mfs_hyper_paper000_constants();
  const int lag = fr == MFS_FRAME_LAGRANGIAN;
  const long npt = (long)N * N;
  double best_plan = INFINITY, best_grid = INFINITY;
  const size_t nz = NDIR * NWAVE, nr = NWAVE + 2; /* zone and ray samples per point */
  unsigned long long flops = 0;                   /* of one run (the same every run) */
  double *kz = malloc(2 * NDIR * NWAVE * (size_t)(nt + 1) * sizeof *kz);
#ifdef _OPENMP
  omp_set_num_threads(nt);
#endif
  for (int r = 0; r < repeat; r++) {
    double t0 = now();
    mfs_disp_plan *pl = NULL;
    mfs_disp_sample *smp = NULL;
    if (lag) {
      mfs_disp_spec sp = {.disc = d, .material = mat};
      mfs_status st;
      pl = mfs_disp_plan_alloc(&sp, &st);
      if (!pl) {
        fprintf(stderr, "bench_map: plan: %s\n", mfs_strerror(st));
        exit(1);
      }
      zone(pl, kz);
      smp = mfs_disp_sample_alloc(pl, NDIR * NWAVE, kz, &st);
      size_t no;
      int nc;
      mfs_disp_plan_work(pl, &no, &nc);
      flops = 2ull * no * nc * nz + (unsigned long long)npt * 2ull * nc * (no * nr + nz);
    }
    double t1p = now();
    unsigned long long fe = 0; /* the Eulerian points' sums */
    MFS_OMP("omp parallel for schedule(dynamic) reduction(+ : fe)")
    for (long q = 0; q < npt; q++) {
      int th = 0;
#ifdef _OPENMP
      th = omp_get_thread_num();
#endif
      double *kzt = kz + 2 * NDIR * NWAVE * (size_t)(th + 1);
      double l1 = 0.3 + 1.7 * (q / N) / (N - 1), l2 = 0.3 + 1.7 * (q % N) / (N - 1);
      mfs_plane_state ps;
      mfs_plane_state_stretch(&mat, l1, l2, &ps);
      mfs_ellipticity e;
      mfs_ellipticity_check(ps.a, 0, &e);
      int pde = 4 * mfs_pde_stable(&e) + 2;
      mfs_disp_plan *own = NULL;
      if (!lag) {
        mfs_disp_spec sp = {.disc = d, .material = mat, .stretch = l1, .stretch_y = l2};
        mfs_status st;
        own = mfs_disp_plan_alloc(&sp, &st);
        if (!own) {
          res[q] = pde - 2;
          continue;
        }
        zone(own, kzt);
        size_t no;
        int nc;
        mfs_disp_plan_work(own, &no, &nc);
        fe += 2ull * no * nc * (nz + nr);
      }
      res[q] = evaluate(own ? own : pl, own ? NULL : smp, own ? kzt : kz, &ps, &e, lag) + pde;
      mfs_disp_plan_free(own);
    }
    double t2 = now();
    if (!lag)
      flops = fe;
    mfs_disp_sample_free(smp);
    mfs_disp_plan_free(pl);
    best_plan = fmin(best_plan, t1p - t0);
    best_grid = fmin(best_grid, t2 - t1p);
  }
  free(kz);
  int npde = 0, nst = 0, nout = 0, nsing = 0, same = 1;
  for (long q = 0; q < npt; q++) {
    int pde = res[q] >> 2, ev = (res[q] & 3) - 2;
    npde += pde;
    nsing += ev == -2;
    nst += ev == 1;
    nout += ev == 1 && !pde;
    same &= !res1 || res1[q] == res[q];
  }
  double tot = best_plan + best_grid;
  fprintf(out, "%s,%dx%d,%ld,%d,%.6g,%.6g,%.6g,%.6g,%.4g,%s,%d,%d,%d,%d,%.1f,%.2f,%.6g\n",
          mfs_frame_name(fr), N, N, npt, nt, best_plan, best_grid, tot, tot / npt,
          res1 ? t1 / tot : 1.0, res1 ? (same ? "1" : "0") : "", npde, nst, nout, nsing, rss_mb(),
          bench_load1(), 1e-9 * (double)flops);
  fflush(out);
  return tot;
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
  fprintf(out, "frame,grid,points,threads,plan_s,grid_s,total_s,s_per_point,speedup,identical,"
               "pde_stable,stable,stable_outside_pde,singular,peak_rss_mb,load1,gflop\n");
  const mfs_frame frames[3] = {MFS_FRAME_LAGRANGIAN, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT};
  for (int s = 0; s < ns; s++)
    for (int f = 0; f < 3; f++) {
      size_t npt = (size_t)sizes[s] * sizes[s];
      int *r1 = malloc(npt * sizeof *r1), *r2 = malloc(npt * sizeof *r2);
      double t1 = run(out, sizes[s], frames[f], repeat, 1, r1, NULL, 0.0);
      run(out, sizes[s], frames[f], repeat, 2, r2, r1, t1);
      free(r1);
      free(r2);
    }
  if (out != stdout)
    fclose(out);
  return 0;
}
