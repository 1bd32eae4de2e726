/* Extreme eigenvalues of the pencil K v = lambda M v of a finite model
 * (K symmetric positive semidefinite, M symmetric positive definite; lambda
 * = omega^2, the squared circular frequencies of the undamped system).
 *
 *   mfs_eig_max         the largest eigenvalue, by ARPACK's implicitly
 *                       restarted Lanczos method (dsaupd / dseupd):
 *                       lumped mass: mode 1 (standard problem) on
 *                         M^-1/2 K M^-1/2, which is symmetric (kept as its
 *                         scaled upper triangle: each product reads half of
 *                         K, the memory traffic that bounds a Lanczos step);
 *                       consistent mass: mode 2 (generalized, OP = M^-1 K,
 *                         B = M), the solves with M by a CHOLMOD Cholesky
 *                         factorization.
 *   mfs_eig_zero_modes  the smallest eigenvalues by shift-invert (ARPACK
 *                       mode 3, OP = (K - sigma M)^-1 M) with a CHOLMOD
 *                       factorization of K - sigma M, sigma = -tol lambda_max:
 *                       slightly negative, so that K - sigma M is positive
 *                       definite even when K has rigid-body or spurious
 *                       zero-energy modes; counts the eigenvalues below
 *                       tol * lambda_max.
 *   mfs_eig_dense       all eigenvalues by LAPACK dsygvd, for n <= 2000: the
 *                       cross-check of the tests.
 *
 * Why CHOLMOD.  Mode 2 needs M^-1 x and mode 3 needs (K - sigma M)^-1 x at
 * every Lanczos step, so the matrix is factored once and each step is two
 * triangular solves.  K and M of a meshfree model are sparse (tens to a
 * hundred entries per row) with no banded structure worth exploiting in 2D,
 * and symmetric positive definite after the shift: a sparse Cholesky with a
 * fill-reducing ordering (AMD/METIS) is the method of choice, and CHOLMOD
 * (SuiteSparse) is the standard, supernodal (BLAS-3) implementation of it:
 * far faster than an iterative solve, which would have to be converged to
 * near machine precision inside every Lanczos step for ARPACK to stay
 * accurate, and than a dense or banded LAPACK factorization, which costs
 * O(n^2) or O(n b^2) memory.  Its symbolic/numeric split (cholmod_analyze,
 * cholmod_factorize) also fits the plan-then-execute style of the library.
 *
 * Reverse communication.  ARPACK's Fortran dsaupd_/dseupd_ (arpack-ng,
 * 32-bit integers) are declared in mfs_eigen.c.  The start vector is a fixed
 * pseudo-random vector, so results do not depend on earlier calls.  ARPACK
 * and CHOLMOD are not thread-safe in this use: one call at a time. */
#ifndef MFS_EIGEN_H
#define MFS_EIGEN_H

#include <stddef.h>

#include "mfs_csr.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The pencil (K, M).  Exactly one of M (consistent mass, CSR) and m
 * (lumped mass: the diagonal, all entries > 0) is given.  Borrowed. */
typedef struct {
  const mfs_csr *K; /* n x n, symmetric; both triangles stored */
  const mfs_csr *M; /* n x n, symmetric positive definite, or NULL */
  const double *m;  /* n diagonal entries, or NULL */
} mfs_pencil;

/* Options of the ARPACK runs; zeros select the defaults. */
typedef struct {
  int ncv;      /* Lanczos vectors kept (default max(2 nev + 1, 20), at most n) */
  int maxiter;  /* implicit restarts allowed (default 10000) */
  double tol;   /* ARPACK's relative accuracy of the Ritz values (default: machine epsilon) */
} mfs_eig_opts;

/* What happened in the runs.  On an ARPACK failure `info` is ARPACK's own
 * code and `routine` names the routine ("dsaupd", "dseupd"); on a CHOLMOD
 * failure `routine` is "cholmod" and cholmod_status its status (e.g. 1 =
 * CHOLMOD_NOT_POSDEF: the shifted matrix or M is not positive definite). */
typedef struct {
  int info;           /* ARPACK info of the failing call; 0 on success */
  const char *routine;/* the failing routine, or "" */
  int cholmod_status; /* CHOLMOD's status of the failing call; 0 if none */
  int iterations;     /* Arnoldi update iterations (iparam(3)), summed over runs */
  int matvecs;        /* operations OP x (iparam(9)), summed over runs */
  int nconv;          /* converged Ritz values of the last run (iparam(5)) */
  int runs;           /* ARPACK runs (zero modes: one per deflation round) */
  double residual;    /* max ||K v - lambda M v||_2 / (lambda_ref ||M v||_2) over the
                         returned pairs, lambda_ref = max(|lambda|, lambda_max) */
  double op_seconds;  /* wall clock spent in the operations OP x and B x (the products
                         and solves), summed over runs; the rest of a run is ARPACK's
                         (0 from the distributed mfs_peig_max) */
  double op_bytes;    /* mfs_eig_max: the bytes one product of its stored operator reads and
                         writes at least once (lib/analysis/mfs_symop.h); 0 elsewhere */
} mfs_eig_info;

