/* bench_assembly: time the pipeline of a large finite model.
 *
 * Square lattice of n x n nodes (dx = 1, finite box), cubic kernel, linear
 * MLS, dilation D = 2, stress-point quadrature on quadrilaterals
 * (stress-quad), anti-plane scalar physics (C = rho = 1).  Phases:
 *
 *   lattice                 mfs_lattice_alloc
 *   quadrature              mfs_quad_alloc
 *   neighbour_search        mfs_plan_alloc, the symbolic plan: cell lists, the neighbour
 *                           lists of the quadrature points and their transpose
 *   shape_tables            mfs_plan_tabulate, the numeric plan: the shape-function table
 *   assembly_K              mfs_assemble_stiffness
 *   assembly_lumped_M       mfs_assemble_mass_lumped
 *   total                   the sum of the above; peak_rss_mb is the peak of the library pipeline
 *   reference_shape_tables  the same table by a straightforward per-point dense MLS:
 *                           3x3 moment matrix in coordinates relative to the evaluation point,
 *                           inverse by LAPACKE_dgesv (identity right-hand side), explicit
 *                           products for phi and grad phi (Belytschko et al. 1994)
 *   reference_shape_tables_global  the same in global coordinates (basis [1, x, y], no shift)
 *
 * error:  lattice: |sum V - area| / area; quadrature: |sum w - area| / area;
 *         shape_tables: max |sum_J phi_J - 1| and |sum_J grad phi_J| over the points;
 *         assembly_K: |K 1|_inf / max |K_IJ|; assembly_lumped_M: |sum m - rho area| / (rho area);
 *         reference_*: max abs difference from the shape_tables table.
 * ratio:  reference_*: reference seconds / shape_tables seconds.  Empty on the other rows.
 * seconds is wall-clock time; user_s and sys_s the CPU time of the phase (sys_s is
 * mostly page faults on first touch of new memory).
 *
 * Each size runs in a forked child, so peak_rss_mb (getrusage ru_maxrss, the
 * process peak so far) belongs to that size alone.  Single-threaded.
 *
 * usage: bench_assembly [-o FILE] [--repeat R] [--no-checks] [N ...]   (default N = 1000)
 * --repeat R runs each size R times (column rep); --no-checks stops after
 * `total` (for profiling the library alone). */
#include <lapacke.h> /* includes <complex.h>: no variable may be called I */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mfstab.h"

#define DILATION 2.0
#define NCOMP 3 /* phi, d/dx, d/dy */

/* Wall-clock (CLOCK_MONOTONIC), user and system CPU seconds.  System time is
 * mostly page faults: first touch of freshly allocated memory. */
typedef struct {
  double wall, user, sys;
} stamp;

static double tv_sec(struct timeval t)
{
  return (double)t.tv_sec + 1e-6 * (double)t.tv_usec;
}

static stamp now(void)
{
  struct timespec t;
  struct rusage u;
  clock_gettime(CLOCK_MONOTONIC, &t);
  getrusage(RUSAGE_SELF, &u);
  return (stamp){(double)t.tv_sec + 1e-9 * (double)t.tv_nsec, tv_sec(u.ru_utime),
                 tv_sec(u.ru_stime)};
}

static stamp since(stamp t0)
{
  stamp t = now();
  return (stamp){t.wall - t0.wall, t.user - t0.user, t.sys - t0.sys};
}

static stamp add(stamp a, stamp b)
{
  return (stamp){a.wall + b.wall, a.user + b.user, a.sys + b.sys};
}

static double peak_rss_mb(void)
{
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return (double)u.ru_maxrss / 1024.0; /* kilobytes on Linux */
}

typedef struct {
  FILE *f;
  int n_side, rep;
  size_t nodes, nq;
} row_ctx;

/* One CSV row; error and ratio are left empty when negative. */
static void row(const row_ctx *r, const char *phase, stamp t, double err, double ratio)
{
  fprintf(r->f, "%d,%zu,%zu,%d,%s,%.4f,%.4f,%.4f,%.1f,", r->n_side, r->nodes, r->nq, r->rep, phase,
          t.wall, t.user, t.sys, peak_rss_mb());
  if (err >= 0.0)
    fprintf(r->f, "%.3e", err);
  fputc(',', r->f);
  if (ratio >= 0.0)
    fprintf(r->f, "%.2f", ratio);
  fputc('\n', r->f);
  fflush(r->f);
}

