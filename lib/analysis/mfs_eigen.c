#include "mfs_eigen.h"
#include "mfs_alloc.h"

#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>
#include <time.h>

#include "mfs_cholmod.h"
#include "mfs_huge.h"

#include "mfs_lapack.h"
#include "mfs_omp.h"
#include "mfs_status.h"
#include "mfs_symop.h"

/* ARPACK (arpack-ng, gfortran, 32-bit integers): Fortran symbols with the
 * hidden string lengths last. */
extern void dsaupd_(int *ido, const char *bmat, const int *n, const char *which, const int *nev,
                    const double *tol, double *resid, const int *ncv, double *v, const int *ldv,
                    int *iparam, int *ipntr, double *workd, double *workl, const int *lworkl,
                    int *info, size_t bmat_len, size_t which_len);
extern void dseupd_(const int *rvec, const char *howmny, int *select, double *d, double *z,
                    const int *ldz, const double *sigma, const char *bmat, const int *n,
                    const char *which, const int *nev, const double *tol, double *resid,
                    const int *ncv, double *v, const int *ldv, int *iparam, int *ipntr,
                    double *workd, double *workl, const int *lworkl, int *info,
                    size_t howmny_len, size_t bmat_len, size_t which_len);

/* ------------------------------------------------------------------ */
/* small helpers                                                        */

static double dot(size_t n, const double *x, const double *y)
{
  double s = 0.0;
  for (size_t i = 0; i < n; i++)
    s += x[i] * y[i];
  return s;
}

static double norm2(size_t n, const double *x)
{
  return sqrt(dot(n, x, x));
}

/* y = A x for a CSR matrix; restrict-qualified so that the row loop
 * vectorizes (this is the cost of every Lanczos step of mfs_eig_max). */
static void matvec(const mfs_csr *A, const double *restrict x, double *restrict y)
{
  const size_t *restrict ptr = A->ptr;
  const int *restrict idx = A->idx;
  const double *restrict val = A->val;
  size_t nrow = A->nrow;
  for (size_t i = 0; i < nrow; i++) {
    double s = 0.0;
    for (size_t e = ptr[i]; e < ptr[i + 1]; e++)
      s += val[e] * x[idx[e]];
    y[i] = s;
  }
}

/* y = M x with the pencil's mass. */
static void mass_apply(const mfs_pencil *P, const double *x, double *y)
{
  size_t n = P->K->nrow;
  if (P->M)
    matvec(P->M, x, y);
  else
    for (size_t i = 0; i < n; i++)
      y[i] = P->m[i] * x[i];
}

void mfs_eig_start_vector(size_t n, double *x)
{
  uint64_t s = 0x9e3779b97f4a7c15ULL;
  for (size_t i = 0; i < n; i++) {
    uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    x[i] = 2.0 * ((double)(z >> 11) * 0x1.0p-53) - 1.0;
  }
}

static int pencil_check(const mfs_pencil *P)
{
  if (!P || !P->K || (P->M == NULL) == (P->m == NULL))
    return MFS_EINVAL;
  size_t n = P->K->nrow;
  if (n < 2 || P->K->ncol != n || n > (size_t)INT32_MAX / 4)
    return MFS_EINVAL;
  if (P->M && (P->M->nrow != n || P->M->ncol != n))
    return MFS_EINVAL;
  if (P->m)
    for (size_t i = 0; i < n; i++)
      if (!(P->m[i] > 0.0) || !isfinite(P->m[i]))
        return MFS_EINVAL;
  return MFS_OK;
}

/* As pencil_check, without the sign of the lumped mass (the certification
 * factors sigma M - K whatever M is: a mass <= 0 makes it fail). */
static int pencil_check_any_mass(const mfs_pencil *P)
{
  if (!P || !P->K || (P->M == NULL) == (P->m == NULL))
    return MFS_EINVAL;
  size_t n = P->K->nrow;
  if (n < 1 || P->K->ncol != n || (P->M && (P->M->nrow != n || P->M->ncol != n)))
    return MFS_EINVAL;
  if (P->m)
    for (size_t i = 0; i < n; i++)
      if (!isfinite(P->m[i]))
        return MFS_EINVAL;
  return MFS_OK;
}

static void info_reset(mfs_eig_info *info)
{
  if (info)
    *info = (mfs_eig_info){.routine = ""};
}

/* ------------------------------------------------------------------ */
/* CHOLMOD: factorizations of symmetric positive definite matrices     */

/* CHOLMOD's own OpenMP loops on the calling thread.  CHOLMOD 3 (SuiteSparse 5)
 * runs loops of its supernodal factorization (clearing its map, zeroing and
 * assembling supernodes) in OpenMP regions of CHOLMOD_OMP_NUM_THREADS = 4
 * threads, a constant of its build that OMP_NUM_THREADS does not change.  At
 * 10^5 particles (2D, cubic MLS, analysis/bench/bench_check.sh) the wake-ups
 * of those teams took 40% of a factorization under OMP_NUM_THREADS=1, and at
 * 2 threads the numeric factorization took 1.5-2.2 s with them, 1.0 s
 * without.  Outside a parallel region of the caller the maximum of active
 * levels is 0 between chol_serial_begin and chol_serial_end, so that every
 * region of CHOLMOD runs on this thread (inside a caller's region they are
 * nested and inactive already).  The loops are independent entry by entry:
 * the factor is the same.  The flops are in the BLAS, which keeps its own
 * threads (OPENBLAS_NUM_THREADS).  The setting is process-wide in libgomp:
 * parallel regions that another thread of the caller starts meanwhile run on
 * one thread (docs/design.md). */
static int chol_serial_begin(void)
{
#ifdef _OPENMP
  if (!omp_in_parallel()) {
    int levels = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
    return levels;
  }
#endif
  return -1;
}

static void chol_serial_end(int levels)
{
#ifdef _OPENMP
  if (levels >= 0)
    omp_set_max_active_levels(levels);
#else
  (void)levels;
#endif
}

