/* Reference explicit solver (see mfs_solver.h). */
#include "mfs_solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_bound.h"
#include "mfs_neighbor.h"
#include "mfs_status.h"

struct mfs_solver_work {
  mfs_particles *p;
  mfs_quad *q;
  mfs_plan *pl;          /* Lagrangian table (order 1), built once */
  unsigned char *fixed;  /* n: displacement prescribed (fixed or velocity end) */
  double *f, *f0;        /* n: internal force, equilibration load */
  double *u0, *v0;       /* n: RK stage base */
  double *ku, *kv;       /* 4n each: RK stage derivatives */
  double *tu;            /* n: stage displacement */
  /* Eulerian */
  double *x, *xq;        /* n, nq current positions */
  double *xb, *xqb;      /* positions at the last neighbour search */
  mfs_nlist *cand;       /* candidates within a + skin */
  size_t cap;            /* capacity of the per-point buffers */
  double *d, *vol, *out, *swork;
  int *loc;
  double a, skin;
};

static const char *const scheme_names[] = {"leapfrog", "euler", "rk2", "rk4"};

const char *mfs_scheme_name(mfs_scheme s)
{
  return (unsigned)s < 4 ? scheme_names[s] : "?";
}

int mfs_scheme_parse(const char *name, mfs_scheme *s)
{
  for (int i = 0; i < 4; i++)
    if (strcmp(name, scheme_names[i]) == 0) {
      *s = (mfs_scheme)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

/* 1D St Venant-Kirchhoff with initial stress: P = F S, S = E (F^2-1)/2 + S0. */
static inline double pk1(const mfs_solver_spec *sp, double F)
{
  return F * (0.5 * sp->modulus * (F * F - 1.0) + sp->initial_stress);
}

/* Prescribed velocity of end k at time t. */
static double bc_vel(const mfs_solver_spec *sp, int k, double t)
{
  return sp->bc[k] == MFS_BC_VELOCITY && t <= sp->bc_until[k] ? sp->bc_velocity[k] : 0.0;
}

/* Its time integral from 0 (the end's displacement). */
static double bc_disp(const mfs_solver_spec *sp, int k, double t)
{
  if (sp->bc[k] != MFS_BC_VELOCITY)
    return 0.0;
  return sp->bc_velocity[k] * fmin(t, sp->bc_until[k]);
}

/* Lagrangian internal force, eqs 77-78. */
static int force_lagrangian(mfs_solver *s, const double *u, double *f)
{
  const mfs_plan *pl = s->w->pl;
  const size_t *ptr = pl->nl->ptr;
  const int *idx = pl->nl->idx;
  const double *tab = pl->tab;
  memset(f, 0, s->n * sizeof *f);
  for (size_t Q = 0; Q < s->nq; Q++) {
    double F = 1.0;
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++)
      F += tab[2 * e + 1] * u[idx[e]];
    double P = pk1(&s->spec, F);
    s->F[Q] = F;
    s->sigma[Q] = P;
    double wP = s->wq[Q] * P;
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++)
      f[idx[e]] += tab[2 * e + 1] * wP;
  }
  return MFS_OK;
}

/* Neighbour candidates of the current quadrature points within a + skin. */
static int search(mfs_solver *s)
{
  mfs_solver_work *w = s->w;
  int st;
  mfs_grid *g = mfs_grid_alloc(1, s->n, w->x, &w->p->box, w->a + w->skin, &st);
  if (!g)
    return st;
  mfs_nlist *nl = mfs_nlist_build(g, s->nq, w->xq, w->a + w->skin, &st);
  mfs_grid_free(g);
  if (!nl)
    return st;
  mfs_nlist_free(w->cand);
  w->cand = nl;
  size_t maxrow = 1;
  for (size_t Q = 0; Q < s->nq; Q++) {
    size_t len = nl->ptr[Q + 1] - nl->ptr[Q];
    maxrow = len > maxrow ? len : maxrow;
  }
  if (maxrow > w->cap) {
    size_t cap = 2 * maxrow;
    double *d = realloc(w->d, cap * sizeof *d), *v = d ? realloc(w->vol, cap * sizeof *v) : NULL;
    if (d)
      w->d = d;
    if (v)
      w->vol = v;
    double *o = v ? realloc(w->out, 2 * cap * sizeof *o) : NULL;
    if (o)
      w->out = o;
    double *sw = o ? realloc(w->swork, mfs_shape_work_len(1, (int)cap) * sizeof *sw) : NULL;
    if (sw)
      w->swork = sw;
    int *l = sw ? realloc(w->loc, cap * sizeof *l) : NULL;
    if (!l)
      return MFS_ENOMEM;
    w->loc = l;
    w->cap = cap;
  }
  memcpy(w->xb, w->x, s->n * sizeof *w->x);
  memcpy(w->xqb, w->xq, s->nq * sizeof *w->xq);
  s->searches++;
  return MFS_OK;
}

