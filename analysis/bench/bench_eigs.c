/* Benchmark (not a test): lambda_max of a 2D anti-plane model, cubic MLS,
 * D = 2, gauss2, lumped mass, on an N x N lattice of the unit square, by
 * ARPACK (mfs_eig_max), and the streaming element bound (mfs_bound_model).
 * One size per process, so that the peak resident memory is that of the
 * size:
 *   bench_eigs NSIDE [--ncv K] [--tol T] [--export PREFIX] [--header]
 * prints one CSV row (with --header, the header first):
 *   tool,nodes,dofs,nnz_K,setup_s,bound_s,eig_s,iterations,matvecs,lambda_max,
 *   bound,residual,peak_rss_mb,op_bytes
 * setup_s: particles, quadrature, shape table and assembly; bound_s: the
 * streaming bound alone (it builds its own particles); eig_s: ARPACK;
 * op_bytes: what one product of its stored operator reads and writes
 * (mfs_eig_info.op_bytes).
 * --export writes PREFIX_K.mtx and PREFIX_M.mtx for the SciPy comparison. */
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
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double peak_mb(void)
{
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_maxrss / 1024.0; /* kB on Linux */
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: bench_eigs NSIDE [--ncv K] [--tol T] [--export PREFIX] [--header]\n");
    return 2;
  }
  int nside = atoi(argv[1]), ncv = 0, header = 0, bound_only = 0;
  double tol = 1e-10;
  const char *export_prefix = NULL;
  for (int i = 2; i < argc; i++) {
    if (strcmp(argv[i], "--ncv") == 0 && i + 1 < argc)
      ncv = atoi(argv[++i]);
    else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
      tol = atof(argv[++i]);
    else if (strcmp(argv[i], "--export") == 0 && i + 1 < argc)
      export_prefix = argv[++i];
    else if (strcmp(argv[i], "--header") == 0)
      header = 1;
    else if (strcmp(argv[i], "--bound-only") == 0)
      bound_only = 1;
    else {
      fprintf(stderr, "bench_eigs: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (nside < 3) {
    fprintf(stderr, "bench_eigs: NSIDE must be >= 3\n");
    return 2;
  }
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.dim = 2;
  s.disc.source = (mfs_source){
    .lattice = MFS_LATTICE_SQUARE, .nx = nside, .ny = nside, .lx = 1.0, .ly = 1.0};
  s.disc.dilation = 2.0;
  s.disc.quadrature = &mfs_quad_gauss[1];

  double t0 = now();
  mfs_bound_result br;
  mfs_status st = mfs_bound_model(&s, &br, NULL);
  double bound_s = now() - t0;
  if (st != MFS_OK) {
    fprintf(stderr, "bench_eigs: bound: %s\n", mfs_strerror(st));
    return 1;
  }
  if (header)
    printf("tool,nodes,dofs,nnz_K,setup_s,bound_s,eig_s,iterations,matvecs,lambda_max,bound,"
           "residual,peak_rss_mb,op_bytes\n");
  if (bound_only) {
    printf("mfstab-bound,%d,%d,0,0,%.4f,0,0,0,0,%.10g,0,%.1f,\n", nside * nside, nside * nside,
           bound_s, br.lambda, peak_mb());
    return 0;
  }
  t0 = now();
  size_t bad;
  mfs_model *m = mfs_model_alloc(&s, &st, &bad);
  if (!m) {
    fprintf(stderr, "bench_eigs: model: %s\n", mfs_strerror(st));
    return 1;
  }
  mfs_model_release_plan(m);
  double setup_s = now() - t0;
  if (export_prefix) {
    char path[4096];
    snprintf(path, sizeof path, "%s_K.mtx", export_prefix);
    FILE *f = fopen(path, "w");
    snprintf(path, sizeof path, "%s_M.mtx", export_prefix);
    FILE *g = fopen(path, "w");
    if (!f || !g || mfs_model_write_mtx(m, f, g) != MFS_OK) {
      fprintf(stderr, "bench_eigs: cannot export to %s\n", export_prefix);
      return 1;
    }
    fclose(f);
    fclose(g);
  }
  mfs_pencil P = {m->K, m->M, m->m};
  mfs_eig_opts eo = {ncv, 0, tol};
  mfs_eig_info info;
  double lam = 0.0;
  t0 = now();
  st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
  double eig_s = now() - t0;
  if (st != MFS_OK) {
    fprintf(stderr, "bench_eigs: ARPACK: %s (info %d)\n", mfs_strerror(st), info.info);
    return 1;
  }
  printf("mfstab,%d,%zu,%zu,%.4f,%.4f,%.4f,%d,%d,%.12g,%.10g,%.3g,%.1f,%.0f\n", nside * nside, m->n,
         m->K->ptr[m->n], setup_s, bound_s, eig_s, info.iterations, info.matvecs, lam, br.lambda,
         info.residual, peak_mb(), info.op_bytes);
  mfs_model_free(m);
  return 0;
}
