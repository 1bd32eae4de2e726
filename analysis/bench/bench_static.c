/* bench_static: the cost of `mfstab static` (paper 004) and Table IV.
 *
 * Mode "solve" (default): the cantilever beam with a method (default efg) at
 * the given node counts, each in a forked child so that peak_rss_mb (getrusage
 * ru_maxrss) belongs to that size alone.  Phases: geometry (mfs_static_alloc:
 * nodes, Gauss points, boundary), assembly (K, f, constraints), solve (the
 * sparse direct solver: CHOLMOD with the Schur complement of the multipliers
 * for EFG), errors (eqs 114-119).  Columns: problem,method,nodes_x,nodes_y,
 * nodes,unknowns,multipliers,quad_points,nnz_K,factor_nnz,solver,geometry_s,
 * assembly_s,solve_s,errors_s,total_s,peak_rss_mb,L2_error_norm,
 * energy_error_norm.  Wall-clock seconds.
 *
 * Mode "table4": Table IV of the paper, the time to compute the shape
 * functions and their derivatives, corrected derivatives (method 1 of
 * section 4.4.3 = shape kb) against MLS (mls), side by side in one run, at
 * 5 x 5 Gauss points of the cells of a 60 x 60 square lattice (dx = 1, the
 * neighbour offsets gathered beforehand: the timing is the shape functions
 * alone), for support radii a = d_m dx.  d_m = 1 cannot be measured with a
 * radial support: at the midpoint of a cell edge only the two nodes of the
 * edge are within dx, and both moment matrices are singular; the paper's
 * multipliers are printed with their decimals lost ("1.?", "2.?", "3.?"), so
 * d_m = 1.5, 2, 2.5, 3, 3.5 are measured and the paper's speedup stands beside
 * every row with the same integer part.  The least of R repetitions.
 * Columns: d_m,support_m,points,mean_neighbours,mls_us_per_point,
 * cd1_us_per_point,speedup,speedup_table2,paper_dm,paper_speedup; speedup_table2
 * is the operation count of Table II, (n C_w + 101 n + 32)/(n C_w + 28 n + 10),
 * with n the mean neighbours and C_w = 20 flops for a kernel with its gradient.
 *
 * usage: bench_static [-o FILE] [--method M] [NX,NY ...]     (default 897,113: 101361 nodes)
 *        bench_static table4 [-o FILE] [--repeat R]          (default R = 5) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mfstab.h"

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double peak_mb(void)
{
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return (double)u.ru_maxrss / 1024.0;
}

static int solve_one(FILE *f, const mfs_static_method *me, int nx, int ny)
{
  mfs_static_spec s = mfs_static_spec_default();
  s.method = me;
  s.nx = nx;
  s.ny = ny;
  mfs_status st;
  const char *field;
  double t0 = now();
  mfs_static *m = mfs_static_alloc(&s, &st, &field);
  if (!m) {
    fprintf(stderr, "bench_static: alloc %d x %d: %s\n", nx, ny, mfs_strerror(st));
    return 1;
  }
  double t1 = now();
  mfs_static_where w;
  st = mfs_static_assemble(m, &w);
  double t2 = now();
  if (st == MFS_OK)
    st = mfs_static_solve(m);
  double t3 = now();
  mfs_static_errors e = {0};
  if (st == MFS_OK)
    st = mfs_static_error_norms(m, &e, &w);
  double t4 = now();
  if (st != MFS_OK) {
    fprintf(stderr, "bench_static: %d x %d: %s\n", nx, ny, mfs_strerror(st));
    mfs_static_free(m);
    return 1;
  }
  mfs_static_info in;
  mfs_static_get_info(m, &in);
  fprintf(f, "beam,%s,%d,%d,%zu,%zu,%zu,%zu,%zu,%.0f,%s,%.3f,%.3f,%.3f,%.3f,%.3f,%.1f,%.6e,%.6e\n",
          me->name, nx, ny, in.nodes, in.unknowns, in.multipliers, in.quad_points, in.nnz_K,
          in.factor_nnz, in.solver, t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0, peak_mb(), e.L2,
          e.energy);
  fflush(f);
  mfs_static_free(m);
  return 0;
}

/* ---- Table IV ------------------------------------------------------------ */

static double time_shape(const mfs_shape_type *sh, const mfs_shape_ctx *c, size_t np,
                         const size_t *ptr, const double *d, double *out, double *work, int repeat,
                         double *check)
{
  double best = INFINITY, sum = 0.0;
  for (int r = 0; r < repeat; r++) {
    double t0 = now();
    sum = 0.0;
    for (size_t Q = 0; Q < np; Q++) {
      int nn = (int)(ptr[Q + 1] - ptr[Q]);
      double rc;
      if (sh->eval(c, nn, d + 2 * ptr[Q], NULL, -1, 1, out, work, &rc) != MFS_OK)
        return NAN;
      sum += out[1]; /* keeps the work observable */
    }
    best = fmin(best, now() - t0);
  }
  *check = sum;
  return best / (double)np * 1e6;
}

