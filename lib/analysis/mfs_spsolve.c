#include "mfs_spsolve.h"
#include "mfs_alloc.h"

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>
#include <suitesparse/umfpack.h>

#include "mfs_cholmod.h"

static double inf_norm_rows(const mfs_csr *A)
{
  double m = 0.0;
  for (size_t i = 0; i < A->nrow; i++) {
    double s = 0.0;
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
      s += fabs(A->val[e]);
    m = s > m ? s : m;
  }
  return m;
}

/* Normwise backward error of x; NAN if x is not finite. */
static double backward_error(const mfs_csr *A, const double *b, const double *x)
{
  double r = 0.0, xn = 0.0, bn = 0.0;
  for (size_t i = 0; i < A->nrow; i++) {
    if (!isfinite(x[i]))
      return NAN;
    double s = -b[i];
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
      s += A->val[e] * x[A->idx[e]];
    r = fmax(r, fabs(s));
    xn = fmax(xn, fabs(x[i]));
    bn = fmax(bn, fabs(b[i]));
  }
  double den = inf_norm_rows(A) * xn + bn;
  return den > 0.0 ? r / den : 0.0;
}

/* ---- CHOLMOD ---------------------------------------------------------- */

/* CHOLMOD's default ordering strategy (nmethods 0, no given permutation:
 * method 1 is AMD, method 2 METIS, tried only where AMD's fill is high, the
 * better one taken) skips an ordering that fails for lack of memory and
 * clears the status: the factorization then uses another ordering than it
 * does with enough memory, with another rounding and another rcond
 * estimate.  1 if that happened after cholmod_l_analyze on a fresh common
 * (the methods' counts start EMPTY): the solvers report it as out of memory
 * rather than a different result. */
static int ordering_skipped(const cholmod_common *c)
{
  if (c->nmethods != 0)
    return 0;
  double lnz = c->method[1].lnz, fl = c->method[1].fl;
  if (lnz < 0.0)
    return 1; /* AMD failed */
  int metis_tried = !(fl < 500.0 * lnz || lnz < 5.0 * c->anz); /* cholmod_analyze's test */
  return metis_tried && c->method[2].lnz < 0.0;
}

/* The Cholesky factor of the symmetric positive definite S (upper
 * triangle) in *L: MFS_OK, MFS_ESYSTEM (not positive definite) or
 * MFS_ENOMEM; info->lib_status is CHOLMOD's status. */
static int factor_spd(cholmod_sparse *S, cholmod_common *c, cholmod_factor **L,
                      mfs_spsolve_info *info)
{
  *L = cholmod_l_analyze(S, c);
  if (!*L || ordering_skipped(c))
    return MFS_ENOMEM;
  int ok = cholmod_l_factorize(S, *L, c);
  info->lib_status = c->status;
  if (!ok || c->status == CHOLMOD_OUT_OF_MEMORY)
    return MFS_ENOMEM;
  if (c->status == CHOLMOD_NOT_POSDEF || (*L)->minor < (*L)->n)
    return MFS_ESYSTEM;
  if (!(*L)->is_super && !(*L)->is_ll) { /* simplicial LDL': positive definite is D > 0 */
    const SuiteSparse_long *Lp = (*L)->p;
    const double *Lx = (*L)->x;
    for (size_t j = 0; j < (*L)->n; j++)
      if (!(Lx[Lp[j]] > 0.0))
        return MFS_ESYSTEM;
  }
  return MFS_OK;
}

