#include "mfs_symop.h"
#include "mfs_alloc.h"

#include <string.h>

#include "mfs_huge.h"

#include "mfs_omp.h"
#include "mfs_status.h"

#define NB MFS_SYMOP_BLOCKS
/* GCC's and Clang's vector types for the products (plain C otherwise, the
 * same sums lane by lane) */
#if defined(__GNUC__)
#define SYMOP_V2D 1
typedef double v2d __attribute__((vector_size(16)));
#endif

void mfs_symop_free(mfs_symop *A)
{
  mfs_free(A->ptr);
  mfs_free(A->rptr);
  mfs_free(A->run);
  mfs_free(A->val);
  mfs_free(A->diag);
  mfs_free(A->z);
  memset(A, 0, sizeof *A);
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

/* Entry e of block row i (block columns idx) starts a run: the first of its
 * row, not the successor of the one before, or the first column beyond its
 * block (hi). */
static int run_starts(const size_t *ptr, const int *idx, size_t i, size_t e, size_t hi)
{
  return e == ptr[i] || idx[e] != idx[e - 1] + 1 || (size_t)idx[e] == hi;
}

/* The blocks of rows, their band buffers and the runs, from the sorted
 * block columns idx of each block row. */
static int op_finish(mfs_symop *A, const int *idx)
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
  size_t nr = 0;
  for (int t = 0; t < NB; t++) {
    size_t top = A->cut[t + 1];
    w = 0;
    for (size_t i = A->cut[t]; i < top; i++)
      for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
        if ((size_t)idx[e] + 1 > top + w)
          w = (size_t)idx[e] + 1 - top;
        nr += (size_t)run_starts(A->ptr, idx, i, e, top);
      }
    A->zoff[t + 1] = A->zoff[t] + w * (size_t)A->b;
  }
  A->z = mfs_malloc((A->zoff[NB] ? A->zoff[NB] : 1) * sizeof *A->z);
  A->rptr = mfs_malloc((nb + 1) * sizeof *A->rptr);
  A->run = mfs_malloc((nr ? nr : 1) * sizeof *A->run);
  if (!A->z || !A->rptr || !A->run)
    return MFS_ENOMEM;
  mfs_advise_huge(A->run, nr * sizeof *A->run);
  size_t q = 0;
  A->rptr[0] = 0;
  for (int t = 0; t < NB; t++)
    for (size_t i = A->cut[t]; i < A->cut[t + 1]; i++) {
      for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
        if (run_starts(A->ptr, idx, i, e, A->cut[t + 1]))
          A->run[q++] = (mfs_symop_run){.col = idx[e], .len = 1};
        else
          A->run[q - 1].len++;
      A->rptr[i + 1] = q;
    }
  A->runs = nr;
  return MFS_OK;
}

/* A builder's end: on success its block columns idx go to the caller (who
 * finishes A from them and frees them), else A and idx are freed. */
static int built(int st, mfs_symop *A, int *idx, int **idxp)
{
  if (st == MFS_OK) {
    *idxp = idx;
    return MFS_OK;
  }
  mfs_free(idx);
  mfs_symop_free(A);
  return st;
}

/* The 2 x 2 build for K made of full blocks in sorted rows (plane strain as
 * mfs_assemble writes it): rows 2i and 2i+1 have the same columns,
 * ascending, in pairs (2j, 2j+1).  The first pass checks it and counts each
 * block row's upper blocks; MFS_ENOTSUP if K is not of that form (then
 * op_build).  The fill needs no scratch and no search, and with x0 it takes
 * the first product y0 = A x0 from the full rows it reads anyway, so the
 * first Lanczos step does not read the operator again.  Each block row on
 * its own (on the threads; the same result).  (Reading K's upper halves in
 * place instead of a copy, no fill at all, made each product 3 times
 * slower: the runs of half rows defeat the prefetchers; the copy is one
 * stream.) */
