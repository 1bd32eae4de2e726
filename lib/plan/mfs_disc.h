/* The discretization descriptor: one struct that says what a particle
 * discretization is, shared by every analysis (stencil, dispersion, finite
 * models, bounds, the reference solvers), each of which takes it plus its
 * own few fields.
 *
 *   source      where the particles come from: an infinite lattice (the
 *               unit-cell analyses: stencil, dispersion; spacing dx and the
 *               square lattice's gamma = dy/dx), a finite box of nx x ny
 *               lattice particles on [0, lx] x [0, ly], periodic or not
 *               (dx = lx/(nx-1), or lx/nx when periodic), perturbed or not,
 *               or a particle set given as arrays (a user's file)
 *   kernel      the weight function (mfs_kernel.h), support radius
 *               a = dilation * dx (docs/user-guide.md "Conventions"), or `support` itself
 *   shape       shape functions (mfs_shape.h)
 *   quadrature  the rule (mfs_quad.h)
 *   frame       Lagrangian or Eulerian kernel (paper 003 section 3.4)
 *   mass        lumped (row sum, eq. 131), consistent (eq. 112), or lumped as
 *               rho times the node volume (node_volume_mass: eq. 119's mass)
 *   material    physics and elastic constants (mfs_material.h)
 *
 * Fill it with designated initializers, starting from mfs_disc_default().
 * mfs_disc_check() validates it once and names the offending field. */
#ifndef MFS_DISC_H
#define MFS_DISC_H

#include <stddef.h>

#include "mfs_kernel.h"
#include "mfs_material.h"
#include "mfs_particles.h"
#include "mfs_quad.h"
#include "mfs_shape.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Kernel frames: Lagrangian; Eulerian as linearized by paper 003 (eq. 71:
 * phi_I moves rigidly with particle I); Eulerian, consistent: the exact
 * linearization of shape functions re-evaluated in current coordinates
 * (1D; docs/errata.md E2). */
typedef enum { MFS_FRAME_LAGRANGIAN, MFS_FRAME_EULERIAN, MFS_FRAME_EULERIAN_CONSISTENT } mfs_frame;

/* "lagrangian", "eulerian", "eulerian-consistent"; parse: MFS_EINVAL if unknown. */
const char *mfs_frame_name(mfs_frame f);
mfs_status mfs_frame_parse(const char *name, mfs_frame *f);

typedef struct {
  mfs_lattice_kind lattice; /* line (1D), square or hex (2D); MFS_LATTICE_POINTS with `points` */
  int nx, ny;               /* particles per direction of a finite box (ny: 2D);
                               nx = 0: the infinite lattice */
  double lx, ly;            /* lengths of the finite box (m) */
  int periodic;             /* the finite box is periodic */
  double spacing;           /* infinite lattice: the spacing dx (m; 0 means 1) */
  double gamma;             /* infinite square lattice: dy/dx (0 means 1) */
  double perturb;           /* finite box: each coordinate moved by up to perturb * dx, in
                               [0, 0.5) (boundary particles along their boundary only;
                               mfs_lattice_spec) */
  unsigned long seed;       /* ... with this GSL mt19937 seed */
  const mfs_point_set *points; /* a particle set (borrowed; lattice MFS_LATTICE_POINTS):
                               nx, ny, lx, ly, periodic, perturb are not used */
} mfs_source;

typedef struct {
  int dim;                         /* 1 or 2 */
  mfs_source source;
  const mfs_kernel_type *kernel;
  double dilation;                 /* D: support radius a = D dx */
  double support;                  /* the support radius a itself (m; 0: a = D dx); required
                                      for a particle set, which has no lattice spacing */
  const mfs_shape_type *shape;
  const mfs_quad_type *quadrature;
  mfs_frame frame;
  int consistent_mass;             /* 0: lumped (row sum, eq. 131) */
  int node_volume_mass;            /* lumped as rho times the node volume (eq. 119's mass)
                                      instead of the row sum; not with consistent_mass */
  mfs_material material;
  double rcond_min;                /* singular moment matrix threshold (0: 1e-12) */
} mfs_disc;