/* max over points of |sum phi - 1| and |sum grad phi|. */
static double partition_error(const mfs_plan *pl)
{
  double e = 0.0;
  for (size_t Q = 0; Q < mfs_plan_npoints(pl); Q++) {
    double s[NCOMP] = {-1.0, 0.0, 0.0};
    mfs_point pt;
    mfs_plan_point(pl, Q, &pt);
    for (size_t k = 0; k < pt.nn; k++)
      for (int c = 0; c < NCOMP; c++)
        s[c] += pt.phi[k * NCOMP + c];
    for (int c = 0; c < NCOMP; c++)
      e = fabs(s[c]) > e ? fabs(s[c]) : e;
  }
  return e;
}

/* Straightforward MLS (linear basis p = [1, x, y], weights W(|x - x_J|)):
 *   phi_J      = p(x)^T A^-1 p(x_J) W_J
 *   phi_J,k    = [p,k^T A^-1 p_J - p^T A^-1 A,k A^-1 p_J] W_J + p^T A^-1 p_J W_J,k
 * with A = sum_J W_J p_J p_J^T, A,k = sum_J W_J,k p_J p_J^T, A^-1 from
 * LAPACKE_dgesv on the identity.  Coordinates relative to the evaluation
 * point (global = 0) or global (global = 1).  out: nnz * NCOMP; returns the
 * number of points where dgesv failed. */
static size_t reference_tables(const mfs_plan *pl, int global, double *out)
{
  const mfs_particles *p = mfs_plan_particles(pl);
  const mfs_quad *q = mfs_plan_quad(pl);
  const mfs_kernel_type *kernel = mfs_plan_disc(pl)->kernel;
  const size_t *ptr;
  const int *idx;
  const double *tab;
  mfs_plan_table(pl, &ptr, &idx, &tab);
  double a = mfs_plan_support(pl);
  size_t nfail = 0;
  for (size_t Q = 0; Q < q->n; Q++) {
    const double *xq = q->x + 2 * Q;
    double o[2] = {global ? xq[0] : 0.0, global ? xq[1] : 0.0}; /* x_Q in the chosen frame */
    double A[9] = {0}, dA[2][9] = {{0}};
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++) {
      double d[2];
      mfs_box_delta(&p->box, xq, p->x + 2 * (size_t)idx[e], d);
      double pj[3] = {1.0, o[0] + d[0], o[1] + d[1]};
      mfs_kernel_value kv = mfs_kernel_radial(kernel, 2, a, hypot(d[0], d[1]));
      double w = kv.W, dw[2] = {-kv.dW_r * d[0], -kv.dW_r * d[1]}; /* d/dx_Q */
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          A[3 * i + j] += w * pj[i] * pj[j];
          dA[0][3 * i + j] += dw[0] * pj[i] * pj[j];
          dA[1][3 * i + j] += dw[1] * pj[i] * pj[j];
        }
    }
    double Ai[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    lapack_int ipiv[3];
    if (LAPACKE_dgesv(LAPACK_ROW_MAJOR, 3, 3, A, 3, ipiv, Ai, 3) != 0) {
      nfail++;
      for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++)
        for (int c = 0; c < NCOMP; c++)
          out[e * NCOMP + c] = NAN;
      continue;
    }
    /* g = A^-1 p(x_Q); dg_k = A^-1 (p,k - A,k A^-1 p) */
    double px[3] = {1.0, o[0], o[1]}, g[3], t[3], dg[2][3];
    for (int i = 0; i < 3; i++)
      g[i] = Ai[3 * i] * px[0] + Ai[3 * i + 1] * px[1] + Ai[3 * i + 2] * px[2];
    for (int k = 0; k < 2; k++) {
      for (int i = 0; i < 3; i++)
        t[i] = (i == k + 1 ? 1.0 : 0.0) -
               (dA[k][3 * i] * g[0] + dA[k][3 * i + 1] * g[1] + dA[k][3 * i + 2] * g[2]);
      for (int i = 0; i < 3; i++)
        dg[k][i] = Ai[3 * i] * t[0] + Ai[3 * i + 1] * t[1] + Ai[3 * i + 2] * t[2];
    }
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++) {
      double d[2];
      mfs_box_delta(&p->box, xq, p->x + 2 * (size_t)idx[e], d);
      double pj[3] = {1.0, o[0] + d[0], o[1] + d[1]};
      mfs_kernel_value kv = mfs_kernel_radial(kernel, 2, a, hypot(d[0], d[1]));
      double gp = g[0] * pj[0] + g[1] * pj[1] + g[2] * pj[2];
      out[e * NCOMP] = gp * kv.W;
      for (int k = 0; k < 2; k++)
        out[e * NCOMP + 1 + k] = (dg[k][0] * pj[0] + dg[k][1] * pj[1] + dg[k][2] * pj[2]) * kv.W -
                                 gp * kv.dW_r * d[k];
    }
  }
  (void)tab;
  return nfail;
}