/* b - a for two 1D coordinates, the minimum image when the box is periodic.
 * Same value as mfs_box_delta for |b - a| < 1.5 L (all points here: x = X + u
 * with X in the box), without its division and nearbyint. */
static inline double delta1(const mfs_box *box, double a, double b)
{
  double t = b - a;
  if (box->periodic) {
    double L = box->hi[0] - box->lo[0];
    if (fabs(t) >= 1.5 * L)
      t -= L * nearbyint(t / L);
    else if (t > 0.5 * L)
      t -= L;
    else if (t < -0.5 * L)
      t += L;
  }
  return t;
}

static inline double max2(double a, double b)
{
  return a > b ? a : b;
}

/* Current positions x = X + u and quadrature points; search again when some
 * point moved more than skin/2 since the last search. */
static int eulerian_positions(mfs_solver *s, const double *u)
{
  mfs_solver_work *w = s->w;
  const mfs_plan *pl = w->pl;
  const mfs_box *box = &w->p->box;
  const int *node = w->q->node;
  double *x = w->x, *xq = w->xq;
  const double *xb = w->xb, *xqb = w->xqb;
  double moved = 0.0;
  int finite = 1;
  for (size_t I = 0; I < s->n; I++) {
    x[I] = s->X[I] + u[I];
    double dI = fabs(delta1(box, xb[I], x[I]));
    finite &= isfinite(dI);
    moved = max2(moved, dI);
  }
  for (size_t Q = 0; Q < s->nq; Q++) {
    if (node[Q] >= 0) {
      xq[Q] = x[node[Q]];
    } else { /* interpolated displacement, Lagrangian table */
      double uq = 0.0;
      for (size_t e = pl->nl->ptr[Q]; e < pl->nl->ptr[Q + 1]; e++)
        uq += pl->tab[2 * e] * u[pl->nl->idx[e]];
      xq[Q] = s->xq0[Q] + uq;
    }
    double dq = fabs(delta1(box, xqb[Q], xq[Q]));
    finite &= isfinite(dq);
    moved = max2(moved, dq);
  }
  if (!finite)
    return MFS_EDOMAIN;
  if (!w->cand || moved > 0.5 * w->skin)
    return search(s);
  return MFS_OK;
}

/* Eulerian internal force, 1D linear MLS: the arithmetic of mls_fast_order1
 * (mfs_shape.c) in the same order, fused with the gather of the neighbours
 * within a and the scatter of the force, so one pass over the candidates
 * and no per-point call.  Results as force_eulerian with mfs_shape_mls. */
