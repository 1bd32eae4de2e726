/* Reference explicit solver (see mfs_solver.h). */
#include "mfs_solver.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_assemble.h"
#include "mfs_bound.h"
#include "mfs_eval.h"
#include "mfs_mls1d.h"
#include "mfs_neighbor.h"
#include "mfs_plan.h"
#include "mfs_status.h"

struct mfs_solver_work {
  mfs_particles *p;
  mfs_quad *q;
  mfs_plan *pl;          /* Lagrangian table (order 1), built once */
  const size_t *tptr;    /* its compressed rows (mfs_plan_table) */
  const int *tidx;
  const double *tab;
  int nc;                /* doubles per table entry */
  mfs_eval ev;           /* Eulerian: shape functions at the current positions */
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
  double *out;
  int *loc;
  double a, skin;
};

/* 1D St Venant-Kirchhoff with initial stress: P = F S, S = E (F^2-1)/2 + S0. */
static inline double pk1(const mfs_material *m, double F)
{
  return F * (0.5 * m->modulus * (F * F - 1.0) + m->initial_stress);
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
  const mfs_solver_work *w = s->w;
  const size_t *ptr = w->tptr;
  const int *idx = w->tidx;
  enum { nc = 2 }; /* mfs_shape_ncomp(1, 1): (phi, phi') per entry, checked at alloc */
  const double *tab = w->tab;
  memset(f, 0, s->n * sizeof *f);
  for (size_t Q = 0; Q < s->nq; Q++) {
    double F = 1.0;
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++)
      F += tab[nc * e + 1] * u[idx[e]];
    double P = pk1(&s->spec.disc.material, F);
    s->F[Q] = F;
    s->sigma[Q] = P;
    double wP = s->wq[Q] * P;
    for (size_t e = ptr[Q]; e < ptr[Q + 1]; e++)
      f[idx[e]] += tab[nc * e + 1] * wP;
  }
  return MFS_OK;
}

/* Neighbour candidates of the current quadrature points within a + skin. */
static int search(mfs_solver *s)
{
  mfs_solver_work *w = s->w;
  size_t maxrow;
  mfs_status st = mfs_nlist_rebuild(1, s->n, w->x, &w->p->box, s->nq, w->xq, w->a + w->skin,
                                    &w->cand, &maxrow);
  if (st == MFS_OK)
    st = mfs_eval_grow(&w->ev, maxrow, 2, &w->out, &w->loc, &w->cap);
  if (st != MFS_OK)
    return st;
  memcpy(w->xb, w->x, s->n * sizeof *w->x);
  memcpy(w->xqb, w->xq, s->nq * sizeof *w->xq);
  s->searches++;
  return MFS_OK;
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
  const mfs_box *box = &w->p->box;
  const int *node = w->q->node;
  double *x = w->x, *xq = w->xq;
  const double *xb = w->xb, *xqb = w->xqb;
  double moved = 0.0;
  int finite = 1;
  for (size_t I = 0; I < s->n; I++) {
    x[I] = s->X[I] + u[I];
    double dI = fabs(mfs_box_delta1(box, xb[I], x[I]));
    finite &= isfinite(dI);
    moved = max2(moved, dI);
  }
  for (size_t Q = 0; Q < s->nq; Q++) {
    if (node[Q] >= 0) {
      xq[Q] = x[node[Q]];
    } else { /* interpolated displacement, Lagrangian table */
      double uq = 0.0;
      for (size_t e = w->tptr[Q]; e < w->tptr[Q + 1]; e++)
        uq += w->tab[2 * e] * u[w->tidx[e]]; /* nc = 2 */
      xq[Q] = s->xq0[Q] + uq;
    }
    double dq = fabs(mfs_box_delta1(box, xqb[Q], xq[Q]));
    finite &= isfinite(dq);
    moved = max2(moved, dq);
  }
  if (!finite)
    return MFS_EDOMAIN;
  if (!w->cand || moved > 0.5 * w->skin)
    return search(s);
  return MFS_OK;
}

/* Eulerian internal force, eqs 64-68: shape functions at the current
 * quadrature points (the point evaluator on the candidates), V_Q = w_Q F_Q,
 * sigma = P; for sph the volumes are the reference volumes V^0 (see header).
 * One body: with kw NULL through the evaluator (any shape), with kw a
 * kernel's inline formula the fused 1D MLS gather inlined (mfs_mls1d.h), one
 * instantiation per built-in kernel below. */
