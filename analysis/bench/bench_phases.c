/* Benchmark (not a test): how the shared machine's phases move the one-thread
 * lambda_max of issue 14 item 4 (docs/benchmarks.md, round 10).  In one
 * process, on bench_lambda's plate (analysis/bench/bench_plate.h; NX x NX
 * nodes, default 316: 2 10^5 unknowns), R rounds (default 20), each of four
 * measurements in turn:
 *   lanczos   one mfs_lanczos_max call (tolerance 1e-6, as bench_lambda
 *             --lanczos): its whole time, its storage build included
 *             (storage_s), as a user's call sees it;
 *   products  the same call's products alone (mfs_lanczos_info.op_seconds:
 *             the matvecs after the one the build takes);
 *   read      one pass reading as many bytes as one product reads, from an
 *             array of its own (eight running sums: no chain of additions
 *             bounds it), the median of 3 passes;
 *   compute   a loop of eight independent multiply-add chains, no memory
 *             (3 10^6 steps), the median of 3 passes: the core's own speed.
 * The same code, data and bits every round: what varies from round to round
 * is the machine.  CSV:
 *   round,kind,seconds,storage_s,matvecs,bytes,gbs,lambda_max,load_1min
 * bytes: what the row's work reads at least once (lanczos: matvecs x the
 * stored operator's bytes, as bench_lambda's limit; products: the products
 * timed; read: its array; compute: empty), gbs = bytes / seconds (empty for
 * compute); analysis/bench/limits.py adds limit_kind, limit_s and fraction
 * (bytes at the one-thread bandwidth of notebooks-data/bench_bandwidth.csv).
 *   bench_phases [NX] [--rounds R] [-o FILE]
 * Run with OMP_NUM_THREADS=1 (the row of the target). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "bench_plate.h"
#include "mfstab.h"

static double median3(double a, double b, double c)
{
  return fmax(fmin(a, b), fmin(fmax(a, b), c));
}

/* One pass reading v[0 .. n-1] (n a multiple of 8), its seconds. */
static double read_pass(const double *v, size_t n, volatile double *sink)
{
  double t0 = bench_now(), s[8] = {0.0};
  for (size_t i = 0; i < n; i += 8)
    for (int k = 0; k < 8; k++)
      s[k] += v[i + k];
  double t = bench_now() - t0;
  *sink += s[0] + s[1] + s[2] + s[3] + s[4] + s[5] + s[6] + s[7];
  return t;
}

/* Eight independent multiply-add chains, its seconds. */
static double compute_pass(volatile double *sink)
{
  double t0 = bench_now(), c[8];
  for (int k = 0; k < 8; k++)
    c[k] = 1.0;
  for (long i = 0; i < 3000000; i++)
    for (int k = 0; k < 8; k++)
      c[k] = c[k] * (1.0 - 1e-7 * (k + 1)) + 1e-9;
  double t = bench_now() - t0;
  *sink += c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7];
  return t;
}

int main(int argc, char **argv)
{
  int nx = 316, rounds = 20;
  const char *out = NULL;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--rounds") == 0 && i + 1 < argc)
      rounds = atoi(argv[++i]);
    else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
      out = argv[++i];
    else if (argv[i][0] != '-')
      nx = atoi(argv[i]);
    else {
      fprintf(stderr, "bench_phases: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (nx < 3 || nx > 3000 || rounds < 1 || rounds > 10000) {
    fprintf(stderr, "bench_phases: NX must be 3..3000 and --rounds 1..10000\n");
    return 2;
  }
  mfs_status st;
  mfs_model *m = bench_plate_model(nx, nx, "bench_phases");
  if (!m)
    return 1;
  mfs_pencil P = {m->K, m->M, m->m};
  mfs_lanczos_opts lo = {.tol = 1e-6};
  mfs_lanczos_info li;
  double lam = 0.0;
  /* one call first: the stored operator's bytes for the read's array */
  if ((st = mfs_lanczos_max(&P, &lo, &lam, &li)) != MFS_OK) {
    fprintf(stderr, "bench_phases: Lanczos: %s\n", mfs_strerror(st));
    return 1;
  }
  size_t nr = ((size_t)li.bytes / sizeof(double) + 7) / 8 * 8;
  double *v = malloc(nr * sizeof *v);
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!v || !f) {
    fprintf(stderr, "bench_phases: %s\n", v ? "cannot open the output" : "out of memory");
    return 1;
  }
  for (size_t i = 0; i < nr; i++)
    v[i] = 1.0 + 1e-9 * (double)(i & 1023);
  volatile double sink = 0.0;
  fprintf(f, "round,kind,seconds,storage_s,matvecs,bytes,gbs,lambda_max,load_1min\n");
  for (int r = 0; r < rounds; r++) {
    double l1 = bench_load1(), t0 = bench_now();
    st = mfs_lanczos_max(&P, &lo, &lam, &li);
    double t = bench_now() - t0;
    if (st != MFS_OK) {
      fprintf(stderr, "bench_phases: Lanczos: %s\n", mfs_strerror(st));
      return 1;
    }
    double b = li.matvecs * li.bytes, bp = (li.matvecs - li.build_product) * li.bytes;
    fprintf(f, "%d,lanczos,%.6f,%.6f,%d,%.0f,%.3f,%.15g,%.2f\n", r, t, li.setup_seconds,
            li.matvecs, b, b / t * 1e-9, lam, l1);
    fprintf(f, "%d,products,%.6f,,%d,%.0f,%.3f,,%.2f\n", r, li.op_seconds,
            li.matvecs - li.build_product, bp, bp / li.op_seconds * 1e-9, l1);
    double a = read_pass(v, nr, &sink), c = read_pass(v, nr, &sink), d = read_pass(v, nr, &sink);
    double tr = median3(a, c, d), br = (double)nr * sizeof *v;
    fprintf(f, "%d,read,%.6f,,,%.0f,%.3f,,%.2f\n", r, tr, br, br / tr * 1e-9, l1);
    a = compute_pass(&sink);
    c = compute_pass(&sink);
    d = compute_pass(&sink);
    fprintf(f, "%d,compute,%.6f,,,,,,%.2f\n", r, median3(a, c, d), l1);
  }
  (void)sink;
  free(v);
  mfs_model_free(m);
  if (out && fclose(f)) {
    fprintf(stderr, "bench_phases: cannot write %s\n", out);
    return 1;
  }
  return 0;
}