static int op_build_pairs(const mfs_csr *K, const double *s, const double *restrict x0,
                          double *restrict y0, int nt, int par, mfs_symop *A, int **idxp)
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
  /* the upper blocks of each block row: its pairs beyond the diagonal, by
   * bisection of row 2 bi's sorted columns (the fill checks the form) */
  MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par) reduction(|:bad)")
  for (long bi = 0; bi < (long)nb; bi++) {
    size_t r0 = kp[2 * bi], r1 = kp[2 * bi + 1], len = r1 - r0, lo = 0, hi = len / 2;
    if (len != kp[2 * bi + 2] - r1 || len % 2) {
      bad = 1;
      continue;
    }
    while (lo < hi) { /* the first pair whose column is beyond 2 bi */
      size_t mid = lo + (hi - lo) / 2;
      if (ki[r0 + 2 * mid] > 2 * bi)
        hi = mid;
      else
        lo = mid + 1;
    }
    A->ptr[bi + 1] = len / 2 - lo;
  }
  if (bad) {
    mfs_symop_free(A);
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
  int *idx = mfs_malloc((nbl ? nbl : 1) * sizeof *idx);
  A->val = mfs_malloc((nbl ? 4 * nbl : 1) * sizeof *A->val);
  int st = MFS_ENOMEM;
  if (!A->diag || !idx || !A->val)
    goto done;
  mfs_advise_huge(A->val, 4 * nbl * sizeof *A->val);
  MFS_OMP("omp parallel for schedule(static) num_threads(nt) if (par) reduction(|:bad)")
  for (long bi = 0; bi < (long)nb; bi++) {
    size_t r0 = kp[2 * bi], r1 = kp[2 * bi + 1], len = r1 - r0, p = A->ptr[bi];
    double s0 = s ? s[2 * bi] : 1.0, s1 = s ? s[2 * bi + 1] : 1.0, y0s = 0.0, y1s = 0.0;
    for (size_t e = 0; e < len; e += 2) {
      int ci = ki[r0 + e];
      if (ci % 2 || ki[r0 + e + 1] != ci + 1 || ki[r1 + e] != ci || ki[r1 + e + 1] != ci + 1 ||
          (e > 0 && ci <= ki[r0 + e - 1]) || (ci > 2 * bi && p == A->ptr[bi + 1])) {
        bad = 1; /* not full sorted 2 x 2 blocks: the general build */
        break;
      }
      size_t c = (size_t)ci;
      double t0 = s ? s[c] : 1.0, t1 = s ? s[c + 1] : 1.0;
      double a00 = s0 * kv[r0 + e] * t0, a01 = s0 * kv[r0 + e + 1] * t1;
      double a10 = s1 * kv[r1 + e] * t0, a11 = s1 * kv[r1 + e + 1] * t1;
      if (x0) {
        y0s += a00 * x0[c] + a01 * x0[c + 1];
        y1s += a10 * x0[c] + a11 * x0[c + 1];
      }
      if (c == 2 * (size_t)bi) { /* the diagonal block from its upper triangle */
        double *d = A->diag + 4 * bi;
        d[0] = a00;
        d[1] = d[2] = a01;
        d[3] = a11;
      } else if (c > 2 * (size_t)bi) {
        double *a = A->val + 4 * p;
        idx[p++] = (int)(c / 2);
        a[0] = a00;
        a[1] = a01;
        a[2] = a10;
        a[3] = a11;
      }
    }
    if (x0) {
      y0[2 * bi] = y0s;
      y0[2 * bi + 1] = y1s;
    }
  }
  st = bad ? MFS_ENOTSUP : MFS_OK;
done:
  return built(st, A, idx, idxp);
}

/* The general build from K and s; work: n ints of scratch. */
static int op_build(const mfs_csr *K, const double *s, int *work, mfs_symop *A, int **idxp)
{
  size_t n = K->nrow;
  memset(A, 0, sizeof *A);
  int b = choose_block(K, work), bb = b * b, *idx = NULL, st = MFS_ENOMEM;
  size_t nb = n / (size_t)b;
  A->n = n;
  A->nb = nb;
  A->b = b;
  A->ptr = mfs_malloc((nb + 1) * sizeof *A->ptr);
  A->diag = mfs_calloc(nb * (size_t)bb, sizeof *A->diag);
  if (!A->ptr || !A->diag)
    goto done;
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
  idx = mfs_malloc((nbl ? nbl : 1) * sizeof *idx);
  A->val = mfs_malloc((nbl ? nbl * (size_t)bb : 1) * sizeof *A->val);
  if (!idx || !A->val)
    goto done;
  mfs_advise_huge(A->val, nbl * (size_t)bb * sizeof *A->val);
  memset(A->val, 0, (nbl ? nbl * (size_t)bb : 1) * sizeof *A->val);
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
          for (; k > p0 && idx[k - 1] > (int)bj; k--)
            idx[k] = idx[k - 1];
          idx[k] = (int)bj;
        }
      }
    for (size_t k = p0; k < p; k++)
      work[idx[k]] = (int)k;
    for (size_t r = (size_t)b * bi; r < (size_t)b * (bi + 1); r++) {
      size_t ri = r - (size_t)b * bi;
      for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
        size_t j = (size_t)K->idx[e], bj = j / (size_t)b, cj = j - bj * (size_t)b;
        double v = s ? s[r] * K->val[e] * s[j] : K->val[e];
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
  st = MFS_OK;
done:
  return built(st, A, idx, idxp);
}