static int cholmod_solve_fn(const mfs_csr *A, const double *b, double *x, mfs_spsolve_info *info)
{
  cholmod_common c;
  mfs_cholmod_start(&c);
  cholmod_sparse *S = NULL;
  cholmod_factor *L = NULL;
  cholmod_dense *B = NULL, *X = NULL;
  int st = MFS_ENOMEM;
  size_t n = A->nrow;
  S = mfs_cholmod_upper(A, &c);
  if (!S)
    goto done;
  st = factor_spd(S, &c, &L, info);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  info->rcond = cholmod_l_rcond(L, &c);
  info->factor_nnz = c.lnz;
  B = cholmod_l_allocate_dense(n, 1, n, CHOLMOD_REAL, &c);
  if (!B)
    goto done;
  memcpy(B->x, b, n * sizeof *b);
  X = cholmod_l_solve(CHOLMOD_A, L, B, &c);
  if (!X)
    goto done;
  memcpy(x, X->x, n * sizeof *x);
  st = MFS_OK;
done:
  cholmod_l_free_dense(&X, &c);
  cholmod_l_free_dense(&B, &c);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_free_sparse(&S, &c);
  cholmod_l_finish(&c);
  return st;
}

/* A CSR matrix read as compressed columns (its transpose), long indices. */
static cholmod_sparse *csr_as_columns(const mfs_csr *A, cholmod_common *c)
{
  size_t nnz = A->ptr[A->nrow];
  cholmod_sparse *S = cholmod_l_allocate_sparse(A->ncol, A->nrow, nnz, 0, 1, 0, CHOLMOD_REAL, c);
  if (!S)
    return NULL;
  SuiteSparse_long *Sp = S->p, *Si = S->i;
  double *Sx = S->x;
  for (size_t j = 0; j <= A->nrow; j++)
    Sp[j] = (SuiteSparse_long)A->ptr[j];
  for (size_t e = 0; e < nnz; e++) {
    Si[e] = A->idx[e];
    Sx[e] = A->val[e];
  }
  if (!cholmod_l_sort(S, c)) {
    cholmod_l_free_sparse(&S, c);
    return NULL;
  }
  return S;
}

static double max_abs(const cholmod_sparse *S)
{
  const SuiteSparse_long *Sp = S->p;
  const double *Sx = S->x;
  double m = 0.0;
  for (SuiteSparse_long e = 0; e < Sp[S->ncol]; e++)
    m = fmax(m, fabs(Sx[e]));
  return m;
}

/* x, lambda of the symmetric saddle-point system: A + rho C^T C by CHOLMOD,
 * the Schur complement by LAPACK. */
