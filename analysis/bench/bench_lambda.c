/* Benchmark (not a test): lambda_max of a 2D plane-strain model (NX x NY
 * nodes, spacing 1 m, cubic MLS, D = 2, stress-quad, lumped mass, free edges)
 * by mfs_eig_max, its time per product against the bandwidth limit of the
 * product, and the certified step (mfs_eig_certify_search) on the same model.
 * analysis/bench/bench_lambda.sh runs it against SciPy's eigsh on the same
 * matrices (docs/benchmarks.md).
 *
 *   bench_lambda NX NY [--tol T] [--ref L] [--rep R] [--certify] [--export PREFIX]
 *                [--header]
 *   --tol T      ARPACK's tolerance (default 1e-6: what the step needs)
 *   --ncv K      Lanczos vectors (default 20, as mfstab eigs)
 *   --ref L      the reference lambda_max (a run at --tol 0): error = |lambda - L| / L
 *   --certify    also the certified step from this run's Lanczos value
 *   --lanczos    lambda_max by mfs_lanczos_max (plain Lanczos, tool mfstab-lanczos; --tol its
 *                residual bound, --ncv ignored) instead of ARPACK's mfs_eig_max
 *   --export P   write P_K.mtx and P_M.mtx (Matrix Market) and stop
 *
 * One CSV row (two with --certify), columns:
 *   tool,rep,nodes,dofs,nnz_K,threads,tol,setup_s,seconds,matvecs,s_per_matvec,
 *   op_s_per_matvec,lambda_max,error,factorizations,dt_fraction,limit_kind,bytes_per_matvec,
 *   bandwidth_gbs,peak_gflops,limit_s,fraction,op_fraction,peak_rss_mb
 * mfstab-lanczos: seconds = mfs_lanczos_max (building its storage included),
 * bytes_per_matvec = what its storage's product reads (mfs_lanczos_info.bytes:
 * 8 B per stored entry and 8 B per run of consecutive block columns, 2 x 2
 * blocks on plane strain; lib/analysis/mfs_symop.h), op_s_per_matvec its
 * product passes.  mfstab: seconds = mfs_eig_max; op_s_per_matvec = the
 * products alone (info.op_seconds / matvecs); bytes_per_matvec = what its
 * product reads and writes at least once (mfs_eig_info.op_bytes: the same
 * storage); limit_s = matvecs *
 * bytes_per_matvec / bandwidth; fraction = limit_s / seconds, op_fraction =
 * limit_s / op seconds; storage_s (mfstab-lanczos) the build of its stored
 * operator, inside seconds (with the 2 x 2 copy it also does the first
 * product), iter_fraction the same fraction over the iteration after it (its
 * products and vector work, without that build and, with the copy, without the
 * first product's bytes).  mfstab-certify: seconds = mfs_eig_certify_search
 * (the factorizations of sigma M - K; the Lanczos value is the row above's),
 * lambda_max = the proven upper bound sigma (1 + margin), dt_fraction =
 * dt_certified / dt_crit = sqrt(L / upper); limit_kind flops: the
 * factorizations' flops at MFS_BENCH_GFLOPS (empty without it).  bandwidth:
 * MFS_BENCH_GBS or measured here (bench_common.h) with the threads of the run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "bench_plate.h"
#include "mfstab.h"

int main(int argc, char **argv)
{
  if (argc < 3) {
    fprintf(stderr, "usage: bench_lambda NX NY [--tol T] [--ncv K] [--ref L] [--rep R] [--certify] "
                    "[--export PREFIX] [--header]\n");
    return 2;
  }
  int nx = atoi(argv[1]), ny = atoi(argv[2]), rep = 1, header = 0, certify = 0, ncv = 20,
      lanczos = 0;
  double tol = 1e-6, ref = 0.0;
  const char *export_prefix = NULL;
  for (int i = 3; i < argc; i++) {
    if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
      tol = atof(argv[++i]);
    else if (strcmp(argv[i], "--ref") == 0 && i + 1 < argc)
      ref = atof(argv[++i]);
    else if (strcmp(argv[i], "--ncv") == 0 && i + 1 < argc)
      ncv = atoi(argv[++i]);
    else if (strcmp(argv[i], "--rep") == 0 && i + 1 < argc)
      rep = atoi(argv[++i]);
    else if (strcmp(argv[i], "--export") == 0 && i + 1 < argc)
      export_prefix = argv[++i];
    else if (strcmp(argv[i], "--certify") == 0)
      certify = 1;
    else if (strcmp(argv[i], "--lanczos") == 0)
      lanczos = 1;
    else if (strcmp(argv[i], "--header") == 0)
      header = 1;
    else {
      fprintf(stderr, "bench_lambda: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (nx < 3 || ny < 3 || tol < 0.0) {
    fprintf(stderr, "bench_lambda: NX, NY must be >= 3 and --tol >= 0\n");
    return 2;
  }
  double t0 = bench_now();
  mfs_status st;
  mfs_model *m = bench_plate_model(nx, ny, "bench_lambda");
  if (!m)
    return 1;
  double setup_s = bench_now() - t0;
  if (export_prefix) {
    char pk[4096], pm[4096];
    snprintf(pk, sizeof pk, "%s_K.mtx", export_prefix);
    snprintf(pm, sizeof pm, "%s_M.mtx", export_prefix);
    FILE *f = fopen(pk, "w"), *g = fopen(pm, "w");
    if (!f || !g || mfs_model_write_mtx(m, f, g) != MFS_OK || fclose(f) || fclose(g)) {
      fprintf(stderr, "bench_lambda: cannot export to %s\n", export_prefix);
      return 1;
    }
    mfs_model_free(m);
    return 0;
  }
  double bytes = 0.0, bps = bench_bandwidth_bps();
  const char *gf = getenv("MFS_BENCH_GFLOPS");
  double flops_ps = gf && atof(gf) > 0.0 ? atof(gf) * 1e9 : 0.0;
  mfs_pencil P = {m->K, m->M, m->m};
  mfs_eig_opts eo = {ncv, 0, tol};
  mfs_eig_info info;
  double lam = 0.0;
  const char *tool = "mfstab";
  double storage_s = -1.0; /* mfstab-lanczos: building its stored operator (with its first product) */
  int first = 0;           /* mfstab-lanczos: the build took the first product */
  t0 = bench_now();
  if (lanczos) {
    mfs_lanczos_opts lo = {.tol = tol > 0.0 ? tol : 1e-14};
    mfs_lanczos_info li;
    st = mfs_lanczos_max(&P, &lo, &lam, &li);
    info = (mfs_eig_info){.matvecs = li.matvecs, .op_seconds = li.op_seconds};
    bytes = li.bytes; /* what its own storage reads (2 x 2 blocks on plane strain) */
    storage_s = li.setup_seconds;
    first = li.build_product;
    tool = "mfstab-lanczos";
  } else {
    st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
    bytes = info.op_bytes; /* what its stored operator reads (lib/analysis/mfs_symop.h) */
  }
  double eig_s = bench_now() - t0;
  if (st != MFS_OK) {
    fprintf(stderr, "bench_lambda: %s: %s (info %d)\n", lanczos ? "Lanczos" : "ARPACK",
            mfs_strerror(st), info.info);
    return 1;
  }
  size_t n = m->n, nnz = m->K->ptr[n];
  if (header)
    puts("tool,rep,nodes,dofs,nnz_K,threads,tol,setup_s,seconds,matvecs,s_per_matvec,"
         "op_s_per_matvec,lambda_max,error,factorizations,dt_fraction,limit_kind,"
         "bytes_per_matvec,bandwidth_gbs,peak_gflops,limit_s,fraction,op_fraction,peak_rss_mb,"
         "storage_s,iter_fraction");
  double limit = info.matvecs * bytes / bps;
  char err[32] = "";
  if (ref > 0.0)
    snprintf(err, sizeof err, "%.3g", fabs(lam - ref) / ref);
  printf("%s,%d,%d,%zu,%zu,%d,%g,%.4f,%.4f,%d,%.6g,%.6g,%.15g,%s,,,bytes,%.0f,%.2f,,%.6g,"
         "%.4f,%.4f,%.1f",
         tool, rep, nx * ny, n, nnz, bench_threads(), tol, setup_s, eig_s, info.matvecs,
         eig_s / info.matvecs, info.op_seconds / info.matvecs, lam, err, bytes, bps * 1e-9,
         limit, limit / eig_s, limit / info.op_seconds, bench_peak_mb());
  /* iter_fraction: the iteration without the one-time storage build, which holds the
   * first product when it is a 2 x 2 copy (block 2): its limit without that product */
  char stor[32] = "", itf[32] = "";
  if (storage_s >= 0.0 && eig_s > storage_s) {
    snprintf(stor, sizeof stor, "%.4f", storage_s);
    snprintf(itf, sizeof itf, "%.4f", (info.matvecs - first) * bytes / bps / (eig_s - storage_s));
  }
  printf(",%s,%s\n", stor, itf);
  if (certify) {
    mfs_certify_opts co = {.lambda_est = lam, .gap = 1e-6};
    mfs_certify_result cr;
    t0 = bench_now();
    st = mfs_eig_certify_search(&P, &co, &cr);
    double cs = bench_now() - t0;
    if (st != MFS_OK || !cr.ok) {
      fprintf(stderr, "bench_lambda: certify: %s\n", st != MFS_OK ? mfs_strerror(st) : "none");
      return 1;
    }
    char lim[96] = ",", frac[32] = "";
    if (flops_ps > 0.0) {
      double l = cr.factorizations * cr.flops / flops_ps;
      snprintf(lim, sizeof lim, "%.2f,%.6g", flops_ps * 1e-9, l);
      snprintf(frac, sizeof frac, "%.4f", l / cs);
    }
    char e2[32] = "", df[32] = "";
    if (ref > 0.0) {
      snprintf(e2, sizeof e2, "%.3g", (cr.lambda_upper - ref) / ref);
      snprintf(df, sizeof df, "%.9f", sqrt(ref / cr.lambda_upper));
    }
    printf("mfstab-certify,%d,%d,%zu,%zu,%d,%g,%.4f,%.4f,,,,%.15g,%s,%d,%s,flops,,,%s,%s,,%.1f",
           rep, nx * ny, n, nnz, bench_threads(), co.gap, setup_s, cs, cr.lambda_upper, e2,
           cr.factorizations, df, lim, frac, bench_peak_mb());
    puts(",,");
  }
  mfs_model_free(m);
  return 0;
}
