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
 *                collapsed N x N Gauss rule otherwise. */
#ifndef MFS_QUAD_H
#define MFS_QUAD_H

#include <stddef.h>

#include "mfs_particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  MFS_QK_NODAL,
  MFS_QK_HALF,    /* particles + cell centres, half each */
  MFS_QK_THIRD,   /* particles + triangle centroids, a third each */
  MFS_QK_VORONOI, /* particles + triangle centroids, Voronoi volumes */
  MFS_QK_GAUSS
} mfs_quad_kind;

typedef struct {
  const char *name;
  mfs_quad_kind kind;
  int dim;              /* 0 any, else the only dimension allowed */
  int lattice;          /* -1 any, else the only mfs_lattice_kind allowed */
  mfs_cell_kind cells;  /* cells the square lattice needs */
  int gauss_n;          /* points per direction (gauss) */
} mfs_quad_rule;

/* Parse a rule name; MFS_EINVAL if unknown (gaussN takes N in 1..10). */
int mfs_quad_rule_parse(const char *name, mfs_quad_rule *rule);

/* MFS_OK if the rule applies to this dimension and lattice, else MFS_EINVAL. */
int mfs_quad_rule_check(const mfs_quad_rule *rule, int dim, mfs_lattice_kind lattice);

typedef struct {
  int dim;
  size_t n;
  double *x;  /* n*dim */
  double *w;  /* n weights (volumes) */
  int *node;  /* particle index of the point, or -1 */
} mfs_quad;

/* The quadrature set of rule on particles p (whose cells must match the
 * rule, see mfs_quad_rule.cells). */
mfs_quad *mfs_quad_alloc(const mfs_quad_rule *rule, const mfs_particles *p, int *status);
void mfs_quad_free(mfs_quad *q);

#ifdef __cplusplus
}
#endif

#endif