static int cholmod_constrained_fn(const mfs_csr *A, const mfs_csr *C, const double *b,
                                  const double *g, double *x, double *lambda,
                                  mfs_spsolve_info *info)
{
  cholmod_common c;
  mfs_cholmod_start(&c);
  size_t n = A->nrow, m = C->nrow;
  int st = MFS_ENOMEM;
  cholmod_sparse *Af = NULL, *Ct = NULL, *CtC = NULL, *Mf = NULL, *M = NULL;
  cholmod_factor *L = NULL;
  cholmod_dense *Bd = NULL, *Z = NULL, *bt = NULL, *y = NULL;
  double *S = NULL, *r = NULL, *wk = NULL;
  lapack_int *iwk = NULL;
  Af = csr_as_columns(A, &c); /* A^T = A */
  Ct = csr_as_columns(C, &c); /* n x m */
  if (!Af || !Ct)
    goto done;
  CtC = cholmod_l_aat(Ct, NULL, 0, 1, &c); /* C^T C */
  if (!CtC)
    goto done;
  double ma = max_abs(Af), mc = max_abs(CtC);
  double rho = mc > 0.0 ? ma / mc : 0.0;
  double al[2] = {1.0, 0.0}, be[2] = {rho, 0.0};
  Mf = cholmod_l_add(Af, CtC, al, be, 1, 1, &c);
  cholmod_l_free_sparse(&Af, &c); /* freed as soon as possible: the peak memory */
  cholmod_l_free_sparse(&CtC, &c);
  if (!Mf)
    goto done;
  M = cholmod_l_copy(Mf, 1, 1, &c); /* the upper triangle, symmetric */
  cholmod_l_free_sparse(&Mf, &c);
  if (!M)
    goto done;
  st = factor_spd(M, &c, &L, info);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  double rcL = cholmod_l_rcond(L, &c);
  info->factor_nnz = c.lnz;
  /* Z = M^-1 C^T (n x m), y = M^-1 (b + rho C^T g) */
  Bd = cholmod_l_allocate_dense(n, m ? m : 1, n, CHOLMOD_REAL, &c);
  bt = cholmod_l_allocate_dense(n, 1, n, CHOLMOD_REAL, &c);
  S = mfs_calloc(m * m + 1, sizeof *S);
  r = mfs_malloc((m + 1) * sizeof *r);
  wk = mfs_malloc((3 * m + 1) * sizeof *wk); /* dpocon's workspaces (the _work driver) */
  iwk = mfs_malloc((m + 1) * sizeof *iwk);
  if (!Bd || !bt || !S || !r || !wk || !iwk)
    goto done;
  double *B = Bd->x, *bv = bt->x;
  memset(B, 0, n * (m ? m : 1) * sizeof *B);
  memcpy(bv, b, n * sizeof *b);
  for (size_t k = 0; k < m; k++)
    for (size_t e = C->ptr[k]; e < C->ptr[k + 1]; e++) {
      B[(size_t)C->idx[e] + n * k] += C->val[e];
      bv[C->idx[e]] += rho * C->val[e] * g[k];
    }
  Z = cholmod_l_solve(CHOLMOD_A, L, Bd, &c);
  y = cholmod_l_solve(CHOLMOD_A, L, bt, &c);
  if (!Z || !y)
    goto done;
  const double *Zx = Z->x, *yx = y->x;
  /* S = C Z, r = C y - g */
  for (size_t k = 0; k < m; k++) {
    r[k] = -g[k];
    for (size_t e = C->ptr[k]; e < C->ptr[k + 1]; e++) {
      size_t i = (size_t)C->idx[e];
      r[k] += C->val[e] * yx[i];
      for (size_t j = 0; j < m; j++)
        S[k + m * j] += C->val[e] * Zx[i + n * j];
    }
  }
  double rcS = 1.0;
  if (m > 0) {
    double anorm = 0.0;
    for (size_t j = 0; j < m; j++) {
      double t = 0.0;
      for (size_t k = 0; k < m; k++)
        t += fabs(S[k + m * j]);
      anorm = fmax(anorm, t);
    }
    lapack_int inf = LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', (lapack_int)m, S, (lapack_int)m);
    if (inf != 0) {
      st = inf > 0 ? MFS_ESYSTEM : MFS_EINVAL;
      info->rcond = 0.0;
      goto done;
    }
    LAPACKE_dpocon_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, S, (lapack_int)m, anorm, &rcS, wk,
                        iwk);
    LAPACKE_dpotrs(LAPACK_COL_MAJOR, 'L', (lapack_int)m, 1, S, (lapack_int)m, r, (lapack_int)m);
  }
  for (size_t i = 0; i < n; i++) {
    double v = yx[i];
    for (size_t k = 0; k < m; k++)
      v -= Zx[i + n * k] * r[k];
    x[i] = v;
  }
  if (lambda)
    memcpy(lambda, r, m * sizeof *r);
  info->rcond = fmin(rcL, rcS);
  st = MFS_OK;
done:
  cholmod_l_free_dense(&Bd, &c);
  cholmod_l_free_dense(&bt, &c);
  cholmod_l_free_dense(&Z, &c);
  cholmod_l_free_dense(&y, &c);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_free_sparse(&M, &c);
  cholmod_l_free_sparse(&Mf, &c);
  cholmod_l_free_sparse(&CtC, &c);
  cholmod_l_free_sparse(&Ct, &c);
  cholmod_l_free_sparse(&Af, &c);
  cholmod_l_finish(&c);
  mfs_free(S);
  mfs_free(r);
  mfs_free(wk);
  mfs_free(iwk);
  return st;
}

/* ---- UMFPACK ---------------------------------------------------------- */

typedef struct {
  int i;
  double v;
} entry;

