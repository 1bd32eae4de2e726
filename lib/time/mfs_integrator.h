/* One interface for the reference solvers (the rod, mfs_solver.h; the
 * linear plate, mfs_solver2d.h; the TSPH bar, mfs_tsph.h), so that a driver
 * such as `mfstab run` has one time loop, one table of probes and one CSV
 * writer: a const type table per solver (as kernels and shapes are), and a
 * view of the state the probes read.
 *
 *   set_state  the initial displacements u (NULL: zero; the TSPH bar has no
 *              displacement and takes NULL) and velocities v (NULL: zero)
 *   stable_dt  the largest stable step of the solver's rule (central
 *              difference 2/sqrt(lambda); TSPH: von Neumann, 0 if none)
 *   set_dt     MFS_EINVAL above it unless force
 *   choose_step choose the stable step again by a rule of mfs_dt_rule
 *              (mfs_explicit.h), before set_state; NULL: the solver has
 *              one rule (TSPH's von Neumann limit)
 *   step_info  what the rule found (NULL where choose_step is NULL)
 *   step       one step of `scheme` (the TSPH bar has its own scheme)
 *   fields     bring the stresses of the view up to date (NULL: always are)
 *   energy     kinetic, potential and (plate) the leapfrog's modified
 *              energy (NAN where the solver has none)
 *   nearest    the degree of freedom of component comp of the particle
 *              nearest (x, y) */
#ifndef MFS_INTEGRATOR_H
#define MFS_INTEGRATOR_H

#include <stddef.h>

#include "mfs_explicit.h"
#include "mfs_model.h"
#include "mfs_solver.h"
#include "mfs_solver2d.h"
#include "mfs_status.h"
#include "mfs_tsph.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a probe reads.  Pointers are into the solver, valid until its next call. */
typedef struct {
  int dim;              /* 1 or 2 */
  size_t n;             /* degrees of freedom */
  int ncomp;            /* components per particle (plane strain: 2) */
  const double *X, *Y;  /* n: reference coordinates of each dof's particle (Y NULL in 1D) */
  const int *comp;      /* n: the component of each dof (NULL: all 0) */
  const double *u;      /* n displacements (NULL: the stress-velocity form) */
  const double *v;      /* n velocities */
  size_t nq;            /* points where the stress is known */
  const double *xq;     /* nq first coordinates */
  const double *sigma;  /* nq stresses (Pa) */
  double dx;            /* particle spacing (1D: the lattice X = i dx) */
  double t, dt;
} mfs_state;

typedef struct {
  const char *name;      /* "rod", "plate", "tsph" */
  const char *step_rule; /* "central-difference", "von Neumann" */
  mfs_status (*set_state)(void *solver, const double *u, const double *v);
  double (*stable_dt)(void *solver);
  mfs_status (*set_dt)(void *solver, double dt, int force);
  mfs_status (*choose_step)(void *solver, mfs_dt_rule rule);
  const mfs_dt_info *(*step_info)(const void *solver);
  mfs_status (*step)(void *solver, mfs_scheme scheme);
  mfs_status (*fields)(void *solver);
  mfs_status (*energy)(void *solver, double *kinetic, double *potential, double *modified);
  void (*state)(const void *solver, mfs_state *st);
  size_t (*nearest)(const void *solver, double x, double y, int comp);
  void (*free)(void *solver);
} mfs_integrator_type;

extern const mfs_integrator_type mfs_integrator_rod;   /* solver: mfs_solver * */
extern const mfs_integrator_type mfs_integrator_plate; /* solver: mfs_solver2d * */
extern const mfs_integrator_type mfs_integrator_tsph;  /* solver: mfs_tsph * */

typedef struct {
  const mfs_integrator_type *type;
  void *solver;       /* owned: type->free frees it */
  mfs_scheme scheme;  /* of step (ignored by tsph) */
} mfs_integrator;

#ifdef __cplusplus
}
#endif

#endif