/* Records the failing call (routine, its code) in info, which may be NULL;
 * returns st.  The eigensolvers' one way to report an ARPACK failure. */
static inline mfs_status mfs_eig_info_fail(mfs_eig_info *info, mfs_status st, const char *routine,
                                           int code)
{
  if (info) {
    info->info = code;
    info->routine = routine;
  }
  return st;
}

/* The start vector of the iterative eigensolvers (mfs_eig_max, mfs_lanczos_max):
 * x[0..n) fixed pseudo-random values in [-1, 1] (splitmix64), so that a run
 * depends neither on ARPACK's internal seed nor on earlier calls, and the
 * solvers start alike. */
void mfs_eig_start_vector(size_t n, double *x);

/* Largest eigenvalue of K v = lambda M v.  v (length n, or NULL) receives
 * its eigenvector, M-normalized.  Returns MFS_OK; MFS_EINVAL (n < 2, both or
 * neither mass given, a lumped mass entry <= 0 or non-finite); MFS_ENOCONV
 * (ARPACK stopped at maxiter: info->info = 1, info->nconv converged);
 * MFS_EARPACK (other ARPACK error, code in info->info); MFS_EDOMAIN (M not
 * positive definite: CHOLMOD status in info); MFS_ENOMEM.  info may be NULL. */
mfs_status mfs_eig_max(const mfs_pencil *P, const mfs_eig_opts *opts, double *lambda, double *v,
                mfs_eig_info *info);

/* Zero-energy modes.  Counts the eigenvalues lambda <= tol * lambda_max
 * (tol > 0, lambda_max > 0 the largest eigenvalue) by shift-invert ARPACK
 * runs with explicit deflation: each run asks for the nev smallest
 * eigenvalues (default 6) of the pencil restricted to the M-orthogonal
 * complement of the zero modes found so far; the modes it finds below the
 * threshold are added, and the rounds go on until a run finds none (so an
 * exactly multiple zero eigenvalue, which a single Lanczos run may see only
 * once, is counted fully).  At most max_modes zero modes are kept (the count
 * is then a lower bound: *count == max_modes). */
typedef struct {
  int count;                /* eigenvalues <= tol * lambda_max */
  double lambda_min_nonzero;/* the smallest eigenvalue above the threshold */
  double lambda_zero_max;   /* the largest of the counted ones (0 if none) */
  double sigma;             /* the shift used */
  double *modes;            /* count x n zero modes, M-orthonormal (if want_modes) */
} mfs_zero_modes;

typedef struct {
  double tol;       /* threshold relative to lambda_max (e.g. 1e-8) */
  int nev;          /* eigenvalues per run (default 6) */
  int max_modes;    /* cap on the count (default 1024) */
  int want_modes;   /* keep the modes in out->modes (free with mfs_free()) */
} mfs_zero_opts;

mfs_status mfs_eig_zero_modes(const mfs_pencil *P, double lambda_max, const mfs_zero_opts *zopts,
                       const mfs_eig_opts *opts, mfs_zero_modes *out, mfs_eig_info *info);

/* Whether the field r (length n) is a zero-energy mode of the pencil:
 * *is_null = ||K r||_2 <= tol * lambda_max * ||M r||_2.  Used to recognize
 * rigid-body modes (K times a rigid mode vanishes for shape functions that
 * reproduce the rigid fields).  MFS_OK or MFS_ENOMEM (then *is_null = 0). */
mfs_status mfs_eig_is_null(const mfs_pencil *P, const double *r, double lambda_max, double tol,
                           int *is_null);

