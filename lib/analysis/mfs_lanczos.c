#include "mfs_lanczos.h"
#include "mfs_alloc.h"

#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#include "mfs_lapack.h"
#include "mfs_omp.h"

#define NB MFS_LANCZOS_BLOCKS
/* GCC's and Clang's vector types for the 2 x 2 product (plain C otherwise) */
#if defined(__GNUC__)
#define LZ_V2D 1
typedef double v2d __attribute__((vector_size(16)));
#endif
/* Below this many stored scalar entries (24 MB) the blocks run on the
 * calling thread (as mfs_eig_max's product: a parallel region per product
 * costs more than it gains there; the sums are the same). */
#define LZ_PARALLEL_MIN ((size_t)1 << 21)

/* The operator A = diag(s) K diag(s), s = m^-1/2: diagonal blocks and the
 * strict upper block triangle, block size b (1 or 2), in block rows. */
typedef struct {
  size_t n, nb;        /* scalar rows; block rows n / b */
  int b;               /* block size */
  size_t *ptr;         /* nb + 1 */
  int *idx;            /* block columns of the stored upper blocks, sorted by row */
  double *val;         /* b*b per stored block, row-major */
  double *diag;        /* b*b per block row: the diagonal block */
  size_t stored;       /* scalar entries stored (upper blocks) */
  size_t cut[NB + 1];  /* block t: block rows cut[t] .. cut[t+1]-1 */
  size_t zoff[NB + 1]; /* block t's band buffer (scalar): z[zoff[t] .. zoff[t+1]-1] */
  double *z;
} lz_op;

static void op_free(lz_op *A)
{
  mfs_free(A->ptr);
  mfs_free(A->idx);
  mfs_free(A->val);
  mfs_free(A->diag);
  mfs_free(A->z);
  memset(A, 0, sizeof *A);
}

static double wall(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The upper block count for block size 2 (mark: nb ints, scratch) and the
 * scalar upper count, to choose the storage that reads fewer bytes. */
static int choose_block(const mfs_csr *K, int *mark)
{
  size_t n = K->nrow, upper = 0, blocks = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++)
      upper += (size_t)K->idx[e] > i;
  if (n % 2)
    return 1;
  size_t nb = n / 2;
  for (size_t bi = 0; bi < nb; bi++)
    mark[bi] = -1;
  for (size_t bi = 0; bi < nb; bi++)
    for (size_t r = 2 * bi; r < 2 * bi + 2; r++)
      for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
        size_t bj = (size_t)K->idx[e] / 2;
        if (bj > bi && mark[bj] != (int)bi) {
          mark[bj] = (int)bi;
          blocks++;
        }
      }
  double b1 = 12.0 * (double)upper + 16.0 * (double)n;
  double b2 = 36.0 * (double)blocks + 8.0 * (double)nb + 32.0 * (double)nb;
  return b2 < b1 ? 2 : 1;
}

/* The blocks of rows and their band buffers (as mfs_eigen.c's sym_csr). */
static int op_cut(lz_op *A)
{
  size_t nb = A->nb, nnz = A->ptr[nb], r = 0, w = 0;
  A->cut[0] = 0;
  for (int t = 1; t <= NB; t++) {
    size_t want = (size_t)((double)nnz * t / NB);
    while (r < nb && (t == NB || A->ptr[r] < want))
      r++;
    A->cut[t] = r;
  }
  A->zoff[0] = 0;
  for (int t = 0; t < NB; t++) {
    size_t top = A->cut[t + 1];
    w = 0;
    for (size_t i = A->cut[t]; i < top; i++)
      for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
        if ((size_t)A->idx[e] + 1 > top + w)
          w = (size_t)A->idx[e] + 1 - top;
    A->zoff[t + 1] = A->zoff[t] + w * (size_t)A->b;
  }
  A->z = mfs_malloc((A->zoff[NB] ? A->zoff[NB] : 1) * sizeof *A->z);
  return A->z ? MFS_OK : MFS_ENOMEM;
}

/* The 2 x 2 build for K made of full blocks in sorted rows (plane strain as
 * mfs_assemble writes it): rows 2i and 2i+1 have the same columns,
 * ascending, in pairs (2j, 2j+1).  The first pass checks it and counts each
 * block row's upper blocks; MFS_ENOTSUP if K is not of that form (then
 * op_build).  The fill needs no scratch and no search, and it takes the
 * first product y0 = A x0 from the full rows it reads anyway, so the first
 * Lanczos step does not read the operator again.  Each block row on its own
 * (on the threads; the same result).  (Reading K's upper halves in place
 * instead of a copy, no fill at all, made each product 3 times slower: the
 * runs of half rows defeat the prefetchers; the copy is one stream.) */
