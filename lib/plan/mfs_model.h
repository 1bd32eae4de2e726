/* Finite models: the assembled stiffness and mass of a bar or a rectangle
 * discretized by particles, for eigenvalue analysis (paper 003 section 5).
 *
 *   1D bar        nx nodes on [0, lx], end nodes on the ends (dx = lx/(nx-1));
 *                 periodic: nx nodes, dx = lx/nx
 *   2D rectangle  nx x ny nodes of a square lattice on [0, lx] x [0, ly]
 *                 (dx = lx/(nx-1), dy = ly/(ny-1)); periodic: dx = lx/nx, dy = ly/ny
 *
 * Any kernel, shape function and quadrature rule (mfs_quad.h; `gauss2` in 1D
 * is two Gauss points per interval between nodes), lumped (row sum, eq. 131)
 * or consistent (eq. 112) mass.  Physics: scalar (1D bar with modulus E, 2D
 * anti-plane shear with shear modulus mu, eq. 113) or 2D plane strain (shear
 * modulus mu and Poisson ratio nu).  Fixed particles (1D: the two ends, 2D:
 * the whole boundary) have their degrees of freedom removed: K and M are the
 * rows and columns of the free degrees of freedom.
 *
 * The model is built with the core machinery (mfs_disc_geometry,
 * mfs_plan_alloc, then mfs_assemble: the pattern of the free dofs and the
 * values together, in one sweep over the rows that evaluates the shape
 * functions block by block, so that no shape table is held), and keeps the plan (its neighbour lists, without a
 * table) for the element bound (mfs_bound.h) and the solvers.  The
 * discretization is an mfs_disc with a finite source (mfs_disc.h). */
#ifndef MFS_MODEL_H
#define MFS_MODEL_H

#include <stddef.h>
#include <stdio.h>

#include "mfs_assemble.h"
#include "mfs_csr.h"
#include "mfs_disc.h"
#include "mfs_plan.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  MFS_FIX_NONE = 0,
  MFS_FIX_ENDS,     /* 1D: the particles at x = 0 and x = lx (a set: its ends) */
  MFS_FIX_BOUNDARY, /* every particle on the boundary (1D: the ends; a 2D set: its convex hull) */
  MFS_FIX_MASK      /* the particles with fix_mask[I] != 0 */
} mfs_fix_kind;

typedef struct {
  mfs_disc disc;      /* a finite source: disc.source.nx, ny, lx, ly, periodic; or a set */
  mfs_fix_kind fixed; /* MFS_FIX_ENDS is 1D only; none when periodic */
  const unsigned char *fix_mask; /* MFS_FIX_MASK: one flag per particle (borrowed) */
} mfs_model_spec;

/* The defaults: 1D, 41 nodes on [0, 1], cubic kernel, MLS, D = 2, gauss2,
 * lumped mass, free, E = rho = 1. */
mfs_model_spec mfs_model_spec_default(void);

/* MFS_OK; or the status of mfs_disc_check (MFS_EINVAL, MFS_ETOOSMALL for a
 * periodic box not longer than two support radii, where a particle would
 * see itself through the box) with *field naming the member ("disc." and
 * mfs_disc_check's name); or MFS_EINVAL with *field "disc.source" (an
 * infinite source), "fixed" (unknown, periodic and fixed, ends in 2D, fewer
 * than 3 particles per direction when fixed, a mask without fix_mask or on
 * a lattice of another size than the particles').  field may be NULL.
 * mfs_model_alloc also refuses (MFS_EINVAL) a model with every particle fixed. */
mfs_status mfs_model_spec_check(const mfs_model_spec *s, const char **field);

typedef struct {
  mfs_model_spec spec;
  mfs_particles *p;       /* the particles */
  mfs_quad *q;            /* the quadrature points */
  mfs_plan *pl;           /* the neighbour lists (no table: mfs_plan_tabulate makes one) */
  mfs_material mat;       /* spec.disc.material */
  int ndof;               /* degrees of freedom per particle */
  unsigned char *fixed;   /* p->n flags: 1 if the particle is fixed */
  size_t n;               /* free degrees of freedom: the order of K and M */
  size_t *dof;            /* n: the full degree of freedom (particle * ndof + component) */
  mfs_csr *K;             /* stiffness on the free dofs, n x n, symmetric PSD; rows sorted */
  mfs_csr *M;             /* consistent mass on the free dofs, or NULL when lumped */
  double *m;              /* lumped mass on the free dofs (n), or NULL when consistent */
  double dx, dy;          /* particle spacing */
  double a;               /* support radius D dx */
  double c;               /* wave speed sqrt(modulus / density): bar, or shear wave */
} mfs_model;

/* Build and assemble a model.  NULL on failure with *status: as
 * mfs_model_spec_check, MFS_ESINGULAR (singular moment matrix at quadrature
 * point *bad, if bad is not NULL), MFS_ENOMEM. */
mfs_model *mfs_model_alloc(const mfs_model_spec *spec, mfs_status *status, size_t *bad);
void mfs_model_free(mfs_model *m);

/* Drop the plan (neighbour lists) and quadrature set, which hold much of the
 * memory of a large model, once the bound has been computed. */
void mfs_model_release_plan(mfs_model *m);

/* The coordinates of the free degrees of freedom: m->n x m->p->dim, row i
 * the position of the particle of dof i (for geometric orderings:
 * mfs_certify_opts.coord).  Free with mfs_free(); NULL on out of memory. */
double *mfs_model_coords(const mfs_model *m);

/* The rigid-body fields of the model that are admissible (satisfy the
 * fixed conditions): none when particles are fixed; else the constant field
 * (scalar), or the two translations and, unless periodic, the in-plane
 * rotation about the centroid of the particles (plane strain).  Returns their count (0 to 3)
 * and, if r is not NULL, writes them as count vectors of length m->n,
 * r[k * n + i]. */
int mfs_model_rigid_fields(const mfs_model *m, double *r);

/* Write K to fK and M (the lumped mass as a diagonal matrix) to fM in
 * Matrix Market coordinate format; a NULL file is skipped.  MFS_OK, MFS_EIO. */
mfs_status mfs_model_write_mtx(const mfs_model *m, FILE *fK, FILE *fM);

#ifdef __cplusplus
}
#endif

#endif
