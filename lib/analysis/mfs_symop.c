#include "mfs_symop.h"
#include "mfs_alloc.h"

#include <stdint.h>
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
/* The fill's values with non-temporal stores where SSE2 has them and the
 * values are 16-byte aligned (mfs_set_allocator's may not be): the copy is
 * read again only by the next product, from memory; no read for ownership
 * of its 58 MB at 316, no cache filled with it (the build at 316, one
 * thread, 15 in one process alternating with 2c840da's: medians 0.60-0.74
 * of its time in three runs, 0.69-0.80 without, load 1.3-2.2) */
#if defined(SYMOP_V2D) && defined(__SSE2__)
#define SYMOP_STREAM 1
#include <emmintrin.h>
#endif

/* Software prefetch of the cache lines of bytes at p + ahead (a hint: nothing
 * happens without GCC's builtin; addresses beyond an array are only
 * computed as integers, never dereferenced).  The fill reads K's rows
 * SYMOP_FILL_AHEAD block rows ahead, the product its values SYMOP_AHEAD
 * bytes ahead: K's 4 KB pages end the hardware's streams, and the product's
 * short runs (4.5 blocks on the plane-strain lattice) left it below the
 * bandwidth (bench_lambda 316, one thread: the product's fastest of 60 went
 * from 4.2-4.4 to 3.4-3.5 ms with it, the same for 4, 8 and 16 KB ahead; the
 * medians, at loads of 2-3, did not change). */
#define SYMOP_FILL_AHEAD 4
#define SYMOP_AHEAD 8192
static inline void prefetch_range(const void *p, size_t ahead, size_t bytes)
{
#if defined(__GNUC__)
  uintptr_t a = ((uintptr_t)p + ahead) & ~(uintptr_t)63, e = (uintptr_t)p + ahead + bytes;
  for (; a < e; a += 64)
    __builtin_prefetch((const void *)a);
#else
  (void)p;
  (void)ahead;
  (void)bytes;
#endif
}

