#include "mfs_spsolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>
#include <suitesparse/umfpack.h>

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

static int cholmod_solve_fn(const mfs_csr *A, const double *b, double *x, mfs_spsolve_info *info)
{
  cholmod_common c;
  cholmod_l_start(&c);
  c.print = 0; /* the library never prints */
  c.error_handler = NULL;
  cholmod_sparse *S = NULL;
  cholmod_factor *L = NULL;
  cholmod_dense *B = NULL, *X = NULL;
  int st = MFS_ENOMEM;
  size_t n = A->nrow, nnz = 0;
  for (size_t j = 0; j < n; j++)
    for (size_t e = A->ptr[j]; e < A->ptr[j + 1]; e++)
      nnz += (size_t)A->idx[e] <= j;
  /* the upper triangle: column j of the symmetric matrix is its row j */
  S = cholmod_l_allocate_sparse(n, n, nnz, 0, 1, 1, CHOLMOD_REAL, &c);
  if (!S)
    goto done;
  SuiteSparse_long *Sp = S->p, *Si = S->i;
  double *Sx = S->x;
  size_t pos = 0;
  Sp[0] = 0;
  for (size_t j = 0; j < n; j++) {
    for (size_t e = A->ptr[j]; e < A->ptr[j + 1]; e++)
      if ((size_t)A->idx[e] <= j) {
        Si[pos] = A->idx[e];
        Sx[pos++] = A->val[e];
      }
    Sp[j + 1] = (SuiteSparse_long)pos;
  }
  if (!cholmod_l_sort(S, &c))
    goto done;
  L = cholmod_l_analyze(S, &c);
  if (!L)
    goto done;
  int ok = cholmod_l_factorize(S, L, &c);
  info->lib_status = c.status;
  if (!ok || c.status == CHOLMOD_OUT_OF_MEMORY)
    goto done;
  if (c.status == CHOLMOD_NOT_POSDEF || L->minor < L->n) {
    st = MFS_ESYSTEM;
    goto done;
  }
  if (!L->is_super && !L->is_ll) { /* simplicial LDL': positive definite is D > 0 */
    const SuiteSparse_long *Lp = L->p;
    const double *Lx = L->x;
    for (size_t j = 0; j < L->n; j++)
      if (!(Lx[Lp[j]] > 0.0)) {
        st = MFS_ESYSTEM;
        goto done;
      }
  }
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
  SuiteSparse_long *Ap = malloc((n + 1) * sizeof *Ap), *Ai = malloc((nnz ? nnz : 1) * sizeof *Ai);
  double *Ax = malloc((nnz ? nnz : 1) * sizeof *Ax);
  entry *row = NULL;
  for (size_t i = 0; i < n; i++)
    maxrow = A->ptr[i + 1] - A->ptr[i] > maxrow ? A->ptr[i + 1] - A->ptr[i] : maxrow;
  row = malloc((maxrow ? maxrow : 1) * sizeof *row);
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
  free(Ap);
  free(Ai);
  free(Ax);
  free(row);
  return st;
}

const mfs_spsolve_type mfs_spsolve_cholmod = {
  .name = "cholmod", .symmetric_only = 1, .solve = cholmod_solve_fn};
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