typedef struct {
  cholmod_common c;
  int started;
  cholmod_factor *L;
  cholmod_dense *B, *X, *Y, *E;
} chol_solver;

static cholmod_sparse *diag_of(size_t n, const double *d, cholmod_common *c)
{
  cholmod_sparse *S = cholmod_l_allocate_sparse(n, n, n, 1, 1, 1, CHOLMOD_REAL, c);
  if (!S)
    return NULL;
  SuiteSparse_long *Sp = S->p, *Si = S->i;
  double *Sx = S->x;
  for (size_t j = 0; j < n; j++) {
    Sp[j] = (SuiteSparse_long)j;
    Si[j] = (SuiteSparse_long)j;
    Sx[j] = d[j];
  }
  Sp[n] = (SuiteSparse_long)n;
  return S;
}

static void chol_free(chol_solver *s)
{
  if (!s->started)
    return;
  cholmod_l_free_factor(&s->L, &s->c);
  cholmod_l_free_dense(&s->B, &s->c);
  cholmod_l_free_dense(&s->X, &s->c);
  cholmod_l_free_dense(&s->Y, &s->c);
  cholmod_l_free_dense(&s->E, &s->c);
  cholmod_l_finish(&s->c);
  s->started = 0;
}

static void chol_start(chol_solver *s)
{
  memset(s, 0, sizeof *s);
  mfs_cholmod_start(&s->c);
  s->started = 1;
}

/* Factor A + shift * B (B may be NULL: A alone; Bdiag: a diagonal B).
 * Returns MFS_OK, MFS_EDOMAIN (not positive definite), MFS_ENOMEM. */
static int chol_factor(chol_solver *s, const mfs_csr *A, const mfs_csr *B, const double *Bdiag,
                       double shift, mfs_eig_info *info)
{
  cholmod_common *c = &s->c;
  cholmod_sparse *Au = mfs_cholmod_upper(A, c), *Bu = NULL, *F = NULL;
  mfs_status st = MFS_ENOMEM;
  if (!Au)
    goto done;
  if (B || Bdiag) {
    Bu = B ? mfs_cholmod_upper(B, c) : diag_of(A->nrow, Bdiag, c);
    if (!Bu)
      goto done;
    double al[2] = {1.0, 0.0}, be[2] = {shift, 0.0};
    F = cholmod_l_add(Au, Bu, al, be, 1, 1, c);
    if (!F)
      goto done;
  } else {
    F = Au;
    Au = NULL;
  }
  s->L = cholmod_l_analyze(F, c);
  if (!s->L)
    goto done;
  int levels = chol_serial_begin();
  int ok = cholmod_l_factorize(F, s->L, c);
  chol_serial_end(levels);
  if (ok && c->status == CHOLMOD_OK && !s->L->is_super && !s->L->is_ll) {
    /* a simplicial LDL' factorization succeeds on indefinite matrices:
     * positive definiteness is D > 0 (the diagonal of the factor) */
    const SuiteSparse_long *Lp = s->L->p;
    const double *Lx = s->L->x;
    for (size_t j = 0; j < s->L->n; j++)
      if (!(Lx[Lp[j]] > 0.0)) {
        c->status = CHOLMOD_NOT_POSDEF;
        break;
      }
  }
  if (!ok || c->status != CHOLMOD_OK || s->L->minor < s->L->n) {
    st = c->status == CHOLMOD_OUT_OF_MEMORY ? MFS_ENOMEM : MFS_EDOMAIN;
    if (info) {
      info->routine = "cholmod";
      info->cholmod_status = c->status != CHOLMOD_OK ? c->status : CHOLMOD_NOT_POSDEF;
    }
    goto done;
  }
  s->B = cholmod_l_allocate_dense(A->nrow, 1, A->nrow, CHOLMOD_REAL, c);
  if (!s->B)
    goto done;
  st = MFS_OK;
done:
  cholmod_l_free_sparse(&Au, c);
  cholmod_l_free_sparse(&Bu, c);
  cholmod_l_free_sparse(&F, c);
  return st;
}

/* y = F^-1 b. */
static int chol_solve(chol_solver *s, const double *b, double *y)
{
  size_t n = s->B->nrow;
  memcpy(s->B->x, b, n * sizeof *b);
  if (!cholmod_l_solve2(CHOLMOD_A, s->L, s->B, NULL, &s->X, NULL, &s->Y, &s->E, &s->c))
    return MFS_ENOMEM;
  memcpy(y, s->X->x, n * sizeof *y);
  return MFS_OK;
}

/* ------------------------------------------------------------------ */
/* ARPACK reverse communication                                        */

/* The operators of one run.  op(ctx, ido, x, y, bx): ido -1 or 1: y = OP x
 * (mode 2: also x <- K x; mode 3 with ido 1: bx = M x is given); ido 2:
 * y = B x. */
typedef struct {
  int n, mode, nev, ncv, maxiter;
  char bmat;
  const char *which;
  double sigma, tol;
  int (*op)(void *ctx, int ido, double *x, double *y, const double *bx);
  void *ctx;
  const double *start; /* initial residual vector (n) */
  /* results: nev eigenvalues d (ascending) and eigenvectors z (n x nev) */
  double *d, *z;
} arpack_job;

