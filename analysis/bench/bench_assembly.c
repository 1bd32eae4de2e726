/* bench_assembly: time the pipeline of a large finite model.
 *
 * Square lattice of n x n nodes (dx = 1, finite box), cubic kernel, linear
 * MLS, dilation D = 2, stress-point quadrature on quadrilaterals
 * (stress-quad), anti-plane scalar physics (C = rho = 1).  Modes (column
 * mode), each size and mode in a fresh process (its own peak memory):
 *
 *   model   what mfs_model_alloc does (finite models and the linear plate
 *           solver alike): no shape table; the pattern once, then the values
 *           filled into it by one sweep that evaluates the shape functions
 *           block by block
 *   table   the plan's table first (mfs_plan_tabulate), then the same
 *           pattern and fill reading it (the solvers' Lagrangian tables; the
 *           reference checks of the table run after it)
 *   solver  mfs_solver2d_alloc on the same model (plane strain, free
 *           edges): assembly and its stable step
 *
 * Phases:
 *   lattice, quadrature     mfs_lattice_alloc, mfs_quad_alloc
 *   neighbour_search        mfs_plan_alloc: cell lists and the lists of the points
 *   shape_tables            (table) mfs_plan_tabulate
 *   transpose               mfs_plan_transpose: the particles' lists of points (what the
 *                           first assembly would build; timed apart, the rows need it)
 *   assembly                mfs_assemble: K (its pattern and values) and the lumped mass in
 *                           one sweep over the rows (model: with the shape functions'
 *                           evaluation), each row's columns sorted and appended in order
 *   rows_only               (model) the same rows without the CSR (rows_only below): not in
 *                           the total; error: the rows whose sum differs from K's (0: the
 *                           same bits; any other count fails the run)
 *   total                   the sum of the phases above but rows_only; ratio (model): the
 *                           CSR build's share, (CPU of assembly - CPU of rows_only) / CPU of
 *                           (transpose + assembly), CPU = user + sys of every thread
 *   separate_pattern        after the total (not in it): the path of the solvers that reuse
 *   separate_fill           a pattern, mfs_assemble_pattern then mfs_assemble_fill into it;
 *                           error: the entries (ptr, idx; values and masses) that differ
 *                           from assembly's (0: the same bits; any other count fails the run)
 *   solver2d_alloc          (solver) the whole mfs_solver2d_alloc
 *   reference_shape_tables  (table) the same table by a straightforward per-point dense MLS:
 *                           3x3 moment matrix in coordinates relative to the evaluation point,
 *                           inverse by LAPACKE_dgesv (identity right-hand side), explicit
 *                           products for phi and grad phi (Belytschko et al. 1994)
 *   reference_shape_tables_global  the same in global coordinates (basis [1, x, y], no shift)
 *
 * error:  lattice: |sum V - area| / area; quadrature: |sum w - area| / area;
 *         shape_tables: max |sum_J phi_J - 1| and |sum_J grad phi_J| over the points;
 *         assembly: |K 1|_inf / max |K_IJ| (and the mass: |sum m - rho area| / (rho area) in
 *         mass_error); reference_*: max abs difference from the shape_tables table.
 * ratio:  reference_*: reference seconds / shape_tables seconds.
 * seconds is wall-clock time; user_s and sys_s the CPU time of the phase (sys_s is
 * mostly page faults on first touch of new memory); threads the OpenMP threads.
 * peak_rss_mb: the process's peak so far; nnz_K the entries of K; bytes_per_nnz the
 * peak (bytes) / nnz_K on the total row (the peak when the assembly returned, before
 * rows_only).  load_1min: the 1-minute load average (/proc/loadavg) when the row was written.
 * limit_s: the bytes the phase must write (lists 4 B, table 24 B per list entry; K's
 * idx 4 B and val 8 B per entry, 8 B per row) at the measured memory bandwidth
 * (bench_common.h; bandwidth_gbs column), the physical lower bound of its time;
 * fraction = limit_s / seconds.  The work is compute-bound, so the fraction is small.
 *
 * usage: bench_assembly [-o FILE] [--repeat R] [--no-checks] [--mode model|table|solver|all]
 *        [N ...]   (default N = 1000, mode all)
 * --repeat R runs each size R times (column rep); --no-checks skips the reference tables. */