static int force_eulerian_mls1(mfs_solver *s, const double *u, double *f)
{
  mfs_solver_work *w = s->w;
  const mfs_shape_ctx *c = &w->pl->ctx;
  const mfs_box *box = &w->p->box;
  void (*keval)(double, double *, double *, double *) = c->kernel->eval;
  const int quartic = c->kernel == &mfs_kernel_quartic;
  const double E = s->spec.modulus, S0 = s->spec.initial_stress, rcmin = c->rcond_min;
  const double ia = 1.0 / c->a, cn = c->kernel->norm[0] * ia, a = w->a;
  const double *x = w->x, *xq = w->xq, *wq = s->wq;
  const size_t *ptr = w->cand->ptr;
  const int *idx = w->cand->idx;
  double *kW = w->out, *kpx = w->d, *kdphi = w->vol;
  int *kJ = w->loc;
  memset(f, 0, s->n * sizeof *f);
  for (size_t Q = 0; Q < s->nq; Q++) {
    const double xQ = xq[Q];
    double a00 = 0, a01 = 0, a11 = 0, b00 = 0, b01 = 0, b11 = 0;
    int nn = 0;
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++) {
      int J = idx[e];
      double dd = delta1(box, xQ, x[J]);
      if (fabs(dd) >= a)
        continue;
      double px = dd * ia, z = fabs(px), wv = 0.0, dw = 0.0, d2w = 0.0;
      if (z < 1.0) {
        if (quartic) /* inline: no call through the table */
          mfs_kernel_quartic_poly(z, &wv, &dw, &d2w);
        else
          keval(z, &wv, &dw, &d2w);
      }
      double W = cn * wv;
      double t = z > 0.0 ? -cn * dw / z * ia : -cn * d2w * ia;
      double gx = t * px;
      a00 += W;
      a01 += W * px;
      a11 += W * px * px;
      b00 += gx;
      b01 += gx * px;
      b11 += gx * px * px;
      kW[2 * nn] = W;
      kW[2 * nn + 1] = gx;
      kpx[nn] = px;
      kJ[nn] = J;
      nn++;
    }
    double det = a00 * a11 - a01 * a01;
    if (!(det > 0.0))
      return MFS_ESINGULAR;
    double i00 = a11 / det, i01 = -a01 / det, i11 = a00 / det;
    double na = max2(fabs(a00) + fabs(a01), fabs(a01) + fabs(a11));
    double ni = max2(fabs(i00) + fabs(i01), fabs(i01) + fabs(i11));
    double rc = 1.0 / (na * ni);
    if (!(rc >= rcmin) || rc == 0.0)
      return MFS_ESINGULAR;
    double g0 = i00, g1 = i01; /* dg = A^-1 (e1/a - dA g) */
    double r0 = -(b00 * g0 + b01 * g1);
    double r1 = ia - (b01 * g0 + b11 * g1);
    double dg0 = i00 * r0 + i01 * r1, dg1 = i01 * r0 + i11 * r1;
    double dudx = 0.0; /* eq. 68 */
    for (int k = 0; k < nn; k++) {
      double px = kpx[k];
      double gp = g0 + g1 * px, dgp = dg0 + dg1 * px;
      double dphi = dgp * kW[2 * k] + gp * kW[2 * k + 1];
      kdphi[k] = dphi;
      dudx += dphi * u[kJ[k]];
    }
    if (!(dudx < 1.0))
      return MFS_EDOMAIN;
    double F = 1.0 / (1.0 - dudx);
    double sig = F * (0.5 * E * (F * F - 1.0) + S0);
    s->F[Q] = F;
    s->sigma[Q] = sig;
    double Vs = wq[Q] * F * sig;
    for (int k = 0; k < nn; k++)
      f[kJ[k]] += kdphi[k] * Vs;
  }
  return MFS_OK;
}

/* Eulerian internal force, eqs 64-68: shape functions at the current
 * quadrature points, V_Q = w_Q F_Q, sigma = P. */
static int force_eulerian(mfs_solver *s, const double *u, double *f)
{
  mfs_solver_work *w = s->w;
  const mfs_plan *pl = w->pl;
  const mfs_box *box = &w->p->box;
  const double E = s->spec.modulus, S0 = s->spec.initial_stress;
  int st = eulerian_positions(s, u);
  if (st != MFS_OK)
    return st;
  if (pl->shape == &mfs_shape_mls && pl->ctx.dim == 1)
    return force_eulerian_mls1(s, u, f);
  memset(f, 0, s->n * sizeof *f);
  const mfs_nlist *cl = w->cand;
  for (size_t Q = 0; Q < s->nq; Q++) {
    int nn = 0, self = -1, node = w->q->node[Q];
    for (size_t e = cl->ptr[Q]; e < cl->ptr[Q + 1]; e++) {
      int J = cl->idx[e];
      double dd = delta1(box, w->xq[Q], w->x[J]);
      if (fabs(dd) >= w->a)
        continue;
      if (J == node)
        self = nn;
      w->d[nn] = dd;
      w->vol[nn] = w->p->vol[J]; /* reference volume V^0 (see header) */
      w->loc[nn] = J;
      nn++;
    }
    double rc;
    st = pl->shape->eval(&pl->ctx, nn, w->d, w->vol, self, 1, w->out, w->swork, &rc);
    if (st != MFS_OK)
      return st;
    double dudx = 0.0; /* eq. 68 */
    for (int k = 0; k < nn; k++)
      dudx += w->out[2 * k + 1] * u[w->loc[k]];
    if (!(dudx < 1.0))
      return MFS_EDOMAIN;
    double F = 1.0 / (1.0 - dudx);
    double sig = F * (0.5 * E * (F * F - 1.0) + S0);
    s->F[Q] = F;
    s->sigma[Q] = sig;
    double Vs = s->wq[Q] * F * sig;
    for (int k = 0; k < nn; k++)
      f[w->loc[k]] += w->out[2 * k + 1] * Vs;
  }
  return MFS_OK;
}

