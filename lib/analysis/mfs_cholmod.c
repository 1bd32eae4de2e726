#include "mfs_cholmod.h"

void mfs_cholmod_start(cholmod_common *c)
{
  cholmod_l_start(c);
  c->print = 0; /* the library never prints */
  c->error_handler = NULL;
}

cholmod_sparse *mfs_cholmod_upper(const mfs_csr *A, cholmod_common *c)
{
  size_t n = A->nrow, nnz = 0;
  for (size_t j = 0; j < n; j++)
    for (size_t e = A->ptr[j]; e < A->ptr[j + 1]; e++)
      nnz += (size_t)A->idx[e] <= j;
  cholmod_sparse *S = cholmod_l_allocate_sparse(n, n, nnz, 0, 1, 1, CHOLMOD_REAL, c);
  if (!S)
    return NULL;
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
  if (!cholmod_l_sort(S, c)) {
    cholmod_l_free_sparse(&S, c);
    return NULL;
  }
  return S;
}
