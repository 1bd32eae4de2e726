/* The point evaluator: the shape functions of a discretization at one point
 * from a list of candidate particles.  It is the one place where "gather a
 * point's neighbours, evaluate its shape functions" is written; every
 * consumer uses it: the plan's tables (mfs_plan.h), the streaming element
 * bound (mfs_bound.h), the Eulerian rod solver (current positions), the
 * consistent Eulerian dispersion (position derivatives) and the closed forms'
 * tabulation.
 *
 * The candidates closer than the support radius a are kept, in the order
 * given (the minimum image in a periodic box); their offsets X_J - X and
 * volumes stay in the evaluator (mfs_eval_offsets) for a consumer that needs
 * them after the call.  The workspace is sized once (mfs_eval_reserve grows
 * it; no allocation per point otherwise). */
#ifndef MFS_EVAL_H
#define MFS_EVAL_H

#include <stddef.h>

#include "mfs_disc.h"
#include "mfs_particles.h"
#include "mfs_shape.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const mfs_shape_type *shape;
  mfs_shape_ctx ctx;   /* kernel, dimension, support radius a, rcond threshold */
  int order, ncomp;    /* derivatives wanted (1 or 2) and doubles per neighbour */
  const mfs_box *box;  /* the domain of the particles (minimum image); borrowed */
  size_t cap;          /* neighbours the workspace holds */
  int nn;              /* neighbours kept by the last call */
  int self;            /* the position of the point's own particle among them, or -1 */
  double *d, *v;       /* cap*dim offsets X_J - X, cap volumes of the last call */
  double *work;        /* the shape functions' scratch */
  mfs_shape_gather_1d_fn fast; /* the shape's fused 1D path, if in use (mfs_eval_fast) */
  int within;          /* the candidates are known to lie within a (the plan's lists):
                          the gather keeps them all without the distance test */
} mfs_eval;

/* An evaluator for the kernel, shape, support radius a and rcond threshold
 * of d, derivatives up to `order`, particles in `box`, room for cap
 * neighbours.  MFS_OK, MFS_EINVAL, MFS_ENOMEM (then ev holds nothing to
 * free, but mfs_eval_free is harmless). */
mfs_status mfs_eval_init(mfs_eval *ev, const mfs_disc *d, double a, int order, const mfs_box *box,
                  size_t cap);
void mfs_eval_free(mfs_eval *ev);

/* Use the shape's fused 1D path (mfs_shape_type.gather_1d) where there is
 * one (1D, order 1): the same values, one pass; but then mfs_eval_offsets
 * and mfs_eval_volumes are not filled.  For loops that evaluate every step. */
void mfs_eval_fast(mfs_eval *ev, int on);

/* Room for cap neighbours.  MFS_OK or MFS_ENOMEM (the old room kept). */
mfs_status mfs_eval_reserve(mfs_eval *ev, size_t cap);

/* Room for `need` neighbours in the evaluator and in a caller's table *out
 * (stride doubles a neighbour) and indices *loc, whose room is *cap: when
 * need exceeds it, all three grow to twice need.  MFS_OK or MFS_ENOMEM
 * (whatever was grown stays valid; *cap unchanged). */
mfs_status mfs_eval_grow(mfs_eval *ev, size_t need, int stride, double **out, int **loc,
                         size_t *cap);

/* Shape functions at x (dim coordinates) from the candidates cand[0..nc)
 * of the particles xp (dim coordinates each) with volumes vol (read only if
 * the shape uses them): keeps those with |X_J - x| < a, writes their
 * indices to idx[0..*nn) and the table to out (*nn * ncomp doubles, the
 * mfs_shape.h layout).  self is the particle located at x (nodal points) or
 * -1.  idx and out need room for nc entries (at most cap: MFS_EINVAL beyond).
 * rcond (may be NULL): the moment matrix's reciprocal condition number.
 * Returns the shape's status (MFS_OK, MFS_ESINGULAR). */
mfs_status mfs_eval_point_general(mfs_eval *ev, const double *x, const double *xp,
                                  const double *vol, const int *cand, size_t nc, int self,
                                  int *idx, double *out, int *nn, double *rcond);
static inline mfs_status mfs_eval_point(mfs_eval *ev, const double *x, const double *xp,
                                        const double *vol, const int *cand, size_t nc, int self,
                                        int *idx, double *out, int *nn, double *rcond)
{
  if (ev->fast && nc <= ev->cap) { /* the same values (ev->d, ev->v not kept) */
    double rc;
    int st = ev->fast(&ev->ctx, ev->box, *x, xp, cand, nc, idx, out, ev->work, nn, &rc, NULL,
                      NULL);
    ev->nn = *nn;
    if (rcond)
      *rcond = rc;
    return (mfs_status)st;
  }
  return mfs_eval_point_general(ev, x, xp, vol, cand, nc, self, idx, out, nn, rcond);
}

/* mfs_eval_point (order 1, 1D: ncomp = 2) and the gradient of the nodal
 * field u (indexed like xp) at x, *grad = sum_J phi_J'(x) u[idx_J], in the
 * same pass where the fast path is in use. */
static inline mfs_status mfs_eval_point_grad(mfs_eval *ev, const double *x, const double *xp,
                                             const double *vol, const int *cand, size_t nc,
                                             int self, int *idx, double *out, int *nn,
                                             const double *u, double *grad)
{
  if (ev->fast && nc <= ev->cap) {
    double rc;
    int st = ev->fast(&ev->ctx, ev->box, *x, xp, cand, nc, idx, out, ev->work, nn, &rc, u, grad);
    ev->nn = *nn;
    return (mfs_status)st;
  }
  mfs_status st = mfs_eval_point_general(ev, x, xp, vol, cand, nc, self, idx, out, nn, NULL);
  if (st == MFS_OK) {
    double g = 0.0;
    for (int k = 0; k < *nn; k++)
      g += out[ev->ncomp * k + 1] * u[idx[k]];
    *grad = g;
  }
  return st;
}

/* The gather alone: keeps the candidates within a (indices to idx, offsets
 * and volumes in the evaluator, ev->self set).  Returns the count, or -1 if
 * nc exceeds the room (mfs_eval_reserve). */
int mfs_eval_gather(mfs_eval *ev, const double *x, const double *xp, const double *vol,
                    const int *cand, size_t nc, int self, int *idx);

/* The offsets (nn*dim) and volumes (nn) of the neighbours of the last call. */
static inline const double *mfs_eval_offsets(const mfs_eval *ev)
{
  return ev->d;
}
static inline const double *mfs_eval_volumes(const mfs_eval *ev)
{
  return ev->v;
}

#ifdef __cplusplus
}
#endif

#endif