static inline int force_eulerian_body(mfs_solver *s, const double *u, double *f,
                                      mfs_mls1d_kernel_fn kw)
{
  mfs_solver_work *w = s->w;
  const mfs_material *mat = &s->spec.disc.material;
  const double E = mat->modulus, S0 = mat->initial_stress;
  int st = eulerian_positions(s, u);
  if (st != MFS_OK)
    return st;
  memset(f, 0, s->n * sizeof *f);
  const mfs_nlist *cl = w->cand;
  for (size_t Q = 0; Q < s->nq; Q++) {
    int nn;
    size_t e0 = cl->ptr[Q], nc = cl->ptr[Q + 1] - e0;
    double dudx = 0.0; /* eq. 68, in the pass that evaluates the shape functions */
    if (kw) {
      double rc;
      st = mfs_mls1d_gather(kw, &w->ev.ctx, w->ev.box, w->xq[Q], w->x, cl->idx + e0, nc, w->loc,
                            w->out, w->ev.work, &nn, &rc, u, &dudx, 0);
    } else {
      st = mfs_eval_point_grad(&w->ev, w->xq + Q, w->x, w->p->vol, cl->idx + e0, nc,
                               w->q->node[Q], w->loc, w->out, &nn, u, &dudx);
    }
    if (st != MFS_OK)
      return st;
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

static int force_eulerian(mfs_solver *s, const double *u, double *f)
{
  return force_eulerian_body(s, u, f, NULL);
}

#define MFS_X_FORCE(name)                                                                 \
  static int force_eulerian_mls1d_##name(mfs_solver *s, const double *u, double *f)      \
  {                                                                                       \
    return force_eulerian_body(s, u, f, mfs_kernel_##name##_w);                           \
  }
MFS_KERNEL_LIST(MFS_X_FORCE)
#undef MFS_X_FORCE

static int (*const force_mls1d[MFS_KERNEL_NIDS])(mfs_solver *, const double *, double *) = {
#define MFS_X_ENTRY(name) [MFS_KERNEL_ID_##name] = force_eulerian_mls1d_##name,
  MFS_KERNEL_LIST(MFS_X_ENTRY)
#undef MFS_X_ENTRY
};

/* The Eulerian force of the solver: the fused MLS loop of its kernel where
 * the evaluator's fast path is in use (1D MLS, a built-in kernel), else the
 * evaluator's. */
static int (*eulerian_force_of(const mfs_solver *s))(mfs_solver *, const double *, double *)
{
  const mfs_disc *d = &s->spec.disc;
  int id = d->kernel->id;
  /* the search keeps every candidate list within the evaluator's room */
  if (s->w->ev.fast && d->shape->gather_1d_is_mls1d && id > 0 && id < MFS_KERNEL_NIDS &&
      force_mls1d[id])
    return force_mls1d[id];
  return force_eulerian;
}

static int force(mfs_solver *s, const double *u, double *f)
{
  return s->spec.disc.frame == MFS_FRAME_EULERIAN ? eulerian_force_of(s)(s, u, f)
                                                  : force_lagrangian(s, u, f);
}

/* Acceleration at displacement u, time t: m a = f0 - f_int(u); zero at ends
 * whose displacement is prescribed. */
static int accel(void *ctx, const double *u, double *a)
{
  mfs_solver *s = ctx;
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
  if (s->spec.disc.source.periodic)
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
enum { POWER_ITERATIONS = 300 };

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
  for (int it = 0; it < POWER_ITERATIONS; it++) {
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

/* The material of the linearized stiffness at u = 0, K(Cbar): scalar, with
 * modulus Cbar = E + S0 (eq. 81) and the rod's density (the element bound,
 * the Gershgorin bound and the certified step use it). */
static mfs_material rod_cbar_material(const mfs_disc *d)
{
  return (mfs_material){.physics = MFS_PHYS_SCALAR,
                        .modulus = d->material.modulus + d->material.initial_stress,
                        .density = d->material.density};
}

/* The linearized stiffness at u = 0 applies to the Gershgorin and certified
 * rules when it is K(Cbar), Cbar = E + S0 (eq. 81): the Lagrangian kernel,
 * or the Eulerian one without initial stress (sigma = 0 at u = 0, so the
 * motion of the shape functions does not enter; with S0 != 0 the Eulerian
 * linearization has the kernel-motion terms of eqs 71-75, not bounded here). */
static const char *stiffness_rule_applies(const mfs_solver *s)
{
  const mfs_disc *d = &s->spec.disc;
  if (d->frame == MFS_FRAME_EULERIAN && d->material.initial_stress != 0.0)
    return "the Eulerian rod with an initial stress: its linearization has kernel-motion terms "
           "that neither bound covers";
  if (!(rod_cbar_material(d).modulus > 0.0))
    return "Cbar = E + S0 <= 0: the linearized stiffness is not positive";
  for (size_t I = 0; I < s->n; I++)
    if (!(s->m[I] > 0.0))
      return "a lumped mass <= 0";
  return NULL;
}

/* The Gershgorin bound of M^-1 K(Cbar) with the rod's masses, from the plan
 * (one pass over the rows, fixed particles removed); *lambda is set only on
 * success. */
static mfs_status rod_gershgorin(mfs_solver *s, double *lambda)
{
  const mfs_material mat = rod_cbar_material(&s->spec.disc);
  mfs_forms f = mfs_forms_stiffness(&mat);
  mfs_gershgorin_op op = {.forms = &f, .ndof = 1, .mass = s->m, .density = mat.density};
  mfs_gershgorin_result g;
  mfs_status st = mfs_gershgorin_op_plan(s->w->pl, &op, s->w->fixed, &g, NULL);
  if (st == MFS_OK)
    *lambda = g.lambda;
  return st;
}

/* The certified step of the pencil (K(Cbar), m) on the free particles. */
static mfs_status rod_certify(mfs_solver *s, mfs_dt_info *info)
{
  const mfs_material mat = rod_cbar_material(&s->spec.disc);
  mfs_csr *K = NULL;
  double *m = NULL;
  mfs_status st = mfs_assemble(s->w->pl, &mat, s->w->fixed, &K, NULL, NULL, NULL);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  if (!(m = mfs_malloc((K->nrow ? K->nrow : 1) * sizeof *m)))
    goto done;
  size_t k = 0;
  for (size_t I = 0; I < s->n; I++)
    if (!s->w->fixed[I])
      m[k++] = s->m[I];
  mfs_pencil P = {.K = K, .M = NULL, .m = m};
  st = mfs_dt_certify(&P, info);
done:
  mfs_free(m);
  mfs_csr_free(K);
  return st;
}

/* mfs_dt_ops's callbacks */
static mfs_status rod_certify_op(void *ctx, mfs_dt_info *in, const char **why)
{
  (void)why;
  return rod_certify(ctx, in);
}

static mfs_status rod_gershgorin_op(void *ctx, double *lambda)
{
  return rod_gershgorin(ctx, lambda);
}

static mfs_status rod_power_op(void *ctx, double *lambda, int *iterations)
{
  mfs_status st = power_lambda(ctx, lambda);
  if (st == MFS_OK)
    *iterations = POWER_ITERATIONS;
  return st;
}

mfs_status mfs_solver_choose_step(mfs_solver *s, mfs_dt_rule rule)
{
  mfs_dt_ops ops = {.ctx = s,
                    .block = stiffness_rule_applies(s),
                    .certify = rod_certify_op,
                    .gershgorin = rod_gershgorin_op,
                    .power = rod_power_op, /* 300 force evaluations: kept once found */
                    .lambda_bound = s->lambda_bound,
                    .negative_phi = s->negative_phi,
                    .power_scale = 1.0};
  int changed;
  mfs_status st = mfs_dt_choose(&ops, rule, &s->step, &changed);
  if (st != MFS_OK || !changed)
    return st;
  if (!isnan(s->step.lambda_power))
    s->lambda_power = s->step.lambda_power;
  s->dt_crit = 2.0 / sqrt(s->step.lambda); /* eq. 120 */
  s->dt = 0.9 * s->dt_crit;
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
    mfs_eval_free(&w->ev);
    mfs_free(w->fixed);
    mfs_free(w->out);
    mfs_free(w->loc);
    mfs_free(w);
  }
  mfs_free(s->u);
  mfs_free(s);
}

mfs_solver *mfs_solver_alloc(const mfs_solver_spec *spec, mfs_status *status, size_t *bad)
{
  mfs_status st = MFS_EINVAL;
  mfs_solver *s = NULL;
  const mfs_disc *d = spec ? &spec->disc : NULL;
  if (!spec || (st = mfs_disc_check(d, NULL)) != MFS_OK)
    goto fail;
  st = MFS_EINVAL;
  if (d->dim != 1 || mfs_disc_infinite(d) || d->source.nx < 3 ||
      d->frame == MFS_FRAME_EULERIAN_CONSISTENT || d->material.physics != MFS_PHYS_SCALAR)
    goto fail;
  st = MFS_ENOMEM;
  s = mfs_calloc(1, sizeof *s);
  if (!s || !(s->w = mfs_calloc(1, sizeof *s->w)))
    goto fail;
  mfs_solver_work *w = s->w;
  s->spec = *spec;
  size_t n = (size_t)d->source.nx;
  s->n = n;
  s->dX = mfs_disc_dx(d);
  if ((st = mfs_disc_geometry(d, &w->p, &w->q)) != MFS_OK)
    goto fail;
  if (!(w->pl = mfs_plan_alloc(d, w->p, w->q, &st)))
    goto fail;
  if ((st = mfs_plan_tabulate(w->pl, 1, bad)) != MFS_OK)
    goto fail;
  mfs_plan_table(w->pl, &w->tptr, &w->tidx, &w->tab);
  w->nc = mfs_plan_ncomp(w->pl);
  if (w->nc != 2) { /* the layout the force loops read */
    st = MFS_EINVAL;
    goto fail;
  }
  st = MFS_ENOMEM;
  size_t nq = w->q->n;
  s->nq = nq;
  s->X = w->p->x;
  s->xq0 = w->q->x;
  s->wq = w->q->w;
  /* one block: u v a m f f0 u0 v0 ku(4) kv(4) tu x xb (13+... n) + F sigma xq xqb (4 nq) */
  double *blk = mfs_calloc(19 * n + 4 * nq, sizeof *blk);
  w->fixed = mfs_calloc(n, 1);
  if (!blk || !w->fixed) {
    mfs_free(blk);
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
    s->m[I] = d->material.density * w->p->vol[I]; /* eq. 51 */
  if (!d->source.periodic) {
    w->fixed[0] = spec->bc[0] != MFS_BC_FREE;
    w->fixed[n - 1] = spec->bc[1] != MFS_BC_FREE;
  }
  w->a = d->dilation * s->dX;
  w->skin = (spec->skin > 0.0 ? spec->skin : 0.5) * s->dX;
  if (d->source.periodic && !(d->source.lx > 2.0 * (w->a + w->skin))) {
    st = MFS_ETOOSMALL;
    goto fail;
  }
  if (d->frame == MFS_FRAME_EULERIAN) {
    if ((st = mfs_eval_init(&w->ev, d, w->a, 1, &w->p->box, 1)) != MFS_OK)
      goto fail;
    mfs_eval_fast(&w->ev, 1);
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
  /* the element bound with Cbar = E + S0 (eqs 81, 132), for the power rule */
  const mfs_material mat = rod_cbar_material(d);
  mfs_bound_result br;
  mfs_status bst = mat.modulus > 0.0 ? mfs_bound_plan(w->pl, &mat, w->fixed, &br) : MFS_EINVAL;
  if ((st = mfs_dt_take_bound(bst, &br, &s->lambda_bound, &s->negative_phi)) != MFS_OK)
    goto fail;
  s->step = mfs_dt_info_init(MFS_DT_GERSHGORIN);
  s->step.requested = (mfs_dt_rule)-1; /* nothing chosen yet */
  if ((st = mfs_solver_choose_step(s, MFS_DT_GERSHGORIN)) != MFS_OK)
    goto fail;
  if ((st = mfs_solver_reset(s)) != MFS_OK)
    goto fail;
  *status = MFS_OK;
  return s;
fail:
  mfs_solver_free(s);
  *status = st;
  return NULL;
}

mfs_status mfs_solver_set_state(mfs_solver *s, const double *u, const double *v)
{
  for (size_t I = 0; I < s->n; I++) {
    s->u[I] = u ? u[I] : 0.0;
    s->v[I] = v ? v[I] : 0.0;
  }
  impose(s, s->u, s->v, s->t);
  return accel(s, s->u, s->a);
}

mfs_status mfs_solver_reset(mfs_solver *s)
{
  s->t = 0.0;
  s->steps = 0;
  return mfs_solver_set_state(s, NULL, NULL);
}

mfs_status mfs_solver_set_dt(mfs_solver *s, double dt, int force_it)
{
  return mfs_explicit_set_dt(&s->dt, dt, s->dt_crit, force_it);
}

/* mfs_explicit's impose callback; the step is eq. 120 in kick-drift-kick form. */
static void impose_cb(void *ctx, double *u, double *v, double t)
{
  impose(ctx, u, v, t);
}

mfs_status mfs_solver_step(mfs_solver *s, mfs_scheme scheme)
{
  mfs_solver_work *w = s->w;
  mfs_explicit_work rk = {w->u0, w->v0, w->ku, w->kv, w->tu};
  mfs_status st = mfs_explicit_step(scheme, s->n, s->u, s->v, s->a, s->t, s->dt, &rk, accel,
                             impose_cb, s);
  if (st == MFS_OK || st == MFS_EDOMAIN) { /* the step was taken */
    s->t += s->dt;
    s->steps++;
  }
  return st;
}

mfs_status mfs_solver_fields(mfs_solver *s)
{
  return force(s, s->u, s->w->f);
}

mfs_status mfs_solver_energy(mfs_solver *s, double *kinetic, double *potential)
{
  mfs_status st = mfs_solver_fields(s);
  if (st != MFS_OK)
    return st;
  double k = 0.0, p = 0.0, E = s->spec.disc.material.modulus,
         S0 = s->spec.disc.material.initial_stress;
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