static int op_build_pairs(const mfs_csr *K, const double *s, const double *restrict x0,
                          double *restrict y0, int nt, int par, lz_op *A)
{
  size_t n = K->nrow, nb = n / 2;
  const size_t *kp = K->ptr;
  const int *ki = K->idx;
  const double *kv = K->val;
  if (n % 2)
    return MFS_ENOTSUP;
  memset(A, 0, sizeof *A);
  A->ptr = mfs_malloc((nb + 1) * sizeof *A->ptr);
  if (!A->ptr)
    return MFS_ENOMEM;
  (void)nt;
  (void)par;
  int bad = 0;
  A->ptr[0] = 0;
  MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par) reduction(|:bad)")
  for (long bi = 0; bi < (long)nb; bi++) {
    size_t r0 = kp[2 * bi], r1 = kp[2 * bi + 1], len = r1 - r0, up = 0;
    if (len != kp[2 * bi + 2] - r1 || len % 2) {
      bad = 1;
      continue;
    }
    for (size_t e = 0; e < len; e += 2) {
      int c = ki[r0 + e];
      if (c % 2 || ki[r0 + e + 1] != c + 1 || ki[r1 + e] != c || ki[r1 + e + 1] != c + 1 ||
          (e > 0 && c <= ki[r0 + e - 1])) {
        bad = 1;
        break;
      }
      up += c > 2 * bi;
    }
    A->ptr[bi + 1] = up;
  }
  if (bad) {
    op_free(A);
    return MFS_ENOTSUP;
  }
  A->n = n;
  A->nb = nb;
  A->b = 2;
  for (size_t bi = 0; bi < nb; bi++)
    A->ptr[bi + 1] += A->ptr[bi];
  size_t nbl = A->ptr[nb];
  A->stored = 4 * nbl;
  A->diag = mfs_calloc(4 * nb, sizeof *A->diag);
  A->idx = mfs_malloc((nbl ? nbl : 1) * sizeof *A->idx);
  A->val = mfs_malloc((nbl ? 4 * nbl : 1) * sizeof *A->val);
  if (!A->diag || !A->idx || !A->val)
    goto oom;
  MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par)")
  for (long bi = 0; bi < (long)nb; bi++) {
    size_t r0 = kp[2 * bi], r1 = kp[2 * bi + 1], len = r1 - r0, p = A->ptr[bi];
    double s0 = s[2 * bi], s1 = s[2 * bi + 1], y0s = 0.0, y1s = 0.0;
    for (size_t e = 0; e < len; e += 2) {
      size_t c = (size_t)ki[r0 + e];
      double t0 = s[c], t1 = s[c + 1];
      double a00 = s0 * kv[r0 + e] * t0, a01 = s0 * kv[r0 + e + 1] * t1;
      double a10 = s1 * kv[r1 + e] * t0, a11 = s1 * kv[r1 + e + 1] * t1;
      y0s += a00 * x0[c] + a01 * x0[c + 1];
      y1s += a10 * x0[c] + a11 * x0[c + 1];
      if (c == 2 * (size_t)bi) { /* the diagonal block from its upper triangle */
        double *d = A->diag + 4 * bi;
        d[0] = a00;
        d[1] = d[2] = a01;
        d[3] = a11;
      } else if (c > 2 * (size_t)bi) {
        double *a = A->val + 4 * p;
        A->idx[p++] = (int)(c / 2);
        a[0] = a00;
        a[1] = a01;
        a[2] = a10;
        a[3] = a11;
      }
    }
    y0[2 * bi] = y0s;
    y0[2 * bi + 1] = y1s;
  }
  if (op_cut(A) != MFS_OK)
    goto oom;
  return MFS_OK;
oom:
  op_free(A);
  return MFS_ENOMEM;
}