static int force(mfs_solver *s, const double *u, double *f)
{
  return s->spec.frame == MFS_FRAME_EULERIAN ? force_eulerian(s, u, f)
                                              : force_lagrangian(s, u, f);
}

/* Acceleration at displacement u, time t: m a = f0 - f_int(u); zero at ends
 * whose displacement is prescribed. */
static int accel(mfs_solver *s, const double *u, double *a)
{
  double *f = s->w->f;
  int st = force(s, u, f);
  if (st != MFS_OK)
    return st;
  int bad = 0;
  for (size_t I = 0; I < s->n; I++) {
    a[I] = s->w->fixed[I] ? 0.0 : (s->w->f0[I] - f[I]) / s->m[I];
    bad |= !isfinite(a[I]);
  }
  return bad ? MFS_EDOMAIN : MFS_OK;
}

/* Impose the end conditions on u, v at time t. */
static void impose(mfs_solver *s, double *u, double *v, double t)
{
  if (s->spec.periodic)
    return;
  size_t end[2] = {0, s->n - 1};
  for (int k = 0; k < 2; k++) {
    if (s->spec.bc[k] == MFS_BC_FREE)
      continue;
    if (u)
      u[end[k]] = bc_disp(&s->spec, k, t);
    if (v)
      v[end[k]] = bc_vel(&s->spec, k, t);
  }
}

/* Largest |eigenvalue| of M^-1 K at u = 0 by power iteration, K v taken as a
 * difference of internal forces (the equilibration load cancels). */
static int power_lambda(mfs_solver *s, double *lambda)
{
  mfs_solver_work *w = s->w;
  double *vec = w->u0, *kv = w->v0, *up = w->tu, *f = w->f;
  size_t n = s->n;
  unsigned long r = 12345;
  for (size_t I = 0; I < n; I++) {
    r = r * 6364136223846793005UL + 1442695040888963407UL;
    vec[I] = w->fixed[I] ? 0.0 : ((double)(r >> 11) / 9007199254740992.0 - 0.5);
  }
  int st = force(s, s->u, w->ku); /* f(0) into ku */
  if (st != MFS_OK)
    return st;
  double lam = 0.0;
  for (int it = 0; it < 300; it++) {
    double nv = 0.0;
    for (size_t I = 0; I < n; I++)
      nv += vec[I] * vec[I];
    nv = sqrt(nv);
    if (!(nv > 0.0))
      break;
    double eps = 1e-7 * s->dX / nv;
    for (size_t I = 0; I < n; I++)
      up[I] = eps * vec[I];
    if ((st = force(s, up, f)) != MFS_OK)
      return st;
    double nk = 0.0;
    for (size_t I = 0; I < n; I++) {
      kv[I] = w->fixed[I] ? 0.0 : (f[I] - w->ku[I]) / (eps * s->m[I]);
      nk += kv[I] * kv[I];
    }
    lam = sqrt(nk) / nv;
    for (size_t I = 0; I < n; I++) /* normalized: no overflow */
      vec[I] = kv[I] / (lam > 0.0 ? lam : 1.0);
  }
  *lambda = lam;
  return MFS_OK;
}

void mfs_solver_free(mfs_solver *s)
{
  if (!s)
    return;
  mfs_solver_work *w = s->w;
  if (w) {
    mfs_plan_free(w->pl);
    mfs_quad_free(w->q);
    mfs_particles_free(w->p);
    mfs_nlist_free(w->cand);
    free(w->fixed);
    free(w->d);
    free(w->vol);
    free(w->out);
    free(w->swork);
    free(w->loc);
    free(w);
  }
  free(s->u);
  free(s);
}

