/* Neighbour search with cell lists: O(N + M) for N points and M queries
 * with a bounded number of points per cell.  Periodic boxes use the
 * minimum image, which needs the radius below half the box length. */
#ifndef MFS_NEIGHBOR_H
#define MFS_NEIGHBOR_H

#include <stddef.h>

#include "mfs_particles.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Points bucketed into cells of side >= radius.  Borrows x. */
typedef struct {
  int dim;
  size_t n;
  const double *x;
  mfs_box box;
  double radius;
  int nc[3];       /* cells per direction */
  double h[3];     /* cell side per direction */
  size_t *start;   /* ncells+1 offsets into item */
  int *item;       /* point indices sorted by cell */
} mfs_grid;

/* Bucket n points x (n*dim) of box for queries of the given radius.
 * NULL with *status = MFS_ETOOSMALL when a periodic box is not larger than
 * twice the radius, MFS_EINVAL for radius <= 0, MFS_ENOMEM. */
mfs_grid *mfs_grid_alloc(int dim, size_t n, const double *x, const mfs_box *box, double radius,
                         mfs_status *status);
void mfs_grid_free(mfs_grid *g);

/* Neighbour lists in compressed rows: the points within distance < radius of
 * query q are idx[ptr[q] .. ptr[q+1]). */
typedef struct {
  size_t nq;
  size_t *ptr;
  int *idx;
} mfs_nlist;

/* Lists for nq query points xq (nq*dim), radius r <= g->radius.
 * Within a row, indices are in increasing order. */
mfs_nlist *mfs_nlist_build(const mfs_grid *g, size_t nq, const double *xq, double r, mfs_status *status);
void mfs_nlist_free(mfs_nlist *nl);

/* The number of (query, point) pairs within r <= g->radius that
 * mfs_nlist_build would list, without the lists: memory O(1), time that of
 * the scan, which stops once the count exceeds limit (*count is then the
 * partial count, > limit).  For a limit on the work before a plan is built
 * where the points may cluster (a particle file).  MFS_OK, MFS_EINVAL. */
mfs_status mfs_grid_count(const mfs_grid *g, size_t nq, const double *xq, double r, double limit,
                          double *count);

/* The search of a moving discretization: the lists of the n points x (dim
 * coordinates each, in box) within r of each of the nq query points xq,
 * through a grid built and dropped; on success *lists (freed) is replaced
 * and *maxlen is the longest list (at least 1).  MFS_OK, the statuses of
 * mfs_grid_alloc and mfs_nlist_build (then *lists is unchanged). */
mfs_status mfs_nlist_rebuild(int dim, size_t n, const double *x, const mfs_box *box, size_t nq,
                             const double *xq, double r, mfs_nlist **lists, size_t *maxlen);

/* The transpose: for each of n points, the queries whose lists hold it. */
mfs_nlist *mfs_nlist_transpose(const mfs_nlist *nl, size_t n, mfs_status *status);

#ifdef __cplusplus
}
#endif

#endif