/* Build A from K and s; work: n ints of scratch. */
static int op_build(const mfs_csr *K, const double *s, int *work, lz_op *A)
{
  size_t n = K->nrow;
  memset(A, 0, sizeof *A);
  int b = choose_block(K, work), bb = b * b;
  size_t nb = n / (size_t)b;
  A->n = n;
  A->nb = nb;
  A->b = b;
  A->ptr = mfs_malloc((nb + 1) * sizeof *A->ptr);
  A->diag = mfs_calloc(nb * (size_t)bb, sizeof *A->diag);
  if (!A->ptr || !A->diag)
    goto oom;
  /* count the upper blocks of each block row */
  for (size_t bi = 0; bi < nb; bi++)
    work[bi] = -1;
  A->ptr[0] = 0;
  for (size_t bi = 0; bi < nb; bi++) {
    size_t c = 0;
    for (size_t r = (size_t)b * bi; r < (size_t)b * (bi + 1); r++)
      for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
        size_t bj = (size_t)K->idx[e] / (size_t)b;
        if (bj > bi && work[bj] != (int)bi) {
          work[bj] = (int)bi;
          c++;
        }
      }
    A->ptr[bi + 1] = A->ptr[bi] + c;
  }
  size_t nbl = A->ptr[nb];
  A->stored = nbl * (size_t)bb;
  A->idx = mfs_malloc((nbl ? nbl : 1) * sizeof *A->idx);
  A->val = mfs_calloc(nbl ? nbl * (size_t)bb : 1, sizeof *A->val);
  if (!A->idx || !A->val)
    goto oom;
  /* the columns of each block row, sorted (insertion: rows are short),
   * then the values through work[bj] = position of block bj in this row */
  for (size_t bi = 0; bi < nb; bi++)
    work[bi] = -1;
  for (size_t bi = 0; bi < nb; bi++) {
    size_t p0 = A->ptr[bi], p = p0;
    for (size_t r = (size_t)b * bi; r < (size_t)b * (bi + 1); r++)
      for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
        size_t bj = (size_t)K->idx[e] / (size_t)b;
        if (bj > bi && work[bj] != -2 - (int)bi) {
          work[bj] = -2 - (int)bi; /* seen in this row */
          size_t k = p++;
          for (; k > p0 && A->idx[k - 1] > (int)bj; k--)
            A->idx[k] = A->idx[k - 1];
          A->idx[k] = (int)bj;
        }
      }
    for (size_t k = p0; k < p; k++)
      work[A->idx[k]] = (int)k;
    for (size_t r = (size_t)b * bi; r < (size_t)b * (bi + 1); r++) {
      size_t ri = r - (size_t)b * bi;
      for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
        size_t j = (size_t)K->idx[e], bj = j / (size_t)b, cj = j - bj * (size_t)b;
        double v = s[r] * K->val[e] * s[j];
        if (bj > bi) {
          A->val[(size_t)work[bj] * (size_t)bb + ri * (size_t)b + cj] += v;
        } else if (bj == bi && j >= r) { /* the diagonal block from its upper triangle */
          A->diag[bi * (size_t)bb + ri * (size_t)b + cj] += v;
          if (j > r)
            A->diag[bi * (size_t)bb + cj * (size_t)b + ri] += v;
        }
      }
    }
  }
  if (op_cut(A) != MFS_OK)
    goto oom;
  return MFS_OK;
oom:
  op_free(A);
  return MFS_ENOMEM;
}

/* Pass 1 of block t: y = A x for its rows, the scatter beyond them into its
 * band buffer. */