#include <lapacke.h> /* includes <complex.h>: no variable may be called I */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mfstab.h"
#include "bench_common.h"

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
  const char *mode;
  size_t nodes, nq, nnz;
  double bps;  /* bandwidth, bytes per second */
  double peak; /* if > 0: the peak_rss_mb of the next row (then reset) */
} row_ctx;

/* The 1-minute load average (/proc/loadavg), or -1. */
static double load_1min(void)
{
  double l = -1.0;
  FILE *f = fopen("/proc/loadavg", "r");
  if (f) {
    if (fscanf(f, "%lf", &l) != 1)
      l = -1.0;
    fclose(f);
  }
  return l;
}

/* One CSV row; error and ratio are left empty when negative, limit_s and
 * fraction when bytes is 0. */
static void row(row_ctx *r, const char *phase, stamp t, double err, double ratio,
                double bytes)
{
  double peak = r->peak > 0.0 ? r->peak : peak_rss_mb(), load = load_1min();
  r->peak = 0.0;
  fprintf(r->f, "%d,%zu,%zu,%d,%s,%d,%s,%.4f,%.4f,%.4f,%.1f,", r->n_side, r->nodes, r->nq, r->rep,
          r->mode, bench_threads(), phase, t.wall, t.user, t.sys, peak);
  if (r->nnz)
    fprintf(r->f, "%zu", r->nnz);
  fputc(',', r->f);
  if (r->nnz && strcmp(phase, "total") == 0)
    fprintf(r->f, "%.2f", peak * 1048576.0 / (double)r->nnz);
  fputc(',', r->f);
  if (err >= 0.0)
    fprintf(r->f, "%.3e", err);
  fputc(',', r->f);
  if (ratio >= 0.0)
    fprintf(r->f, "%.3f", ratio);
  fputc(',', r->f);
  if (bytes > 0.0 && t.wall > 0.0)
    fprintf(r->f, "%.5f,%.4f", bytes / r->bps, bytes / r->bps / t.wall);
  else
    fputc(',', r->f);
  fprintf(r->f, ",%.2f,", r->bps * 1e-9);
  if (load >= 0.0)
    fprintf(r->f, "%.2f", load);
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

/* |K 1|_inf / max |K_IJ| */
static double k_ones(const mfs_csr *K)
{
  double kmax = 0.0, ymax = 0.0;
  for (size_t i = 0; i < K->nrow; i++) {
    double y = 0.0;
    for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++) {
      y += K->val[e];
      kmax = fabs(K->val[e]) > kmax ? fabs(K->val[e]) : kmax;
    }
    ymax = fabs(y) > ymax ? fabs(y) : ymax;
  }
  return ymax / kmax;
}

/* The rows of the model mode without the CSR (phase rows_only): what
 * mfs_assemble does to evaluate and accumulate, and nothing else.  The same
 * blocks of rows as mfs_row_sweep's without a table (B = n / (4 threads) in
 * 1024 .. 65536 / threads, lib/plan/mfs_assemble.c sweep_block), each thread
 * evaluating its block's points (mfs_plan_eval_point, into a chunk of their
 * table rows) and accumulating each row's terms, K_IJ += (w C) (grad phi_I .
 * grad phi_J) and the lumped mass, into a dense window of the columns, with
 * the arithmetic of the assembly's (fuse_scalar_2d), the columns met marked
 * in a bitmap of the window (the least a dense window needs to be read and
 * cleared again); the window is then read once in column order (the row's
 * sum, sum_J K_IJ in that order, into sum[i]) and cleared.  No columns are
 * collected, no counts, no idx, val or ptr written, no blocks moved, no
 * pages of K touched.  With vals (phase values_only: the numeric fill
 * alone), the values are also written as they are read, at K's row offsets
 * (a fresh array of nnz_K doubles: the values' pages first touched here as
 * a fill into a pattern touches them), and compared with K's bit for bit.
 * Returns the rows whose sum is not bit for bit that of K's row in its order
 * (or whose lumped mass is not m's, or with vals whose values or length are
 * not K's), or SIZE_MAX if the workspace cannot be had. */
