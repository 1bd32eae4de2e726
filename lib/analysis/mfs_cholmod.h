/* CHOLMOD as the library uses it (internal, not installed): a common that
 * never prints nor calls an error handler, and the upper triangle of a
 * symmetric CSR matrix as a CHOLMOD matrix.  Used by mfs_eigen (shift-invert
 * Lanczos, the certified step) and mfs_spsolve (the static solvers). */
#ifndef MFS_CHOLMOD_H
#define MFS_CHOLMOD_H

#include <suitesparse/cholmod.h>

#include "mfs_csr.h"

/* cholmod_l_start with printing and the error handler off. */
void mfs_cholmod_start(cholmod_common *c);

/* The upper triangle of the symmetric A (its rows are the columns of its
 * transpose, which is itself), columns sorted; NULL on out of memory. */
cholmod_sparse *mfs_cholmod_upper(const mfs_csr *A, cholmod_common *c);

/* A fill-reducing order of the unknowns of a matrix with the pattern of
 * A + B (B may be NULL; both symmetric CSR, n x n) from their coordinates
 * x (n x dim): nested dissection by coordinate bisection.  A part larger
 * than 64 unknowns is split at the median of its longer extent; the left
 * unknowns coupled to a right one are its separator, ordered after both
 * halves.  O(nnz log n) and no graph partitioner: for particles in the
 * plane, the fill of nested dissection at the cost of a minimum degree
 * ordering.  perm (n): the order, new position -> unknown.  1, or 0 on
 * out of memory. */
int mfs_cholmod_geometric_order(size_t n, const mfs_csr *A, const mfs_csr *B, const double *x,
                                int dim, SuiteSparse_long *perm);

#endif