static double max_diff(size_t n, const double *x, const double *y)
{
  double e = 0.0;
  for (size_t i = 0; i < n; i++) {
    double t = fabs(x[i] - y[i]);
    if (!(t <= e))
      e = isnan(t) ? INFINITY : t;
  }
  return e;
}

/* One size.  Returns 0, or 1 with a message on stderr. */
static int bench(FILE *f, int n_side, int rep, int checks)
{
  mfs_status st = MFS_OK, rc = 1;
  const char *what = "";
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  mfs_csr *K = NULL;
  double *m = NULL, *ones = NULL, *y = NULL, *ref = NULL;
  row_ctx r = {f, n_side, rep, (size_t)n_side * (size_t)n_side, 0};
  mfs_lattice_spec ls = {.dim = 2,
                         .lattice = MFS_LATTICE_SQUARE,
                         .nx = n_side,
                         .ny = n_side,
                         .dx = 1.0,
                         .gamma = 1.0,
                         .cells = MFS_CELLS_QUAD};
  mfs_disc disc = mfs_disc_default();
  disc.dim = 2;
  disc.dilation = DILATION;
  mfs_material mat = {.physics = MFS_PHYS_SCALAR, .modulus = 1.0, .density = 1.0};
  double area = (double)(n_side - 1) * (double)(n_side - 1);

  stamp t0 = now();
  p = mfs_lattice_alloc(&ls, &st);
  stamp t_lat = since(t0);
  what = "lattice";
  if (!p)
    goto done;
  double sv = 0.0;
  for (size_t i = 0; i < p->n; i++)
    sv += p->vol[i];
  t0 = now();
  q = mfs_quad_alloc(&mfs_quad_stress_quad, p, &st);
  stamp t_quad = since(t0);
  what = "quadrature";
  if (!q)
    goto done;
  r.nq = q->n;
  row(&r, "lattice", t_lat, fabs(sv - area) / area, -1.0);
  double sw = 0.0;
  for (size_t Q = 0; Q < q->n; Q++)
    sw += q->w[Q];
  row(&r, "quadrature", t_quad, fabs(sw - area) / area, -1.0);
  stamp t_total = add(t_lat, t_quad);

  /* the plan: symbolic, then numeric */
  t0 = now();
  pl = mfs_plan_alloc(&disc, p, q, &st);
  stamp t_nb = since(t0);
  what = "neighbour search";
  if (!pl)
    goto done;
  row(&r, "neighbour_search", t_nb, -1.0, -1.0);
  t0 = now();
  st = mfs_plan_tabulate(pl, 1, NULL);
  stamp t_sh = since(t0);
  what = "shape tables";
  if (st != MFS_OK)
    goto done;
  row(&r, "shape_tables", t_sh, partition_error(pl), -1.0);
  t_total = add(t_total, add(t_nb, t_sh));

  t0 = now();
  st = mfs_assemble_stiffness(pl, &mat, &K);
  stamp t_K = since(t0);
  what = "stiffness";
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  ones = malloc(p->n * sizeof *ones);
  y = malloc(p->n * sizeof *y);
  m = malloc(p->n * sizeof *m);
  if (!ones || !y || !m)
    goto done;
  for (size_t i = 0; i < p->n; i++)
    ones[i] = 1.0;
  mfs_csr_matvec(K, ones, y);
  double kmax = 0.0, ymax = 0.0;
  for (size_t e = 0; e < K->ptr[K->nrow]; e++)
    kmax = fabs(K->val[e]) > kmax ? fabs(K->val[e]) : kmax;
  for (size_t i = 0; i < p->n; i++)
    ymax = fabs(y[i]) > ymax ? fabs(y[i]) : ymax;
  row(&r, "assembly_K", t_K, ymax / kmax, -1.0);
  t0 = now();
  st = mfs_assemble_mass_lumped(pl, &mat, m);
  stamp t_M = since(t0);
  what = "lumped mass";
  if (st != MFS_OK)
    goto done;
  double sm = 0.0;
  for (size_t i = 0; i < p->n; i++)
    sm += m[i];
  row(&r, "assembly_lumped_M", t_M, fabs(sm - mat.density * area) / (mat.density * area), -1.0);
  t_total = add(t_total, add(t_K, t_M));
  row(&r, "total", t_total, -1.0, -1.0);
  mfs_csr_free(K);
  K = NULL;
  if (!checks) {
    rc = 0;
    goto done;
  }

  /* cross-checks, after the library pipeline's peak */
  size_t nnz = mfs_plan_nnz(pl);
  const size_t *tptr;
  const int *tidx;
  const double *tab;
  mfs_plan_table(pl, &tptr, &tidx, &tab);
  st = MFS_ENOMEM;
  what = "reference";
  ref = malloc((nnz ? nnz : 1) * NCOMP * sizeof *ref);
  if (!ref)
    goto done;
  for (int global = 0; global < 2; global++) {
    t0 = now();
    size_t nfail = reference_tables(pl, global, ref);
    stamp t_ref = since(t0);
    row(&r, global ? "reference_shape_tables_global" : "reference_shape_tables", t_ref,
        nfail ? INFINITY : max_diff(nnz * NCOMP, ref, tab), t_ref.wall / t_sh.wall);
  }
  st = MFS_OK;
  rc = 0;
done:
  if (rc)
    fprintf(stderr, "bench_assembly: n = %d: %s: %s\n", n_side, what, mfs_strerror(st));
  free(ref);
  free(m);
  free(ones);
  free(y);
  mfs_csr_free(K);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return rc;
}