static size_t rows_only(const mfs_plan *pl, double c0, double rho, const mfs_csr *K,
                        const double *m, double *sum, double *vals)
{
  const size_t n = mfs_plan_particles(pl)->n;
  const size_t *tptr;
  const int *tidx;
  const double *ttab;
  mfs_plan_table(pl, &tptr, &tidx, &ttab);
  const int nt = bench_threads(), nc = 3;
  size_t B = n / (4 * (size_t)nt), hi = 65536 / (size_t)nt;
  hi = hi < 1024 ? 1024 : hi;
  B = B < 1024 ? 1024 : B > hi ? hi : B;
  const size_t nb = (n + B - 1) / B, mx = mfs_plan_max_neighbours(pl);
  size_t span = 1, ent = 1, pts = 1, wide = 1; /* the largest block's points and rows */
  for (size_t b = 0; b < nb; b++) {
    size_t r1 = (b + 1) * B < n ? (b + 1) * B : n, q0 = SIZE_MAX, q1 = 0, e = 0;
    for (size_t i = b * B; i < r1; i++) {
      size_t nq;
      const int *Q;
      mfs_plan_particle_points(pl, i, &nq, &Q);
      if (nq) {
        q0 = (size_t)Q[0] < q0 ? (size_t)Q[0] : q0;
        q1 = (size_t)Q[nq - 1] > q1 ? (size_t)Q[nq - 1] : q1;
        int lo = INT32_MAX, h = -1;
        for (size_t t = 0; t < nq; t++) {
          size_t e0 = tptr[Q[t]], e1 = tptr[Q[t] + 1];
          if (e1 > e0) {
            lo = tidx[e0] < lo ? tidx[e0] : lo;
            h = tidx[e1 - 1] > h ? tidx[e1 - 1] : h;
          }
        }
        wide = h >= lo && (size_t)(h - lo) + 1 > wide ? (size_t)(h - lo) + 1 : wide;
      }
    }
    if (q0 != SIZE_MAX) {
      span = q1 - q0 + 1 > span ? q1 - q0 + 1 : span;
      pts = q1 - q0 + 1 > pts ? q1 - q0 + 1 : pts;
      for (size_t Q = q0; Q <= q1; Q++)
        e += tptr[Q + 1] - tptr[Q];
      ent = e > ent ? e : ent;
    }
  }
  /* per thread: evaluator, slots and chunk (as large as the block's window
   * of points: not smaller than the library's), the dense window of columns */
  mfs_eval ev[64];
  int *slot[64] = {0}, *need[64] = {0}, *kept[64] = {0};
  double *ctab[64] = {0}, *acc[64] = {0};
  uint64_t *bits[64] = {0};
  size_t bad = 0;
  int ok = nt <= 64;
  memset(ev, 0, sizeof ev);
  for (int t = 0; t < nt && ok; t++) {
    ok = mfs_plan_evaluator(pl, 1, ev + t) == MFS_OK;
    slot[t] = malloc(span * sizeof *slot[t]);
    need[t] = malloc(pts * sizeof *need[t]);
    kept[t] = malloc(mx * sizeof *kept[t]);
    ctab[t] = malloc(ent * nc * sizeof *ctab[t]);
    acc[t] = calloc(wide, sizeof *acc[t]);
    bits[t] = malloc(((wide >> 6) + 1) * sizeof *bits[t]);
    ok = ok && slot[t] && need[t] && kept[t] && ctab[t] && acc[t] && bits[t];
    for (size_t k = 0; ok && k < span; k++)
      slot[t][k] = -1;
  }
  if (!ok) {
    bad = SIZE_MAX;
    goto done;
  }
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
  for (size_t b = 0; b < nb; b++) {
    const int t = omp_get_thread_num();
    size_t r1 = (b + 1) * B < n ? (b + 1) * B : n, q0 = SIZE_MAX, np = 0, ne = 0;
    for (size_t i = b * B; i < r1; i++) {
      size_t nq;
      const int *Q;
      mfs_plan_particle_points(pl, i, &nq, &Q);
      q0 = nq && (size_t)Q[0] < q0 ? (size_t)Q[0] : q0;
    }
    for (size_t i = b * B; i < r1; i++) { /* the block's points, evaluated */
      size_t nq;
      const int *Q;
      mfs_plan_particle_points(pl, i, &nq, &Q);
      for (size_t k = 0; k < nq; k++)
        if (slot[t][Q[k] - q0] < 0) {
          slot[t][Q[k] - q0] = (int)ne;
          ne += tptr[Q[k] + 1] - tptr[Q[k]];
          need[t][np++] = Q[k];
        }
    }
    for (size_t k = 0; k < np; k++)
      mfs_plan_eval_point(pl, ev + t, (size_t)need[t][k], kept[t],
                          ctab[t] + (size_t)slot[t][need[t][k] - q0] * nc, NULL);
    for (size_t i = b * B; i < r1; i++) { /* the rows */
      size_t nq;
      const int *Q;
      mfs_plan_particle_points(pl, i, &nq, &Q);
      int lo = INT32_MAX, h = -1; /* the row's window of columns */
      for (size_t k = 0; k < nq; k++)
        if (tptr[Q[k] + 1] > tptr[Q[k]]) {
          lo = tidx[tptr[Q[k]]] < lo ? tidx[tptr[Q[k]]] : lo;
          h = tidx[tptr[Q[k] + 1] - 1] > h ? tidx[tptr[Q[k] + 1] - 1] : h;
        }
      const size_t nw = h < lo ? 0 : ((size_t)(h - lo) >> 6) + 1;
      double *a = acc[t], lump = 0.0, s = 0.0;
      uint64_t *bt = bits[t];
      memset(bt, 0, nw * sizeof *bt);
      const mfs_quad *q = mfs_plan_quad(pl);
      for (size_t k = 0; k < nq; k++) {
        size_t e0 = tptr[Q[k]], nn = tptr[Q[k] + 1] - e0, iI = 0;
        const int *ix = tidx + e0;
        const double *tab = ctab[t] + (size_t)slot[t][Q[k] - q0] * nc, w = q->w[Q[k]];
        while (iI < nn && ix[iI] != (int)i)
          iI++;
        iI = iI == nn ? 0 : iI;
        const double *fi = tab + iI * nc, wc = w * c0, i1 = fi[1], i2 = fi[2];
        lump += rho * w * fi[0];
        for (size_t e = 0; e < nn; e++) {
          const double *fj = tab + e * nc;
          double g = 0.0;
          g += i1 * fj[1];
          g += i2 * fj[2];
          unsigned d = (unsigned)(ix[e] - lo);
          a[d] += wc * g;
          bt[d >> 6] |= (uint64_t)1 << (d & 63);
        }
      }
      size_t o = K->ptr[i];
      if (vals)
        for (size_t u = 0; u < nw; u++) /* read once in order, written, cleared */
          for (uint64_t v = bt[u]; v; v &= v - 1) {
            unsigned d = (unsigned)(u << 6) + (unsigned)__builtin_ctzll(v);
            s += a[d];
            vals[o++] = a[d];
            a[d] = 0.0;
          }
      else
        for (size_t u = 0; u < nw; u++) /* read once in order and cleared */
          for (uint64_t v = bt[u]; v; v &= v - 1) {
            unsigned d = (unsigned)(u << 6) + (unsigned)__builtin_ctzll(v);
            s += a[d];
            a[d] = 0.0;
          }
      sum[i] = s;
      if (vals && (o != K->ptr[i + 1] ||
                   memcmp(vals + K->ptr[i], K->val + K->ptr[i], (o - K->ptr[i]) * sizeof *vals)))
        sum[i] = NAN;
      if (lump != m[i])
        sum[i] = NAN;
    }
    for (size_t k = 0; k < np; k++)
      slot[t][need[t][k] - q0] = -1;
  }
  for (size_t i = 0; i < n; i++) { /* K's rows' sums, in its order */
    double s = 0.0;
    for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++)
      s += K->val[e];
    bad += memcmp(&s, sum + i, sizeof s) != 0;
  }