/* Wall clock in seconds (what info->op_seconds sums). */
static double wall(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int arpack_run(arpack_job *j, mfs_eig_info *info)
{
  int n = j->n, nev = j->nev, ncv = j->ncv, ldv = n, lworkl = ncv * (ncv + 8);
  int ido = 0, ainfo = 1, iparam[11] = {0}, ipntr[14] = {0};
  mfs_status st = MFS_ENOMEM;
  double *resid = mfs_malloc((size_t)n * sizeof *resid);
  double *v = mfs_malloc((size_t)n * (size_t)ncv * sizeof *v);
  double *workd = mfs_malloc(3 * (size_t)n * sizeof *workd);
  double *workl = mfs_malloc((size_t)lworkl * sizeof *workl);
  double *dd = mfs_malloc((size_t)ncv * 2 * sizeof *dd);
  int *select = mfs_malloc((size_t)ncv * sizeof *select);
  if (!resid || !v || !workd || !workl || !dd || !select)
    goto done;
  mfs_advise_huge(v, (size_t)n * (size_t)ncv * sizeof *v); /* the basis every step streams */
  memcpy(resid, j->start, (size_t)n * sizeof *resid);
  iparam[0] = 1; /* exact shifts */
  iparam[2] = j->maxiter;
  iparam[3] = 1;
  iparam[6] = j->mode;
  mfs_lapack_reset(); /* LAPACK's complaints inside ARPACK (mfs_lapack.h) */
  for (;;) {
    dsaupd_(&ido, &j->bmat, &n, j->which, &nev, &j->tol, resid, &ncv, v, &ldv, iparam, ipntr,
            workd, workl, &lworkl, &ainfo, 1, 2);
    if (mfs_lapack_last()->count > 0) {
      st = mfs_eig_info_fail(info, MFS_EARPACK, "dsaupd (LAPACK)", mfs_lapack_last()->info);
      goto done;
    }
    if (ido == -1 || ido == 1 || ido == 2) {
      double t0 = info ? wall() : 0.0;
      st = j->op(j->ctx, ido, workd + ipntr[0] - 1, workd + ipntr[1] - 1,
                 ido == 1 && j->mode == 3 ? workd + ipntr[2] - 1 : NULL);
      if (info)
        info->op_seconds += wall() - t0;
      if (st != MFS_OK)
        goto done;
      continue;
    }
    break;
  }
  if (info) {
    info->iterations += iparam[2];
    info->matvecs += iparam[8];
    info->nconv = iparam[4];
    info->runs++;
  }
  if (ainfo == 1) {
    st = mfs_eig_info_fail(info, MFS_ENOCONV, "dsaupd", 1);
    goto done;
  }
  if (ainfo != 0) {
    st = mfs_eig_info_fail(info, MFS_EARPACK, "dsaupd", ainfo);
    goto done;
  }
  int rvec = 1, einfo = 0;
  dseupd_(&rvec, "A", select, dd, v, &ldv, &j->sigma, &j->bmat, &n, j->which, &nev, &j->tol,
          resid, &ncv, v, &ldv, iparam, ipntr, workd, workl, &lworkl, &einfo, 1, 1, 2);
  if (einfo == 0 && mfs_lapack_last()->count > 0)
    einfo = -mfs_lapack_last()->info - 1000; /* a LAPACK argument error inside dseupd */
  if (einfo != 0) {
    st = mfs_eig_info_fail(info, MFS_EARPACK, "dseupd", einfo);
    goto done;
  }
  /* ascending eigenvalues with their vectors (selection sort: nev is small) */
  int *ord = select; /* reuse: ncv >= nev */
  for (int i = 0; i < nev; i++)
    ord[i] = i;
  for (int i = 0; i < nev; i++)
    for (int k = i + 1; k < nev; k++)
      if (dd[ord[k]] < dd[ord[i]]) {
        int t = ord[i];
        ord[i] = ord[k];
        ord[k] = t;
      }
  for (int i = 0; i < nev; i++) {
    j->d[i] = dd[ord[i]];
    if (!isfinite(j->d[i])) {
      st = mfs_eig_info_fail(info, MFS_EARPACK, "dseupd", 0);
      goto done;
    }
    if (j->z)
      memcpy(j->z + (size_t)i * n, v + (size_t)ord[i] * n, (size_t)n * sizeof *v);
  }
  st = MFS_OK;
done:
  mfs_free(resid);
  mfs_free(v);
  mfs_free(workd);
  mfs_free(workl);
  mfs_free(dd);
  mfs_free(select);
  return st;
}

static int default_ncv(const mfs_eig_opts *o, int nev, size_t n)
{
  int ncv = o && o->ncv > 0 ? o->ncv : (2 * nev + 1 > 20 ? 2 * nev + 1 : 20);
  if (ncv <= nev)
    ncv = nev + 1;
  if ((size_t)ncv > n)
    ncv = (int)n;
  return ncv;
}

/* ------------------------------------------------------------------ */
/* largest eigenvalue                                                  */

/* The product of mfs_eig_max: A = M^-1/2 K M^-1/2 (lumped) or K
 * (consistent) as lib/analysis/mfs_symop.h stores it, half of K's bytes. */
typedef struct {
  const mfs_pencil *P;
  mfs_symop A; /* lumped: M^-1/2 K M^-1/2; consistent: K */
  double *s;   /* lumped: m^-1/2 */
  double *t;   /* work, n */
  chol_solver *ch;
} max_ctx;

/* Mode 1: y = M^-1/2 K M^-1/2 x. */
static int op_lumped(void *vc, int ido, double *x, double *y, const double *bx)
{
  (void)ido;
  (void)bx;
  max_ctx *c = vc;
  mfs_symop_apply(&c->A, x, y);
  return MFS_OK;
}

/* Mode 2: y = M^-1 K x and x <- K x; or y = M x. */
static int op_consistent(void *vc, int ido, double *x, double *y, const double *bx)
{
  (void)bx;
  max_ctx *c = vc;
  size_t n = c->P->K->nrow;
  if (ido == 2) {
    matvec(c->P->M, x, y);
    return MFS_OK;
  }
  mfs_symop_apply(&c->A, x, c->t);
  memcpy(x, c->t, n * sizeof *x);
  return chol_solve(c->ch, c->t, y);
}

/* ||K v - lambda M v|| / (ref ||M v||). */
static double pair_residual(const mfs_pencil *P, double lambda, double ref, const double *v,
                            double *w1, double *w2)
{
  size_t n = P->K->nrow;
  matvec(P->K, v, w1);
  mass_apply(P, v, w2);
  double nm = norm2(n, w2);
  for (size_t i = 0; i < n; i++)
    w1[i] -= lambda * w2[i];
  double r = norm2(n, w1) / (ref * nm);
  return isfinite(r) ? r : INFINITY;
}

mfs_status mfs_eig_max(const mfs_pencil *P, const mfs_eig_opts *opts, double *lambda, double *v,
                mfs_eig_info *info)
{
  info_reset(info);
  int st = pencil_check(P);
  if (st != MFS_OK)
    return st;
  size_t n = P->K->nrow;
  chol_solver ch = {0};
  max_ctx c = {P, {0}, NULL, NULL, &ch};
  double *start = NULL, *z = NULL, *w2 = NULL, d[1];
  st = MFS_ENOMEM;
  c.t = mfs_malloc(n * sizeof *c.t);
  start = mfs_malloc(n * sizeof *start);
  z = mfs_malloc(n * sizeof *z);
  w2 = mfs_malloc(n * sizeof *w2);
  if (!c.t || !start || !z || !w2)
    goto done;
  mfs_eig_start_vector(n, start);
  arpack_job j = {.n = (int)n,
                  .nev = 1,
                  .ncv = default_ncv(opts, 1, n),
                  .maxiter = opts && opts->maxiter > 0 ? opts->maxiter : 10000,
                  .which = "LA",
                  .sigma = 0.0,
                  .tol = opts && opts->tol > 0.0 ? opts->tol : 0.0,
                  .ctx = &c,
                  .start = start,
                  .d = d,
                  .z = z};
  if (P->m) {
    c.s = mfs_malloc(n * sizeof *c.s);
    if (!c.s)
      goto done;
    for (size_t i = 0; i < n; i++)
      c.s[i] = 1.0 / sqrt(P->m[i]);
    int have_y;
    st = mfs_symop_build(P->K, c.s, NULL, NULL, mfs_omp_threads(), 0, &c.A, &have_y);
    if (st != MFS_OK)
      goto done;
    j.mode = 1;
    j.bmat = 'I';
    j.op = op_lumped;
  } else {
    int have_y;
    st = mfs_symop_build(P->K, NULL, NULL, NULL, mfs_omp_threads(), 0, &c.A, &have_y);
    if (st != MFS_OK)
      goto done;
    chol_start(&ch);
    st = chol_factor(&ch, P->M, NULL, NULL, 0.0, info);
    if (st != MFS_OK)
      goto done;
    j.mode = 2;
    j.bmat = 'G';
    j.op = op_consistent;
  }
  st = arpack_run(&j, info);
  if (st != MFS_OK)
    goto done;
  if (info)
    info->op_bytes = mfs_symop_bytes(&c.A);
  mfs_symop_free(&c.A); /* before the residual: give the memory back */
  if (P->m) /* eigenvector of the pencil: M^-1/2 u, M-normalized as u is normalized */
    for (size_t i = 0; i < n; i++)
      z[i] *= c.s[i];
  *lambda = d[0];
  if (info)
    info->residual = pair_residual(P, d[0], fabs(d[0]), z, c.t, w2);
  if (v)
    memcpy(v, z, n * sizeof *v);
done:
  chol_free(&ch);
  mfs_symop_free(&c.A);
  mfs_free(c.s);
  mfs_free(c.t);
  mfs_free(start);
  mfs_free(z);
  mfs_free(w2);
  return st;
}

/* ------------------------------------------------------------------ */
/* zero-energy modes: shift-invert with deflation                      */

typedef struct {
  const mfs_pencil *P;
  chol_solver *ch;
  size_t k;          /* deflated modes */
  const double *Z;   /* k x n, M-orthonormal */
  const double *MZ;  /* k x n: M Z */
  double *b;         /* work, n */
} si_ctx;

/* x <- x - Z (W^T x), W = MZ or Z. */
static void project(size_t n, size_t k, const double *Z, const double *W, double *x)
{
  for (size_t r = 0; r < k; r++) {
    double a = dot(n, W + r * n, x);
    const double *zr = Z + r * n;
    for (size_t i = 0; i < n; i++)
      x[i] -= a * zr[i];
  }
}

/* Mode 3 on the deflated pencil, OP = P (K - sigma M)^-1 M P with the
 * M-orthogonal projector P = I - Z Z^T M (M-self-adjoint, as OP is). */
static int op_shift_invert(void *vc, int ido, double *x, double *y, const double *bx)
{
  si_ctx *c = vc;
  size_t n = c->P->K->nrow;
  if (ido == 2) {
    mass_apply(c->P, x, y);
    return MFS_OK;
  }
  if (ido == 1 && bx) {
    memcpy(c->b, bx, n * sizeof *bx);
  } else {
    mass_apply(c->P, x, c->b);
  }
  /* M P x = M x - MZ (Z^T M x) */
  project(n, c->k, c->MZ, c->Z, c->b);
  int st = chol_solve(c->ch, c->b, y);
  if (st != MFS_OK)
    return st;
  project(n, c->k, c->Z, c->MZ, y);
  return MFS_OK;
}

/* Append v (M-normalized, then M-orthogonalized against Z twice) to Z. */
static int append_mode(const mfs_pencil *P, size_t n, size_t *k, double *Z, double *MZ,
                       const double *v)
{
  double *z = Z + *k * n, *mz = MZ + *k * n;
  memcpy(z, v, n * sizeof *z);
  for (int pass = 0; pass < 2; pass++)
    project(n, *k, Z, MZ, z);
  mass_apply(P, z, mz);
  double nrm = sqrt(dot(n, z, mz));
  if (!(nrm > 0.0) || !isfinite(nrm))
    return MFS_EDOMAIN;
  for (size_t i = 0; i < n; i++) {
    z[i] /= nrm;
    mz[i] /= nrm;
  }
  (*k)++;
  return MFS_OK;
}

mfs_status mfs_eig_zero_modes(const mfs_pencil *P, double lambda_max, const mfs_zero_opts *zo,
                       const mfs_eig_opts *opts, mfs_zero_modes *out, mfs_eig_info *info)
{
  info_reset(info);
  memset(out, 0, sizeof *out);
  int st = pencil_check(P);
  if (st != MFS_OK)
    return st;
  if (!zo || !(zo->tol > 0.0) || !(lambda_max > 0.0) || !isfinite(lambda_max))
    return MFS_EINVAL;
  size_t n = P->K->nrow;
  int nev_req = zo->nev > 0 ? zo->nev : 6;
  size_t cap = zo->max_modes > 0 ? (size_t)zo->max_modes : 1024;
  if (cap > n)
    cap = n;
  double thr = zo->tol * lambda_max;
  out->sigma = -thr;
  out->lambda_min_nonzero = INFINITY;

  chol_solver ch = {0};
  chol_start(&ch);
  double *Z = NULL, *MZ = NULL, *start = NULL, *d = NULL, *zv = NULL, *w1 = NULL, *w2 = NULL;
  si_ctx c = {P, &ch, 0, NULL, NULL, NULL};
  st = MFS_ENOMEM;
  Z = mfs_malloc(cap * n * sizeof *Z);
  MZ = mfs_malloc(cap * n * sizeof *MZ);
  start = mfs_malloc(n * sizeof *start);
  c.b = mfs_malloc(n * sizeof *c.b);
  w1 = mfs_malloc(n * sizeof *w1);
  w2 = mfs_malloc(n * sizeof *w2);
  if (!Z || !MZ || !start || !c.b || !w1 || !w2)
    goto done;
  c.Z = Z;
  c.MZ = MZ;
  /* K - sigma M = K + thr M: positive definite for K positive semidefinite */
  st = chol_factor(&ch, P->K, P->M, P->m, thr, info);
  if (st != MFS_OK)
    goto done;
  double resmax = 0.0;
  for (;;) {
    size_t rem = n - c.k;
    if (rem <= 1) { /* the one eigenvalue left is lambda_max */
      if (out->lambda_min_nonzero > lambda_max)
        out->lambda_min_nonzero = lambda_max;
      break;
    }
    int nev = nev_req < (int)(rem - 1) ? nev_req : (int)(rem - 1);
    int ncv = default_ncv(opts, nev, n);
    if (ncv <= nev)
      ncv = nev + 1;
    mfs_free(d);
    mfs_free(zv);
    d = mfs_malloc((size_t)nev * sizeof *d);
    zv = mfs_malloc((size_t)nev * n * sizeof *zv);
    st = MFS_ENOMEM;
    if (!d || !zv)
      goto done;
    mfs_eig_start_vector(n, start);
    project(n, c.k, Z, MZ, start);
    arpack_job j = {.n = (int)n,
                    .mode = 3,
                    .nev = nev,
                    .ncv = ncv,
                    .maxiter = opts && opts->maxiter > 0 ? opts->maxiter : 10000,
                    .bmat = 'G',
                    .which = "LM",
                    .sigma = -thr,
                    .tol = opts && opts->tol > 0.0 ? opts->tol : 0.0,
                    .op = op_shift_invert,
                    .ctx = &c,
                    .start = start,
                    .d = d,
                    .z = zv};
    st = arpack_run(&j, info);
    if (st != MFS_OK)
      goto done;
    int found = 0;
    for (int i = 0; i < nev; i++) {
      double r = pair_residual(P, d[i], fabs(d[i]) > lambda_max ? fabs(d[i]) : lambda_max,
                               zv + (size_t)i * n, w1, w2);
      resmax = r > resmax ? r : resmax;
      if (d[i] <= thr) {
        if (c.k < cap) {
          st = append_mode(P, n, &c.k, Z, MZ, zv + (size_t)i * n);
          if (st != MFS_OK)
            goto done;
          found++;
        }
        out->lambda_zero_max = d[i] > out->lambda_zero_max ? d[i] : out->lambda_zero_max;
      } else if (d[i] < out->lambda_min_nonzero) {
        out->lambda_min_nonzero = d[i];
      }
    }
    if (found == 0 || c.k >= cap)
      break;
    if (found == nev && nev_req < 256)
      nev_req *= 2;
  }
  if (!isfinite(out->lambda_min_nonzero))
    out->lambda_min_nonzero = lambda_max;
  out->count = (int)c.k;
  if (info)
    info->residual = resmax;
  if (zo->want_modes && c.k > 0) {
    st = MFS_ENOMEM;
    out->modes = mfs_malloc(c.k * n * sizeof *out->modes);
    if (!out->modes)
      goto done;
    memcpy(out->modes, Z, c.k * n * sizeof *Z);
  }
  st = MFS_OK;
done:
  chol_free(&ch);
  mfs_free(Z);
  mfs_free(MZ);
  mfs_free(start);
  mfs_free(c.b);
  mfs_free(d);
  mfs_free(zv);
  mfs_free(w1);
  mfs_free(w2);
  return st;
}

mfs_status mfs_eig_is_null(const mfs_pencil *P, const double *r, double lambda_max, double tol,
                           int *is_null)
{
  size_t n = P->K->nrow;
  double *a = mfs_malloc(n * sizeof *a), *b = mfs_malloc(n * sizeof *b);
  mfs_status st = MFS_ENOMEM;
  *is_null = 0;
  if (a && b) {
    matvec(P->K, r, a);
    mass_apply(P, r, b);
    *is_null = norm2(n, a) <= tol * lambda_max * norm2(n, b);
    st = MFS_OK;
  }
  mfs_free(a);
  mfs_free(b);
  return st;
}

/* ------------------------------------------------------------------ */
/* certification: Cholesky factorizations of sigma M - K               */

typedef struct {
  cholmod_common c;
  cholmod_factor *L;
  cholmod_sparse *S;      /* the lower triangle of Q (sigma M - K) Q', Q L's order */
  double *kx, *mx;        /* the entries of K and M in the pattern of S */
  SuiteSparse_long *perm; /* a geometric order, or NULL: CHOLMOD's */
  double order_s, analyze_s, numeric_s; /* wall seconds, summed */
} cert_ws;

static void cert_free(cert_ws *w)
{
  mfs_free(w->perm);
  mfs_free(w->kx);
  mfs_free(w->mx);
  cholmod_l_free_factor(&w->L, &w->c);
  cholmod_l_free_sparse(&w->S, &w->c);
  cholmod_l_finish(&w->c);
}

enum { CERT_AMD_MAX = 300000 };

/* The pattern of the upper triangle of K + M (M: P->M, or the diagonal of
 * the lumped mass), sorted columns, for the symbolic analysis; mark (n) is
 * workspace. */
static cholmod_sparse *cert_pattern(const mfs_pencil *P, SuiteSparse_long *mark, cholmod_common *c)
{
  const mfs_csr *K = P->K, *M = P->M;
  size_t n = K->nrow, nnz = 0;
  for (size_t j = 0; j < n; j++)
    mark[j] = -1;
  for (int pass = 0; pass < 2; pass++) {
    cholmod_sparse *A = NULL;
    SuiteSparse_long *Ap = NULL, *Ai = NULL;
    if (pass == 1) {
      A = cholmod_l_allocate_sparse(n, n, nnz, 0, 1, 1, CHOLMOD_PATTERN, c);
      if (!A)
        return NULL;
      Ap = A->p;
      Ai = A->i;
      for (size_t j = 0; j < n; j++)
        mark[j] = -1;
    }
    size_t pos = 0;
    for (size_t j = 0; j < n; j++) {
      SuiteSparse_long sj = (SuiteSparse_long)j;
      if (pass == 1)
        Ap[j] = (SuiteSparse_long)pos;
      for (int t = 0; t < 3; t++) { /* K's row j, M's (or the diagonal) */
        const mfs_csr *B = t == 0 ? K : M;
        size_t lo = 0, hi = 1;
        if (t == 2 || B) {
          lo = t == 2 ? 0 : B->ptr[j];
          hi = t == 2 ? 1 : B->ptr[j + 1];
        } else {
          continue;
        }
        for (size_t e = lo; e < hi; e++) {
          size_t i = t == 2 ? j : (size_t)B->idx[e];
          if (i <= j && mark[i] != sj) {
            mark[i] = sj;
            if (pass == 1)
              Ai[pos] = (SuiteSparse_long)i;
            pos++;
          }
        }
      }
    }
    if (pass == 0) {
      nnz = pos;
    } else {
      Ap[n] = (SuiteSparse_long)pos;
      if (!cholmod_l_sort(A, c)) {
        cholmod_l_free_sparse(&A, c);
        return NULL;
      }
      return A;
    }
  }
  return NULL;
}

/* S = the lower triangle of Q (K + M) Q' in CHOLMOD's form, Q = L->Perm
 * (new -> old), columns sorted (rows visited in the new order), with the
 * entries of K and M apart in w->kx and w->mx: one pass per factorization
 * forms sigma M - K in place (cholmod_l_factorize would permute and
 * transpose the matrix at every call).  iw (2n) is workspace. */
static int cert_permuted(cert_ws *w, const mfs_pencil *P, SuiteSparse_long *iw)
{
  const mfs_csr *K = P->K, *M = P->M;
  size_t n = K->nrow;
  const SuiteSparse_long *Q = w->L->Perm;
  SuiteSparse_long *inv = iw, *mark = iw + n;
  for (size_t r = 0; r < n; r++) {
    inv[Q[r]] = (SuiteSparse_long)r;
    mark[r] = -1;
  }
  /* the columns' counts */
  cholmod_sparse *S = NULL;
  SuiteSparse_long *Sp = NULL, *Si = NULL, *next = NULL;
  for (int pass = 0; pass < 2; pass++) {
    if (pass == 1) {
      size_t nnz = 0;
      for (size_t k = 0; k < n; k++) {
        SuiteSparse_long t = (SuiteSparse_long)nnz;
        nnz += (size_t)Sp[k];
        Sp[k] = t;
      }
      Sp[n] = (SuiteSparse_long)nnz;
      S = w->S = cholmod_l_allocate_sparse(n, n, nnz, 1, 1, -1, CHOLMOD_REAL, &w->c);
      w->kx = mfs_calloc(nnz ? nnz : 1, sizeof *w->kx);
      w->mx = mfs_calloc(nnz ? nnz : 1, sizeof *w->mx);
      if (!S || !w->kx || !w->mx) {
        mfs_free(Sp);
        mfs_free(next);
        return 0;
      }
      SuiteSparse_long *p = S->p;
      memcpy(p, Sp, (n + 1) * sizeof *p);
      mfs_free(Sp);
      Sp = p;
      Si = S->i;
      memcpy(next, Sp, n * sizeof *next); /* the next free place of each column */
      for (size_t r = 0; r < n; r++)
        mark[r] = -1;
    } else {
      Sp = mfs_calloc(n + 1, sizeof *Sp);
      next = mfs_malloc((n ? n : 1) * sizeof *next);
      if (!Sp || !next) {
        mfs_free(Sp);
        mfs_free(next);
        return 0;
      }
    }
    for (size_t r = 0; r < n; r++) { /* row r of the new order: row j = Q[r] of K and M */
      size_t j = (size_t)Q[r];
      SuiteSparse_long sr = (SuiteSparse_long)r;
      for (int t = 0; t < 2; t++) {
        const mfs_csr *B = t == 0 ? K : M;
        size_t lo = B ? B->ptr[j] : 0, hi = B ? B->ptr[j + 1] : 1;
        for (size_t e = lo; e < hi; e++) {
          size_t i = B ? (size_t)B->idx[e] : j;
          SuiteSparse_long cc = inv[i];
          if (cc > sr)
            continue;
          double v = B ? B->val[e] : P->m[j];
          if (mark[cc] != sr) { /* a new entry (r, cc) */
            mark[cc] = sr;
            if (pass == 0) {
              Sp[cc]++;
            } else {
              SuiteSparse_long q = next[cc]++;
              Si[q] = sr;
            }
          }
          if (pass == 1) {
            double *x = t == 0 ? w->kx : w->mx;
            x[next[cc] - 1] += v; /* rows arrive in order: the entry is the column's last */
          }
        }
      }
    }
  }
  mfs_free(next);
  S->sorted = 1;
  return 1;
}

/* x (n x dim, or NULL): the unknowns' coordinates, for a geometric order;
 * order: MFS_CERT_ORDER_*.  The order and the symbolic analysis, once. */
static int cert_init(cert_ws *w, const mfs_pencil *P, const double *x, int dim, int order)
{
  memset(w, 0, sizeof *w);
  mfs_cholmod_start(&w->c);
  w->c.supernodal = CHOLMOD_SUPERNODAL; /* LL', stops at the first bad pivot */
  /* the ordering's own cost counts: at 10^5 particles (2D, cubic MLS, one
   * core) CHOLMOD's nested dissection (NESDIS) spent 1.8-2.0 s ordering and
   * 1.9-2.3 s factoring, METIS 1.4-1.6 s and 1.8-2.0 s, AMD 0.2-0.3 s and
   * 2.3-2.7 s (up to twice the flops of nested dissection, 1.05-1.3 times its
   * entries).  With the unknowns' coordinates, a geometric nested dissection
   * (mfs_cholmod_geometric_order: the fill of nested dissection in less time
   * than AMD); without, AMD up to CERT_AMD_MAX unknowns, METIS above, where
   * AMD's extra fill grows faster than METIS's cost (measured:
   * analysis/bench/bench_check.c) */
  w->c.nmethods = 1;
  size_t n = P->K->nrow;
  w->c.method[0].ordering = n <= CERT_AMD_MAX ? CHOLMOD_AMD : CHOLMOD_METIS;
  if (order == MFS_CERT_ORDER_AMD)
    w->c.method[0].ordering = CHOLMOD_AMD;
  else if (order == MFS_CERT_ORDER_METIS)
    w->c.method[0].ordering = CHOLMOD_METIS;
  else if (order == MFS_CERT_ORDER_NESDIS)
    w->c.method[0].ordering = CHOLMOD_NESDIS;
  if (x && dim > 0 && (order == MFS_CERT_ORDER_DEFAULT || order == MFS_CERT_ORDER_GEOMETRIC)) {
    double t0 = wall();
    w->perm = mfs_malloc((n ? n : 1) * sizeof *w->perm);
    if (!w->perm || !mfs_cholmod_geometric_order(n, P->K, P->M, x, dim, w->perm))
      return MFS_ENOMEM;
    w->c.method[0].ordering = CHOLMOD_GIVEN;
    w->order_s = wall() - t0;
  }
  double t0 = wall();
  SuiteSparse_long *iw = mfs_malloc((2 * n + 1) * sizeof *iw);
  cholmod_sparse *A = iw ? cert_pattern(P, iw, &w->c) : NULL;
  if (A)
    w->L = w->perm ? cholmod_l_analyze_p(A, w->perm, NULL, 0, &w->c) : cholmod_l_analyze(A, &w->c);
  cholmod_l_free_sparse(&A, &w->c);
  int ok = w->L && cert_permuted(w, P, iw);
  mfs_free(iw);
  w->analyze_s = wall() - t0;
  return ok ? MFS_OK : MFS_ENOMEM;
}

/* gamma_m / (1 - gamma_m), gamma_m = m u / (1 - m u). */
static double gamma_ratio(double m)
{
  double u = 0x1.0p-53, g = m * u / (1.0 - m * u);
  return g / (1.0 - g);
}

/* Row counts of the supernodal factor (the amalgamated pattern, a superset
 * of the true one): the longest row k of L and the longest row w of L + L'. */
static void factor_rows(const cholmod_factor *L, int *kmax, int *wmax, long *work)
{
  size_t n = L->n;
  const SuiteSparse_long *super = L->super, *pi = L->pi, *sx = L->s;
  memset(work, 0, n * sizeof *work);
  long colmax = 0;
  for (size_t sn = 0; sn < L->nsuper; sn++) {
    long k1 = super[sn], k2 = super[sn + 1], nc = k2 - k1, nr = pi[sn + 1] - pi[sn];
    for (long t = 0; t < nr; t++) {
      long r = sx[pi[sn] + t];
      work[r] += t < nc ? t + 1 : nc; /* the triangle, then full rows */
    }
    colmax = nr > colmax ? nr : colmax; /* the first column of a supernode is its longest */
  }
  long rk = 0;
  for (size_t i = 0; i < n; i++)
    rk = work[i] > rk ? work[i] : rk;
  *kmax = (int)rk;
  *wmax = (int)(rk + colmax - 1);
}

/* cholmod_l_super_numeric of S into L, CHOLMOD's loops on this thread
 * (chol_serial_begin). */
static int cert_numeric(cholmod_sparse *S, cholmod_factor *L, cholmod_common *c)
{
  double zero[2] = {0.0, 0.0};
  int levels = chol_serial_begin();
  int ok = cholmod_l_super_numeric(S, NULL, zero, L, c);
  chol_serial_end(levels);
  return ok;
}

static int cert_factor(cert_ws *w, double sigma, mfs_certificate *out)
{
  cholmod_common *c = &w->c;
  double t0 = wall();
  double *Sx = w->S->x;
  const double *kx = w->kx, *mx = w->mx;
  size_t nnz = (size_t)((SuiteSparse_long *)w->S->p)[w->S->ncol];
  for (size_t e = 0; e < nnz; e++) /* fl(fl(sigma m) - k): as cholmod_l_add formed it */
    Sx[e] = sigma * mx[e] - kx[e];
  c->status = CHOLMOD_OK;
  int ok = cert_numeric(w->S, w->L, c);
  w->numeric_s += wall() - t0;
  if (c->status == CHOLMOD_OUT_OF_MEMORY)
    return MFS_ENOMEM;
  out->ok = ok && c->status == CHOLMOD_OK && w->L->minor == w->L->n && w->L->is_super;
  out->factor_nnz = (double)w->L->xsize;
  out->flops = c->fl;
  out->margin = 0.0;
  out->max_row = 0;
  if (out->ok) {
    long *work = mfs_malloc(w->L->n * sizeof *work);
    if (!work)
      return MFS_ENOMEM;
    int k, wr;
    factor_rows(w->L, &k, &wr, work);
    mfs_free(work);
    out->max_row = k;
    out->margin = (double)wr * gamma_ratio((double)k + 1.0) + 5.0 * 0x1.0p-53;
  }
  return MFS_OK;
}

mfs_status mfs_eig_certify(const mfs_pencil *P, double sigma, mfs_certificate *out)
{
  memset(out, 0, sizeof *out);
  int st = pencil_check_any_mass(P);
  if (st != MFS_OK || !(sigma > 0.0) || !isfinite(sigma))
    return MFS_EINVAL;
  cert_ws w;
  st = cert_init(&w, P, NULL, 0, MFS_CERT_ORDER_DEFAULT);
  if (st == MFS_OK)
    st = cert_factor(&w, sigma, out);
  cert_free(&w);
  return st;
}

/* One trial of the search at sigma: a success becomes the upper end hi (and
 * its certificate best), a failure the lower end lo and, if the largest,
 * r->sigma_failed.  Counts the factorization. */
static mfs_status cert_try(cert_ws *w, double sigma, mfs_certify_result *r, double *lo, double *hi,
                           mfs_certificate *best)
{
  mfs_certificate c;
  mfs_status st = cert_factor(w, sigma, &c);
  r->factorizations++;
  if (st != MFS_OK)
    return st;
  if (c.ok) {
    *hi = sigma;
    *best = c;
  } else {
    *lo = sigma;
    r->sigma_failed = sigma > r->sigma_failed ? sigma : r->sigma_failed;
  }
  return MFS_OK;
}

mfs_status mfs_eig_certify_search(const mfs_pencil *P, const mfs_certify_opts *o,
                                  mfs_certify_result *r)
{
  memset(r, 0, sizeof *r);
  int st = pencil_check_any_mass(P);
  if (st != MFS_OK || !o || !(o->lambda_est > 0.0) || !isfinite(o->lambda_est))
    return MFS_EINVAL;
  double gap = o->gap > 0.0 ? o->gap : 1e-6, growth = o->growth > 1.0 ? o->growth : 10.0;
  int maxf = o->max_factorizations > 0 ? o->max_factorizations : 30;
  cert_ws w;
  st = cert_init(&w, P, o->coord_dim > 0 ? o->coord : NULL, o->coord_dim, o->order);
  double lo = o->lambda_est, hi = 0.0;
  mfs_certificate best = {0};
  /* bracket: sigma's gap grows by `growth` until a factorization succeeds */
  while (st == MFS_OK && hi == 0.0 && r->factorizations < maxf) {
    st = cert_try(&w, o->lambda_est * (1.0 + gap), r, &lo, &hi, &best);
    gap *= growth;
  }
  for (int k = 0; st == MFS_OK && hi > 0.0 && k < o->refine && r->factorizations < maxf; k++)
    st = cert_try(&w, 0.5 * (lo + hi), r, &lo, &hi, &best); /* bisection */
  if (st == MFS_OK && hi > 0.0) {
    r->ok = 1;
    r->sigma = hi;
    r->margin = best.margin;
    r->lambda_upper = hi * (1.0 + best.margin);
    r->factor_nnz = best.factor_nnz;
    r->flops = best.flops;
  }
  if (w.L)
    r->supernodes = (int)w.L->nsuper;
  r->order_s = w.order_s;
  r->analyze_s = w.analyze_s;
  r->numeric_s = w.numeric_s;
  cert_free(&w);
  return st;
}

/* ------------------------------------------------------------------ */
/* dense cross-check                                                   */

mfs_status mfs_eig_dense(const mfs_pencil *P, double *w)
{
  int st = pencil_check(P);
  if (st != MFS_OK)
    return st;
  size_t n = P->K->nrow;
  if (n > MFS_EIG_DENSE_MAX)
    return MFS_EINVAL;
  double *A = mfs_calloc(n * n, sizeof *A), *B = mfs_calloc(n * n, sizeof *B);
  st = MFS_ENOMEM;
  if (!A || !B)
    goto done;
  for (size_t i = 0; i < n; i++)
    for (size_t e = P->K->ptr[i]; e < P->K->ptr[i + 1]; e++)
      A[i * n + (size_t)P->K->idx[e]] += P->K->val[e];
  if (P->M) {
    for (size_t i = 0; i < n; i++)
      for (size_t e = P->M->ptr[i]; e < P->M->ptr[i + 1]; e++)
        B[i * n + (size_t)P->M->idx[e]] += P->M->val[e];
  } else {
    for (size_t i = 0; i < n; i++)
      B[i * n + i] = P->m[i];
  }
  mfs_lapack_reset();
  lapack_int info = LAPACKE_dsygvd(LAPACK_ROW_MAJOR, 1, 'N', 'U', (lapack_int)n, A,
                                   (lapack_int)n, B, (lapack_int)n, w);
  if (info == 0 && mfs_lapack_last()->count == 0)
    st = MFS_OK;
  else if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR)
    st = MFS_ENOMEM;
  else
    st = info > (lapack_int)n ? MFS_EDOMAIN : MFS_ELAPACK;
done:
  mfs_free(A);
  mfs_free(B);
  return st;
}