int mfs_symop_build(const mfs_csr *K, const double *s, const double *x0, double *y0, int nt,
                    int par, mfs_symop *A, int *have_y)
{
  int *idx = NULL;
  *have_y = 0;
  int st = op_build_pairs(K, s, x0, y0, nt, par, A, &idx);
  if (st == MFS_OK) {
    *have_y = x0 != NULL;
  } else if (st == MFS_ENOTSUP) {
    int *work = mfs_malloc((K->nrow ? K->nrow : 1) * sizeof *work);
    st = work ? op_build(K, s, work, A, &idx) : MFS_ENOMEM;
    mfs_free(work);
  }
  if (st == MFS_OK)
    st = op_finish(A, idx);
  mfs_free(idx);
  if (st != MFS_OK) {
    mfs_symop_free(A);
    *have_y = 0;
  }
  return st;
}

/* The 2 x 2 rows of block t: for each block row the blocks' two row sums
 * lane-wise (summed at the row's end) and the transposed scatter to
 * (y_2j, y_2j+1), one 2-vector update per block. */
static void block_rows2(const mfs_symop *A, size_t lo, size_t hi, const double *restrict x,
                        double *restrict y, double *restrict zb)
{
  const size_t *restrict ptr = A->ptr, *restrict rptr = A->rptr;
  const mfs_symop_run *restrict run = A->run;
  const double *restrict dg = A->diag;
  for (size_t i = 2 * lo; i < 2 * hi; i++)
    y[i] = 0.0;
  for (size_t i = lo; i < hi; i++) {
    const double *d = dg + 4 * i, *v = A->val + 4 * ptr[i];
    double x0 = x[2 * i], x1 = x[2 * i + 1];
#ifdef SYMOP_V2D
    v2d x0v = {x0, x0}, x1v = {x1, x1}, acc0 = {0.0, 0.0}, acc1 = {0.0, 0.0};
#else
    double a00 = 0.0, a01 = 0.0, a10 = 0.0, a11 = 0.0;
#endif
    for (size_t r = rptr[i]; r < rptr[i + 1]; r++) {
      size_t c = (size_t)run[r].col, len = (size_t)run[r].len;
      const double *xr = x + 2 * c;
      double *yr = c < hi ? y + 2 * c : zb + 2 * (c - hi);
      for (size_t k = 0; k < len; k++, v += 4) {
#ifdef SYMOP_V2D
        v2d r0, r1, xj, yv;
        memcpy(&r0, v, sizeof r0);
        memcpy(&r1, v + 2, sizeof r1);
        memcpy(&xj, xr + 2 * k, sizeof xj);
        acc0 += r0 * xj;
        acc1 += r1 * xj;
        memcpy(&yv, yr + 2 * k, sizeof yv);
        yv += r0 * x0v + r1 * x1v;
        memcpy(yr + 2 * k, &yv, sizeof yv);
#else
        double xj0 = xr[2 * k], xj1 = xr[2 * k + 1];
        a00 += v[0] * xj0;
        a01 += v[1] * xj1;
        a10 += v[2] * xj0;
        a11 += v[3] * xj1;
        yr[2 * k] += v[0] * x0 + v[2] * x1;
        yr[2 * k + 1] += v[1] * x0 + v[3] * x1;
#endif
      }
    }
#ifdef SYMOP_V2D
    double a00 = acc0[0], a01 = acc0[1], a10 = acc1[0], a11 = acc1[1];
#endif
    y[2 * i] += d[0] * x0 + d[1] * x1 + (a00 + a01);
    y[2 * i + 1] += d[2] * x0 + d[3] * x1 + (a10 + a11);
  }
}

/* The scalar rows of block t: each run read and updated two entries per
 * 2-vector, the row's sum in two lanes (even and odd positions of its runs;
 * an odd run's last entry apart), added at the row's end.  One loop over
 * column indices, one entry at a time, ran at about half the bandwidth (its
 * instructions bounded it): the runs took 10-13 % less time per product
 * (bench_eigs 316, the cubic anti-plane model: 5.5 entries per run). */