static void pass_product(const lz_op *A, int t, const double *restrict x, double *restrict y)
{
  const size_t *restrict ptr = A->ptr;
  const int *restrict idx = A->idx;
  const double *restrict val = A->val, *restrict dg = A->diag;
  size_t lo = A->cut[t], hi = A->cut[t + 1], wb = A->zoff[t + 1] - A->zoff[t];
  double *restrict zb = A->z + A->zoff[t];
  for (size_t k = 0; k < wb; k++)
    zb[k] = 0.0;
  if (A->b == 2) {
    for (size_t i = 2 * lo; i < 2 * hi; i++)
      y[i] = 0.0;
    for (size_t i = lo; i < hi; i++) {
      const double *d = dg + 4 * i;
      double x0 = x[2 * i], x1 = x[2 * i + 1];
#ifdef LZ_V2D
      /* a block's two rows and the pair x_j as 2-vectors: the row sums
       * accumulate lane-wise (summed at the row's end), the scatter to
       * (y_2j, y_2j+1) is one 2-vector update; half the instructions of the
       * scalar loop, whose 1-thread product ran at 0.5 of the bandwidth */
      v2d x0v = {x0, x0}, x1v = {x1, x1}, acc0 = {0.0, 0.0}, acc1 = {0.0, 0.0};
      for (size_t e = ptr[i]; e < ptr[i + 1]; e++) {
        size_t j = (size_t)idx[e];
        v2d r0, r1, xj, yv;
        memcpy(&r0, val + 4 * e, sizeof r0);
        memcpy(&r1, val + 4 * e + 2, sizeof r1);
        memcpy(&xj, x + 2 * j, sizeof xj);
        acc0 += r0 * xj;
        acc1 += r1 * xj;
        double *yj = j < hi ? y + 2 * j : zb + 2 * (j - hi);
        memcpy(&yv, yj, sizeof yv);
        yv += r0 * x0v + r1 * x1v;
        memcpy(yj, &yv, sizeof yv);
      }
      y[2 * i] += d[0] * x0 + d[1] * x1 + (acc0[0] + acc0[1]);
      y[2 * i + 1] += d[2] * x0 + d[3] * x1 + (acc1[0] + acc1[1]);
#else
      double s0 = d[0] * x0 + d[1] * x1, s1 = d[2] * x0 + d[3] * x1;
      for (size_t e = ptr[i]; e < ptr[i + 1]; e++) {
        size_t j = (size_t)idx[e];
        const double *a = val + 4 * e;
        double xj0 = x[2 * j], xj1 = x[2 * j + 1];
        s0 += a[0] * xj0 + a[1] * xj1;
        s1 += a[2] * xj0 + a[3] * xj1;
        double t0 = a[0] * x0 + a[2] * x1, t1 = a[1] * x0 + a[3] * x1;
        double *yj = j < hi ? y + 2 * j : zb + 2 * (j - hi);
        yj[0] += t0;
        yj[1] += t1;
      }
      y[2 * i] += s0;
      y[2 * i + 1] += s1;
#endif
    }
    return;
  }
  for (size_t i = lo; i < hi; i++)
    y[i] = dg[i] * x[i];
  for (size_t i = lo; i < hi; i++) {
    double xi = x[i], s = 0.0;
    for (size_t e = ptr[i]; e < ptr[i + 1]; e++) {
      size_t j = (size_t)idx[e];
      s += val[e] * x[j];
      if (j < hi)
        y[j] += val[e] * xi;
      else
        zb[j - hi] += val[e] * xi;
    }
    y[i] += s;
  }
}

/* Pass 2 of block t: the earlier blocks' bands into its rows of y (in block
 * order; not when y is whole: the first product, from the build), then
 * w = y - beta qp into qp, and the partial sums of q.w, w.w and q.q. */
static void pass_vectors(const lz_op *A, int t, double *restrict y, const double *restrict q,
                         double *restrict qp, double beta, int whole, double sums[3])
{
  size_t b = (size_t)A->b, lo = b * A->cut[t], hi = b * A->cut[t + 1];
  for (int u = 0; u < t && !whole; u++) {
    size_t z0 = b * A->cut[u + 1], z1 = z0 + A->zoff[u + 1] - A->zoff[u];
    const double *zu = A->z + A->zoff[u];
    size_t r0 = z0 > lo ? z0 : lo, r1 = z1 < hi ? z1 : hi;
    for (size_t r = r0; r < r1; r++)
      y[r] += zu[r - z0];
  }
  double sa = 0.0, sw = 0.0, sq = 0.0;
  for (size_t r = lo; r < hi; r++) {
    double w = y[r] - beta * qp[r];
    qp[r] = w;
    sa += q[r] * w;
    sw += w * w;
    sq += q[r] * q[r];
  }
  sums[0] = sa;
  sums[1] = sw;
  sums[2] = sq;
}

/* The largest eigenvalue theta of the k x k tridiagonal (d, e) and the last
 * component of its unit eigenvector. */
typedef struct {
  double *w, *z, *work;
  lapack_int *iblock, *isplit, *iwork, ifail[1];
} tri_ws;

