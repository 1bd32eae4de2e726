/* bench_assembly: time the pipeline of a large finite model.
 *
 * Square lattice of n x n nodes (dx = 1, finite box), cubic kernel, linear
 * MLS, dilation D = 2, stress-point quadrature on quadrilaterals
 * (stress-quad), anti-plane scalar physics (C = rho = 1).  Phases:
 *
 *   lattice                 mfs_lattice_alloc
 *   quadrature              mfs_quad_alloc
 *   neighbour_search        mfs_grid_alloc + mfs_nlist_build on the quadrature points
 *   shape_tables            the shape-function table over those lists (the rest of
 *                           mfs_plan_alloc, done here with the public API)
 *   assembly_K              mfs_assemble_stiffness
 *   assembly_lumped_M       mfs_assemble_mass_lumped
 *   total                   the sum of the above; peak_rss_mb is the peak of the library pipeline
 *   plan_alloc              mfs_plan_alloc as a whole (cross-check of the split above)
 *   reference_shape_tables  the same table by a straightforward per-point dense MLS:
 *                           3x3 moment matrix in coordinates relative to the evaluation point,
 *                           inverse by LAPACKE_dgesv (identity right-hand side), explicit
 *                           products for phi and grad phi (Belytschko et al. 1994)
 *   reference_shape_tables_global  the same in global coordinates (basis [1, x, y], no shift)
 *
 * error:  lattice: |sum V - area| / area; quadrature: |sum w - area| / area;
 *         shape_tables: max |sum_J phi_J - 1| and |sum_J grad phi_J| over the points;
 *         assembly_K: |K 1|_inf / max |K_IJ|; assembly_lumped_M: |sum m - rho area| / (rho area);
 *         plan_alloc and reference_*: max abs difference from the shape_tables table.
 * ratio:  reference_*: reference seconds / shape_tables seconds; plan_alloc: its seconds /
 *         (neighbour_search + shape_tables).  Empty on the other rows.
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

/* The shape-function table of pl->nl, as mfs_plan_alloc builds it. */
static int shape_tables(mfs_plan *pl)
{
  const mfs_particles *p = pl->p;
  const mfs_quad *q = pl->q;
  const mfs_nlist *nl = pl->nl;
  int dim = p->dim, st = MFS_ENOMEM;
  size_t nnz = nl->ptr[q->n], maxrow = 1;
  double *d = NULL, *v = NULL, *work = NULL;
  for (size_t Q = 0; Q < q->n; Q++) {
    size_t len = nl->ptr[Q + 1] - nl->ptr[Q];
    maxrow = len > maxrow ? len : maxrow;
  }
  pl->tab = malloc((nnz ? nnz : 1) * pl->ncomp * sizeof *pl->tab);
  d = malloc(maxrow * dim * sizeof *d);
  v = malloc(maxrow * sizeof *v);
  work = malloc(mfs_shape_work_len(dim, (int)maxrow) * sizeof *work);
  if (!pl->tab || !d || !v || !work)
    goto done;
  for (size_t Q = 0; Q < q->n; Q++) {
    size_t e0 = nl->ptr[Q];
    int nn = (int)(nl->ptr[Q + 1] - e0), self = -1;
    const double *xq = q->x + Q * dim;
    for (int J = 0; J < nn; J++) {
      int i = nl->idx[e0 + J];
      mfs_box_delta(&p->box, xq, p->x + (size_t)i * dim, d + J * dim);
      v[J] = p->vol[i];
      if (i == q->node[Q])
        self = J;
    }
    double rc;
    st = pl->shape->eval(&pl->ctx, nn, d, v, self, pl->order, pl->tab + e0 * pl->ncomp, work, &rc);
    if (rc < pl->rcond)
      pl->rcond = rc;
    if (st != MFS_OK) {
      pl->bad = Q;
      goto done;
    }
  }
  st = MFS_OK;
done:
  free(d);
  free(v);
  free(work);
  return st;
}

