/* Order statistics without allocation (internal, not installed): the k-th
 * smallest of a strided array by radix selection, and the quartiles of a
 * point set's coordinates.  Used by the duplicate test and the typical
 * spacing of particle sets (lib/core/mfs_particles.c) and by the cell grid
 * of the neighbour search when a few far points would stretch its cells
 * (lib/core/mfs_neighbor.c). */
#ifndef MFS_SELECT_H
#define MFS_SELECT_H

#include <stddef.h>

/* The k-th smallest (from 0) of v[0], v[stride], ... (n values, none NaN;
 * k < n): 8 passes over them, nothing allocated, so nothing can fail. */
double mfs_kth_smallest(const double *v, size_t n, size_t stride, size_t k);

/* The quartiles q1[k] <= q3[k] of coordinate k of the n points x (n*dim,
 * finite, n >= 1): ranks (m - 1) / 4 and 3 (m - 1) / 4 of m values, every
 * point up to 4096 of them, else every step-th point (4096 to 8191 of them:
 * the callers size cells and scale tolerances with them; selection over
 * 10^6 points at every call cost 0.1-0.2 s per particle file). */
void mfs_quartiles(int dim, size_t n, const double *x, double *q1, double *q3);

#endif