mfs_solver *mfs_solver_alloc(const mfs_solver_spec *spec, int *status, size_t *bad)
{
  int st = MFS_EINVAL;
  mfs_solver *s = NULL;
  mfs_quad_rule rule;
  if (!spec || spec->n < 3 || !(spec->length > 0.0) || !(spec->density > 0.0) ||
      !(spec->modulus > 0.0) || !isfinite(spec->initial_stress) || !spec->kernel ||
      !spec->shape || !(spec->dilation > 0.0) || !spec->quadrature ||
      mfs_quad_rule_parse(spec->quadrature, &rule) != MFS_OK ||
      mfs_quad_rule_check(&rule, 1, MFS_LATTICE_LINE) != MFS_OK)
    goto fail;
  st = MFS_ENOMEM;
  s = calloc(1, sizeof *s);
  if (!s || !(s->w = calloc(1, sizeof *s->w)))
    goto fail;
  mfs_solver_work *w = s->w;
  s->spec = *spec;
  s->spec.quadrature = NULL; /* not kept: the caller's string */
  if (!(s->spec.rcond_min > 0.0))
    s->spec.rcond_min = 1e-12;
  size_t n = (size_t)spec->n;
  s->n = n;
  s->dX = spec->length / (double)(spec->periodic ? n : n - 1);
  mfs_lattice_spec ls = {.dim = 1,
                         .lattice = MFS_LATTICE_LINE,
                         .nx = spec->n,
                         .ny = 1,
                         .dx = s->dX,
                         .gamma = 1.0,
                         .periodic = spec->periodic,
                         .cells = rule.cells};
  if (!(w->p = mfs_lattice_alloc(&ls, &st)))
    goto fail;
  if (!(w->q = mfs_quad_alloc(&rule, w->p, &st)))
    goto fail;
  mfs_plan_spec ps = {spec->kernel, spec->shape, spec->dilation, 1, s->spec.rcond_min};
  if (!(w->pl = mfs_plan_alloc(&ps, w->p, w->q, &st, bad)))
    goto fail;
  st = MFS_ENOMEM;
  size_t nq = w->q->n;
  s->nq = nq;
  s->X = w->p->x;
  s->xq0 = w->q->x;
  s->wq = w->q->w;
  /* one block: u v a m f f0 u0 v0 ku(4) kv(4) tu x xb (13+... n) + F sigma xq xqb (4 nq) */
  double *blk = calloc(19 * n + 4 * nq, sizeof *blk);
  w->fixed = calloc(n, 1);
  if (!blk || !w->fixed) {
    free(blk);
    goto fail;
  }
  s->u = blk;
  s->v = blk + n;
  s->a = blk + 2 * n;
  s->m = blk + 3 * n;
  w->f = NULL; /* part of blk: freed with s->u */
  double *f = blk + 4 * n;
  w->f0 = blk + 5 * n;
  w->u0 = blk + 6 * n;
  w->v0 = blk + 7 * n;
  w->ku = blk + 8 * n;
  w->kv = blk + 12 * n;
  w->tu = blk + 16 * n;
  w->x = blk + 17 * n;
  w->xb = blk + 18 * n;
  s->F = blk + 19 * n;
  s->sigma = s->F + nq;
  w->xq = s->sigma + nq;
  w->xqb = w->xq + nq;
  w->f = f;
  for (size_t I = 0; I < n; I++)
    s->m[I] = spec->density * w->p->vol[I]; /* eq. 51 */
  if (!spec->periodic) {
    w->fixed[0] = spec->bc[0] != MFS_BC_FREE;
    w->fixed[n - 1] = spec->bc[1] != MFS_BC_FREE;
  }
  w->a = spec->dilation * s->dX;
  w->skin = (spec->skin > 0.0 ? spec->skin : 0.5) * s->dX;
  if (spec->periodic && !(spec->length > 2.0 * (w->a + w->skin))) {
    st = MFS_ETOOSMALL;
    goto fail;
  }
  for (size_t I = 0; I < n; I++)
    w->x[I] = s->X[I];
  for (size_t Q = 0; Q < nq; Q++)
    w->xq[Q] = s->xq0[Q];
  /* equilibration load: f0 = f_int(0) */
  if (spec->equilibrate) {
    st = force(s, s->u, w->f0);
    if (st != MFS_OK)
      goto fail;
  }
  /* stable step: element bound with Cbar = E + S0 (eqs 81, 132) and power iteration */
  mfs_material mat = {MFS_PHYS_SCALAR, spec->modulus + spec->initial_stress, 0.0,
                      spec->density};
  mfs_bound_result br;
  if (mat.modulus > 0.0 && mfs_bound_plan(w->pl, &mat, w->fixed, &br) == MFS_OK) {
    s->lambda_bound = br.lambda;
    s->negative_phi = br.negative_phi;
  }
  if ((st = power_lambda(s, &s->lambda_power)) != MFS_OK)
    goto fail;
  /* The element bound is proven only where every phi_I > 0 (eq. 132) and can
   * be far above lambda_max where some phi_I is tiny (MLS at free ends with
   * nodal integration: 1e16 times); the power estimate converges to lambda_max
   * from below.  Use the proven bound, but no more than 5% above the estimate. */
  double lam = 1.05 * s->lambda_power;
  if (s->negative_phi == 0 && s->lambda_bound > 0.0 && s->lambda_bound < lam)
    lam = s->lambda_bound;
  if (!(lam > 0.0) || !isfinite(lam)) {
    st = MFS_EDOMAIN;
    goto fail;
  }
  s->dt_crit = 2.0 / sqrt(lam); /* eq. 120 */
  s->dt = 0.9 * s->dt_crit;
  if ((st = mfs_solver_reset(s)) != MFS_OK)
    goto fail;
  *status = MFS_OK;
  return s;
fail:
  mfs_solver_free(s);
  *status = st;
  return NULL;
}

