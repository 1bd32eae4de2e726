/* Quadrature sets: points and weights (volumes) whose sum is the domain
 * volume.  Rules (paper 003 sections 3.3, 4.2, 4.4 and Fig. 12):
 *   nodal        the particles, with their volumes
 *   stress       1D: particles and interval midpoints, half of each volume each
 *   stress-quad  particles and quadrilateral centres, half and half (Fig. 12a)
 *   stress-tri   particles and centroids of triangles cut by one diagonal,
 *                a third each (Fig. 12b)
 *   stress-star  the same with alternating diagonals, Voronoi volumes (Fig. 12c)
 *   stress-hex   hexagonal lattice, particles and triangle centroids, a third each (Fig. 12d)
 *   gaussN       N Gauss points per direction in every background cell
 *                (gauss1, gauss2, ...); triangles: centroid for N = 1,
 *                collapsed N x N Gauss rule otherwise.
 * On a particle set (MFS_LATTICE_POINTS) the cells are its intervals (1D)
 * or Delaunay triangles (2D): nodal, stress (1D), stress-tri (2D: stress
 * points at the triangle centroids) and gaussN apply. */
#ifndef MFS_QUAD_H
#define MFS_QUAD_H

#include <stddef.h>

#include "mfs_particles.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A quadrature rule: a const type table, like kernels and shape functions.
 * Points are generated from the fields: particles carrying node_share of
 * their volume; with `centres`, a point at the centroid of every background
 * cell carrying the rest of the cell's measure; with `voronoi`, every
 * point's weight replaced by its Voronoi area; with gauss_n, gauss_n points
 * per direction in every cell (triangles: the centroid for 1, a collapsed
 * gauss_n x gauss_n rule otherwise). */
typedef struct {
  const char *name;
  unsigned dims;        /* bit d (1 << d) set: defined in dimension d */
  unsigned lattices;    /* bit k (1 << mfs_lattice_kind) set: defined on lattice k */
  mfs_cell_kind cells;  /* how the cells of a square lattice must be cut */
  double node_share;    /* share of a particle's volume at the particle (0: no point there) */
  int centres;          /* stress points: a point at each cell centroid */
  int voronoi;          /* weights from the Voronoi areas of all points (2D) */
  int gauss_n;          /* Gauss points per direction in every cell (0: none) */
} mfs_quad_type;

extern const mfs_quad_type mfs_quad_nodal;       /* the particles */
extern const mfs_quad_type mfs_quad_stress;      /* 1D stress points */
extern const mfs_quad_type mfs_quad_stress_quad; /* Fig. 12a */
extern const mfs_quad_type mfs_quad_stress_tri;  /* Fig. 12b */
extern const mfs_quad_type mfs_quad_stress_star; /* Fig. 12c */
extern const mfs_quad_type mfs_quad_stress_hex;  /* Fig. 12d */
extern const mfs_quad_type mfs_quad_gauss[10];   /* gauss1 .. gauss10 */

/* NULL-terminated list of every rule, for lookup by name. */
extern const mfs_quad_type *const mfs_quad_types[];

/* The rule called `name`, or NULL. */
const mfs_quad_type *mfs_quad_find(const char *name);

/* 1 if the rule is defined in dimension dim on lattice kind `lattice`. */
int mfs_quad_applies(const mfs_quad_type *t, int dim, mfs_lattice_kind lattice);

/* 1 if the rule has points other than the particles (stress or Gauss points). */
static inline int mfs_quad_has_stress_points(const mfs_quad_type *t)
{
  return t->centres || t->gauss_n > 0;
}

typedef struct {
  int dim;
  size_t n;
  double *x;  /* n*dim */
  double *w;  /* n weights (volumes) */
  int *node;  /* particle index of the point, or -1 */
} mfs_quad;

/* The quadrature set of rule t on particles p (whose cells must be cut as
 * t->cells says).  NULL with *status: MFS_EINVAL (the rule does not apply),
 * MFS_ENOMEM. */
mfs_quad *mfs_quad_alloc(const mfs_quad_type *t, const mfs_particles *p, mfs_status *status);
void mfs_quad_free(mfs_quad *q);

/* An empty point set in dimension dim with room for cap points (n = 0; at
 * least one point's room is allocated), for a caller that fills it; NULL on
 * out of memory. */
mfs_quad *mfs_quad_empty(int dim, size_t cap);

#ifdef __cplusplus
}
#endif

#endif