static int cmp_entry(const void *a, const void *b)
{
  int x = ((const entry *)a)->i, y = ((const entry *)b)->i;
  return (x > y) - (x < y);
}

static int umfpack_solve_fn(const mfs_csr *A, const double *b, double *x, mfs_spsolve_info *info)
{
  size_t n = A->nrow, nnz = A->ptr[n], maxrow = 0;
  int st = MFS_ENOMEM;
  void *Sym = NULL, *Num = NULL;
  SuiteSparse_long *Ap = mfs_malloc((n + 1) * sizeof *Ap), *Ai = mfs_malloc((nnz ? nnz : 1) * sizeof *Ai);
  double *Ax = mfs_malloc((nnz ? nnz : 1) * sizeof *Ax);
  entry *row = NULL;
  for (size_t i = 0; i < n; i++)
    maxrow = A->ptr[i + 1] - A->ptr[i] > maxrow ? A->ptr[i + 1] - A->ptr[i] : maxrow;
  row = mfs_malloc((maxrow ? maxrow : 1) * sizeof *row);
  if (!Ap || !Ai || !Ax || !row)
    goto done;
  /* row i of A, sorted, is column i of A^T */
  Ap[0] = 0;
  for (size_t i = 0; i < n; i++) {
    size_t e0 = A->ptr[i], len = A->ptr[i + 1] - e0;
    for (size_t k = 0; k < len; k++)
      row[k] = (entry){A->idx[e0 + k], A->val[e0 + k]};
    qsort(row, len, sizeof *row, cmp_entry);
    for (size_t k = 0; k < len; k++) {
      Ai[e0 + k] = row[k].i;
      Ax[e0 + k] = row[k].v;
    }
    Ap[i + 1] = (SuiteSparse_long)(e0 + len);
  }
  double Control[UMFPACK_CONTROL], Info[UMFPACK_INFO];
  umfpack_dl_defaults(Control);
  Control[UMFPACK_PRL] = 0; /* the library never prints */
  SuiteSparse_long s = umfpack_dl_symbolic((SuiteSparse_long)n, (SuiteSparse_long)n, Ap, Ai, Ax,
                                           &Sym, Control, Info);
  info->lib_status = (int)s;
  if (s != UMFPACK_OK) {
    st = s == UMFPACK_ERROR_out_of_memory ? MFS_ENOMEM : MFS_EINVAL;
    goto done;
  }
  s = umfpack_dl_numeric(Ap, Ai, Ax, Sym, &Num, Control, Info);
  info->lib_status = (int)s;
  info->rcond = Info[UMFPACK_RCOND];
  info->factor_nnz = Info[UMFPACK_LNZ] + Info[UMFPACK_UNZ];
  if (s == UMFPACK_WARNING_singular_matrix) {
    st = MFS_ESYSTEM;
    info->rcond = 0.0;
    goto done;
  }
  if (s != UMFPACK_OK) {
    st = s == UMFPACK_ERROR_out_of_memory ? MFS_ENOMEM : MFS_EINVAL;
    goto done;
  }
  s = umfpack_dl_solve(UMFPACK_At, Ap, Ai, Ax, x, b, Num, Control, Info);
  if (s != UMFPACK_OK) {
    st = s == UMFPACK_ERROR_out_of_memory ? MFS_ENOMEM : MFS_ESYSTEM;
    goto done;
  }
  st = MFS_OK;
done:
  umfpack_dl_free_numeric(&Num);
  umfpack_dl_free_symbolic(&Sym);
  mfs_free(Ap);
  mfs_free(Ai);
  mfs_free(Ax);
  mfs_free(row);
  return st;
}

const mfs_spsolve_type mfs_spsolve_cholmod = {.name = "cholmod",
                                              .symmetric_only = 1,
                                              .solve = cholmod_solve_fn,
                                              .solve_constrained = cholmod_constrained_fn};
const mfs_spsolve_type mfs_spsolve_umfpack = {
  .name = "umfpack", .symmetric_only = 0, .solve = umfpack_solve_fn};