int main(int argc, char **argv)
{
  const char *outpath = NULL;
  int sizes[64], ns = 0, checks = 1, reps = 1;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      printf("usage: bench_assembly [-o FILE] [--repeat R] [--no-checks] [N ...]\n"
             "  N x N square lattice (default 1000), each size R times (default 1) in a fresh\n"
             "  process; --no-checks: library phases only\n");
      return 0;
    }
    if (strcmp(argv[i], "--repeat") == 0) {
      char *end;
      long r = i + 1 < argc ? strtol(argv[i + 1], &end, 10) : 0;
      if (i + 1 == argc || *end != '\0' || r < 1 || r > 100) {
        fprintf(stderr, "bench_assembly: --repeat: expected a count in 1 .. 100\n");
        return 2;
      }
      reps = (int)r;
      i++;
      continue;
    }
    if (strcmp(argv[i], "--no-checks") == 0) {
      checks = 0;
      continue;
    }
    if (strcmp(argv[i], "-o") == 0) {
      if (++i == argc) {
        fprintf(stderr, "bench_assembly: -o: missing value\n");
        return 2;
      }
      outpath = argv[i];
      continue;
    }
    char *end;
    long n = strtol(argv[i], &end, 10);
    if (*end != '\0' || end == argv[i] || n < 8 || n > 20000 || ns == 64) {
      fprintf(stderr, "bench_assembly: '%s': expected a lattice size N in 8 .. 20000\n",
              argv[i]);
      return 2;
    }
    sizes[ns++] = (int)n;
  }
  if (ns == 0)
    sizes[ns++] = 1000;
  FILE *f = outpath ? fopen(outpath, "w") : stdout;
  if (!f) {
    fprintf(stderr, "bench_assembly: -o %s: cannot open\n", outpath);
    return 2;
  }
  fprintf(f, "n_side,nodes,quad_points,rep,phase,seconds,user_s,sys_s,peak_rss_mb,error,ratio\n");
  fflush(f);
  int rc = 0;
  for (int s = 0; s < ns; s++)
    for (int rep = 1; rep <= reps; rep++) {
      pid_t pid = fork(); /* a fresh process per run: its own peak RSS */
      if (pid == 0) {
        int c = bench(f, sizes[s], rep, checks);
        fflush(f);
        _exit(c);
      }
      int status = 1;
      if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status))
        rc = 1;
    }
  if (outpath && fclose(f) != 0)
    rc = 1;
  return rc;
}