static int table4(FILE *f, int repeat)
{
  const int N = 60;
  mfs_lattice_spec ls = {.dim = 2, .lattice = MFS_LATTICE_SQUARE, .nx = N, .ny = N, .dx = 1.0,
                         .gamma = 1.0, .cells = MFS_CELLS_QUAD};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&ls, &st);
  mfs_quad *q = p ? mfs_quad_alloc(&mfs_quad_gauss[4], p, &st) : NULL;
  if (!q)
    return 1;
  fputs("d_m,support_m,points,mean_neighbours,mls_us_per_point,cd1_us_per_point,speedup,"
        "speedup_table2,paper_dm,paper_speedup\n",
        f);
  const double dms[5] = {1.5, 2.0, 2.5, 3.0, 3.5};
  for (int k = 0; k < 5; k++) {
    double a = dms[k];
    mfs_grid *g = mfs_grid_alloc(2, p->n, p->x, &p->box, a, &st);
    /* the points whose support lies inside the lattice: no boundary effect */
    size_t np = 0, *keep = malloc(q->n * sizeof *keep);
    for (size_t Q = 0; Q < q->n; Q++) {
      const double *x = q->x + 2 * Q;
      if (x[0] > a && x[0] < N - 1 - a && x[1] > a && x[1] < N - 1 - a)
        keep[np++] = Q;
    }
    double *xq = malloc(2 * np * sizeof *xq);
    for (size_t i = 0; i < np; i++)
      memcpy(xq + 2 * i, q->x + 2 * keep[i], 2 * sizeof *xq);
    mfs_nlist *nl = mfs_nlist_build(g, np, xq, a, &st);
    size_t nnz = nl->ptr[np], maxn = 0;
    double *d = malloc(2 * nnz * sizeof *d);
    for (size_t Q = 0; Q < np; Q++) {
      maxn = nl->ptr[Q + 1] - nl->ptr[Q] > maxn ? nl->ptr[Q + 1] - nl->ptr[Q] : maxn;
      for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++)
        for (int c = 0; c < 2; c++)
          d[2 * e + c] = p->x[2 * (size_t)nl->idx[e] + c] - xq[2 * Q + c];
    }
    double *out = malloc(3 * maxn * sizeof *out);
    double *work = malloc(mfs_shape_work_len(2, (int)maxn) * sizeof *work);
    mfs_shape_ctx c = {.kernel = &mfs_kernel_cubic, .dim = 2, .a = a, .rcond_min = 1e-12};
    double s1, s2;
    double tm = time_shape(&mfs_shape_mls, &c, np, nl->ptr, d, out, work, repeat, &s1);
    double tk = time_shape(&mfs_shape_kb, &c, np, nl->ptr, d, out, work, repeat, &s2);
    double n = (double)nnz / (double)np, cw = 20.0;
    double pred = (n * cw + 101.0 * n + 32.0) / (n * cw + 28.0 * n + 10.0);
    const char *pdm = k == 0 ? "1.?" : (k < 3 ? "2.?" : "3.?");
    const char *psp = k < 3 ? "3.?" : "2.?";
    fprintf(f, "%g,%g,%zu,%.3f,%.4f,%.4f,%.4f,%.4f,%s,%s\n", dms[k], a, np, n, tm, tk, tm / tk,
            pred, pdm, psp);
    fflush(f);
    if (!isfinite(s1 + s2))
      fprintf(stderr, "bench_static: non-finite shape functions at d_m = %g\n", dms[k]);
    free(out);
    free(work);
    free(d);
    free(xq);
    free(keep);
    mfs_nlist_free(nl);
    mfs_grid_free(g);
  }
  mfs_quad_free(q);
  mfs_particles_free(p);
  return 0;
}

int main(int argc, char **argv)
{
  const char *outpath = NULL;
  const mfs_static_method *me = &mfs_static_efg;
  int repeat = 5, t4 = 0, nsize = 0;
  int sizes[64][2];
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
      outpath = argv[++i];
    else if (strcmp(argv[i], "--method") == 0 && i + 1 < argc)
      me = mfs_static_method_find(argv[++i]);
    else if (strcmp(argv[i], "--repeat") == 0 && i + 1 < argc)
      repeat = atoi(argv[++i]);
    else if (strcmp(argv[i], "table4") == 0)
      t4 = 1;
    else if (nsize < 64 && sscanf(argv[i], "%d,%d", &sizes[nsize][0], &sizes[nsize][1]) == 2)
      nsize++;
    else {
      fprintf(stderr, "bench_static: '%s': unknown argument\n", argv[i]);
      return 2;
    }
  }
  if (!me || repeat < 1) {
    fprintf(stderr, "bench_static: bad --method or --repeat\n");
    return 2;
  }
  FILE *f = outpath ? fopen(outpath, "w") : stdout;
  if (!f) {
    fprintf(stderr, "bench_static: cannot write %s\n", outpath);
    return 1;
  }
  int rc = 0;
  if (t4) {
    rc = table4(f, repeat);
  } else {
    if (!nsize) {
      sizes[0][0] = 897;
      sizes[0][1] = 113;
      nsize = 1;
    }
    fputs("problem,method,nodes_x,nodes_y,nodes,unknowns,multipliers,quad_points,nnz_K,"
          "factor_nnz,solver,geometry_s,assembly_s,solve_s,errors_s,total_s,peak_rss_mb,"
          "L2_error_norm,energy_error_norm\n",
          f);
    fflush(f);
    for (int k = 0; k < nsize; k++) {
      pid_t pid = fork();
      if (pid == 0)
        _exit(solve_one(f, me, sizes[k][0], sizes[k][1]));
      int status;
      waitpid(pid, &status, 0);
      rc |= !WIFEXITED(status) || WEXITSTATUS(status) != 0;
    }
  }
  if (f != stdout)
    fclose(f);
  return rc;
}
