#include "mfs_plan.h"
#include "mfs_alloc.h"

#include <stdlib.h>
#include <string.h>

#include "mfs_eval.h"
#include "mfs_neighbor.h"
#include "mfs_threads.h"

struct mfs_plan {
  mfs_disc disc;          /* kernel, shape, dilation, rcond (the source is not used) */
  const mfs_particles *p; /* borrowed */
  const mfs_quad *q;      /* borrowed */
  double a;               /* support radius D p->dx */
  mfs_nlist *nl;          /* quadrature point -> particles within a */
  size_t *tptr;           /* p->n + 1: particle -> points that see it (transpose), */
  int *tq;                /* built by the first mfs_plan_transpose; tq set last */
  size_t maxrow;          /* longest list */
  int order, ncomp;       /* of the table; 0 before mfs_plan_tabulate */
  double *tab;            /* nl->ptr[nq] * ncomp */
  double rcond;           /* smallest reciprocal condition number met */
};

void mfs_plan_free(mfs_plan *pl)
{
  if (!pl)
    return;
  mfs_nlist_free(pl->nl);
  mfs_free(pl->tptr);
  mfs_free(pl->tq);
  mfs_free(pl->tab);
  mfs_free(pl);
}

mfs_plan *mfs_plan_alloc(const mfs_disc *d, const mfs_particles *p, const mfs_quad *q,
                         mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_plan *pl = NULL;
  mfs_grid *g = NULL;
  if (!d || !p || !q || !d->kernel || !d->shape || !(d->dilation > 0.0) || q->dim != p->dim)
    goto done;
  st = MFS_ENOMEM;
  pl = mfs_calloc(1, sizeof *pl);
  if (!pl)
    goto done;
  pl->disc = *d;
  pl->disc.dim = p->dim; /* the particles decide; the source of d is not used */
  pl->p = p;
  pl->q = q;
  pl->a = d->support > 0.0 ? d->support : d->dilation * p->dx;
  pl->rcond = 1.0;
  g = mfs_grid_alloc(p->dim, p->n, p->x, &p->box, pl->a, &st);
  if (!g)
    goto done;
  pl->nl = mfs_nlist_build(g, q->n, q->x, pl->a, &st);
  if (!pl->nl)
    goto done;
  size_t nq = q->n;
  pl->maxrow = 1;
  for (size_t Q = 0; Q < nq; Q++) {
    size_t len = pl->nl->ptr[Q + 1] - pl->nl->ptr[Q];
    pl->maxrow = len > pl->maxrow ? len : pl->maxrow;
  }
  st = MFS_OK;
done:
  mfs_grid_free(g);
  if (st != MFS_OK) {
    mfs_plan_free(pl);
    pl = NULL;
  }
  if (status)
    *status = st;
  return pl;
}

mfs_status mfs_plan_evaluator(const mfs_plan *pl, int order, mfs_eval *ev)
{
  *ev = (mfs_eval){0};
  if (!pl || order < 1 || order > 2)
    return MFS_EINVAL;
  mfs_status st = mfs_eval_init(ev, &pl->disc, pl->a, order, &pl->p->box, pl->maxrow);
  ev->within = 1; /* the lists hold exactly the particles within a (mfs_nlist_build) */
  return st;
}

mfs_status mfs_plan_eval_point(const mfs_plan *pl, mfs_eval *ev, size_t Q, int *kept, double *out,
                               double *rcond)
{
  const mfs_nlist *nl = pl->nl;
  size_t e0 = nl->ptr[Q], len = nl->ptr[Q + 1] - e0;
  int nn;
  double rc = 1.0;
  mfs_status st = mfs_eval_point(ev, pl->q->x + Q * (size_t)pl->p->dim, pl->p->x, pl->p->vol,
                                 nl->idx + e0, len, pl->q->node[Q], kept, out, &nn, &rc);
  if (rcond)
    *rcond = rc;
  return st;
}

/* The table in parallel: each thread a contiguous range of points in
 * increasing order, stopping at its first failure, so that the failing point
 * reported (the smallest) and every value are those of the serial loop. */
mfs_status mfs_plan_tabulate(mfs_plan *pl, int order, size_t *bad)
{
  if (!pl || order < 1 || order > 2)
    return MFS_EINVAL;
  mfs_free(pl->tab);
  pl->tab = NULL;
  pl->order = pl->ncomp = 0;
  const size_t nq = pl->q->n;
  const int ncomp = mfs_shape_ncomp(pl->p->dim, order), nt = mfs_threads();
  double *tab = mfs_malloc((pl->nl->ptr[nq] ? pl->nl->ptr[nq] : 1) * (size_t)ncomp * sizeof *tab);
  mfs_eval *ev = mfs_calloc((size_t)nt, sizeof *ev);
  int *kept = mfs_malloc((size_t)nt * pl->maxrow * sizeof *kept);
  mfs_status st = tab && ev && kept ? MFS_OK : MFS_ENOMEM;
  for (int t = 0; t < nt && st == MFS_OK; t++)
    st = mfs_plan_evaluator(pl, order, ev + t);
  double rcond = 1.0;
  size_t first_bad = nq;
  mfs_status bad_st = MFS_OK;
  if (st == MFS_OK) {
#pragma omp parallel num_threads(nt)
    {
      const int t = mfs_thread_id();
      double rc_t = 1.0;
      int failed = 0;
#pragma omp for schedule(static)
      for (size_t Q = 0; Q < nq; Q++) {
        if (failed)
          continue;
        double rc;
        mfs_status s = mfs_plan_eval_point(pl, ev + t, Q, kept + (size_t)t * pl->maxrow,
                                           tab + pl->nl->ptr[Q] * (size_t)ncomp, &rc);
        rc_t = rc < rc_t ? rc : rc_t;
        if (s != MFS_OK) {
          failed = 1;
#pragma omp critical(mfs_plan_tabulate)
          if (Q < first_bad) {
            first_bad = Q;
            bad_st = s;
          }
        }
      }
#pragma omp critical(mfs_plan_tabulate)
      rcond = rc_t < rcond ? rc_t : rcond;
    }
    if (first_bad < nq) {
      st = bad_st;
      if (bad)
        *bad = first_bad;
    }
  }
  if (ev)
    for (int t = 0; t < nt; t++)
      mfs_eval_free(ev + t);
  mfs_free(ev);
  mfs_free(kept);
  pl->rcond = rcond;
  if (st != MFS_OK) {
    mfs_free(tab);
    return st;
  }
  pl->tab = tab;
  pl->order = order;
  pl->ncomp = ncomp;
  return MFS_OK;
}