/* Certification of a time step.  A Cholesky factorization LL' of
 * sigma M - K that runs to completion proves sigma M - K positive
 * semidefinite up to rounding, hence lambda_max <= sigma (1 + margin) and
 * every step dt <= 2 / sqrt(sigma (1 + margin)) stable for the undamped
 * central difference method.  The margin covers the rounding: the computed
 * factor is the exact one of sigma M - K + E with |E_ij| <= g sqrt(A_ii A_jj),
 * g = gamma_{k+1} / (1 - gamma_{k+1}), gamma_m = m u / (1 - m u), k the
 * longest row of L (Higham, Accuracy and Stability of Numerical Algorithms,
 * Thms 10.3 and 10.5), and E lies in the pattern of L + L' (w entries in its
 * longest row), so E >= -w g diag(A) and diag(A) <= sigma diag(M); with a
 * lumped mass diag(M) = M, and margin = w g + 5u (5u: forming sigma m_i -
 * K_ii).  With a consistent mass the same margin bounds the rounding
 * relative to diag(M), not M: proven up to a factor lambda_max(M^-1 diag M)
 * on the margin, which the output says.  CHOLMOD's supernodal LL' (it stops
 * at the first pivot that is not positive). */
typedef struct {
  int ok;            /* the factorization ran to completion */
  double margin;     /* relative rounding margin of the proof (ok only) */
  double factor_nnz; /* entries of the supernodal factor */
  double flops;      /* floating-point operations of one factorization (CHOLMOD's count) */
  int max_row;       /* k: the longest row of L */
} mfs_certificate;

/* Factor sigma M - K once.  MFS_OK (c->ok says whether it is positive
 * definite), MFS_EINVAL (bad pencil or sigma <= 0), MFS_ENOMEM. */
mfs_status mfs_eig_certify(const mfs_pencil *P, double sigma, mfs_certificate *c);

/* The search of the smallest certified sigma from an estimate of lambda_max
 * (a Lanczos value, which lies below lambda_max): sigma_0 = lambda_est
 * (1 + gap), multiplied up by (1 + gap growth^k) after each failure, until a
 * factorization succeeds or max_factorizations are spent; then `refine`
 * bisection steps between the last failure (or lambda_est) and the success.
 * One symbolic analysis, one numeric factorization per sigma. */
typedef struct {
  double lambda_est;      /* > 0 */
  double gap;             /* first relative gap (default 1e-6) */
  double growth;          /* gap growth after a failure (default 10) */
  int max_factorizations; /* default 30 */
  int refine;             /* bisection steps after the first success (default 0) */
  const double *coord;    /* optional: the unknowns' coordinates (order x coord_dim), for a
                             geometric fill-reducing order (nested dissection by coordinate
                             bisection); NULL: AMD (METIS above 3e5 unknowns) */
  int coord_dim;          /* 1, 2 or 3 with coord */
  int order;              /* MFS_CERT_ORDER_*: the fill-reducing order (0: the default above) */
} mfs_certify_opts;

/* The orders mfs_certify_opts.order asks for (benchmarks compare them):
 * the geometric nested dissection (needs coord), CHOLMOD's AMD, METIS, and
 * its own nested dissection NESDIS (CAMD on METIS's separators). */
enum {
  MFS_CERT_ORDER_DEFAULT = 0,
  MFS_CERT_ORDER_GEOMETRIC,
  MFS_CERT_ORDER_AMD,
  MFS_CERT_ORDER_METIS,
  MFS_CERT_ORDER_NESDIS
};

typedef struct {
  int ok;                 /* some sigma was certified */
  double sigma;           /* the smallest certified sigma */
  double lambda_upper;    /* sigma (1 + margin): a proven upper bound of lambda_max */
  double margin;          /* of that certificate */
  double sigma_failed;    /* the largest sigma whose factorization failed (0 if none):
                             lambda_max >= sigma_failed up to rounding */
  int factorizations;
  double factor_nnz;
  double flops;           /* of one factorization */
  int supernodes;         /* of the factor */
  double order_s;         /* wall seconds: the fill-reducing order (geometric: ours; else in
                             CHOLMOD's analysis), */
  double analyze_s;       /* the symbolic analysis (with the order, for CHOLMOD's orders), */
  double numeric_s;       /* the numeric factorizations (all of them, with forming sigma M - K) */
} mfs_certify_result;

/* MFS_OK (r->ok 0 if no sigma was certified), MFS_EINVAL, MFS_ENOMEM. */
mfs_status mfs_eig_certify_search(const mfs_pencil *P, const mfs_certify_opts *o,
                                  mfs_certify_result *r);

/* The order of the largest problem mfs_eig_dense accepts. */
#define MFS_EIG_DENSE_MAX 2000

/* All n eigenvalues, ascending, into w (n), by LAPACKE_dsygvd on dense
 * copies (O(n^2) memory, O(n^3) time).  MFS_EINVAL for n > MFS_EIG_DENSE_MAX
 * or a bad pencil; MFS_EDOMAIN if M is not positive definite; MFS_ELAPACK;
 * MFS_ENOMEM. */
mfs_status mfs_eig_dense(const mfs_pencil *P, double *w);

#ifdef __cplusplus
}
#endif

#endif
