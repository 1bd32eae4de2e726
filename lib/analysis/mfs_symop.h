/* The symmetric operator A = diag(s) K diag(s) as the iterative
 * eigensolvers read it (internal, not installed): the diagonal blocks and
 * the strict upper block triangle of K, block size b (1, or 2 for the
 * plane-strain pairs), each block row's blocks as runs of consecutive block
 * columns.  The product reads about half of K's bytes, which is what the
 * Lanczos steps of mfs_eig_max (ARPACK) and mfs_lanczos_max spend their
 * time on.
 *
 * The product runs by MFS_SYMOP_BLOCKS row blocks, cut where the stored
 * blocks cross t nnz / MFS_SYMOP_BLOCKS; the number of blocks does not
 * depend on the thread count, so neither does the result.  Block t writes y
 * for its own rows (the diagonal, its rows' sums, the transposed scatter
 * y_j += a_ij^T x_i for j in the block); the scatter beyond its last row
 * goes into the block's own band buffer (columns cut[t+1] .. its largest
 * column), added to the rows of the later blocks in the order of the
 * blocks; no run crosses its block's end.  On a lattice the band is a few
 * rows of particles wide.  Used by lib/analysis/mfs_eigen.c and
 * mfs_lanczos.c. */
#ifndef MFS_SYMOP_H
#define MFS_SYMOP_H

#include <stddef.h>

#include "mfs_csr.h"

#define MFS_SYMOP_BLOCKS 8

/* Block columns col .. col + len - 1 of a block row. */
typedef struct {
  int col, len;
} mfs_symop_run;

typedef struct {
  size_t n, nb;        /* scalar rows; block rows n / b */
  int b;               /* block size, 1 or 2 */
  size_t *ptr;         /* nb + 1: block row i's blocks val[b*b*ptr[i] .. b*b*ptr[i+1]-1] */
  size_t *rptr;        /* nb + 1: its runs run[rptr[i] .. rptr[i+1]-1] */
  mfs_symop_run *run;
  double *val;         /* b*b per stored block, row-major */
  double *diag;        /* b*b per block row: the diagonal block */
  size_t stored;       /* scalar entries stored (upper blocks) */
  size_t runs;         /* runs stored */
  size_t cut[MFS_SYMOP_BLOCKS + 1];  /* block t: block rows cut[t] .. cut[t+1]-1 */
  size_t zoff[MFS_SYMOP_BLOCKS + 1]; /* block t's band buffer (scalar): z[zoff[t] .. zoff[t+1]-1] */
  double *z;
  void *mem;           /* the 2 x 2 build's one block holding val, diag and rptr (NULL: each
                          its own allocation) */
} mfs_symop;

/* Builds A from the symmetric K (both triangles stored) and s (n; NULL:
 * s = 1), block size 2 where it reads fewer bytes than 1.  With x0 (n) and
 * y0 (n) given, and K made of full 2 x 2 blocks in sorted rows (plane strain
 * as mfs_assemble writes it), the build also takes the first product
 * y0 = A x0 from the rows it reads anyway and sets *have_y = 1 (else 0).
 * nt, par: the threads of the build's loops (the same result for any).
 * MFS_OK or MFS_ENOMEM (A then empty). */
int mfs_symop_build(const mfs_csr *K, const double *s, const double *x0, double *y0, int nt,
                    int par, mfs_symop *A, int *have_y);

void mfs_symop_free(mfs_symop *A);

/* Pass 1 of block t of y = A x: its rows of y, the band's terms into its
 * buffer. */
void mfs_symop_block(const mfs_symop *A, int t, const double *x, double *y);

/* Pass 2 of block t: the earlier blocks' band buffers into its rows of y,
 * in the order of the blocks. */
void mfs_symop_bands(const mfs_symop *A, int t, double *y);

/* y = A x: both passes of every block, on the threads when there are more
 * than one and A stores at least MFS_SYMOP_PARALLEL_MIN scalar entries. */
#define MFS_SYMOP_PARALLEL_MIN ((size_t)1 << 21)
void mfs_symop_apply(const mfs_symop *A, const double *x, double *y);

/* The bytes one product reads and writes at least once: the stored
 * operator (values, runs, row pointers, diagonal blocks), x read and y
 * written. */
double mfs_symop_bytes(const mfs_symop *A);

#endif
