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

#endif
