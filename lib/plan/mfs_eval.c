#include "mfs_eval.h"
#include "mfs_alloc.h"

#include <stdlib.h>

#include "mfs_status.h"

mfs_status mfs_eval_init(mfs_eval *ev, const mfs_disc *d, double a, int order, const mfs_box *box,
                  size_t cap)
{
  *ev = (mfs_eval){0};
  if (!d || !d->kernel || !d->shape || !(a > 0.0) || order < 1 || order > 2 || !box ||
      d->dim < 1 || d->dim > 3)
    return MFS_EINVAL;
  ev->shape = d->shape;
  ev->ctx = (mfs_shape_ctx){
    .kernel = d->kernel, .dim = d->dim, .a = a, .rcond_min = mfs_disc_rcond(d)};
  ev->order = order;
  ev->ncomp = mfs_shape_ncomp(d->dim, order);
  ev->box = box;
  return mfs_eval_reserve(ev, cap > 0 ? cap : 1);
}

void mfs_eval_fast(mfs_eval *ev, int on)
{
  ev->fast = on && ev->ctx.dim == 1 && ev->order == 1 && ev->shape->gather_1d
               ? ev->shape->gather_1d(ev->ctx.kernel)
               : NULL;
}

void mfs_eval_free(mfs_eval *ev)
{
  if (!ev)
    return;
  mfs_free(ev->d);
  mfs_free(ev->v);
  mfs_free(ev->work);
  ev->d = ev->v = ev->work = NULL;
  ev->cap = 0;
}

mfs_status mfs_eval_reserve(mfs_eval *ev, size_t cap)
{
  if (cap <= ev->cap)
    return MFS_OK;
  int dim = ev->ctx.dim;
  double *d = mfs_malloc(cap * (size_t)dim * sizeof *d);
  double *v = mfs_malloc(cap * sizeof *v);
  size_t wl = mfs_shape_work_len(dim, (int)cap);
  double *w = mfs_malloc((wl > 7 * cap ? wl : 7 * cap) * sizeof *w); /* gather_1d: 7 cap */
  if (!d || !v || !w) {
    mfs_free(d);
    mfs_free(v);
    mfs_free(w);
    return MFS_ENOMEM;
  }
  mfs_eval_free(ev);
  ev->d = d;
  ev->v = v;
  ev->work = w;
  ev->cap = cap;
  return MFS_OK;
}

int mfs_eval_gather(mfs_eval *ev, const double *x, const double *xp, const double *vol,
                    const int *cand, size_t nc, int self, int *idx)
{
  ev->nn = 0;
  ev->self = -1;
  if (nc > ev->cap)
    return -1;
  const int dim = ev->ctx.dim;
  const double a2 = ev->ctx.a * ev->ctx.a;
  int k = 0, s = -1;
  if (dim == 2 && !ev->box->periodic) { /* the common case, unrolled: the same operations */
    const double x0 = x[0], x1 = x[1];
    double *d = ev->d, *v = ev->v;
    for (size_t c = 0; c < nc; c++) {
      const int J = cand[c];
      const double d0 = xp[2 * (size_t)J] - x0, d1 = xp[2 * (size_t)J + 1] - x1;
      if (!ev->within && !(d0 * d0 + d1 * d1 < a2))
        continue;
      d[2 * k] = d0;
      d[2 * k + 1] = d1;
      v[k] = vol ? vol[J] : 0.0;
      s = J == self ? k : s;
      idx[k++] = J;
    }
    ev->nn = k;
    ev->self = s;
    return k;
  }
  for (size_t c = 0; c < nc; c++) {
    int J = cand[c];
    double *dj = ev->d + (size_t)k * dim;
    mfs_box_delta(ev->box, x, xp + (size_t)J * dim, dj);
    if (!ev->within) {
      double r2 = 0.0;
      for (int l = 0; l < dim; l++)
        r2 += dj[l] * dj[l];
      if (!(r2 < a2))
        continue;
    }
    ev->v[k] = vol ? vol[J] : 0.0;
    if (J == self)
      s = k;
    idx[k++] = J;
  }
  ev->nn = k;
  ev->self = s;
  return k;
}

mfs_status mfs_eval_point_general(mfs_eval *ev, const double *x, const double *xp,
                                  const double *vol, const int *cand, size_t nc, int self,
                                  int *idx, double *out, int *nn, double *rcond)
{
  int k = mfs_eval_gather(ev, x, xp, vol, cand, nc, self, idx);
  *nn = k > 0 ? k : 0;
  if (k < 0)
    return MFS_EINVAL;
  double rc = 1.0;
  int st = ev->shape->eval(&ev->ctx, k, ev->d, ev->v, ev->self, ev->order, out, ev->work, &rc);
  if (rcond)
    *rcond = rc;
  return st;
}

mfs_status mfs_eval_grow(mfs_eval *ev, size_t need, int stride, double **out, int **loc,
                         size_t *cap)
{
  if (need <= *cap)
    return MFS_OK;
  size_t c = 2 * need;
  double *o = mfs_realloc(*out, (size_t)stride * c * sizeof *o);
  if (!o)
    return MFS_ENOMEM;
  *out = o;
  int *l = mfs_realloc(*loc, c * sizeof *l);
  if (!l)
    return MFS_ENOMEM;
  *loc = l;
  if (mfs_eval_reserve(ev, c) != MFS_OK)
    return MFS_ENOMEM;
  *cap = c;
  return MFS_OK;
}
