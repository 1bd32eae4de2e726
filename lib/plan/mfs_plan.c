#include "mfs_plan.h"
#include "mfs_alloc.h"

#include <stdlib.h>
#include <string.h>

#include "mfs_eval.h"
#include "mfs_neighbor.h"

struct mfs_plan {
  mfs_disc disc;          /* kernel, shape, dilation, rcond (the source is not used) */
  const mfs_particles *p; /* borrowed */
  const mfs_quad *q;      /* borrowed */
  double a;               /* support radius D p->dx */
  mfs_nlist *nl;          /* quadrature point -> particles within a */
  size_t *tptr;           /* p->n + 1: particle -> points that see it (transpose) */
  int *tq;
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
  st = MFS_ENOMEM;
  size_t n = p->n, nq = q->n, nnz = pl->nl->ptr[nq];
  pl->maxrow = 1;
  for (size_t Q = 0; Q < nq; Q++) {
    size_t len = pl->nl->ptr[Q + 1] - pl->nl->ptr[Q];
    pl->maxrow = len > pl->maxrow ? len : pl->maxrow;
  }
  pl->tptr = mfs_calloc(n + 1, sizeof *pl->tptr);
  pl->tq = mfs_malloc((nnz ? nnz : 1) * sizeof *pl->tq);
  size_t *next = mfs_malloc((n ? n : 1) * sizeof *next);
  if (!pl->tptr || !pl->tq || !next) {
    mfs_free(next);
    goto done;
  }
  for (size_t e = 0; e < nnz; e++)
    pl->tptr[pl->nl->idx[e] + 1]++;
  for (size_t i = 0; i < n; i++)
    pl->tptr[i + 1] += pl->tptr[i];
  memcpy(next, pl->tptr, n * sizeof *next);
  for (size_t Q = 0; Q < nq; Q++)
    for (size_t e = pl->nl->ptr[Q]; e < pl->nl->ptr[Q + 1]; e++)
      pl->tq[next[pl->nl->idx[e]]++] = (int)Q;
  mfs_free(next);
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

mfs_status mfs_plan_tabulate(mfs_plan *pl, int order, size_t *bad)
{
  if (!pl || order < 1 || order > 2)
    return MFS_EINVAL;
  mfs_free(pl->tab);
  pl->tab = NULL;
  pl->order = pl->ncomp = 0;
  const mfs_particles *p = pl->p;
  const mfs_quad *q = pl->q;
  const mfs_nlist *nl = pl->nl;
  int ncomp = mfs_shape_ncomp(p->dim, order);
  mfs_eval ev;
  mfs_status st = mfs_eval_init(&ev, &pl->disc, pl->a, order, &p->box, pl->maxrow);
  ev.within = 1; /* the lists hold exactly the particles within a (mfs_nlist_build) */
  double *tab = mfs_malloc((nl->ptr[q->n] ? nl->ptr[q->n] : 1) * (size_t)ncomp * sizeof *tab);
  int *kept = mfs_malloc(pl->maxrow * sizeof *kept);
  if (st == MFS_OK && (!tab || !kept))
    st = MFS_ENOMEM;
  double rcond = 1.0;
  for (size_t Q = 0; Q < q->n && st == MFS_OK; Q++) {
    size_t e0 = nl->ptr[Q], len = nl->ptr[Q + 1] - e0;
    int nn;
    double rc;
    st = mfs_eval_point(&ev, q->x + Q * (size_t)p->dim, p->x, p->vol, nl->idx + e0, len,
                        q->node[Q], kept, tab + e0 * (size_t)ncomp, &nn, &rc);
    rcond = rc < rcond ? rc : rcond;
    if (st != MFS_OK && bad)
      *bad = Q;
  }
  mfs_eval_free(&ev);
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