/* 1D, infinite line lattice of unit spacing, cubic kernel, D = 2, MLS,
 * nodal quadrature, Lagrangian, lumped, scalar, E = rho = 1, nu = 0.25. */
mfs_disc mfs_disc_default(void);

/* MFS_OK, or MFS_EINVAL with *field (if field is not NULL) the name of the
 * first offending member ("dim", "source.lattice", "source.nx", "source.ny",
 * "source.lx", "source.ly", "source.spacing", "source.gamma", "kernel",
 * "dilation", "support", "source.points", "source.perturb", "shape", "quadrature", "frame",
 * "material.physics",
 * "material.modulus", "material.density", "material.poisson",
 * "material.initial_stress", "rcond_min"), or MFS_ETOOSMALL with *field
 * "source.nx" or "source.ny" for a periodic box not longer than two support
 * radii (a particle would see itself through the box). */
mfs_status mfs_disc_check(const mfs_disc *d, const char **field);

/* 1 if the source is the infinite lattice. */
static inline int mfs_disc_infinite(const mfs_disc *d)
{
  return d->source.nx == 0 && !d->source.points;
}

/* 1 if the source is a particle set given as arrays. */
static inline int mfs_disc_points(const mfs_disc *d)
{
  return d->source.points != NULL;
}

/* The spacings dx and dy (dy = 0 in 1D) and the support radius (support, or
 * a = D dx).  A particle set's spacing is its points->spacing (the typical
 * spacing of its volumes, mfs_point_set_spacing, which the caller computes
 * once); where that is 0, an estimate: (max x - min x) / (n - 1) in 1D,
 * sqrt(A / n) in 2D with A the sum of the volumes or the bounding box's area. */
double mfs_disc_dx(const mfs_disc *d);
double mfs_disc_dy(const mfs_disc *d);
double mfs_disc_support(const mfs_disc *d);

/* The rcond threshold in use (rcond_min, or 1e-12 for 0). */
double mfs_disc_rcond(const mfs_disc *d);

/* An estimate of the size of a plan of d on n particles (a lattice of the
 * descriptor's kind, any box): *points quadrature points (may be NULL) and
 * the returned count of neighbour-list entries, within a few tens of per
 * cent; for limits on the work before anything is built.  In doubles: no
 * overflow for absurd inputs. */
double mfs_disc_plan_entries(const mfs_disc *d, double n, double *points);

/* An estimate of the peak memory, in bytes, of a finite model of d on n
 * particles (its plan, its stiffness and consistent mass, a few vectors):
 * within a factor of about 1.5 of the measured peak; for a refusal before
 * the machine runs out of memory. */
double mfs_disc_model_bytes(const mfs_disc *d, double n);

/* The particles and quadrature points of a finite source (the lattice of
 * the box, cut as the rule needs, perturbed as the source says; or the
 * particle set, with its cells where the rule needs them:
 * mfs_particles_from_set).  MFS_OK, the statuses of mfs_disc_check
 * (MFS_EINVAL also for an infinite source) and of mfs_particles_from_set
 * (MFS_EDOMAIN: no triangulation), MFS_ENOMEM; *p and *q are NULL on
 * failure. */
mfs_status mfs_disc_geometry(const mfs_disc *d, mfs_particles **p, mfs_quad **q);

/* A periodic box of nx x ny particles of the infinite lattice of d (spacing
 * and gamma of d->source), and its quadrature points: the unit-cell
 * analyses build their rows on it.  MFS_OK, MFS_EINVAL, MFS_ENOMEM. */
mfs_status mfs_disc_periodic_box(const mfs_disc *d, int nx, int ny, mfs_particles **p, mfs_quad **q);

#ifdef __cplusplus
}
#endif

#endif