static int tri_top(lapack_int k, const double *d, const double *e, tri_ws *t, double *theta,
                   double *last)
{
  if (k == 1) {
    *theta = d[0];
    *last = 1.0;
    return MFS_OK;
  }
  lapack_int m = 0, nsplit = 0;
  mfs_lapack_reset();
  lapack_int info = LAPACKE_dstebz_work('I', 'E', k, 0.0, 0.0, k, k, 0.0, d, e, &m, &nsplit,
                                        t->w, t->iblock, t->isplit, t->work, t->iwork);
  if (info != 0 || m != 1 || mfs_lapack_last()->count)
    return MFS_ELAPACK;
  info = LAPACKE_dstein_work(LAPACK_COL_MAJOR, k, d, e, 1, t->w, t->iblock, t->isplit, t->z, k,
                             t->work, t->iwork, t->ifail);
  if (info != 0 || mfs_lapack_last()->count)
    return MFS_ELAPACK;
  *theta = t->w[0];
  *last = t->z[k - 1];
  return MFS_OK;
}

static int pencil_ok(const mfs_pencil *P)
{
  if (!P || !P->K || (P->M == NULL) == (P->m == NULL))
    return MFS_EINVAL;
  size_t n = P->K->nrow;
  if (n < 2 || P->K->ncol != n || n > (size_t)INT32_MAX / 4)
    return MFS_EINVAL;
  if (P->M)
    return MFS_ENOTSUP;
  for (size_t i = 0; i < n; i++)
    if (!(P->m[i] > 0.0) || !isfinite(P->m[i]))
      return MFS_EINVAL;
  return MFS_OK;
}