done:
  for (int t = 0; t < nt && t < 64; t++) {
    mfs_eval_free(ev + t);
    free(slot[t]);
    free(need[t]);
    free(kept[t]);
    free(ctab[t]);
    free(acc[t]);
    free(bits[t]);
  }
  return bad;
}

typedef enum { MODE_MODEL, MODE_TABLE, MODE_SOLVER } bench_mode;
static const char *const mode_names[] = {"model", "table", "solver"};

/* The solver mode: mfs_solver2d_alloc on the lattice (plane strain, free edges). */
static int bench_solver2d(row_ctx *r, int n_side)
{
  mfs_model_spec ms = mfs_model_spec_default();
  ms.disc.dim = 2;
  ms.disc.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .nx = n_side, .ny = n_side,
                                .lx = (double)(n_side - 1), .ly = (double)(n_side - 1),
                                .gamma = 1.0};
  ms.disc.quadrature = &mfs_quad_stress_quad;
  ms.disc.dilation = DILATION;
  ms.disc.material = (mfs_material){.physics = MFS_PHYS_PLANE_STRAIN, .modulus = 1.0,
                                    .poisson = 0.25, .density = 1.0};
  mfs_status st;
  stamp t0 = now();
  mfs_solver2d *s = mfs_solver2d_alloc(&ms, &st, NULL);
  stamp t = since(t0);
  if (!s) {
    fprintf(stderr, "bench_assembly: n = %d: solver: %s\n", n_side, mfs_strerror(st));
    return 1;
  }
  r->nnz = s->model->K->ptr[s->model->K->nrow];
  r->nq = s->model->q ? s->model->q->n : 0;
  double bytes = 12.0 * (double)r->nnz + 8.0 * (double)s->model->K->nrow;
  row(r, "solver2d_alloc", t, k_ones(s->model->K), -1.0, bytes);
  row(r, "total", t, -1.0, -1.0, bytes);
  mfs_solver2d_free(s);
  return 0;
}

