#include "mfs_lanczos.h"
#include "mfs_alloc.h"

#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#include "mfs_huge.h"
#include "mfs_lapack.h"
#include "mfs_omp.h"
#include "mfs_symop.h"

#define NB MFS_SYMOP_BLOCKS
_Static_assert(MFS_LANCZOS_BLOCKS == MFS_SYMOP_BLOCKS, "the product's blocks are the operator's");

static double wall(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Pass 2 of block t: the earlier blocks' bands into its rows of y (in block
 * order; not when y is whole: the first product, from the build), then
 * w = y - beta qp into qp, and the partial sums of q.w, w.w and q.q. */
static void pass_vectors(const mfs_symop *A, int t, double *restrict y, const double *restrict q,
                         double *restrict qp, double beta, int whole, double sums[3])
{
  size_t b = (size_t)A->b, lo = b * A->cut[t], hi = b * A->cut[t + 1];
  if (!whole)
    mfs_symop_bands(A, t, y);
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
  mfs_symop A = {0};
  tri_ws tw = {0};
  /* s, q, q_prev and y in one block, with 2 MB pages where it is large:
   * their first touch in 4 KB pages cost about 1.1-1.6 ms per MB here (7-10
   * ms at 2 10^5 unknowns); from 4 MB on the block is made 8 MB, the least
   * mfs_advise_huge advises (the rest is never touched) */
  size_t vb = 4 * n * sizeof(double), huge = (size_t)8 << 20;
  if (vb >= huge / 2 && vb < huge)
    vb = huge;
  double *vec = mfs_malloc(vb), *s = vec, *q = vec ? vec + n : NULL,
         *qp = vec ? vec + 2 * n : NULL, *y = vec ? vec + 3 * n : NULL;
  if (vec) {
    mfs_advise_huge(vec, vb);
    memset(qp, 0, n * sizeof *qp);
  }
  double *al = mfs_malloc((kmax + 1) * sizeof *al), *be = mfs_malloc((kmax + 1) * sizeof *be);
  tw.w = mfs_malloc((kmax + 1) * sizeof *tw.w);
  tw.z = mfs_malloc((kmax + 1) * sizeof *tw.z);
  tw.work = mfs_malloc(5 * (kmax + 1) * sizeof *tw.work);
  tw.iblock = mfs_malloc((kmax + 1) * sizeof *tw.iblock);
  tw.isplit = mfs_malloc((kmax + 1) * sizeof *tw.isplit);
  tw.iwork = mfs_malloc(3 * (kmax + 1) * sizeof *tw.iwork);
  st = MFS_ENOMEM;
  if (!vec || !al || !be || !tw.w || !tw.z || !tw.work || !tw.iblock ||
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
  int par = P->K->ptr[n] >= 2 * MFS_SYMOP_PARALLEL_MIN, have_y = 0;
  double tb = wall();
  /* with the 2 x 2 copy the build takes the first product (have_y) */
  st = mfs_symop_build(P->K, s, q, y, nt, par, &A, &have_y);
  if (st != MFS_OK)
    goto done;
  tb = wall() - tb;
  if (info) {
    info->block = A.b;
    info->build_product = have_y;
    info->bytes = mfs_symop_bytes(&A);
  }
  par = A.stored >= MFS_SYMOP_PARALLEL_MIN;
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
        MFS_OMP("omp for schedule(dynamic, 1)")
        for (int t = 0; t < NB; t++)
          mfs_symop_block(&A, t, q, y);
      }
      MFS_OMP("omp master")
      t1 = wall();
      MFS_OMP("omp for schedule(dynamic, 1)")
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
      MFS_OMP("omp parallel for schedule(dynamic, 1) num_threads(nt) if (par)")
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
    MFS_OMP("omp parallel for schedule(dynamic, 1) num_threads(nt) if (par)")
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
  mfs_symop_free(&A);
  mfs_free(vec);
  mfs_free(al);
  mfs_free(be);
  mfs_free(tw.w);
  mfs_free(tw.z);
  mfs_free(tw.work);
  mfs_free(tw.iblock);
  mfs_free(tw.isplit);
  mfs_free(tw.iwork);
  return st;
}
