/* lambda_max of a lumped-mass pencil by plain symmetric Lanczos (issue 14
 * item 4): for the questions that need the largest eigenvalue only to a
 * relative 1e-6 .. 1e-8 (the explicit step dt_crit = 2 / sqrt(lambda_max),
 * the estimate the certified step starts from), without ARPACK's work
 * around the products.
 *
 * The method.  Lanczos on A = M^-1/2 K M^-1/2 (M = diag(m), K symmetric)
 * from a fixed pseudo-random start vector (the one mfs_eig_max uses), with
 * three vectors and no reorthogonalization and no restarts: in floating
 * point the Lanczos vectors lose orthogonality once a Ritz value converges,
 * and what follows are "ghost" copies of the converged values (Paige 1971,
 * Parlett, The Symmetric Eigenvalue Problem, ch. 13): the largest Ritz value
 * still converges to lambda_max, the ghosts only duplicate it.  Every step
 * takes the largest eigenvalue theta_k of the tridiagonal T_k by bisection
 * (LAPACK dstebz) and the last component s_k of its eigenvector (dstein),
 * and stops when the Ritz residual bound
 *
 *     beta_k |s_k| <= tol * theta_k,
 *
 * beta_k |s_k| being ||A y - theta_k y|| for the Ritz vector y (ARPACK's
 * test in dsaupd, the same tol means the same accuracy).  What it says:
 * theta_k is a Ritz value, so theta_k <= lambda_max (a LOWER bound, up to
 * rounding), and some eigenvalue of A lies within beta_k |s_k| of it
 * (within (beta_k s_k)^2 / gap when the gap to the rest of the spectrum is
 * known).  That this eigenvalue is lambda_max and not a lower one is what a
 * random start vector makes overwhelmingly likely, not what is proven: the
 * bound is an error estimate, not a proof.  Where a proof is needed the
 * certified step (mfs_eig_certify_search) starts from this value.
 *
 * The storage.  The diagonal and the strict upper triangle of A (each
 * product reads half of K), in 2 x 2 blocks when K is made of them (plane
 * strain: the two displacement components of a particle pair; 36 bytes per
 * 4 entries instead of 48), else in scalar entries (12 bytes per entry).
 * The product runs by MFS_LANCZOS_BLOCKS row blocks, cut at equal shares
 * of the stored entries; the number of blocks does not depend on the
 * thread count, nor do the sums: the result is the same bits for any
 * OMP_NUM_THREADS.  A block writes y for its own rows and its scatter
 * beyond its last row into its own band buffer; the second pass adds the
 * bands (in the order of the blocks) and does the step's vector work in the
 * same sweep (w = y - beta q_prev, the partial sums of q.w, w.w and q.q by
 * block, combined in block order, so that beta = ||w - alpha q|| comes from
 * them); a third pass forms the next Lanczos vector.  So a step reads the
 * operator once plus about seven vectors.  The 2 x 2 copy is written in one
 * pass over K that also takes the first product from K's full rows.
 *
 * Consistent mass is not handled (MFS_ENOTSUP): mfs_eig_max (ARPACK mode 2
 * with CHOLMOD) stays the solver there. */
#ifndef MFS_LANCZOS_H
#define MFS_LANCZOS_H

#include <stddef.h>

#include "mfs_eigen.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The row blocks of the product (fixed: the result does not depend on the
 * thread count). */
#define MFS_LANCZOS_BLOCKS 8

/* Options; zeros select the defaults. */
typedef struct {
  double tol;  /* the stopping rule's relative residual bound (default 1e-8; 1e-14 <= tol < 1) */
  int maxiter; /* Lanczos steps (= products) allowed (default 5000) */
} mfs_lanczos_opts;

/* What happened. */
typedef struct {
  int matvecs;       /* products A x (= Lanczos steps) */
  double bound;      /* beta_k |s_k| / theta_k at the stop (the relative error estimate) */
  double op_seconds; /* wall clock of the product passes (the rest: vector work, T_k's
                        eigenvalue; with the 2 x 2 copy the first product is in the build) */
  double setup_seconds; /* wall clock of building the stored operator (in the total, not in
                           op_seconds) */
  int block;         /* 1 or 2: the storage's block size */
  int build_product; /* 1: the build took the first product (the 2 x 2 copy; its time is in
                        setup_seconds, not in op_seconds) */
  double bytes;      /* bytes one product reads and writes at least once: the stored operator
                        (values, indices, row pointers, diagonal), x read and y written */
} mfs_lanczos_info;

/* Largest eigenvalue of K v = lambda m v (lumped mass m, all entries > 0
 * and finite; P->M must be NULL).  *lambda = theta_k at the stop.  Returns
 * MFS_OK; MFS_EINVAL (n < 2, a mass <= 0 or non-finite, tol out of range,
 * maxiter < 0); MFS_ENOTSUP (consistent mass); MFS_ENOCONV (maxiter steps
 * without meeting the rule: *lambda is the last theta_k, info->bound its
 * estimate); MFS_EDOMAIN (a non-finite value in the iteration: K has
 * non-finite entries); MFS_ELAPACK (dstebz or dstein failed); MFS_ENOMEM.
 * info may be NULL. */
mfs_status mfs_lanczos_max(const mfs_pencil *P, const mfs_lanczos_opts *opts, double *lambda,
                           mfs_lanczos_info *info);

#ifdef __cplusplus
}
#endif

#endif
