/* Areas of the Voronoi cells of a 2D point set, clipped to the box or, in a
 * periodic box, of the periodic tessellation.  Half-plane clipping with
 * neighbours from cell lists: O(N) for point sets of bounded density. */
#ifndef MFS_VORONOI_H
#define MFS_VORONOI_H

#include <stddef.h>

#include "mfs_particles.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* area[i] for the n points x (n*2) of box.  Returns MFS_OK, MFS_EINVAL
 * (not 2D, a point outside a finite box) or MFS_ENOMEM. */
mfs_status mfs_voronoi_areas(size_t n, const double *x, const mfs_box *box, double *area);

#ifdef __cplusplus
}
#endif

#endif
