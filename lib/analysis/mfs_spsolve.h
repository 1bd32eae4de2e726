/* Sparse direct solution of A x = b: CHOLMOD (symmetric positive definite
 * matrices, supernodal Cholesky) and UMFPACK (any square matrix, LU with
 * partial pivoting), each a const table, chosen by capability fields:
 *
 *   cholmod  needs a symmetric positive definite A (symmetric_only); reads
 *            the upper triangle of A.  A factorization that meets a
 *            non-positive pivot is a singular system.
 *   umfpack  any square A: the CSR arrays of A are the compressed columns of
 *            A^T, which UMFPACK factors; the solve is with its transpose.
 *
 * Both report the solver's reciprocal condition estimate (CHOLMOD: min/max
 * of diag L; UMFPACK: min/max of |diag U| after its row scaling) and the
 * normwise backward error of the computed x; no tolerance is buried: the
 * caller passes rcond_min. */
#ifndef MFS_SPSOLVE_H
#define MFS_SPSOLVE_H

#include <stddef.h>

#include "mfs_csr.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  double rcond;       /* the solver's reciprocal condition estimate */
  double backward;    /* |A x - b|_inf / (|A|_inf |x|_inf + |b|_inf) */
  double factor_nnz;  /* entries of the factor(s) (L; L + U) */
  int lib_status;     /* CHOLMOD common status / UMFPACK status of the factorization */
} mfs_spsolve_info;

typedef struct {
  const char *name;
  int symmetric_only; /* A must be symmetric positive definite */
  int (*solve)(const mfs_csr *A, const double *b, double *x, mfs_spsolve_info *info);
  /* The symmetric saddle-point system of mfs_spsolve_constrained without
   * forming it (NULL: the solver factors the saddle-point matrix itself). */
  int (*solve_constrained)(const mfs_csr *A, const mfs_csr *C, const double *b, const double *g,
                           double *x, double *lambda, mfs_spsolve_info *info);
} mfs_spsolve_type;

extern const mfs_spsolve_type mfs_spsolve_cholmod;
extern const mfs_spsolve_type mfs_spsolve_umfpack;
extern const mfs_spsolve_type *const mfs_spsolve_types[]; /* NULL-terminated */
const mfs_spsolve_type *mfs_spsolve_find(const char *name);

/* x = A^-1 b for square A (n x n CSR; unsorted rows are fine), b and x of
 * length n (they may not alias).  MFS_OK; MFS_ESYSTEM (a singular matrix,
 * a non-positive pivot for cholmod, rcond below rcond_min, or a non-finite
 * x); MFS_EINVAL (not square, NULL); MFS_ENOMEM.  info (may be NULL) is
 * filled as far as the solve got. */
mfs_status mfs_spsolve(const mfs_spsolve_type *t, const mfs_csr *A, const double *b, double *x,
                       double rcond_min, mfs_spsolve_info *info);

/* The saddle-point system of a constrained problem (Lagrange multipliers):
 *
 *   [ A   Ct^T ] [ x      ]   [ b ]      A n x n, C and Ct m x n (Ct = NULL: Ct = C,
 *   [ C   0    ] [ lambda ] = [ g ]      the symmetric case)
 *
 * With Ct = NULL and a solver with solve_constrained (cholmod): A must be
 * symmetric positive semidefinite with no null vector that C leaves
 * unconstrained; A + rho C^T C (rho = max |A_ij| / max |(C^T C)_ij|) is
 * factored by CHOLMOD and the m x m Schur complement C (A + rho C^T C)^-1
 * C^T by LAPACK (dense: m is the number of multipliers); rcond is the
 * smaller of the two estimates.  Otherwise the (n + m) square matrix is
 * assembled and solved by t->solve (a symmetric_only solver: MFS_EINVAL).
 * lambda (m values) may be NULL.  backward is that of the whole system.
 * Statuses as mfs_spsolve. */
mfs_status mfs_spsolve_constrained(const mfs_spsolve_type *t, const mfs_csr *A, const mfs_csr *C,
                                   const mfs_csr *Ct, const double *b, const double *g, double *x,
                                   double *lambda, double rcond_min, mfs_spsolve_info *info);

#ifdef __cplusplus
}
#endif

#endif