const mfs_spsolve_type *const mfs_spsolve_types[] = {&mfs_spsolve_cholmod, &mfs_spsolve_umfpack,
                                                     NULL};

const mfs_spsolve_type *mfs_spsolve_find(const char *name)
{
  for (int i = 0; name && mfs_spsolve_types[i]; i++)
    if (strcmp(name, mfs_spsolve_types[i]->name) == 0)
      return mfs_spsolve_types[i];
  return NULL;
}

mfs_status mfs_spsolve(const mfs_spsolve_type *t, const mfs_csr *A, const double *b, double *x,
                       double rcond_min, mfs_spsolve_info *info)
{
  mfs_spsolve_info tmp;
  if (!info)
    info = &tmp;
  *info = (mfs_spsolve_info){.rcond = NAN, .backward = NAN, .factor_nnz = NAN};
  if (!t || !A || !b || !x || A->nrow != A->ncol)
    return MFS_EINVAL;
  if (A->nrow == 0)
    return MFS_OK;
  int st = t->solve(A, b, x, info);
  if (st != MFS_OK)
    return (mfs_status)st;
  info->backward = backward_error(A, b, x);
  if (isnan(info->backward) || !(info->rcond >= rcond_min) || info->rcond == 0.0)
    return MFS_ESYSTEM;
  return MFS_OK;
}

/* The (n + m) square saddle-point matrix [[A, Ct^T], [C, 0]] in CSR. */
static mfs_csr *saddle_matrix(const mfs_csr *A, const mfs_csr *C, const mfs_csr *Ct)
{
  size_t n = A->nrow, m = C->nrow, N = n + m;
  size_t *cnt = mfs_calloc(n + 1, sizeof *cnt);
  mfs_csr *K = cnt ? mfs_csr_alloc(N, N, A->ptr[n] + C->ptr[m] + Ct->ptr[m]) : NULL;
  if (!K) {
    mfs_free(cnt);
    return NULL;
  }
  for (size_t e = 0; e < Ct->ptr[m]; e++)
    cnt[Ct->idx[e]]++;
  size_t pos = 0;
  for (size_t i = 0; i < n; i++) {
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
      K->idx[pos] = A->idx[e];
      K->val[pos++] = A->val[e];
    }
    pos += cnt[i]; /* the row's entries of Ct^T, below */
    K->ptr[i + 1] = pos;
  }
  for (size_t i = 0; i < n; i++)
    cnt[i] = K->ptr[i + 1] - cnt[i];
  for (size_t k = 0; k < m; k++)
    for (size_t e = Ct->ptr[k]; e < Ct->ptr[k + 1]; e++) {
      size_t i = (size_t)Ct->idx[e];
      K->idx[cnt[i]] = (int)(n + k);
      K->val[cnt[i]++] = Ct->val[e];
    }
  for (size_t k = 0; k < m; k++) {
    for (size_t e = C->ptr[k]; e < C->ptr[k + 1]; e++) {
      K->idx[pos] = C->idx[e];
      K->val[pos++] = C->val[e];
    }
    K->ptr[n + k + 1] = pos;
  }
  mfs_free(cnt);
  return K;
}

/* The normwise backward error of (x, l) for the saddle-point system, from
 * its blocks: r = [A x + Ct^T l - b; C x - g], in *be (NAN if (x, l) is not
 * finite).  MFS_OK, or MFS_ENOMEM (a failure to allocate is not a large
 * backward error: the caller would call the system singular). */