size_t mfs_plan_npoints(const mfs_plan *pl)
{
  return pl->q->n;
}

void mfs_plan_point(const mfs_plan *pl, size_t Q, mfs_point *pt)
{
  size_t e0 = pl->nl->ptr[Q];
  pt->nn = pl->nl->ptr[Q + 1] - e0;
  pt->idx = pl->nl->idx + e0;
  pt->phi = pl->tab ? pl->tab + e0 * (size_t)pl->ncomp : NULL;
  pt->ncomp = pl->ncomp;
  pt->w = pl->q->w[Q];
  pt->x = pl->q->x + Q * (size_t)pl->q->dim;
  pt->node = pl->q->node[Q];
}

void mfs_plan_table(const mfs_plan *pl, const size_t **ptr, const int **idx, const double **tab)
{
  *ptr = pl->nl->ptr;
  *idx = pl->nl->idx;
  *tab = pl->tab;
}

/* The transpose by counting (no sort): the points of each particle in
 * increasing order, as the lists are walked in order. */
static mfs_status build_transpose(const mfs_nlist *nl, size_t n, size_t **tptr_out, int **tq_out)
{
  const size_t nq = nl->nq, nnz = nl->ptr[nq];
  size_t *tptr = mfs_calloc(n + 1, sizeof *tptr);
  int *tq = mfs_malloc((nnz ? nnz : 1) * sizeof *tq);
  size_t *next = mfs_malloc((n ? n : 1) * sizeof *next);
  if (!tptr || !tq || !next) {
    mfs_free(tptr);
    mfs_free(tq);
    mfs_free(next);
    return MFS_ENOMEM;
  }
  for (size_t e = 0; e < nnz; e++)
    tptr[nl->idx[e] + 1]++;
  for (size_t i = 0; i < n; i++)
    tptr[i + 1] += tptr[i];
  memcpy(next, tptr, n * sizeof *next);
  for (size_t Q = 0; Q < nq; Q++)
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++)
      tq[next[nl->idx[e]]++] = (int)Q;
  mfs_free(next);
  *tptr_out = tptr;
  *tq_out = tq;
  return MFS_OK;
}

mfs_status mfs_plan_transpose(const mfs_plan *cpl)
{
  if (!cpl)
    return MFS_EINVAL;
  /* a cache of the (logically const) plan: built once, under a lock, and
   * published by its last pointer */
  mfs_plan *pl = (mfs_plan *)cpl;
  if (__atomic_load_n(&pl->tq, __ATOMIC_ACQUIRE))
    return MFS_OK;
  mfs_status st = MFS_OK;
#pragma omp critical(mfs_plan_transpose)
  {
    if (!__atomic_load_n(&pl->tq, __ATOMIC_ACQUIRE)) {
      size_t *tptr = NULL;
      int *tq = NULL;
      st = build_transpose(pl->nl, pl->p->n, &tptr, &tq);
      if (st == MFS_OK) {
        pl->tptr = tptr;
        __atomic_store_n(&pl->tq, tq, __ATOMIC_RELEASE);
      }
    }
  }
  return st;
}

void mfs_plan_particle_points(const mfs_plan *pl, size_t I, size_t *n, const int **Q)
{
  *n = pl->tptr[I + 1] - pl->tptr[I];
  *Q = pl->tq + pl->tptr[I];
}

const mfs_particles *mfs_plan_particles(const mfs_plan *pl)
{
  return pl->p;
}

const mfs_quad *mfs_plan_quad(const mfs_plan *pl)
{
  return pl->q;
}

const mfs_disc *mfs_plan_disc(const mfs_plan *pl)
{
  return &pl->disc;
}

int mfs_plan_order(const mfs_plan *pl)
{
  return pl->order;
}

int mfs_plan_ncomp(const mfs_plan *pl)
{
  return pl->ncomp;
}

double mfs_plan_support(const mfs_plan *pl)
{
  return pl->a;
}

double mfs_plan_rcond(const mfs_plan *pl)
{
  return pl->rcond;
}

size_t mfs_plan_max_neighbours(const mfs_plan *pl)
{
  return pl->maxrow;
}

size_t mfs_plan_nnz(const mfs_plan *pl)
{
  return pl->nl->ptr[pl->q->n];
}