static void block_rows1(const mfs_symop *A, size_t lo, size_t hi, const double *restrict x,
                        double *restrict y, double *restrict zb)
{
  const size_t *restrict ptr = A->ptr, *restrict rptr = A->rptr;
  const mfs_symop_run *restrict run = A->run;
  const double *restrict dg = A->diag;
  for (size_t i = lo; i < hi; i++)
    y[i] = dg[i] * x[i];
  for (size_t i = lo; i < hi; i++) {
    const double *v = A->val + ptr[i];
    double xi = x[i], s0 = 0.0, s1 = 0.0, t = 0.0;
#ifdef SYMOP_V2D
    v2d acc = {0.0, 0.0}, xiv = {xi, xi};
#endif
    for (size_t r = rptr[i]; r < rptr[i + 1]; r++) {
      size_t c = (size_t)run[r].col, len = (size_t)run[r].len, k = 0;
      const double *xr = x + c;
      double *yr = c < hi ? y + c : zb + (c - hi);
      for (; k + 1 < len; k += 2) {
#ifdef SYMOP_V2D
        v2d a, xx, yy;
        memcpy(&a, v + k, sizeof a);
        memcpy(&xx, xr + k, sizeof xx);
        memcpy(&yy, yr + k, sizeof yy);
        acc += a * xx;
        yy += a * xiv;
        memcpy(yr + k, &yy, sizeof yy);
#else
        s0 += v[k] * xr[k];
        s1 += v[k + 1] * xr[k + 1];
        yr[k] += v[k] * xi;
        yr[k + 1] += v[k + 1] * xi;
#endif
      }
      if (k < len) {
        t += v[k] * xr[k];
        yr[k] += v[k] * xi;
      }
      v += len;
    }
#ifdef SYMOP_V2D
    s0 = acc[0];
    s1 = acc[1];
#endif
    y[i] += (s0 + s1) + t;
  }
}

void mfs_symop_block(const mfs_symop *A, int t, const double *restrict x, double *restrict y)
{
  size_t lo = A->cut[t], hi = A->cut[t + 1], wb = A->zoff[t + 1] - A->zoff[t];
  double *restrict zb = A->z + A->zoff[t];
  for (size_t k = 0; k < wb; k++)
    zb[k] = 0.0;
  if (A->b == 2)
    block_rows2(A, lo, hi, x, y, zb);
  else
    block_rows1(A, lo, hi, x, y, zb);
}

void mfs_symop_bands(const mfs_symop *A, int t, double *restrict y)
{
  size_t b = (size_t)A->b, lo = b * A->cut[t], hi = b * A->cut[t + 1];
  for (int u = 0; u < t; u++) {
    size_t z0 = b * A->cut[u + 1], z1 = z0 + A->zoff[u + 1] - A->zoff[u];
    const double *zu = A->z + A->zoff[u];
    size_t r0 = z0 > lo ? z0 : lo, r1 = z1 < hi ? z1 : hi;
    for (size_t r = r0; r < r1; r++)
      y[r] += zu[r - z0];
  }
}

void mfs_symop_apply(const mfs_symop *A, const double *x, double *y)
{
  const int nt = mfs_omp_threads(), par = nt > 1 && A->stored >= MFS_SYMOP_PARALLEL_MIN;
  if (par) {
    MFS_OMP("omp parallel num_threads(nt)")
    {
      MFS_OMP("omp for schedule(static)")
      for (int t = 0; t < NB; t++)
        mfs_symop_block(A, t, x, y);
      MFS_OMP("omp for schedule(static)")
      for (int t = 0; t < NB; t++)
        mfs_symop_bands(A, t, y);
    }
  } else { /* the same blocks on the calling thread, without a parallel region
            * (a one-thread region's outlined loop ran about 20 % slower) */
    for (int t = 0; t < NB; t++)
      mfs_symop_block(A, t, x, y);
    for (int t = 0; t < NB; t++)
      mfs_symop_bands(A, t, y);
  }
}

double mfs_symop_bytes(const mfs_symop *A)
{
  return 8.0 * (double)A->stored + (double)(A->runs * sizeof(mfs_symop_run)) +
         16.0 * (double)(A->nb + 1) + 8.0 * (double)(A->nb * (size_t)(A->b * A->b)) +
         16.0 * (double)A->n;
}
