/* Benchmark (not a test; issue 14 item 8): the machine's limits that the other
 * benchmarks state their work against, with 1 and 2 threads.
 *   memory bandwidth: bench_common.h's STREAM-like read (s += a b, 16 B per
 *     element) and triad (a = b + q c, 24 B per element), 3 arrays of 128 MiB,
 *     best of 8 x 7 passes (the machine is shared: the best is the closest to
 *     what it can do);
 *   flop rate: dgemm through the BLAS the build links (n = 1000, C += A B,
 *     2 n^3 flops, best of 5; with 2 threads each thread its own matrices, at
 *     the same time) and a loop of multiply-adds on 8 independent accumulators
 *     in L1 (what this build's own C code reaches: no -march, so SSE2).
 *
 *   bench_bandwidth [--header]
 * CSV: kernel,threads,bytes,flops,seconds,gbs,gflops
 *   rows read, triad, dgemm, fma_loop per thread count, then `limit`: gbs the
 *   larger of read and triad, gflops dgemm's (with 2 threads at least those of
 *   1 thread): what analysis/bench/run.sh passes
 *   to the other benchmarks (MFS_BENCH_GBS, MFS_BENCH_GFLOPS). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"

void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k,
            const double *alpha, const double *a, const int *lda, const double *b, const int *ldb,
            const double *beta, double *c, const int *ldc);

/* dgemm on each of nt threads at once; the best wall time of 5. */
static double gemm_seconds(int nt, int n)
{
  size_t nn = (size_t)n * (size_t)n;
  double *m = malloc(3 * nn * (size_t)nt * sizeof *m), best = 1e30;
  if (!m)
    return 0.0;
  for (size_t i = 0; i < 3 * nn * (size_t)nt; i++)
    m[i] = 1.0 + 1e-3 * (double)(i % 97);
  for (int rep = 0; rep < 5; rep++) {
    double t0 = bench_now();
#pragma omp parallel num_threads(nt)
    {
      int t = 0;
#ifdef _OPENMP
      t = omp_get_thread_num();
#endif
      const double one = 1.0, beta = 0.5;
      double *a = m + 3 * nn * (size_t)t, *b = a + nn, *c = b + nn;
      dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &beta, c, &n);
    }
    double dt = bench_now() - t0;
    best = dt < best ? dt : best;
  }
  free(m);
  return best;
}

/* opaque to the compiler, so that the loop below is not folded */
volatile double fma_b = 0.9999999, fma_c = 1e-7;

/* multiply-adds on 8 accumulators per thread: 2 flops each. */
static double fma_seconds(int nt, long iters, double *sink)
{
  double best = 1e30, total = 0.0;
  for (int rep = 0; rep < 5; rep++) {
    double t0 = bench_now(), s = 0.0;
#pragma omp parallel num_threads(nt) reduction(+ : s)
    {
      double a[8] = {1, 1, 1, 1, 1, 1, 1, 1};
      const double b = fma_b, c = fma_c;
      for (long i = 0; i < iters; i++)
        for (int k = 0; k < 8; k++)
          a[k] = a[k] * b + c;
      for (int k = 0; k < 8; k++)
        s += a[k];
    }
    double dt = bench_now() - t0;
    best = dt < best ? dt : best;
    total += s;
  }
  *sink = total;
  return best;
}

int main(int argc, char **argv)
{
  if (argc > 1 && strcmp(argv[1], "--header") == 0)
    puts("kernel,threads,bytes,flops,seconds,gbs,gflops");
  const size_t n = BENCH_STREAM_N;
  const int gn = 1000;
  const long iters = 50000000;
  double sink = 0.0, g_prev = 0.0, gf_prev = 0.0;
  for (int nt = 1; nt <= 2; nt++) {
    bench_bandwidth bw = bench_stream(nt);
    for (int k = 1; k < 8; k++) { /* the machine is shared: the best of 8 x 7 passes */
      bench_bandwidth b2 = bench_stream(nt);
      bw.read_gbs = b2.read_gbs > bw.read_gbs ? b2.read_gbs : bw.read_gbs;
      bw.triad_gbs = b2.triad_gbs > bw.triad_gbs ? b2.triad_gbs : bw.triad_gbs;
    }
    printf("read,%d,%.0f,0,%.6f,%.3f,\n", nt, 16.0 * n, 16.0 * n / (bw.read_gbs * 1e9),
           bw.read_gbs);
    printf("triad,%d,%.0f,0,%.6f,%.3f,\n", nt, 24.0 * n, 24.0 * n / (bw.triad_gbs * 1e9),
           bw.triad_gbs);
    double fl = 2.0 * gn * (double)gn * gn * nt, tg = gemm_seconds(nt, gn);
    printf("dgemm,%d,0,%.0f,%.6f,,%.3f\n", nt, fl, tg, tg > 0 ? fl / tg * 1e-9 : 0.0);
    double ff = 16.0 * (double)iters * nt, tf = fma_seconds(nt, iters, &sink);
    printf("fma_loop,%d,0,%.0f,%.6f,,%.3f\n", nt, ff, tf, ff / tf * 1e-9);
    /* the limit of 2 threads is at least that of 1 (on the shared machine the
       second thread's measurement can come out lower) */
    double g = bw.read_gbs > bw.triad_gbs ? bw.read_gbs : bw.triad_gbs;
    double gf = tg > 0 ? fl / tg * 1e-9 : 0.0;
    g = g > g_prev ? g : g_prev;
    gf = gf > gf_prev ? gf : gf_prev;
    g_prev = g;
    gf_prev = gf;
    printf("limit,%d,,,,%.3f,%.3f\n", nt, g, gf);
  }
  if (sink == 12345.678)
    puts("#");
  return 0;
}