/* One size in one mode.  Returns 0, or 1 with a message on stderr. */
static int bench(FILE *f, int n_side, int rep, bench_mode mode, int checks, double bps)
{
  mfs_status st = MFS_OK, rc = 1;
  const char *what = "";
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  mfs_csr *K = NULL, *K2 = NULL;
  double *m = NULL, *m2 = NULL, *ref = NULL;
  row_ctx r = {f, n_side, rep, mode_names[mode], (size_t)n_side * (size_t)n_side, 0, 0, bps, 0.0};
  if (mode == MODE_SOLVER)
    return bench_solver2d(&r, n_side);
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
  row(&r, "lattice", t_lat, fabs(sv - area) / area, -1.0, 0.0);
  double sw = 0.0;
  for (size_t Q = 0; Q < q->n; Q++)
    sw += q->w[Q];
  row(&r, "quadrature", t_quad, fabs(sw - area) / area, -1.0, 0.0);
  stamp t_total = add(t_lat, t_quad);

  /* the plan: symbolic, then (table) numeric */
  t0 = now();
  pl = mfs_plan_alloc(&disc, p, q, &st);
  stamp t_nb = since(t0);
  what = "neighbour search";
  if (!pl)
    goto done;
  size_t pnnz = mfs_plan_nnz(pl);
  row(&r, "neighbour_search", t_nb, -1.0, -1.0, 8.0 * (double)pnnz);
  t_total = add(t_total, t_nb);
  stamp t_sh = {0, 0, 0};
  if (mode == MODE_TABLE) {
    t0 = now();
    st = mfs_plan_tabulate(pl, 1, NULL);
    t_sh = since(t0);
    what = "shape tables";
    if (st != MFS_OK)
      goto done;
    row(&r, "shape_tables", t_sh, partition_error(pl), -1.0, 24.0 * (double)pnnz);
    t_total = add(t_total, t_sh);
  }

  st = MFS_ENOMEM;
  m = malloc(p->n * sizeof *m);
  if (!m)
    goto done;
  /* the particles' lists of points (built by the first assembly, timed apart:
   * the rows need them with or without a CSR) */
  t0 = now();
  st = mfs_plan_transpose(pl);
  stamp t_tr = since(t0);
  what = "transpose";
  if (st != MFS_OK)
    goto done;
  row(&r, "transpose", t_tr, -1.0, -1.0, 4.0 * (double)pnnz + 8.0 * (double)p->n);
  t_total = add(t_total, t_tr);
  t0 = now();
  st = mfs_assemble(pl, &mat, NULL, &K, NULL, m, NULL);
  stamp t_asm = since(t0);
  what = "assembly";
  if (st != MFS_OK)
    goto done;
  double peak_total = peak_rss_mb();
  r.nnz = K->ptr[K->nrow];
  double sm = 0.0;
  for (size_t i = 0; i < p->n; i++)
    sm += m[i];
  fprintf(stderr, "bench_assembly: n = %d, %s: mass error %.3e\n", n_side, r.mode,
          fabs(sm - mat.density * area) / (mat.density * area));
  row(&r, "assembly", t_asm, k_ones(K), -1.0,
      12.0 * (double)r.nnz + 8.0 * (double)(K->nrow + p->n));
  t_total = add(t_total, t_asm);
  /* the CSR build's share (model mode): the assembly's time less that of
   * its rows alone (rows_only: the same evaluation and accumulation, no
   * CSR), over the assembly's (the transpose and mfs_assemble) */
  double share = -1.0;
  if (mode == MODE_MODEL) {
    /* CPU time (user + sys, every thread's): on a shared machine the wall
     * time of two passes run one after the other is not comparable */
    const double c_asm = t_asm.user + t_asm.sys, c_all = t_tr.user + t_tr.sys + c_asm;
    for (int fill = 0; fill < 2; fill++) {
      double *sum = malloc(p->n * sizeof *sum), *vals = NULL;
      st = MFS_ENOMEM;
      what = fill ? "values_only" : "rows_only";
      if (!sum || (fill && !(vals = malloc((r.nnz ? r.nnz : 1) * sizeof *vals)))) {
        free(sum);
        goto done;
      }
      t0 = now();
      size_t nbad = rows_only(pl, mat.modulus, mat.density, K, m, sum, vals);
      stamp t_rows = since(t0);
      free(sum);
      free(vals);
      if (nbad == SIZE_MAX)
        goto done;
      double c_rows = t_rows.user + t_rows.sys, sh = (c_asm - c_rows) / c_all;
      sh = sh < 0.0 ? 0.0 : sh;
      row(&r, what, t_rows, (double)nbad, sh,
          fill ? 8.0 * (double)(r.nnz + p->n) : 8.0 * (double)p->n);
      st = MFS_EINVAL;
      if (nbad) {
        fprintf(stderr, "bench_assembly: n = %d: %zu rows of %s differ from K's\n", n_side, nbad,
                what);
        goto done;
      }
      share = sh; /* the total's: beyond the numeric fill */
    }
  }
  r.peak = peak_total;
  row(&r, "total", t_total, -1.0, share,
      12.0 * (double)r.nnz + 8.0 * (double)(K->nrow + p->n) +
          (mode == MODE_TABLE ? 32.0 : 8.0) * (double)pnnz);
  /* the separate path of the solvers (a pattern reused): after the total's
   * peak, not in it; error: the entries that differ from the one sweep's */
  t0 = now();
  st = mfs_assemble_pattern(pl, 1, NULL, &K2);
  stamp t_pat = since(t0);
  what = "separate_pattern";
  if (st != MFS_OK)
    goto done;
  size_t ndiff = K2->ptr[K2->nrow] != r.nnz;
  for (size_t i = 0; i <= K->nrow && !ndiff; i++)
    ndiff += K2->ptr[i] != K->ptr[i];
  for (size_t e = 0; e < r.nnz && !ndiff; e++)
    ndiff += K2->idx[e] != K->idx[e];
  row(&r, "separate_pattern", t_pat, (double)ndiff, -1.0,
      4.0 * (double)r.nnz + 8.0 * (double)K->nrow);
  if (ndiff)
    fprintf(stderr, "bench_assembly: n = %d, %s: the separate pattern differs\n", n_side, r.mode);
  st = ndiff ? MFS_EINVAL : MFS_ENOMEM;
  if (ndiff || !(m2 = malloc(p->n * sizeof *m2)))
    goto done;
  t0 = now();
  st = mfs_assemble_fill(pl, &mat, NULL, K2, NULL, m2, NULL);
  stamp t_fill = since(t0);
  what = "separate_fill";
  if (st != MFS_OK)
    goto done;
  for (size_t e = 0; e < r.nnz; e++)
    ndiff += K2->val[e] != K->val[e];
  for (size_t i = 0; i < p->n; i++)
    ndiff += m2[i] != m[i];
  row(&r, "separate_fill", t_fill, (double)ndiff, -1.0,
      8.0 * (double)r.nnz + 8.0 * (double)p->n);
  st = MFS_EINVAL;
  if (ndiff) {
    fprintf(stderr, "bench_assembly: n = %d, %s: %zu values of the separate fill differ\n",
            n_side, r.mode, ndiff);
    goto done;
  }
  mfs_csr_free(K2);
  K2 = NULL;
  mfs_csr_free(K);
  K = NULL;
  if (!checks || mode != MODE_TABLE) {
    rc = 0;
    goto done;
  }

  /* cross-checks, after the library pipeline's peak */
  const size_t *tptr;
  const int *tidx;
  const double *tab;
  mfs_plan_table(pl, &tptr, &tidx, &tab);
  st = MFS_ENOMEM;
  what = "reference";
  ref = malloc((pnnz ? pnnz : 1) * NCOMP * sizeof *ref);
  if (!ref)
    goto done;
  for (int global = 0; global < 2; global++) {
    t0 = now();
    size_t nfail = reference_tables(pl, global, ref);
    stamp t_ref = since(t0);
    row(&r, global ? "reference_shape_tables_global" : "reference_shape_tables", t_ref,
        nfail ? INFINITY : max_diff(pnnz * NCOMP, ref, tab), t_ref.wall / t_sh.wall, 0.0);
  }
  st = MFS_OK;
  rc = 0;
done:
  if (rc)
    fprintf(stderr, "bench_assembly: n = %d: %s: %s\n", n_side, what, mfs_strerror(st));
  free(ref);
  free(m);
  free(m2);
  mfs_csr_free(K);
  mfs_csr_free(K2);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return rc;
}

