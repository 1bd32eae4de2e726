/* Two builds of libmfstab side by side in one process (not a test): the 1D
 * rays of bench_dispersion's family 1d (quartic MLS, Eulerian nodal, D = 1.5,
 * 2.5, five stresses x 1000 wave numbers), through mfs_disp_ray of library A
 * and of library B, loaded with dlopen (RTLD_LOCAL: each its own symbols),
 * the two alternating call by call.  The machine runs a whole process at one
 * of two speed levels (docs/benchmarks.md): timed in one process, both
 * libraries run at the same level, so their ratio holds from run to run where
 * two processes' times do not.
 *   ray           one mfs_disp_ray per (dilation, stress)
 *   ray-stresses  one per dilation, for the five stresses at once
 * CSV: phase,points,repeats,seconds_a,seconds_b,ns_per_point_a,ns_per_point_b,
 *   ratio,identical,peak_rss_mb,load1
 * (seconds: the best of the repeats; ratio = B / A; identical: the two
 * libraries' omega^2 the same bits).
 * usage: bench_dispersion_ab LIB_A LIB_B [--repeat R] [-o FILE]
 *   e.g. bench_dispersion_ab /tmp/old/build/lib/libmfstab.so build/lib/libmfstab.so
 * Not a test: nothing here asserts a time. */
#include <complex.h>
#undef I
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "mfstab.h"

enum { NK = 1000, NSIG = 5, NDIL = 2 };

typedef struct {
  void *h;
  mfs_status (*ray)(const mfs_disp_plan *, const double *, size_t, double, const double *,
                    size_t, double complex *, size_t);
  void (*plan_free)(mfs_disp_plan *);
  mfs_disp_plan *pl[NDIL];
} lib;

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void *sym(void *h, const char *path, const char *name)
{
  void *p = dlsym(h, name);
  if (!p) {
    fprintf(stderr, "bench_dispersion_ab: %s: no symbol %s\n", path, name);
    exit(1);
  }
  return p;
}

/* The library at path and its two plans, made with its own functions and
 * kernel table (a spec holds pointers into the library that reads it). */
static void load(lib *L, const char *path)
{
  L->h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!L->h) {
    fprintf(stderr, "bench_dispersion_ab: %s\n", dlerror());
    exit(1);
  }
  /* function pointers from dlsym's void * by copying the bytes (POSIX
   * guarantees the representation; ISO C has no conversion between them) */
  mfs_disp_plan *(*alloc)(const mfs_disp_spec *, mfs_status *);
  mfs_disc (*disc_default)(void);
  void *p = sym(L->h, path, "mfs_disp_plan_alloc");
  memcpy(&alloc, &p, sizeof p);
  p = sym(L->h, path, "mfs_disc_default");
  memcpy(&disc_default, &p, sizeof p);
  p = sym(L->h, path, "mfs_disp_ray");
  memcpy(&L->ray, &p, sizeof p);
  p = sym(L->h, path, "mfs_disp_plan_free");
  memcpy(&L->plan_free, &p, sizeof p);
  const mfs_kernel_type *quartic = sym(L->h, path, "mfs_kernel_quartic");
  const double dil[NDIL] = {1.5, 2.5};
  for (int d = 0; d < NDIL; d++) {
    mfs_disp_spec s = {.disc = disc_default(), .stretch = 1.0};
    s.disc.kernel = quartic;
    s.disc.dilation = dil[d];
    s.disc.frame = MFS_FRAME_EULERIAN;
    mfs_status st;
    L->pl[d] = alloc(&s, &st);
    if (!L->pl[d]) {
      fprintf(stderr, "bench_dispersion_ab: %s: plan: status %d\n", path, (int)st);
      exit(1);
    }
  }
}

/* One pass of a phase over the family into w (NDIL x NSIG x NK); its seconds. */
static double pass(const lib *L, int shared, const double *kap, double complex *w)
{
  static const double sig[NSIG] = {-0.5, 0.0, 0.25, 0.5, 1.0};
  double t0 = now();
  for (int d = 0; d < NDIL; d++) {
    double complex *wd = w + (size_t)d * NSIG * NK;
    if (shared) {
      L->ray(L->pl[d], sig, NSIG, 0.0, kap, NK, wd, 0);
    } else {
      for (int s = 0; s < NSIG; s++)
        L->ray(L->pl[d], sig + s, 1, 0.0, kap, NK, wd + (size_t)s * NK, 0);
    }
  }
  return now() - t0;
}

int main(int argc, char **argv)
{
  const char *pa = NULL, *pb = NULL, *out = NULL;
  int repeat = 300;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-o") && i + 1 < argc)
      out = argv[++i];
    else if (!pa)
      pa = argv[i];
    else if (!pb)
      pb = argv[i];
    else
      pa = NULL, i = argc;
  }
  if (!pa || !pb || repeat < 1) {
    fprintf(stderr, "usage: bench_dispersion_ab LIB_A LIB_B [--repeat R] [-o FILE]\n");
    return 2;
  }
  lib A, B;
  load(&A, pa);
  load(&B, pb);
  double kap[NK];
  for (int i = 0; i < NK; i++)
    kap[i] = (double)i / (NK - 1);
  const size_t nw = (size_t)NDIL * NSIG * NK;
  double complex *wa = malloc(nw * sizeof *wa), *wb = malloc(nw * sizeof *wb);
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!wa || !wb || !f) {
    fprintf(stderr, "bench_dispersion_ab: out of memory or %s: cannot write\n", out ? out : "-");
    return 1;
  }
  double load1 = 0.0;
  FILE *la = fopen("/proc/loadavg", "r");
  if (la) {
    if (fscanf(la, "%lf", &load1) != 1)
      load1 = 0.0;
    fclose(la);
  }
  fprintf(f, "phase,points,repeats,seconds_a,seconds_b,ns_per_point_a,ns_per_point_b,ratio,"
             "identical,peak_rss_mb,load1\n");
  for (int shared = 0; shared < 2; shared++) {
    double ba = 1e300, bb = 1e300;
    for (int r = 0; r < repeat; r++) { /* A, B, A, B, ...: the same level for both */
      double ta = pass(&A, shared, kap, wa), tb = pass(&B, shared, kap, wb);
      ba = ta < ba ? ta : ba;
      bb = tb < bb ? tb : bb;
    }
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    fprintf(f, "%s,%zu,%d,%.6g,%.6g,%.4g,%.4g,%.4f,%d,%.1f,%.2f\n",
            shared ? "ray-stresses" : "ray", nw, repeat, ba, bb, 1e9 * ba / nw, 1e9 * bb / nw,
            bb / ba, !memcmp(wa, wb, nw * sizeof *wa), u.ru_maxrss / 1024.0, load1);
  }
  for (int d = 0; d < NDIL; d++) {
    A.plan_free(A.pl[d]);
    B.plan_free(B.pl[d]);
  }
  free(wa);
  free(wb);
  if (f != stdout)
    fclose(f);
  return 0;
}
