#include "mfs_csr.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>

#include "mfs_status.h"

mfs_csr *mfs_csr_alloc(size_t nrow, size_t ncol, size_t nnz)
{
  mfs_csr *A = mfs_calloc(1, sizeof *A);
  if (!A)
    return NULL;
  A->nrow = nrow;
  A->ncol = ncol;
  A->ptr = mfs_calloc(nrow + 1, sizeof *A->ptr);
  A->idx = mfs_malloc((nnz ? nnz : 1) * sizeof *A->idx);
  A->val = mfs_malloc((nnz ? nnz : 1) * sizeof *A->val);
  if (!A->ptr || !A->idx || !A->val) {
    mfs_csr_free(A);
    return NULL;
  }
  return A;
}

void mfs_csr_free(mfs_csr *A)
{
  if (!A)
    return;
  mfs_free(A->ptr);
  mfs_free(A->idx);
  mfs_free(A->val);
  mfs_free(A);
}

void mfs_csr_matvec(const mfs_csr *A, const double *x, double *y)
{
  for (size_t i = 0; i < A->nrow; i++) {
    double s = 0.0;
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
      s += A->val[e] * x[A->idx[e]];
    y[i] = s;
  }
}

double mfs_csr_get(const mfs_csr *A, size_t i, int j)
{
  for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
    if (A->idx[e] == j)
      return A->val[e];
  return 0.0;
}

double mfs_csr_asymmetry(const mfs_csr *A, double *amax)
{
  double d = 0.0, m = 0.0;
  for (size_t i = 0; i < A->nrow; i++)
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++) {
      double t = fabs(A->val[e] - mfs_csr_get(A, (size_t)A->idx[e], (int)i));
      d = t > d ? t : d;
      m = fabs(A->val[e]) > m ? fabs(A->val[e]) : m;
    }
  if (amax)
    *amax = m;
  return d;
}

mfs_status mfs_csr_write_mtx(const mfs_csr *A, FILE *f)
{
  if (fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n%zu %zu %zu\n", A->nrow,
              A->ncol, A->ptr[A->nrow]) < 0)
    return MFS_EIO;
  for (size_t i = 0; i < A->nrow; i++)
    for (size_t e = A->ptr[i]; e < A->ptr[i + 1]; e++)
      if (fprintf(f, "%zu %d %.17g\n", i + 1, A->idx[e] + 1, A->val[e]) < 0)
        return MFS_EIO;
  return MFS_OK;
}
