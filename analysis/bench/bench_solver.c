/* Benchmark of the reference solver: 1D EFG (MLS, quartic, D = 1.5), nodal
 * integration, fixed rod with a sine standing wave; leapfrog steps at
 * 0.9 dt_crit.  Reports particle-steps per second (one core) for the
 * Lagrangian and the Eulerian kernel, and the run's error: max |u - u_exact|
 * / amplitude against the continuum standing wave u = A sin(pi X/L) cos(omega t).
 * Usage: bench_solver [N] [STEPS] [-o FILE]   (defaults 100000, 200). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mfs_solver.h"
#include "mfstab.h"

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(int argc, char **argv)
{
  int n = 100000, steps = 200;
  const char *out = NULL;
  int pos = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-o") && i + 1 < argc)
      out = argv[++i];
    else if (pos++ == 0)
      n = atoi(argv[i]);
    else
      steps = atoi(argv[i]);
  }
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f)
    return 1;
  fprintf(f, "frame,n,steps,seconds,particle_steps_per_s,rel_error,searches\n");
  for (int fr = 0; fr < 2; fr++) {
    mfs_solver_spec sp = {.n = n, .length = 1.0, .density = 1.0, .modulus = 1.0,
                          .kernel = &mfs_kernel_quartic, .shape = &mfs_shape_mls,
                          .dilation = 1.5,
                          .frame = fr ? MFS_FRAME_EULERIAN : MFS_FRAME_LAGRANGIAN,
                          .quadrature = "nodal", .bc = {MFS_BC_FIXED, MFS_BC_FIXED},
                          .bc_until = {INFINITY, INFINITY}, .equilibrate = 1};
    int st;
    mfs_solver *s = mfs_solver_alloc(&sp, &st, NULL);
    if (!s) {
      fprintf(stderr, "bench_solver: %s\n", mfs_strerror(st));
      return 1;
    }
    double A = 1e-6, *u = malloc(s->n * sizeof *u);
    for (size_t I = 0; I < s->n; I++)
      u[I] = A * sin(M_PI * s->X[I]);
    mfs_solver_set_state(s, u, NULL);
    double t0 = now();
    for (int k = 0; k < steps && st == MFS_OK; k++)
      st = mfs_solver_step(s, MFS_SCHEME_LEAPFROG);
    double sec = now() - t0, err = 0, w = M_PI; /* c = 1, L = 1 */
    for (size_t I = 0; I < s->n; I++)
      err = fmax(err, fabs(s->u[I] - A * sin(M_PI * s->X[I]) * cos(w * s->t)));
    fprintf(f, "%s,%d,%d,%.6g,%.6g,%.3g,%ld\n", fr ? "eulerian" : "lagrangian", n, steps, sec,
            (double)n * steps / sec, err / A, s->searches);
    free(u);
    mfs_solver_free(s);
  }
  if (out)
    fclose(f);
  return 0;
}
