/* Plans: built once from a discretization and its particles and quadrature
 * points, reused by every assembly, bound and time step.  Split as CSparse
 * splits symbolic from numeric factorization:
 *
 *   mfs_plan_alloc      symbolic: the neighbour lists of the quadrature points
 *                       (cell lists, O(N); radius a = D dx); their transpose
 *                       (the points that see each particle) is built by the
 *                       first consumer that reads it (mfs_plan_transpose)
 *   mfs_plan_tabulate   numeric: the shape functions and derivatives at every
 *                       point (order 1: values and gradients; 2: also second
 *                       derivatives), by the point evaluator (mfs_eval.h)
 *
 * The plan is opaque; consumers read it point by point (mfs_plan_point) and
 * particle by particle (mfs_plan_particle_points). */
#ifndef MFS_PLAN_H
#define MFS_PLAN_H

#include <stddef.h>

#include "mfs_disc.h"
#include "mfs_eval.h"
#include "mfs_particles.h"
#include "mfs_quad.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mfs_plan mfs_plan;

/* One quadrature point as the plan holds it. */
typedef struct {
  size_t nn;          /* neighbours (particles within a) */
  const int *idx;     /* nn particle indices, increasing */
  const double *phi;  /* nn * ncomp: the table row (mfs_shape.h layout; NULL before
                         mfs_plan_tabulate) */
  int ncomp;          /* doubles per neighbour */
  double w;           /* weight (volume) */
  const double *x;    /* dim coordinates */
  int node;           /* the particle at the point, or -1 */
} mfs_point;

/* The neighbour structure of quadrature points q among particles p for the
 * kernel, shape, support radius (d->support, or a = D p->dx) and rcond
 * threshold of d; p and q
 * are borrowed and must outlive the plan.  NULL with *status: MFS_EINVAL
 * (bad d, dimensions of p and q differ), MFS_ETOOSMALL (a periodic box not
 * longer than 2a), MFS_ENOMEM. */
mfs_plan *mfs_plan_alloc(const mfs_disc *d, const mfs_particles *p, const mfs_quad *q,
                         mfs_status *status);
void mfs_plan_free(mfs_plan *pl);

/* The shape-function table, derivatives up to `order` (1 or 2).  MFS_OK;
 * MFS_ESINGULAR (a singular moment matrix at quadrature point *bad, if bad
 * is not NULL); MFS_EINVAL; MFS_ENOMEM.  May be called again (another
 * order); on failure the plan has no table. */
mfs_status mfs_plan_tabulate(mfs_plan *pl, int order, size_t *bad);

/* An evaluator for the plan's points: its kernel, shape, support radius,
 * rcond threshold and box, derivatives up to `order`, room for its longest
 * list (what mfs_plan_tabulate uses; one per thread).  Free with
 * mfs_eval_free.  MFS_OK, MFS_EINVAL, MFS_ENOMEM. */
mfs_status mfs_plan_evaluator(const mfs_plan *pl, int order, mfs_eval *ev);

/* The table row of point Q by ev (mfs_plan_evaluator), into out (nn *
 * ncomp doubles of ev's order, nn the length of Q's list); kept (room for
 * nn ints) receives the neighbours, equal to Q's list.  The same values as
 * mfs_plan_tabulate's row of Q, so that a consumer may evaluate points as it
 * needs them instead of holding the table.  rcond may be NULL.  The shape's
 * status (MFS_OK, MFS_ESINGULAR). */
mfs_status mfs_plan_eval_point(const mfs_plan *pl, mfs_eval *ev, size_t Q, int *kept, double *out,
                               double *rcond);

size_t mfs_plan_npoints(const mfs_plan *pl);
void mfs_plan_point(const mfs_plan *pl, size_t Q, mfs_point *pt);

/* The whole table in compressed rows, for loops that run every time step:
 * point Q's neighbours are idx[ptr[Q] .. ptr[Q+1]), their entries
 * tab[e * ncomp ..] for e in that range (tab NULL before tabulation). */
void mfs_plan_table(const mfs_plan *pl, const size_t **ptr, const int **idx, const double **tab);

/* The transpose of the lists, particle -> the quadrature points that see
 * it: built on the first call (by counting, O(entries); a cache of the
 * const plan, so that consumers without rows, the time steps of the tables,
 * the unit cells' sums, do not pay for it), kept until mfs_plan_free.  Safe
 * to call from several threads (a lock around the first build; the
 * library's row assemblers call it before their parallel loops).  MFS_OK,
 * MFS_EINVAL (pl NULL), MFS_ENOMEM. */
mfs_status mfs_plan_transpose(const mfs_plan *pl);

/* The quadrature points that see particle I, increasing: *n of them in
 * (*Q)[0..n).  The transpose must have been built (mfs_plan_transpose). */
void mfs_plan_particle_points(const mfs_plan *pl, size_t particle, size_t *n, const int **Q);

const mfs_particles *mfs_plan_particles(const mfs_plan *pl);
const mfs_quad *mfs_plan_quad(const mfs_plan *pl);
const mfs_disc *mfs_plan_disc(const mfs_plan *pl);
int mfs_plan_order(const mfs_plan *pl);         /* 0 before tabulation */
int mfs_plan_ncomp(const mfs_plan *pl);
double mfs_plan_support(const mfs_plan *pl);    /* a: d->support or D dx */
double mfs_plan_rcond(const mfs_plan *pl);      /* smallest reciprocal condition number met */
size_t mfs_plan_max_neighbours(const mfs_plan *pl);
size_t mfs_plan_nnz(const mfs_plan *pl);        /* sum of the list lengths */

#ifdef __cplusplus
}
#endif

#endif