/* max over points of |sum phi - 1| and |sum grad phi|. */
static double partition_error(const mfs_plan *pl)
{
  double e = 0.0;
  for (size_t Q = 0; Q < pl->nl->nq; Q++) {
    double s[NCOMP] = {-1.0, 0.0, 0.0};
    for (size_t k = pl->nl->ptr[Q]; k < pl->nl->ptr[Q + 1]; k++)
      for (int c = 0; c < NCOMP; c++)
        s[c] += pl->tab[k * NCOMP + c];
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
  const mfs_particles *p = pl->p;
  const mfs_quad *q = pl->q;
  const mfs_nlist *nl = pl->nl;
  double a = pl->ctx.a;
  size_t nfail = 0;
  for (size_t Q = 0; Q < q->n; Q++) {
    const double *xq = q->x + 2 * Q;
    double o[2] = {global ? xq[0] : 0.0, global ? xq[1] : 0.0}; /* x_Q in the chosen frame */
    double A[9] = {0}, dA[2][9] = {{0}};
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++) {
      double d[2];
      mfs_box_delta(&p->box, xq, p->x + 2 * (size_t)nl->idx[e], d);
      double pj[3] = {1.0, o[0] + d[0], o[1] + d[1]};
      mfs_kernel_value kv = mfs_kernel_radial(pl->ctx.kernel, 2, a, hypot(d[0], d[1]));
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
      for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++)
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
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++) {
      double d[2];
      mfs_box_delta(&p->box, xq, p->x + 2 * (size_t)nl->idx[e], d);
      double pj[3] = {1.0, o[0] + d[0], o[1] + d[1]};
      mfs_kernel_value kv = mfs_kernel_radial(pl->ctx.kernel, 2, a, hypot(d[0], d[1]));
      double gp = g[0] * pj[0] + g[1] * pj[1] + g[2] * pj[2];
      out[e * NCOMP] = gp * kv.W;
      for (int k = 0; k < 2; k++)
        out[e * NCOMP + 1 + k] = (dg[k][0] * pj[0] + dg[k][1] * pj[1] + dg[k][2] * pj[2]) * kv.W -
                                 gp * kv.dW_r * d[k];
    }
  }
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
  int st = MFS_OK, rc = 1;
  const char *what = "";
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_grid *g = NULL;
  mfs_plan *pl = NULL, *pl2 = NULL;
  mfs_csr *K = NULL;
  double *m = NULL, *ones = NULL, *y = NULL, *ref = NULL;
  row_ctx r = {f, n_side, rep, (size_t)n_side * (size_t)n_side, 0};
  mfs_lattice_spec ls = {2, MFS_LATTICE_SQUARE, n_side, n_side, 1.0, 1.0, 0, MFS_CELLS_QUAD,
                         0.0, 0};
  mfs_quad_rule rule;
  mfs_plan_spec spec = {&mfs_kernel_cubic, &mfs_shape_mls, DILATION, 1, 1e-12};
  mfs_material mat = {MFS_PHYS_SCALAR, 1.0, 0.0, 1.0};
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
  mfs_quad_rule_parse("stress-quad", &rule);
  t0 = now();
  q = mfs_quad_alloc(&rule, p, &st);
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

  /* the plan, in the two steps of mfs_plan_alloc */
  st = MFS_ENOMEM;
  what = "plan";
  pl = calloc(1, sizeof *pl);
  if (!pl)
    goto done;
  pl->dim = 2;
  pl->p = p;
  pl->q = q;
  pl->shape = spec.shape;
  pl->order = spec.order;
  pl->ncomp = mfs_shape_ncomp(2, spec.order);
  pl->ctx = (mfs_shape_ctx){spec.kernel, 2, spec.dilation * p->dx, spec.rcond_min};
  pl->rcond = 1.0;
  t0 = now();
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, pl->ctx.a, &st);
  if (g)
    pl->nl = mfs_nlist_build(g, q->n, q->x, pl->ctx.a, &st);
  mfs_grid_free(g);
  g = NULL;
  stamp t_nb = since(t0);
  what = "neighbour search";
  if (!pl->nl)
    goto done;
  row(&r, "neighbour_search", t_nb, -1.0, -1.0);
  t0 = now();
  st = shape_tables(pl);
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
  size_t nnz = pl->nl->ptr[q->n];
  t0 = now();
  pl2 = mfs_plan_alloc(&spec, p, q, &st, NULL);
  stamp t_plan = since(t0);
  what = "mfs_plan_alloc";
  if (!pl2)
    goto done;
  double e_plan = pl2->nl->ptr[q->n] == nnz &&
                      memcmp(pl2->nl->idx, pl->nl->idx, nnz * sizeof *pl->nl->idx) == 0
                    ? max_diff(nnz * NCOMP, pl2->tab, pl->tab)
                    : INFINITY;
  row(&r, "plan_alloc", t_plan, e_plan, t_plan.wall / (t_nb.wall + t_sh.wall));
  mfs_plan_free(pl2);
  pl2 = NULL;
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
        nfail ? INFINITY : max_diff(nnz * NCOMP, ref, pl->tab), t_ref.wall / t_sh.wall);
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
  mfs_plan_free(pl2);
  mfs_plan_free(pl);
  mfs_grid_free(g);
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
