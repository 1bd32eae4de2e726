/* Geometry of particle sets that come without a lattice (a user's file):
 * the Delaunay triangulation of a 2D set, its dual areas, the convex hull.
 *
 * Why Qhull.  The triangulation is computed by Qhull (libqhull_r, Debian
 * libqhull-dev): the standard implementation of the Quickhull algorithm
 * (Barber, Dobkin, Huhdanpaa 1996), maintained since 1993 and the one
 * behind the Delaunay routines of SciPy, Octave and R; O(n log n) in 2D;
 * its options handle the degenerate inputs particle sets are made of
 * (lattices are cocircular everywhere: 'Qz' adds a point at infinity,
 * 'Qt' triangulates the non-simplicial facets, 'Qbb' scales the lifted
 * coordinate); and its reentrant API keeps no global state, takes an error
 * stream (which this module discards: the library never prints) and returns
 * an exit code (mapped to a status). */
#ifndef MFS_DELAUNAY_H
#define MFS_DELAUNAY_H

#include <stddef.h>

#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The Delaunay triangles of n points x (n*2): *ntri triangles, (*tri)[3t..3t+3)
 * vertex indices counter-clockwise, allocated (mfs_free()).  Triangles of zero
 * area (Qhull's triangulation of cocircular points may make them: area
 * below 1e-12 of the mean) are dropped.  MFS_OK; MFS_EINVAL (n < 3);
 * MFS_EDOMAIN (Qhull failed: all points on a line, or a precision error);
 * MFS_ENOMEM. */
mfs_status mfs_delaunay_2d(size_t n, const double *x, size_t *ntri, int **tri);

/* The dual area of every vertex of a triangulation: each triangle's area
 * split among its vertices by the Voronoi regions of the vertices within
 * the triangle (its circumcentre partition), or, for an obtuse triangle,
 * half to the obtuse vertex and a quarter to each other one (the "mixed
 * area" of Meyer, Desbrun, Schroeder, Barr 2003).  Every share is positive
 * and the areas sum to the triangulated area; where no triangle is obtuse
 * the area of a vertex is its Voronoi cell within the triangulation (on a
 * lattice: dx dy inside, half on an edge, a quarter at a corner, whichever
 * diagonals the triangulation chose).  area (n) is overwritten. */
void mfs_dual_areas(size_t n, const double *x, size_t ntri, const int *tri, double *area);

/* The vertices of the convex hull of n points x (n*2), collinear points on
 * its edges included: hull[i] = 1 for those, 0 for the others (Andrew's
 * monotone chain, O(n log n)).  MFS_OK, MFS_ENOMEM. */
mfs_status mfs_convex_hull_2d(size_t n, const double *x, unsigned char *hull);

#ifdef __cplusplus
}
#endif

#endif
