/* Benchmark of the reference solver: 1D EFG (MLS, quartic), nodal
 * integration, fixed rod (L = 1, rho0 = E = 1, c = 1) with a sine standing
 * wave u = A sin(pi X), A = 1e-6; leapfrog steps at 0.9 dt_crit.  One row per
 * (frame, dilation): Lagrangian and Eulerian kernel, D = 1.5 and 2.
 *
 * Columns: particles, scheme, frame, dilation, steps, seconds (wall time of
 * the step loop alone), particle_steps_per_s (particles * steps / seconds,
 * one core), error, peak_rss_mb (peak resident set of the process so far,
 * getrusage).
 *
 * error: the relative energy drift of the run, |H(t_end) - H(0)| / H(0),
 * H = kinetic + potential from mfs_solver_energy (evaluated outside the
 * timed loop).  The Lagrangian discrete dynamics conserve a modified energy,
 * so for leapfrog this is the O((omega dt)^2) oscillation of H; the Eulerian
 * kernel is not conservative and its drift also measures that.
 *
 * Usage: bench_solver [N] [STEPS] [-o [FILE]]   (defaults 100000, 200;
 * -o alone writes notebooks-data/bench_solver.csv; without -o, stdout). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "mfs_solver.h"
#include "mfstab.h"

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double peak_rss_mb(void)
{
  struct rusage ru;
  return getrusage(RUSAGE_SELF, &ru) == 0 ? ru.ru_maxrss / 1024.0 : NAN; /* kB on Linux */
}

/* One benchmark row; MFS status. */
static int run(FILE *f, int n, int steps, mfs_frame frame, double dilation)
{
  const mfs_scheme scheme = MFS_SCHEME_LEAPFROG;
  mfs_disc d = mfs_disc_default();
  d.source = (mfs_source){.lattice = MFS_LATTICE_LINE, .nx = n, .lx = 1.0};
  d.kernel = &mfs_kernel_quartic;
  d.dilation = dilation;
  d.frame = frame;
  mfs_solver_spec sp = {.disc = d,
                        .bc = {MFS_BC_FIXED, MFS_BC_FIXED},
                        .bc_until = {INFINITY, INFINITY},
                        .equilibrate = 1};
  mfs_status st;
  mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
  if (!s)
    return st;
  double A = 1e-6, *u = malloc(s->n * sizeof *u);
  if (!u) {
    mfs_solver_free(s);
    return MFS_ENOMEM;
  }
  for (size_t I = 0; I < s->n; I++)
    u[I] = A * sin(M_PI * s->X[I]);
  double k0, p0, k1, p1;
  st = mfs_solver_set_state(s, u, NULL);
  if (st == MFS_OK)
    st = mfs_solver_energy(s, &k0, &p0);
  double t0 = now();
  for (int k = 0; k < steps && st == MFS_OK; k++)
    st = mfs_solver_step(s, scheme);
  double sec = now() - t0;
  if (st == MFS_OK)
    st = mfs_solver_energy(s, &k1, &p1);
  if (st == MFS_OK) {
    double h0 = k0 + p0, err = fabs(k1 + p1 - h0) / fabs(h0);
    fprintf(f, "%d,%s,%s,%g,%d,%.6g,%.6g,%.3e,%.1f\n", n, mfs_scheme_name(scheme),
            frame == MFS_FRAME_EULERIAN ? "eulerian" : "lagrangian", dilation, steps, sec,
            (double)n * steps / sec, err, peak_rss_mb());
    fflush(f);
  }
  free(u);
  mfs_solver_free(s);
  return st;
}

int main(int argc, char **argv)
{
  int n = 100000, steps = 200;
  const char *out = NULL;
  int pos = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-o")) {
      if (i + 1 < argc && argv[i + 1][0] != '-' &&
          strspn(argv[i + 1], "0123456789") != strlen(argv[i + 1]))
        out = argv[++i];
      else
        out = "notebooks-data/bench_solver.csv";
    } else if (pos++ == 0) {
      n = atoi(argv[i]);
    } else {
      steps = atoi(argv[i]);
    }
  }
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f) {
    perror(out);
    return 1;
  }
  fprintf(f, "particles,scheme,frame,dilation,steps,seconds,particle_steps_per_s,error,"
             "peak_rss_mb\n");
  static const double dil[2] = {1.5, 2.0};
  mfs_status st = MFS_OK;
  for (int fr = 0; fr < 2 && st == MFS_OK; fr++)
    for (int d = 0; d < 2 && st == MFS_OK; d++)
      st = run(f, n, steps, fr ? MFS_FRAME_EULERIAN : MFS_FRAME_LAGRANGIAN, dil[d]);
  if (out)
    fclose(f);
  if (st != MFS_OK) {
    fprintf(stderr, "bench_solver: %s\n", mfs_strerror(st));
    return 1;
  }
  return 0;
}
