/* Compressed sparse row matrices.  Column indices within a row are
 * distinct but not necessarily sorted. */
#ifndef MFS_CSR_H
#define MFS_CSR_H

#include <stddef.h>
#include <stdio.h>
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  size_t nrow, ncol;
  size_t *ptr; /* nrow+1 */
  int *idx;    /* ptr[nrow] column indices */
  double *val; /* ptr[nrow] values */
} mfs_csr;

/* Room for nnz entries; ptr zeroed.  NULL on failure. */
mfs_csr *mfs_csr_alloc(size_t nrow, size_t ncol, size_t nnz);
void mfs_csr_free(mfs_csr *A);

/* y = A x */
void mfs_csr_matvec(const mfs_csr *A, const double *x, double *y);

/* Entry (i, j), 0 if not stored. */
double mfs_csr_get(const mfs_csr *A, size_t i, int j);

/* max |A_ij - A_ji| over stored entries, and max |A_ij| in *amax. */
double mfs_csr_asymmetry(const mfs_csr *A, double *amax);

/* Write in Matrix Market coordinate real general format. Returns MFS_OK or MFS_EIO. */
mfs_status mfs_csr_write_mtx(const mfs_csr *A, FILE *f);

#ifdef __cplusplus
}
#endif

#endif
