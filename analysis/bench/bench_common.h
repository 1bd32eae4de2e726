/* What the benchmarks share (not a test): timers, peak memory, and the
 * machine's memory bandwidth, the physical limit that the CSV of every
 * benchmark states its work against (issue 14: `limit_s` = the bytes the work
 * must move at the measured bandwidth, `fraction` = limit_s / seconds).
 *
 * Bandwidth: a STREAM-like loop (McCalpin's kernels) over three arrays of
 * 2^24 doubles (128 MiB each: 4 times this machine's 32 MiB L3, so that no
 * pass is served from the cache), best of 7 passes:
 *   read   s += a[i] * b[i]          16 bytes per element (the loads of a
 *                                    sparse product: matrix, index, vector)
 *   triad  a[i] = b[i] + q * c[i]    24 bytes per element as STREAM counts them
 *                                    (the write-allocate read of a[] not counted)
 * with OpenMP over the threads asked for.  The larger of the two is the limit
 * (a lower bound on the time of moving the bytes).  MFS_BENCH_GBS=X (GB/s,
 * 10^9 bytes) skips the measurement (analysis/bench/run.sh measures once and
 * passes it to every benchmark of the run). */
#ifndef MFS_BENCH_COMMON_H
#define MFS_BENCH_COMMON_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static inline double bench_now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The 1-minute load average (NAN if /proc/loadavg cannot be read). */
static inline double bench_load1(void)
{
  double l = NAN;
  FILE *f = fopen("/proc/loadavg", "r");
  if (f) {
    if (fscanf(f, "%lf", &l) != 1)
      l = NAN;
    fclose(f);
  }
  return l;
}

/* qsort's comparison of doubles, ascending. */
static inline int bench_cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static inline double bench_peak_mb(void)
{
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return (double)u.ru_maxrss / 1024.0; /* kB on Linux */
}

static inline int bench_threads(void)
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

#define BENCH_STREAM_N ((size_t)1 << 24) /* doubles per array */

typedef struct {
  double read_gbs, triad_gbs; /* 10^9 bytes per second */
  int threads;
} bench_bandwidth;

/* The measurement with `threads` threads (0: the default count). */
static inline bench_bandwidth bench_stream(int threads)
{
  bench_bandwidth bw = {0.0, 0.0, threads > 0 ? threads : bench_threads()};
  const size_t n = BENCH_STREAM_N;
  double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
  if (!a || !b || !c) {
    free(a);
    free(b);
    free(c);
    return bw;
  }
  int nt = bw.threads;
  (void)nt;
#pragma omp parallel for num_threads(nt) schedule(static)
  for (size_t i = 0; i < n; i++) { /* first touch by the threads that use them */
    a[i] = 1.0;
    b[i] = 2.0 + 1e-9 * (double)i;
    c[i] = 0.5;
  }
  volatile double sink = 0.0;
  for (int pass = 0; pass < 7; pass++) {
    double t0 = bench_now(), s = 0.0;
#pragma omp parallel for num_threads(nt) schedule(static) reduction(+ : s)
    for (size_t i = 0; i < n; i++)
      s += a[i] * b[i];
    double tr = bench_now() - t0;
    sink += s;
    t0 = bench_now();
#pragma omp parallel for num_threads(nt) schedule(static)
    for (size_t i = 0; i < n; i++)
      a[i] = b[i] + 0.25 * c[i];
    double tt = bench_now() - t0;
    double r = 16.0 * (double)n / tr * 1e-9, t = 24.0 * (double)n / tt * 1e-9;
    bw.read_gbs = r > bw.read_gbs ? r : bw.read_gbs;
    bw.triad_gbs = t > bw.triad_gbs ? t : bw.triad_gbs;
  }
  (void)sink;
  free(a);
  free(b);
  free(c);
  return bw;
}

/* The limit's bandwidth in bytes per second: MFS_BENCH_GBS if set, else the
 * larger of the two measured (with the default thread count). */
static inline double bench_bandwidth_bps(void)
{
  const char *e = getenv("MFS_BENCH_GBS");
  if (e && atof(e) > 0.0)
    return atof(e) * 1e9;
  bench_bandwidth bw = bench_stream(0);
  double g = bw.read_gbs > bw.triad_gbs ? bw.read_gbs : bw.triad_gbs;
  return g * 1e9;
}

#endif