static int saddle_backward(const mfs_csr *A, const mfs_csr *C, const mfs_csr *Ct,
                           const double *b, const double *g, const double *x, const double *l,
                           double *be)
{
  size_t n = A->nrow, m = C->nrow;
  double *r = mfs_calloc(n + m + 1, sizeof *r), *rs = mfs_calloc(n + m + 1, sizeof *rs);
  if (!r || !rs) {
    mfs_free(r);
    mfs_free(rs);
    return MFS_ENOMEM;
  }
  double xn = 0.0, bn = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(x[i]))
      goto bad;
    xn = fmax(xn, fabs(x[i]));
    bn = fmax(bn, fabs(b[i]));
    r[i] = -b[i];
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
      r[i] += A->val[e] * x[A->idx[e]];
      rs[i] += fabs(A->val[e]);
    }
  }
  for (size_t k = 0; k < m; k++) {
    if (!isfinite(l[k]))
      goto bad;
    xn = fmax(xn, fabs(l[k]));
    bn = fmax(bn, fabs(g[k]));
    r[n + k] = -g[k];
    for (size_t e = C->ptr[k]; e < C->ptr[k + 1]; e++) {
      r[n + k] += C->val[e] * x[C->idx[e]];
      rs[n + k] += fabs(C->val[e]);
    }
    for (size_t e = Ct->ptr[k]; e < Ct->ptr[k + 1]; e++) {
      r[Ct->idx[e]] += Ct->val[e] * l[k];
      rs[Ct->idx[e]] += fabs(Ct->val[e]);
    }
  }
  double rn = 0.0, an = 0.0;
  for (size_t i = 0; i < n + m; i++) {
    rn = fmax(rn, fabs(r[i]));
    an = fmax(an, rs[i]);
  }
  *be = an * xn + bn > 0.0 ? rn / (an * xn + bn) : 0.0;
  mfs_free(r);
  mfs_free(rs);
  return MFS_OK;
bad:
  *be = NAN;
  mfs_free(r);
  mfs_free(rs);
  return MFS_OK;
}

mfs_status mfs_spsolve_constrained(const mfs_spsolve_type *t, const mfs_csr *A, const mfs_csr *C,
                                   const mfs_csr *Ct, const double *b, const double *g, double *x,
                                   double *lambda, double rcond_min, mfs_spsolve_info *info)
{
  mfs_spsolve_info tmp;
  if (!info)
    info = &tmp;
  *info = (mfs_spsolve_info){.rcond = NAN, .backward = NAN, .factor_nnz = NAN};
  if (!t || !A || !C || !b || !x || A->nrow != A->ncol || C->ncol != A->nrow ||
      (Ct && (Ct->nrow != C->nrow || Ct->ncol != C->ncol)) || (C->nrow && !g))
    return MFS_EINVAL;
  size_t n = A->nrow, m = C->nrow;
  mfs_csr *K = NULL;
  double *rhs = NULL, *sol = mfs_malloc((n + m + 1) * sizeof *sol);
  int st = MFS_ENOMEM;
  if (!sol)
    goto done;
  if (!Ct && t->solve_constrained) {
    st = t->solve_constrained(A, C, b, g, sol, sol + n, info);
  } else {
    st = MFS_EINVAL;
    if (t->symmetric_only) /* the saddle-point matrix is indefinite */
      goto done;
    st = MFS_ENOMEM;
    K = saddle_matrix(A, C, Ct ? Ct : C);
    rhs = mfs_malloc((n + m + 1) * sizeof *rhs);
    if (!K || !rhs)
      goto done;
    memcpy(rhs, b, n * sizeof *b);
    if (m)
      memcpy(rhs + n, g, m * sizeof *g);
    st = t->solve(K, rhs, sol, info);
  }
  if (st != MFS_OK)
    goto done;
  st = saddle_backward(A, C, Ct ? Ct : C, b, g, sol, sol + n, &info->backward);
  if (st != MFS_OK)
    goto done;
  if (isnan(info->backward) || !(info->rcond >= rcond_min) || info->rcond == 0.0)
    st = MFS_ESYSTEM;
  memcpy(x, sol, n * sizeof *x);
  if (lambda)
    memcpy(lambda, sol + n, m * sizeof *lambda);
done:
  mfs_csr_free(K);
  mfs_free(rhs);
  mfs_free(sol);
  return (mfs_status)st;
}