int main(int argc, char **argv)
{
  const char *outpath = NULL;
  int sizes[64], ns = 0, checks = 1, reps = 1, mode_lo = MODE_MODEL, mode_hi = MODE_SOLVER;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      printf("usage: bench_assembly [-o FILE] [--repeat R] [--no-checks] "
             "[--mode model|table|solver|all] [N ...]\n"
             "  N x N square lattice (default 1000), each size and mode R times (default 1) in\n"
             "  a fresh process; --no-checks: no reference tables\n");
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
    if (strcmp(argv[i], "--mode") == 0) {
      const char *v = i + 1 < argc ? argv[++i] : "";
      int k = -1;
      for (int j = 0; j < 3; j++)
        if (strcmp(v, mode_names[j]) == 0)
          k = j;
      if (k < 0 && strcmp(v, "all") != 0) {
        fprintf(stderr, "bench_assembly: --mode: expected model, table, solver or all\n");
        return 2;
      }
      mode_lo = k < 0 ? MODE_MODEL : k;
      mode_hi = k < 0 ? MODE_SOLVER : k;
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
  /* measured in a child: libgomp's threads do not survive fork(), and a
   * child forked after the parent's first parallel region waits for them
   * forever in its own first one */
  double bps = 0.0;
  int pfd[2];
  if (pipe(pfd) == 0) {
    pid_t pid = fork();
    if (pid == 0) {
      double b = bench_bandwidth_bps();
      _exit(write(pfd[1], &b, sizeof b) == (ssize_t)sizeof b ? 0 : 1);
    }
    close(pfd[1]);
    if (pid > 0 && read(pfd[0], &bps, sizeof bps) != (ssize_t)sizeof bps)
      bps = 0.0;
    close(pfd[0]);
    if (pid > 0)
      waitpid(pid, NULL, 0);
  }
  fprintf(f, "n_side,nodes,quad_points,rep,mode,threads,phase,seconds,user_s,sys_s,peak_rss_mb,"
             "nnz_K,bytes_per_nnz,error,ratio,limit_s,fraction,bandwidth_gbs,load_1min\n");
  fflush(f);
  int rc = 0;
  for (int s = 0; s < ns; s++)
    for (int rep = 1; rep <= reps; rep++)
      for (int mode = mode_lo; mode <= mode_hi; mode++) {
        pid_t pid = fork(); /* a fresh process per run: its own peak RSS */
        if (pid == 0) {
          int c = bench(f, sizes[s], rep, (bench_mode)mode, checks, bps);
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
