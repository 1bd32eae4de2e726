/* Benchmark (not a test): the distributed finite model (lib/analysis/
 * mfs_peigs.h) phase by phase, on the ranks it is launched on, or the same
 * phases in one process with the one-process library calls (--serial).
 *
 *   mpirun -np N bench_peigs NX NY [--ref LAMBDA] [--tol T] [--header]
 *   bench_peigs NX NY --serial [--tol T] [--header]
 *
 * The model: 2D plane strain on an NX x NY square lattice of [0, NX-1] x
 * [0, NY-1] (dx = 1), cubic MLS, D = 2, stress-quad, lumped mass, E = 1,
 * nu = 0.3, rho = 1, free.  Phases (seconds, the slowest rank's):
 *   build       geometry, partition, local plan, rows and halo (serial:
 *               mfs_model_alloc)
 *   gershgorin  the Gershgorin bound from the rows
 *   bound       the element bound (then the plan is released, as mfstab eigs does)
 *   eig         lambda_max (PARPACK / ARPACK, ncv 20, tolerance T, default 1e-10)
 * One CSV row on standard output (rank 0):
 *   mode,ranks,nodes,dofs,build_s,gershgorin_s,bound_s,eig_s,total_s,matvecs,
 *   eig_s_per_matvec,lambda_max,lambda_gershgorin,error,rows_max,halo_max,
 *   halo_bytes_per_matvec,nnz_max,plan_nnz_max,peak_rss_mb_max,peak_rss_mb_sum
 * error: |lambda - LAMBDA| / LAMBDA with --ref (empty without); halo bytes:
 * the doubles all ranks receive in one product, times 8; peak_rss: the peak
 * resident memory of a rank (getrusage), largest and summed over the ranks. */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "mfstab.h"
#include "bench_plate.h"

static double peak_mb(void)
{
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_maxrss / 1024.0; /* kB on Linux */
}

static double tmax(double t)
{
  double m = 0.0;
  MPI_Allreduce(&t, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return m;
}

static double dsum(double v)
{
  double s = 0.0;
  MPI_Allreduce(&v, &s, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

static _Noreturn void fail(const char *what, mfs_status st)
{
  fprintf(stderr, "bench_peigs: %s: %s\n", what, mfs_strerror(st));
  MPI_Abort(MPI_COMM_WORLD, 1);
  exit(1);
}

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (argc < 3) {
    if (rank == 0)
      fprintf(stderr, "usage: bench_peigs NX NY [--serial] [--ref LAMBDA] [--tol T] [--header]\n");
    MPI_Finalize();
    return 2;
  }
  int nx = atoi(argv[1]), ny = atoi(argv[2]), serial = 0, header = 0;
  double ref = NAN, tol = 1e-10;
  for (int i = 3; i < argc; i++) {
    if (strcmp(argv[i], "--serial") == 0)
      serial = 1;
    else if (strcmp(argv[i], "--header") == 0)
      header = 1;
    else if (strcmp(argv[i], "--ref") == 0 && i + 1 < argc)
      ref = atof(argv[++i]);
    else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
      tol = atof(argv[++i]);
  }
  mfs_model_spec s = bench_plate_spec(nx, ny);
  mfs_eig_opts eo = {20, 0, tol};
  mfs_eig_info info;
  mfs_gershgorin_result g;
  mfs_bound_result b;
  double lam = NAN, t0, tb, tg, tbd, te;
  mfs_status st;
  size_t dofs = 0;
  mfs_pmodel_info in = {0};
  MPI_Barrier(MPI_COMM_WORLD);
  t0 = MPI_Wtime();
  if (serial) {
    size_t bad;
    mfs_model *m = mfs_model_alloc(&s, &st, &bad);
    if (!m)
      fail("model", st);
    tb = MPI_Wtime();
    mfs_gershgorin_csr(m->K, m->m, m->dof, &g);
    tg = MPI_Wtime();
    mfs_bound_of_model(m, &b);
    size_t pnnz1 = mfs_plan_nnz(m->pl);
    mfs_model_release_plan(m); /* as mfstab eigs */
    tbd = MPI_Wtime();
    mfs_pencil P = {m->K, NULL, m->m};
    st = mfs_eig_max(&P, &eo, &lam, NULL, &info);
    if (st != MFS_OK)
      fail("lambda_max", st);
    te = MPI_Wtime();
    dofs = m->n;
    in = (mfs_pmodel_info){.rows = m->n, .nnz = m->K->ptr[m->n], .plan_nnz = pnnz1};
    mfs_model_free(m);
  } else {
    mfs_pmodel *pm = mfs_pmodel_alloc(&s, (int)MPI_Comm_c2f(MPI_COMM_WORLD), 1, &st, NULL);
    if (!pm)
      fail("distributed model", st);
    tb = MPI_Wtime();
    st = mfs_pmodel_gershgorin(pm, &g);
    if (st != MFS_OK)
      fail("Gershgorin", st);
    tg = MPI_Wtime();
    st = mfs_pmodel_bound(pm, &b);
    if (st != MFS_OK)
      fail("element bound", st);
    mfs_pmodel_release_plan(pm); /* as mfstab eigs */
    tbd = MPI_Wtime();
    st = mfs_peig_max(pm, &eo, &lam, &info);
    if (st != MFS_OK)
      fail("lambda_max", st);
    te = MPI_Wtime();
    mfs_pmodel_sizes(pm, &in);
    dofs = in.dofs;
    mfs_pmodel_free(pm);
  }
  double build = tmax(tb - t0), gt = tmax(tg - tb), bt = tmax(tbd - tg), et = tmax(te - tbd);
  double total = tmax(te - t0);
  double rows = tmax((double)in.rows), halo = tmax((double)in.halo);
  double halo_all = dsum((double)in.halo), nnz = tmax((double)in.nnz);
  double pnnz = tmax((double)in.plan_nnz), rss = peak_mb();
  double rss_max = tmax(rss), rss_sum = dsum(rss);
  if (rank == 0) {
    if (header)
      printf("mode,ranks,nodes,dofs,build_s,gershgorin_s,bound_s,eig_s,total_s,matvecs,"
             "eig_s_per_matvec,lambda_max,lambda_gershgorin,error,rows_max,halo_max,"
             "halo_bytes_per_matvec,nnz_max,plan_nnz_max,peak_rss_mb_max,peak_rss_mb_sum\n");
    printf("%s,%d,%d,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%.6g,%.16g,%.16g,", serial ? "serial" : "mpi",
           size, nx * ny, dofs, build, gt, bt, et, total, info.matvecs,
           et / (info.matvecs > 0 ? info.matvecs : 1), lam, g.lambda);
    if (!isnan(ref))
      printf("%.3g", fabs(lam - ref) / ref);
    printf(",%.0f,%.0f,%.0f,%.0f,%.0f,%.1f,%.1f\n", rows, halo, 8.0 * halo_all, nnz, pnnz,
           rss_max, rss_sum);
  }
  MPI_Finalize();
  return 0;
}