void mfs_symop_free(mfs_symop *A)
{
  mfs_free(A->ptr);
  if (A->mem) { /* val, diag and rptr in it */
    mfs_free(A->mem);
  } else {
    mfs_free(A->rptr);
    mfs_free(A->val);
    mfs_free(A->diag);
  }
  mfs_free(A->run);
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

/* The row blocks: cut where the stored blocks cross t nnz / NB (from ptr
 * alone). */
static void op_cuts(mfs_symop *A)
{
  size_t nb = A->nb, nnz = A->ptr[nb], r = 0;
  A->cut[0] = 0;
  for (int t = 1; t <= NB; t++) {
    size_t want = (size_t)((double)nnz * t / NB);
    while (r < nb && (t == NB || A->ptr[r] < want))
      r++;
    A->cut[t] = r;
  }
}

/* The band buffers from the widths w[t] (block columns beyond block t's
 * last row that its scatter reaches). */
static int op_bands(mfs_symop *A, const size_t *w)
{
  A->zoff[0] = 0;
  for (int t = 0; t < NB; t++)
    A->zoff[t + 1] = A->zoff[t] + w[t] * (size_t)A->b;
  A->z = mfs_malloc((A->zoff[NB] ? A->zoff[NB] : 1) * sizeof *A->z);
  return A->z ? MFS_OK : MFS_ENOMEM;
}

/* Entry e of block row i (block columns idx) starts a run: the first of its
 * row, not the successor of the one before, or the first column beyond its
 * block (hi). */
static int run_starts(const size_t *ptr, const int *idx, size_t i, size_t e, size_t hi)
{
  return e == ptr[i] || idx[e] != idx[e - 1] + 1 || (size_t)idx[e] == hi;
}

/* The runs and band buffers of the general build, from the sorted block
 * columns idx of each block row (the row blocks cut already). */
static int op_finish(mfs_symop *A, const int *idx)
{
  size_t nb = A->nb, nr = 0, w[NB];
  for (int t = 0; t < NB; t++) {
    size_t top = A->cut[t + 1], wt = 0;
    for (size_t i = A->cut[t]; i < top; i++)
      for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
        if ((size_t)idx[e] + 1 > top + wt)
          wt = (size_t)idx[e] + 1 - top;
        nr += (size_t)run_starts(A->ptr, idx, i, e, top);
      }
    w[t] = wt;
  }
  A->rptr = mfs_malloc((nb + 1) * sizeof *A->rptr);
  A->run = mfs_malloc((nr ? nr : 1) * sizeof *A->run);
  if (!A->rptr || !A->run || op_bands(A, w) != MFS_OK)
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

#if defined(__GNUC__)
#define SYMOP_INLINE __attribute__((always_inline)) inline /* has_s, has_x constants where called */
#else
#define SYMOP_INLINE inline
#endif

/* Pair e of rows v0, v1 (columns c, c + 1) scaled: a = s_r v t_c, row-major
 * (a00, a01, a10, a11); y0's two terms a_r0 x_c + a_r1 x_c+1 added to ys
 * (the same products and sums, in the same order, as scalar code). */
#ifdef SYMOP_V2D
static SYMOP_INLINE void pair_scaled(const double *restrict v0, const double *restrict v1,
                                     const double *restrict s, const double *restrict x0,
                                     size_t c, int has_s, int has_x, v2d s0v, v2d s1v,
                                     double *restrict a, v2d *ys, int nt_store)
{
  v2d r0, r1;
  memcpy(&r0, v0, sizeof r0);
  memcpy(&r1, v1, sizeof r1);
  if (has_s) {
    v2d t;
    memcpy(&t, s + c, sizeof t);
    r0 = s0v * r0 * t;
    r1 = s1v * r1 * t;
  }
#ifdef SYMOP_STREAM
  if (nt_store) {
    _mm_stream_pd(a, r0);
    _mm_stream_pd(a + 2, r1);
  } else
#endif
  {
    memcpy(a, &r0, sizeof r0);
    memcpy(a + 2, &r1, sizeof r1);
  }
  if (has_x) {
    v2d xv, p0, p1;
    memcpy(&xv, x0 + c, sizeof xv);
    p0 = r0 * xv;
    p1 = r1 * xv;
    /* (p0[0] + p0[1], p1[0] + p1[1]) */
    *ys += (v2d){p0[0], p1[0]} + (v2d){p0[1], p1[1]}; /* GCC and Clang alike */
  }
}
#else
static SYMOP_INLINE void pair_scaled(const double *restrict v0, const double *restrict v1,
                                     const double *restrict s, const double *restrict x0,
                                     size_t c, int has_s, int has_x, double s0, double s1,
                                     double *restrict a, double ys[2], int nt_store)
{
  (void)nt_store;
  double t0 = has_s ? s[c] : 1.0, t1 = has_s ? s[c + 1] : 1.0;
  a[0] = has_s ? s0 * v0[0] * t0 : v0[0];
  a[1] = has_s ? s0 * v0[1] * t1 : v0[1];
  a[2] = has_s ? s1 * v1[0] * t0 : v1[0];
  a[3] = has_s ? s1 * v1[1] * t1 : v1[1];
  if (has_x) {
    ys[0] += a[0] * x0[c] + a[1] * x0[c + 1];
    ys[1] += a[2] * x0[c] + a[3] * x0[c + 1];
  }
}
#endif

/* One block row of the 2 x 2 fill (rows of len entries, columns k0, k1,
 * values v0, v1; lo of its len / 2 pairs at or left of the diagonal): y0's
 * two entries from the full rows (every pair in order: the same sums as one
 * loop over the row), the diagonal block d, the upper blocks into a, and
 * their runs from run[q] (a run ends where the columns jump or reach top,
 * its row block's end); returns the runs' end, *last the last upper block
 * column + 1 (0: none); *bad |= anything not of the form (rows with other
 * columns, odd or unpaired columns, unsorted: the pairs from lo on are then
 * not the upper ones, and the build is dropped). */
static SYMOP_INLINE size_t fill_row2(const int *restrict k0, const int *restrict k1,
                                     const double *restrict v0, const double *restrict v1,
                                     size_t len, size_t lo, size_t bi, const double *restrict s,
                                     const double *restrict x0, int has_s, int has_x,
                                     double *restrict y0, double *restrict d, double *restrict a,
                                     mfs_symop_run *restrict run, size_t q, size_t top,
                                     int stream, size_t *last, int *bad)
{
  double t[4];
  int b = memcmp(k0, k1, len * sizeof *k0) != 0, prev = -2;
  size_t np = len / 2, p = 0;
#ifdef SYMOP_V2D
  double s0 = has_s ? s[2 * bi] : 1.0, s1 = has_s ? s[2 * bi + 1] : 1.0;
  v2d s0v = {s0, s0}, s1v = {s1, s1}, ys = {0.0, 0.0};
#define SYMOP_YS &ys
#else
  double s0 = has_s ? s[2 * bi] : 1.0, s1 = has_s ? s[2 * bi + 1] : 1.0, ys[2] = {0.0, 0.0};
  double s0v = s0, s1v = s1;
#define SYMOP_YS ys
#endif
  d[0] = d[1] = d[2] = d[3] = 0.0; /* (no diagonal block stored: zeros) */
  for (; p < lo; p++) { /* left of the diagonal: y0's terms only */
    int ci = k0[2 * p];
    size_t c = (size_t)(ci & ~1); /* even: in bounds when the form is not kept */
    b |= (ci & 1) | (k0[2 * p + 1] != ci + 1) | (ci <= prev);
    prev = ci;
    pair_scaled(v0 + 2 * p, v1 + 2 * p, s, x0, c, has_s, has_x, s0v, s1v, t, SYMOP_YS, 0);
    if (c == 2 * bi) { /* the diagonal block from its upper triangle */
      d[0] = t[0];
      d[1] = d[2] = t[1];
      d[3] = t[3];
    }
  }
  size_t end = (size_t)-1; /* the column after the run being written */
  for (; p < np; p++, a += 4) {
    int ci = k0[2 * p];
    size_t c = (size_t)(ci & ~1), bj = c / 2;
    b |= (ci & 1) | (k0[2 * p + 1] != ci + 1) | (ci <= prev);
    prev = ci;
    pair_scaled(v0 + 2 * p, v1 + 2 * p, s, x0, c, has_s, has_x, s0v, s1v, a, SYMOP_YS,
                stream);
    if (bj != end || bj == top)
      run[q++] = (mfs_symop_run){.col = (int)bj, .len = 1};
    else
      run[q - 1].len++;
    end = bj + 1;
  }
#undef SYMOP_YS
  if (has_x) {
    y0[2 * bi] = ys[0];
    y0[2 * bi + 1] = ys[1];
  }
  *last = lo < np ? (size_t)k0[len - 2] / 2 + 1 : 0;
  *bad |= b;
  return q;
}

/* Block t's rows of the fill (has_s, has_x constants: a copy each). */
static SYMOP_INLINE size_t fill_block2(const mfs_csr *K, const double *s, const double *x0,
                                       int has_s, int has_x, double *y0, mfs_symop *A, int t,
                                       size_t q, size_t *wt, int *bad)
{
  const size_t *kp = K->ptr;
  size_t top = A->cut[t + 1], w = 0;
  const int stream = ((uintptr_t)A->val & 15) == 0;
  for (size_t bi = A->cut[t]; bi < top; bi++) {
    size_t r0 = kp[2 * bi], len = kp[2 * bi + 1] - r0, p0 = A->ptr[bi], last = 0;
    if (bi + SYMOP_FILL_AHEAD < A->nb) {
      size_t f0 = kp[2 * (bi + SYMOP_FILL_AHEAD)], f1 = kp[2 * (bi + SYMOP_FILL_AHEAD) + 2];
      prefetch_range(K->val + f0, 0, (f1 - f0) * sizeof *K->val);
      prefetch_range(K->idx + f0, 0, (f1 - f0) * sizeof *K->idx);
    }
    q = fill_row2(K->idx + r0, K->idx + r0 + len, K->val + r0, K->val + r0 + len, len,
                  len / 2 - (A->ptr[bi + 1] - p0), bi, s, x0, has_s, has_x, y0,
                  A->diag + 4 * bi, A->val + 4 * p0, A->run, q, top, stream, &last, bad);
    A->rptr[bi + 1] = q;
    if (last > top + w)
      w = last - top;
  }
#ifdef SYMOP_STREAM
  _mm_sfence(); /* the streamed values before anything that follows */
#endif
  *wt = w;
  return q;
}

/* fill_block2 with its flags constant (one specialized copy per case). */
static size_t fill_block2_any(const mfs_csr *K, const double *s, const double *x0, double *y0,
                              mfs_symop *A, int t, size_t q, size_t *wt, int *bad)
{
  if (s && x0)
    return fill_block2(K, s, x0, 1, 1, y0, A, t, q, wt, bad);
  if (s)
    return fill_block2(K, s, NULL, 1, 0, NULL, A, t, q, wt, bad);
  if (x0)
    return fill_block2(K, NULL, x0, 0, 1, y0, A, t, q, wt, bad);
  return fill_block2(K, NULL, NULL, 0, 0, NULL, A, t, q, wt, bad);
}

/* The 2 x 2 build for K made of full blocks in sorted rows (plane strain as
 * mfs_assemble writes it): rows 2i and 2i+1 have the same columns,
 * ascending, in pairs (2j, 2j+1).  The first pass counts each block row's
 * upper blocks (bisection of its sorted columns); the row blocks are cut
 * from these counts; the fill (fill_row2, by row block, on the threads; the
 * same result) checks the form, writes the values, the diagonal blocks and
 * the runs, and with x0 takes the first product y0 = A x0 from the full
 * rows it reads anyway, so the first Lanczos step does not read the
 * operator again.  MFS_ENOTSUP if K is not of that form (then op_build).
 * Each row block's runs start at its first row's block offset (there are
 * never more runs than blocks) and are moved down after the fill.  (Reading
 * K's upper halves in place instead of a copy, no fill at all, made each
 * product 3 times slower: the runs of half rows defeat the prefetchers; the
 * copy is one stream.) */
static int op_build_pairs(const mfs_csr *K, const double *s, const double *restrict x0,
                          double *restrict y0, int nt, int par, mfs_symop *A)
{
  size_t n = K->nrow, nb = n / 2;
  const size_t *kp = K->ptr;
  const int *ki = K->idx;
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
   * bisection of row 2 bi's sorted columns (the fill checks the form), 16
   * rows at a time so that their probes' cache misses overlap */
  MFS_OMP("omp parallel for schedule(dynamic, 64) num_threads(nt) if (par) reduction(|:bad)")
  for (long g = 0; g < (long)nb; g += 16) {
    size_t m = (size_t)g + 16 <= nb ? 16 : nb - (size_t)g, lo[16], hi[16], more = 0;
    for (size_t j = 0; j < m; j++) {
      size_t bi = (size_t)g + j, r1 = kp[2 * bi + 1], len = r1 - kp[2 * bi];
      if (len != kp[2 * bi + 2] - r1 || len % 2)
        bad = 1;
      lo[j] = 0;
      hi[j] = len / 2;
      more |= lo[j] < hi[j];
    }
    while (more) { /* the first pair whose column is beyond 2 bi */
      more = 0;
      for (size_t j = 0; j < m; j++)
        if (lo[j] < hi[j]) {
          size_t bi = (size_t)g + j, mid = lo[j] + (hi[j] - lo[j]) / 2;
          if ((size_t)ki[kp[2 * bi] + 2 * mid] > 2 * bi)
            hi[j] = mid;
          else
            lo[j] = mid + 1;
          more |= lo[j] < hi[j];
        }
    }
    for (size_t j = 0; j < m; j++) {
      size_t bi = (size_t)g + j;
      A->ptr[bi + 1] = (kp[2 * bi + 1] - kp[2 * bi]) / 2 - lo[j];
    }
  }
  int st = MFS_ENOTSUP;
  if (bad)
    goto done;
  A->n = n;
  A->nb = nb;
  A->b = 2;
  for (size_t bi = 0; bi < nb; bi++)
    A->ptr[bi + 1] += A->ptr[bi];
  size_t nbl = A->ptr[nb], w[NB] = {0}, nr[NB] = {0};
  A->stored = 4 * nbl;
  op_cuts(A);
  st = MFS_ENOMEM;
  /* the values, the diagonal blocks and the run pointers in one block with
   * 2 MB pages (8-byte types, written once each by the fill): the first
   * touch of fresh 4 KB pages cost about 1.1-1.6 ms per MB here (13 MB:
   * 14-21 ms, with 2 MB pages 2.4-5 ms) */
  size_t nval = 4 * nbl, nblk = nval + 4 * nb + (nb + 1);
  _Static_assert(sizeof(size_t) == sizeof(double), "the block's entries are 8 bytes");
  A->mem = mfs_malloc(nblk * sizeof(double));
  /* the runs from each row block's first row's block offset (at most one run
   * per block), or one after the other when the blocks run in order on one
   * thread (then a dense array worth 2 MB pages too) */
  const int inorder = nt <= 1 || !par;
  A->run = mfs_malloc((nbl ? nbl : 1) * sizeof *A->run);
  if (!A->mem || !A->run)
    goto done;
  mfs_advise_huge(A->mem, nblk * sizeof(double));
  if (inorder)
    mfs_advise_huge(A->run, nbl * sizeof *A->run);
  A->val = A->mem;
  A->diag = A->val + nval;
  A->rptr = (size_t *)(void *)(A->diag + 4 * nb);
  A->rptr[0] = 0;
  size_t q0[NB];
  if (inorder) {
    size_t q = 0;
    for (int t = 0; t < NB; t++) {
      q0[t] = q;
      q = fill_block2_any(K, s, x0, y0, A, t, q, w + t, &bad);
      nr[t] = q - q0[t];
    }
  } else {
    MFS_OMP("omp parallel for schedule(dynamic, 1) num_threads(nt) reduction(|:bad)")
    for (int t = 0; t < NB; t++) {
      size_t q = q0[t] = A->ptr[A->cut[t]];
      q = fill_block2_any(K, s, x0, y0, A, t, q, w + t, &bad);
      nr[t] = q - q0[t];
    }
  }
  if (bad) {
    st = MFS_ENOTSUP; /* not full sorted 2 x 2 blocks: the general build */
    goto done;
  }
  /* each row block's runs down to the end of the ones before */
  size_t off = nr[0];
  for (int t = 1; t < NB; t++) {
    if (q0[t] != off) {
      memmove(A->run + off, A->run + q0[t], nr[t] * sizeof *A->run);
      for (size_t bi = A->cut[t]; bi < A->cut[t + 1]; bi++)
        A->rptr[bi + 1] -= q0[t] - off;
    }
    off += nr[t];
  }
  A->runs = off;
  if (off < nbl) { /* give back the unused end (a failed shrink keeps the block) */
    mfs_symop_run *r = mfs_realloc(A->run, (off ? off : 1) * sizeof *A->run);
    if (r)
      A->run = r;
  }
  st = op_bands(A, w);
done:
  if (st != MFS_OK)
    mfs_symop_free(A);
  return st;
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
  *have_y = 0;
  int st = op_build_pairs(K, s, x0, y0, nt, par, A);
  if (st == MFS_OK) {
    *have_y = x0 != NULL;
  } else if (st == MFS_ENOTSUP) {
    int *idx = NULL, *work = mfs_malloc((K->nrow ? K->nrow : 1) * sizeof *work);
    st = work ? op_build(K, s, work, A, &idx) : MFS_ENOMEM;
    mfs_free(work);
    if (st == MFS_OK) {
      op_cuts(A);
      st = op_finish(A, idx);
    }
    mfs_free(idx);
    if (st != MFS_OK)
      mfs_symop_free(A);
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
    prefetch_range(v, SYMOP_AHEAD, 32 * (ptr[i + 1] - ptr[i]));
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
      MFS_OMP("omp for schedule(dynamic, 1)")
      for (int t = 0; t < NB; t++)
        mfs_symop_block(A, t, x, y);
      MFS_OMP("omp for schedule(dynamic, 1)")
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