mfs_status mfs_lanczos_max(const mfs_pencil *P, const mfs_lanczos_opts *opts, double *lambda,
                           mfs_lanczos_info *info)
{
  if (info)
    *info = (mfs_lanczos_info){0};
  double tol = opts && opts->tol != 0.0 ? opts->tol : 1e-8;
  int maxiter = opts && opts->maxiter != 0 ? opts->maxiter : 5000;
  if (!(tol >= 1e-14 && tol < 1.0) || maxiter < 0)
    return MFS_EINVAL;
  int st = pencil_ok(P);
  if (st != MFS_OK)
    return st;
  size_t n = P->K->nrow, kmax = (size_t)maxiter;
  lz_op A = {0};
  tri_ws tw = {0};
  double *s = mfs_malloc(n * sizeof *s), *q = mfs_malloc(n * sizeof *q),
         *qp = mfs_calloc(n, sizeof *qp), *y = mfs_malloc(n * sizeof *y);
  double *al = mfs_malloc((kmax + 1) * sizeof *al), *be = mfs_malloc((kmax + 1) * sizeof *be);
  int *work = mfs_malloc(n * sizeof *work);
  tw.w = mfs_malloc((kmax + 1) * sizeof *tw.w);
  tw.z = mfs_malloc((kmax + 1) * sizeof *tw.z);
  tw.work = mfs_malloc(5 * (kmax + 1) * sizeof *tw.work);
  tw.iblock = mfs_malloc((kmax + 1) * sizeof *tw.iblock);
  tw.isplit = mfs_malloc((kmax + 1) * sizeof *tw.isplit);
  tw.iwork = mfs_malloc(3 * (kmax + 1) * sizeof *tw.iwork);
  st = MFS_ENOMEM;
  if (!s || !q || !qp || !y || !al || !be || !work || !tw.w || !tw.z || !tw.work || !tw.iblock ||
      !tw.isplit || !tw.iwork)
    goto done;
  for (size_t i = 0; i < n; i++)
    s[i] = 1.0 / sqrt(P->m[i]);
  mfs_eig_start_vector(n, q); /* as mfs_eig_max */
  double nq = 0.0;
  for (size_t i = 0; i < n; i++)
    nq += q[i] * q[i];
  nq = 1.0 / sqrt(nq);
  for (size_t i = 0; i < n; i++)
    q[i] *= nq;
  const int nt = mfs_omp_threads();
  int par = P->K->ptr[n] >= 2 * LZ_PARALLEL_MIN, have_y = 1;
  double tb = wall();
  st = op_build_pairs(P->K, s, q, y, nt, par, &A);
  if (st == MFS_ENOTSUP) {
    have_y = 0; /* the general build: the first product by pass 1 */
    st = op_build(P->K, s, work, &A);
  }
  if (st != MFS_OK)
    goto done;
  tb = wall() - tb;
  mfs_free(work);
  work = NULL;
  if (info) {
    info->block = A.b;
    info->bytes = 12.0 * (double)A.stored * (A.b == 2 ? 0.75 : 1.0) +
                  8.0 * (double)(A.nb + 1) + 8.0 * (double)(A.nb * (size_t)(A.b * A.b)) +
                  16.0 * (double)n;
  }
  par = A.stored >= LZ_PARALLEL_MIN;
  (void)nt;
  (void)par;
  double beta = 0.0, theta = 0.0, bound = INFINITY, op_s = 0.0, sums[NB][3], ww[NB];
  int k = 0;
  st = MFS_ENOCONV;
  while (k < maxiter) {
    double t0 = wall(), t1 = t0;
    MFS_OMP("omp parallel num_threads(nt) if (par)")
    {
      if (!have_y) {
        MFS_OMP("omp for schedule(static)")
        for (int t = 0; t < NB; t++)
          pass_product(&A, t, q, y);
      }
      MFS_OMP("omp master")
      t1 = wall();
      MFS_OMP("omp for schedule(static)")
      for (int t = 0; t < NB; t++)
        pass_vectors(&A, t, y, q, qp, beta, have_y, sums[t]);
    }
    op_s += t1 - t0;
    have_y = 0;
    double alpha = 0.0, w2 = 0.0, q2 = 0.0;
    for (int t = 0; t < NB; t++) {
      alpha += sums[t][0];
      w2 += sums[t][1];
      q2 += sums[t][2];
    }
    /* beta = ||w - alpha q||, w = A q - beta_prev q_prev: from the sums of
     * the same sweep, w.w - 2 alpha q.w + alpha^2 q.q (q.q taken, not assumed
     * 1: with q.q = 1 assumed, a normalization error grows by up to
     * alpha^2 / beta^2 a step and the Ritz values leave the spectrum: a 1D
     * Laplacian of order 400 gave 12 times lambda_max).  Where it cancels
     * (beta^2 < 1e-2 w.w: it would lose more than two digits) the
     * subtraction is done first and the norm taken of its result. */
    double b2 = w2 - 2.0 * alpha * alpha + alpha * alpha * q2;
    int exact = !(b2 > 1e-2 * w2);
    if (exact) {
      MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par)")
      for (int t = 0; t < NB; t++) {
        size_t lo = (size_t)A.b * A.cut[t], hi = (size_t)A.b * A.cut[t + 1];
        double sw = 0.0;
        for (size_t r = lo; r < hi; r++) {
          double w = qp[r] - alpha * q[r];
          qp[r] = w;
          sw += w * w;
        }
        ww[t] = sw;
      }
      b2 = 0.0;
      for (int t = 0; t < NB; t++)
        b2 += ww[t];
    }
    al[k] = alpha;
    be[k] = beta = sqrt(b2);
    k++;
    if (!isfinite(alpha) || !isfinite(beta)) {
      st = MFS_EDOMAIN;
      break;
    }
    double last = 1.0;
    if ((st = tri_top(k, al, be, &tw, &theta, &last)) != MFS_OK)
      break;
    bound = beta * fabs(last);
    if (bound <= tol * fabs(theta) || beta == 0.0) {
      st = MFS_OK;
      break;
    }
    st = MFS_ENOCONV;
    double ib = 1.0 / beta;
    MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par)")
    for (int t = 0; t < NB; t++) {
      size_t lo = (size_t)A.b * A.cut[t], hi = (size_t)A.b * A.cut[t + 1];
      if (exact)
        for (size_t r = lo; r < hi; r++)
          qp[r] *= ib;
      else
        for (size_t r = lo; r < hi; r++)
          qp[r] = (qp[r] - alpha * q[r]) * ib;
    }
    double *sw = q; /* q_{k+1} is in qp: it becomes q, q_k the previous one */
    q = qp;
    qp = sw;
  }
  if (st == MFS_OK || st == MFS_ENOCONV)
    *lambda = theta;
  if (info) {
    info->matvecs = k;
    info->bound = theta != 0.0 ? bound / fabs(theta) : INFINITY;
    info->op_seconds = op_s;
    info->setup_seconds = tb;
  }
done:
  op_free(&A);
  mfs_free(s);
  mfs_free(q);
  mfs_free(qp);
  mfs_free(y);
  mfs_free(al);
  mfs_free(be);
  mfs_free(work);
  mfs_free(tw.w);
  mfs_free(tw.z);
  mfs_free(tw.work);
  mfs_free(tw.iblock);
  mfs_free(tw.isplit);
  mfs_free(tw.iwork);
  return st;
}