int mfs_solver_set_state(mfs_solver *s, const double *u, const double *v)
{
  for (size_t I = 0; I < s->n; I++) {
    s->u[I] = u ? u[I] : 0.0;
    s->v[I] = v ? v[I] : 0.0;
  }
  impose(s, s->u, s->v, s->t);
  return accel(s, s->u, s->a);
}

int mfs_solver_reset(mfs_solver *s)
{
  s->t = 0.0;
  s->steps = 0;
  return mfs_solver_set_state(s, NULL, NULL);
}

int mfs_solver_set_dt(mfs_solver *s, double dt, int force_it)
{
  if (!(dt > 0.0) || !isfinite(dt) || (dt > s->dt_crit && !force_it))
    return MFS_EINVAL;
  s->dt = dt;
  return MFS_OK;
}

/* mfs_explicit's callbacks (central difference: eq. 120, kick-drift-kick). */
static int accel_cb(void *ctx, const double *u, double *a)
{
  return accel(ctx, u, a);
}

static void impose_cb(void *ctx, double *u, double *v, double t)
{
  impose(ctx, u, v, t);
}

int mfs_solver_step(mfs_solver *s, mfs_scheme scheme)
{
  mfs_solver_work *w = s->w;
  mfs_explicit_work rk = {w->u0, w->v0, w->ku, w->kv, w->tu};
  int st = mfs_explicit_step(scheme, s->n, s->u, s->v, s->a, s->t, s->dt, &rk, accel_cb,
                             impose_cb, s);
  if (st == MFS_OK || st == MFS_EDOMAIN) { /* the step was taken */
    s->t += s->dt;
    s->steps++;
  }
  return st;
}

int mfs_solver_fields(mfs_solver *s)
{
  return force(s, s->u, s->w->f);
}

int mfs_solver_energy(mfs_solver *s, double *kinetic, double *potential)
{
  int st = mfs_solver_fields(s);
  if (st != MFS_OK)
    return st;
  double k = 0.0, p = 0.0, E = s->spec.modulus, S0 = s->spec.initial_stress;
  for (size_t I = 0; I < s->n; I++)
    k += 0.5 * s->m[I] * s->v[I] * s->v[I];
  for (size_t Q = 0; Q < s->nq; Q++) {
    double g = s->F[Q] * s->F[Q] - 1.0;
    p += s->wq[Q] * (0.5 * S0 * g + 0.125 * E * g * g);
  }
  for (size_t I = 0; I < s->n; I++)
    p -= s->w->f0[I] * s->u[I];
  *kinetic = k;
  *potential = p;
  return MFS_OK;
}

size_t mfs_solver_nearest(const mfs_solver *s, double X)
{
  double r = floor(X / s->dX + 0.5);
  if (r < 0)
    r = 0;
  if (r > (double)(s->n - 1))
    r = (double)(s->n - 1);
  return (size_t)r;
}
