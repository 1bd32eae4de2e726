/* Reference explicit solver for linear Lagrangian models (see mfs_solver2d.h). */
#include "mfs_solver2d.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_assemble.h"
#include "mfs_bound.h"
#include "mfs_eval.h"
#include "mfs_neighbor.h"
#include "mfs_status.h"

struct mfs_solver2d_work {
  double *u0, *v0; /* n: RK stage base */
  double *ku, *kv; /* 4n each: RK stage derivatives */
  double *tu;      /* n: stage displacement */
  int *comp;       /* n: s->comp */
  /* the initially stressed (nonlinear) plate */
  double sig0[4];        /* sigma0, 2 x 2 (Pa) */
  double lam, mu;        /* Lame constants (Pa) */
  const size_t *tptr;    /* the model's shape table at the reference points */
  const int *tidx;
  const double *tab;
  int nc;
  double *uf, *ff;       /* 2 np: full displacement and internal force */
  double *f0;            /* n: the internal force at u = 0 (applied as a load) */
  /* Eulerian kernel */
  mfs_eval ev;           /* shape functions at the current positions */
  double *x, *xq;        /* 2 np, 2 nq: current positions */
  double *xb, *xqb;      /* at the last neighbour search */
  mfs_nlist *cand;       /* candidates within a + skin */
  size_t cap;
  double *out;
  int *loc;
  double a, skin;
  double smax;           /* the largest principal |sigma0| (Pa) */
};

enum { POWER_ITERATIONS = 300 };

static int force_nl(mfs_solver2d *s, const double *u, double *f);

/* a = -M^-1 K u (linear) or M^-1 (f_int(0) - f_int(u)) (initially stressed);
 * MFS_EDOMAIN if some a_i is not finite. */
static int accel(void *ctx, const double *u, double *a)
{
  mfs_solver2d *s = ctx;
  if (s->stressed) {
    int st = force_nl(s, u, a);
    if (st != MFS_OK)
      return st;
    int bad = 0;
    for (size_t i = 0; i < s->n; i++) {
      a[i] = -(a[i] - s->w->f0[i]) / s->m[i];
      bad |= !isfinite(a[i]);
    }
    return bad ? MFS_EDOMAIN : MFS_OK;
  }
  mfs_csr_matvec(s->model->K, u, a);
  int bad = 0;
  for (size_t i = 0; i < s->n; i++) {
    a[i] = -a[i] / s->m[i];
    bad |= !isfinite(a[i]);
  }
  return bad ? MFS_EDOMAIN : MFS_OK;
}


/* ---- the initially stressed plate (mfs_solver2d.h) ---- */

/* S = sigma0 + lambda tr(E) I + 2 mu E, E = (F^T F - I)/2 = (H + H^T + H^T H)/2 from
 * H = F - I (2 x 2, plane strain; written in H: no cancellation for small strains). */
static void svk(const mfs_solver2d_work *w, const double *H, double *S, double *E)
{
  E[0] = H[0] + 0.5 * (H[0] * H[0] + H[2] * H[2]);
  E[1] = E[2] = 0.5 * (H[1] + H[2] + H[0] * H[1] + H[2] * H[3]);
  E[3] = H[3] + 0.5 * (H[1] * H[1] + H[3] * H[3]);
  double tr = E[0] + E[3];
  for (int i = 0; i < 4; i++)
    S[i] = w->sig0[i] + 2.0 * w->mu * E[i] + (i == 0 || i == 3 ? w->lam * tr : 0.0);
}

/* The full displacement of the free dofs u (fixed particles at rest). */
static void full(const mfs_solver2d *s, const double *u, double *uf)
{
  memset(uf, 0, 2 * s->model->p->n * sizeof *uf);
  for (size_t i = 0; i < s->n; i++)
    uf[s->model->dof[i]] = u[i];
}

/* Lagrangian kernel: F_Q = I + sum_K u_K (x) grad0 phi_K(X_Q), P = F S,
 * f_K = sum_Q w_Q P grad0 phi_K. */
static int force_lagrangian(mfs_solver2d *s, const double *uf, double *ff)
{
  mfs_solver2d_work *w = s->w;
  const mfs_quad *q = s->model->q;
  const int nc = w->nc;
  for (size_t Q = 0; Q < q->n; Q++) {
    double H[4] = {0.0, 0.0, 0.0, 0.0}; /* F - I */
    for (size_t e = w->tptr[Q]; e < w->tptr[Q + 1]; e++) {
      const double *t = w->tab + e * (size_t)nc, *uk = uf + 2 * (size_t)w->tidx[e];
      H[0] += uk[0] * t[1];
      H[1] += uk[0] * t[2];
      H[2] += uk[1] * t[1];
      H[3] += uk[1] * t[2];
    }
    double S[4], E[4], P[4]; /* P = F S = S + H S */
    svk(w, H, S, E);
    P[0] = S[0] + H[0] * S[0] + H[1] * S[2];
    P[1] = S[1] + H[0] * S[1] + H[1] * S[3];
    P[2] = S[2] + H[2] * S[0] + H[3] * S[2];
    P[3] = S[3] + H[2] * S[1] + H[3] * S[3];
    double wq = q->w[Q];
    for (size_t e = w->tptr[Q]; e < w->tptr[Q + 1]; e++) {
      const double *t = w->tab + e * (size_t)nc;
      double *fk = ff + 2 * (size_t)w->tidx[e];
      fk[0] += wq * (P[0] * t[1] + P[1] * t[2]);
      fk[1] += wq * (P[2] * t[1] + P[3] * t[2]);
    }
  }
  return MFS_OK;
}

/* Neighbour candidates of the current quadrature points within a + skin. */
static int search(mfs_solver2d *s)
{
  mfs_solver2d_work *w = s->w;
  const mfs_particles *p = s->model->p;
  const mfs_quad *q = s->model->q;
  size_t maxrow;
  mfs_status st = mfs_nlist_rebuild(2, p->n, w->x, &p->box, q->n, w->xq, w->a + w->skin,
                                    &w->cand, &maxrow);
  if (st == MFS_OK)
    st = mfs_eval_grow(&w->ev, maxrow, 3, &w->out, &w->loc, &w->cap);
  if (st != MFS_OK)
    return st;
  memcpy(w->xb, w->x, 2 * p->n * sizeof *w->x);
  memcpy(w->xqb, w->xq, 2 * q->n * sizeof *w->xq);
  s->searches++;
  return MFS_OK;
}

/* Current positions: particles X + u; points at particles with them, other
 * points with the interpolated displacement sum_K phi_K(X_Q) u_K (the
 * reference table); search again when something moved more than skin/2. */
static int eulerian_positions(mfs_solver2d *s, const double *uf)
{
  mfs_solver2d_work *w = s->w;
  const mfs_particles *p = s->model->p;
  const mfs_quad *q = s->model->q;
  double moved = 0.0;
  int finite = 1;
  for (size_t i = 0; i < 2 * p->n; i++) {
    w->x[i] = p->x[i] + uf[i];
    finite &= isfinite(w->x[i]);
  }
  for (size_t I = 0; I < p->n; I++) {
    double d[3];
    mfs_box_delta(&p->box, w->xb + 2 * I, w->x + 2 * I, d);
    moved = fmax(moved, hypot(d[0], d[1]));
  }
  for (size_t Q = 0; Q < q->n; Q++) {
    double uq[2] = {0.0, 0.0};
    if (q->node[Q] >= 0) {
      uq[0] = uf[2 * (size_t)q->node[Q]];
      uq[1] = uf[2 * (size_t)q->node[Q] + 1];
    } else {
      for (size_t e = w->tptr[Q]; e < w->tptr[Q + 1]; e++) {
        double ph = w->tab[e * (size_t)w->nc];
        uq[0] += ph * uf[2 * (size_t)w->tidx[e]];
        uq[1] += ph * uf[2 * (size_t)w->tidx[e] + 1];
      }
    }
    w->xq[2 * Q] = q->x[2 * Q] + uq[0];
    w->xq[2 * Q + 1] = q->x[2 * Q + 1] + uq[1];
    finite &= isfinite(w->xq[2 * Q]) && isfinite(w->xq[2 * Q + 1]);
    double d[3];
    mfs_box_delta(&p->box, w->xqb + 2 * Q, w->xq + 2 * Q, d);
    moved = fmax(moved, hypot(d[0], d[1]));
  }
  if (!finite)
    return MFS_EDOMAIN;
  if (!w->cand || moved > 0.5 * w->skin)
    return search(s);
  return MFS_OK;
}

/* Eulerian kernel: shape functions at the current points among the current
 * particles (radius a = D dx, sph volumes the reference ones: phi_I is a
 * fixed function of x - x_I); F_Q^-1 = I - sum_K u_K (x) grad phi_K(x_Q)
 * (eq. 68 in 2D), sigma = J^-1 F S F^T, V_Q = J w_Q, f_K = sum_Q V_Q sigma grad phi_K. */
static int force_eulerian(mfs_solver2d *s, const double *uf, double *ff)
{
  mfs_solver2d_work *w = s->w;
  const mfs_particles *p = s->model->p;
  const mfs_quad *q = s->model->q;
  int st = eulerian_positions(s, uf);
  if (st != MFS_OK)
    return st;
  const mfs_nlist *cl = w->cand;
  for (size_t Q = 0; Q < q->n; Q++) {
    int nn;
    size_t e0 = cl->ptr[Q];
    st = mfs_eval_point(&w->ev, w->xq + 2 * Q, w->x, p->vol, cl->idx + e0, cl->ptr[Q + 1] - e0,
                        q->node[Q], w->loc, w->out, &nn, NULL);
    if (st != MFS_OK)
      return st;
    double G[4] = {0.0, 0.0, 0.0, 0.0}; /* grad_x u: F^-1 = I - G */
    for (int k = 0; k < nn; k++) {
      const double *t = w->out + 3 * k, *uk = uf + 2 * (size_t)w->loc[k];
      G[0] += uk[0] * t[1];
      G[1] += uk[0] * t[2];
      G[2] += uk[1] * t[1];
      G[3] += uk[1] * t[2];
    }
    double Fi[4] = {1.0 - G[0], -G[1], -G[2], 1.0 - G[3]};
    double di = Fi[0] * Fi[3] - Fi[1] * Fi[2];
    if (!(di > 0.0))
      return MFS_EDOMAIN; /* an inverted configuration */
    double F[4] = {Fi[3] / di, -Fi[1] / di, -Fi[2] / di, Fi[0] / di}, J = 1.0 / di;
    double H[4] = {F[0] * G[0] + F[1] * G[2], F[0] * G[1] + F[1] * G[3], /* F - I = F G */
                   F[2] * G[0] + F[3] * G[2], F[2] * G[1] + F[3] * G[3]};
    double S[4], E[4], FS[4], sg[4];
    svk(w, H, S, E);
    FS[0] = F[0] * S[0] + F[1] * S[2];
    FS[1] = F[0] * S[1] + F[1] * S[3];
    FS[2] = F[2] * S[0] + F[3] * S[2];
    FS[3] = F[2] * S[1] + F[3] * S[3];
    sg[0] = (FS[0] * F[0] + FS[1] * F[1]) / J;
    sg[1] = (FS[0] * F[2] + FS[1] * F[3]) / J;
    sg[2] = (FS[2] * F[0] + FS[3] * F[1]) / J;
    sg[3] = (FS[2] * F[2] + FS[3] * F[3]) / J;
    double V = q->w[Q] * J;
    for (int k = 0; k < nn; k++) {
      const double *t = w->out + 3 * k;
      double *fk = ff + 2 * (size_t)w->loc[k];
      fk[0] += V * (sg[0] * t[1] + sg[1] * t[2]);
      fk[1] += V * (sg[2] * t[1] + sg[3] * t[2]);
    }
  }
  return MFS_OK;
}

/* The internal force on the free dofs. */
static int force_nl(mfs_solver2d *s, const double *u, double *f)
{
  mfs_solver2d_work *w = s->w;
  full(s, u, w->uf);
  memset(w->ff, 0, 2 * s->model->p->n * sizeof *w->ff);
  int st = s->model->spec.disc.frame == MFS_FRAME_EULERIAN ? force_eulerian(s, w->uf, w->ff)
                                                           : force_lagrangian(s, w->uf, w->ff);
  if (st != MFS_OK)
    return st;
  for (size_t i = 0; i < s->n; i++)
    f[i] = w->ff[s->model->dof[i]];
  return MFS_OK;
}

/* Strain energy of the Lagrangian plate, sum_Q w_Q (sigma0:E + lambda/2 tr(E)^2 + mu E:E),
 * minus the work of the load f0 (dpsi/dE = S). */
static double energy_lagrangian(mfs_solver2d *s, const double *u)
{
  mfs_solver2d_work *w = s->w;
  const mfs_quad *q = s->model->q;
  full(s, u, w->uf);
  double e = 0.0;
  for (size_t Q = 0; Q < q->n; Q++) {
    double H[4] = {0.0, 0.0, 0.0, 0.0};
    for (size_t ee = w->tptr[Q]; ee < w->tptr[Q + 1]; ee++) {
      const double *t = w->tab + ee * (size_t)w->nc, *uk = w->uf + 2 * (size_t)w->tidx[ee];
      H[0] += uk[0] * t[1];
      H[1] += uk[0] * t[2];
      H[2] += uk[1] * t[1];
      H[3] += uk[1] * t[2];
    }
    double S[4], E[4];
    svk(w, H, S, E);
    double tr = E[0] + E[3], EE = E[0] * E[0] + 2.0 * E[1] * E[1] + E[3] * E[3];
    double s0E = w->sig0[0] * E[0] + 2.0 * w->sig0[1] * E[1] + w->sig0[3] * E[3];
    e += q->w[Q] * (s0E + 0.5 * w->lam * tr * tr + w->mu * EE);
  }
  for (size_t i = 0; i < s->n; i++)
    e -= w->f0[i] * u[i];
  return e;
}

/* lambda_max of B = M^-1/2 K M^-1/2 (the eigenvalues of M^-1 K) from below:
 * the Rayleigh quotient x^T B x / x^T x of the power iteration. */
static double power_lambda(mfs_solver2d *s)
{
  size_t n = s->n;
  double *x = s->w->u0, *y = s->w->v0, *Bx = s->w->tu;
  unsigned long r = 12345;
  for (size_t i = 0; i < n; i++) {
    r = r * 6364136223846793005UL + 1442695040888963407UL;
    x[i] = (double)(r >> 11) / 9007199254740992.0 - 0.5;
  }
  double rho = 0.0;
  for (int it = 0; it < POWER_ITERATIONS; it++) {
    double xx = 0.0;
    for (size_t i = 0; i < n; i++) {
      xx += x[i] * x[i];
      y[i] = x[i] / sqrt(s->m[i]);
    }
    if (!(xx > 0.0))
      break;
    mfs_csr_matvec(s->model->K, y, Bx);
    double xBx = 0.0, bb = 0.0;
    for (size_t i = 0; i < n; i++) {
      Bx[i] /= sqrt(s->m[i]);
      xBx += x[i] * Bx[i];
      bb += Bx[i] * Bx[i];
    }
    rho = xBx / xx;
    double nb = sqrt(bb); /* normalized: no overflow */
    if (!(nb > 0.0))
      break;
    for (size_t i = 0; i < n; i++)
      x[i] = Bx[i] / nb;
  }
  return rho;
}

void mfs_solver2d_free(mfs_solver2d *s)
{
  if (!s)
    return;
  mfs_model_free(s->model);
  mfs_free(s->u); /* the block of every vector */
  if (s->w) {
    mfs_solver2d_work *w = s->w;
    mfs_free(w->comp);
    mfs_free(w->uf); /* the block of the stressed plate's vectors */
    mfs_eval_free(&w->ev);
    mfs_nlist_free(w->cand);
    mfs_free(w->out);
    mfs_free(w->loc);
  }
  mfs_free(s->w);
  mfs_free(s);
}

/* The tangent of P = F S at F = I under sigma0 (plane strain): dP_ij/dH_kl =
 * delta_ik sigma0_lj + lambda delta_ij delta_kl + mu (delta_ik delta_jl +
 * delta_il delta_jk); the block (i, k) of column k of a row of gradient
 * products A^{jl} (mfs_forms.outer) is sum_jl tangent_ijkl A^{jl}. */
static void stressed_block(const void *ctx, const mfs_row *row, size_t k, double *blk)
{
  const mfs_solver2d_work *w = ctx;
  const double *A = row->K + 4 * k;
  for (int i = 0; i < 2; i++)
    for (int kk = 0; kk < 2; kk++) {
      double v = 0.0;
      for (int j = 0; j < 2; j++)
        for (int l = 0; l < 2; l++) {
          double t = (i == kk ? w->sig0[l * 2 + j] : 0.0) + (i == j && kk == l ? w->lam : 0.0) +
                     w->mu * ((i == kk && j == l ? 1.0 : 0.0) + (i == l && j == kk ? 1.0 : 0.0));
          v += t * A[j * 2 + l];
        }
      blk[i * 2 + kk] = v;
    }
}

/* Which operator the step's bound sees: 0 the assembled K (the linear plate,
 * and the Eulerian kernel without stress: sigma = 0 at u = 0, so the motion
 * of the shape functions does not enter the linearization); 1 the stressed
 * Lagrangian tangent (streamed); -1 none (the stressed Eulerian kernel:
 * kernel-motion terms not bounded here). */
static int step_operator(const mfs_solver2d *s)
{
  if (!s->stressed || s->w->smax == 0.0)
    return 0;
  return s->model->spec.disc.frame == MFS_FRAME_LAGRANGIAN ? 1 : -1;
}

/* mfs_dt_ops's callbacks */
static mfs_status plate_certify_op(void *ctx, mfs_dt_info *in, const char **why)
{
  mfs_solver2d *s = ctx;
  if (step_operator(s) != 0) {
    *why = "the stressed plate's tangent stiffness is not assembled: no certificate";
    return MFS_EDOMAIN;
  }
  mfs_pencil P = {.K = s->model->K, .M = NULL, .m = s->model->m};
  return mfs_dt_certify(&P, in);
}

static mfs_status plate_gershgorin_op(void *ctx, double *lambda)
{
  mfs_solver2d *s = ctx;
  const mfs_model *md = s->model;
  mfs_gershgorin_result g;
  mfs_status st;
  if (step_operator(s) == 0) {
    st = mfs_gershgorin_csr(md->K, md->m, md->dof, &g);
  } else {
    mfs_forms f = mfs_forms_stiffness(&md->mat);
    f.outer = 1;
    mfs_gershgorin_op gop = {.forms = &f, .ndof = 2, .block = stressed_block, .ctx = s->w,
                             .density = md->mat.density};
    st = mfs_gershgorin_op_plan(md->pl, &gop, md->fixed, &g, NULL);
  }
  if (st == MFS_OK)
    *lambda = g.lambda;
  return st;
}

static mfs_status plate_power_op(void *ctx, double *lambda, int *iterations)
{
  *lambda = power_lambda(ctx);
  *iterations = POWER_ITERATIONS;
  return MFS_OK;
}

mfs_status mfs_solver2d_choose_step(mfs_solver2d *s, mfs_dt_rule rule)
{
  const char *block = NULL; /* neither stiffness rule applies */
  for (size_t i = 0; i < s->n && !block; i++)
    if (!(s->m[i] > 0.0))
      block = "a lumped mass <= 0";
  if (!block && step_operator(s) < 0)
    block = "the stressed Eulerian plate: its linearization has kernel-motion terms that neither "
            "bound covers";
  /* stressed: the power value is an estimate, the initial-stress terms O(sigma0/mu) of K */
  mfs_dt_ops ops = {.ctx = s,
                    .block = block,
                    .certify = plate_certify_op,
                    .gershgorin = plate_gershgorin_op,
                    .power = plate_power_op,
                    .lambda_bound = s->lambda_bound,
                    .negative_phi = s->negative_phi,
                    .power_scale = s->stressed ? 1.0 + s->w->smax / s->model->mat.modulus : 1.0,
                    .power_unproven = s->stressed};
  int changed;
  mfs_status st = mfs_dt_choose(&ops, rule, &s->step, &changed);
  if (st != MFS_OK || !changed)
    return st;
  if (!isnan(s->step.lambda_power))
    s->lambda_power = s->step.lambda_power;
  s->lambda = s->step.lambda;
  s->dt_crit = mfs_dt_crit(s->step.lambda); /* eq. 120 */
  s->dt = 0.9 * s->dt_crit;
  return MFS_OK;
}

mfs_solver2d *mfs_solver2d_alloc(const mfs_model_spec *spec, mfs_status *status, size_t *bad)
{
  return mfs_solver2d_alloc_stressed(spec, NULL, 0.0, status, bad);
}

/* The stressed plate's work: the reference table, the load, the Eulerian buffers. */
static mfs_status stressed_init(mfs_solver2d *s, const double *sigma0, double skin)
{
  mfs_solver2d_work *w = s->w;
  const mfs_model *md = s->model;
  const mfs_particles *p = md->p;
  const mfs_quad *q = md->q;
  w->sig0[0] = sigma0[0];
  w->sig0[1] = w->sig0[2] = sigma0[2];
  w->sig0[3] = sigma0[1];
  w->mu = md->mat.modulus;
  w->lam = mfs_material_lambda(&md->mat);
  /* the model holds no table (mfs_model.h): the force loops read one every step */
  mfs_status tst = mfs_plan_tabulate(md->pl, 1, NULL);
  if (tst != MFS_OK)
    return tst;
  mfs_plan_table(md->pl, &w->tptr, &w->tidx, &w->tab);
  w->nc = mfs_plan_ncomp(md->pl);
  size_t np = p->n, nq = q->n;
  int euler = md->spec.disc.frame == MFS_FRAME_EULERIAN;
  /* one block: uf ff (2 np each), f0 (n), and for the Eulerian kernel x xb (2 np each), xq xqb (2 nq each) */
  size_t len = 4 * np + s->n + (euler ? 4 * np + 4 * nq : 0);
  double *blk = mfs_calloc(len ? len : 1, sizeof *blk);
  if (!blk)
    return MFS_ENOMEM;
  w->uf = blk;
  w->ff = blk + 2 * np;
  w->f0 = blk + 4 * np;
  if (euler) {
    w->x = w->f0 + s->n;
    w->xb = w->x + 2 * np;
    w->xq = w->xb + 2 * np;
    w->xqb = w->xq + 2 * nq;
    w->a = md->a;
    w->skin = (skin > 0.0 ? skin : 0.5) * md->dx;
    mfs_status st = mfs_eval_init(&w->ev, &md->spec.disc, w->a, 1, &p->box, 16);
    if (st != MFS_OK)
      return st;
  }
  s->stressed = 1;
  /* the load that makes u = 0 an equilibrium (zero to rounding on a periodic lattice) */
  double *zero = s->w->tu;
  memset(zero, 0, s->n * sizeof *zero);
  return force_nl(s, zero, w->f0);
}

mfs_solver2d *mfs_solver2d_alloc_stressed(const mfs_model_spec *spec, const double *sigma0,
                                          double skin, mfs_status *status, size_t *bad)
{
  mfs_status st = MFS_EINVAL;
  mfs_solver2d *s = NULL;
  if (!spec || spec->disc.consistent_mass || !(skin >= 0.0))
    goto fail;
  int stressed = spec->disc.frame != MFS_FRAME_LAGRANGIAN ||
                 (sigma0 && (sigma0[0] != 0.0 || sigma0[1] != 0.0 || sigma0[2] != 0.0));
  if (stressed) {
    st = MFS_ENOTSUP;
    if (spec->disc.material.physics != MFS_PHYS_PLANE_STRAIN || spec->disc.dim != 2 ||
        spec->disc.frame == MFS_FRAME_EULERIAN_CONSISTENT)
      goto fail;
    st = MFS_EINVAL;
    for (int k = 0; k < 3; k++)
      if (!isfinite(sigma0 ? sigma0[k] : 0.0))
        goto fail;
  }
  st = MFS_ENOMEM;
  if (!(s = mfs_calloc(1, sizeof *s)) || !(s->w = mfs_calloc(1, sizeof *s->w)))
    goto fail;
  if (!(s->model = mfs_model_alloc(spec, &st, bad)))
    goto fail;
  st = MFS_ENOMEM;
  const mfs_model *md = s->model;
  size_t n = md->n;
  s->n = n;
  s->m = md->m;
  /* one block: u v a u0 v0 ku(4) kv(4) tu X Y */
  double *blk = mfs_calloc(16 * n, sizeof *blk);
  int *comp = s->w->comp = mfs_malloc(n * sizeof *comp);
  s->u = blk; /* both freed by mfs_solver2d_free */
  if (!blk || !comp)
    goto fail;
  s->v = blk + n;
  s->a = blk + 2 * n;
  s->w->u0 = blk + 3 * n;
  s->w->v0 = blk + 4 * n;
  s->w->ku = blk + 5 * n;
  s->w->kv = blk + 9 * n;
  s->w->tu = blk + 13 * n;
  double *X = blk + 14 * n, *Y = blk + 15 * n;
  s->X = X;
  s->Y = Y;
  s->comp = comp;
  int dim = md->p->dim;
  for (size_t i = 0; i < n; i++) {
    size_t particle = md->dof[i] / (size_t)md->ndof;
    comp[i] = (int)(md->dof[i] % (size_t)md->ndof);
    X[i] = md->p->x[particle * (size_t)dim];
    Y[i] = dim > 1 ? md->p->x[particle * (size_t)dim + 1] : 0.0;
  }
  /* the element bound, for the power rule */
  mfs_bound_result br;
  mfs_status bst = mfs_bound_of_model(md, &br);
  if ((st = mfs_dt_take_bound(bst, &br, &s->lambda_bound, &s->negative_phi)) != MFS_OK)
    goto fail;
  if (stressed) {
    double sx = sigma0 ? sigma0[0] : 0.0, sy = sigma0 ? sigma0[1] : 0.0, t = sigma0 ? sigma0[2] : 0.0;
    s->w->smax = 0.5 * fabs(sx + sy) + hypot(0.5 * (sx - sy), t); /* largest principal |sigma0| */
    if ((st = stressed_init(s, sigma0 ? sigma0 : (const double[3]){0, 0, 0}, skin)) != MFS_OK)
      goto fail;
  }
  s->step = mfs_dt_info_init(MFS_DT_GERSHGORIN);
  s->step.requested = (mfs_dt_rule)-1; /* nothing chosen yet */
  if ((st = mfs_solver2d_choose_step(s, MFS_DT_GERSHGORIN)) != MFS_OK)
    goto fail;
  mfs_solver2d_reset(s);
  *status = MFS_OK;
  return s;
fail:
  mfs_solver2d_free(s);
  *status = st;
  return NULL;
}

void mfs_solver2d_reset(mfs_solver2d *s)
{
  memset(s->u, 0, 3 * s->n * sizeof *s->u); /* u v a: contiguous */
  s->t = 0.0;
  s->steps = 0;
}

mfs_status mfs_solver2d_set_state(mfs_solver2d *s, const double *u, const double *v)
{
  for (size_t i = 0; i < s->n; i++)
    if ((u && !isfinite(u[i])) || (v && !isfinite(v[i])))
      return MFS_EDOMAIN;
  for (size_t i = 0; i < s->n; i++) {
    s->u[i] = u ? u[i] : 0.0;
    s->v[i] = v ? v[i] : 0.0;
  }
  return accel(s, s->u, s->a);
}

mfs_status mfs_solver2d_set_dt(mfs_solver2d *s, double dt, int force)
{
  return mfs_explicit_set_dt(&s->dt, dt, s->dt_crit, force);
}

/* Central difference, eq. 120, in kick-drift-kick form. */
mfs_status mfs_solver2d_step(mfs_solver2d *s, mfs_scheme scheme)
{
  mfs_solver2d_work *w = s->w;
  mfs_explicit_work rk = {w->u0, w->v0, w->ku, w->kv, w->tu};
  mfs_status st = mfs_explicit_step(scheme, s->n, s->u, s->v, s->a, s->t, s->dt, &rk, accel, NULL, s);
  if (st == MFS_OK || st == MFS_EDOMAIN) { /* the step was taken */
    s->t += s->dt;
    s->steps++;
  }
  return st;
}

void mfs_solver2d_energy(mfs_solver2d *s, double *kinetic, double *potential, double *modified)
{
  double k = 0.0, p = 0.0, aa = 0.0;
  if (s->stressed) {
    for (size_t i = 0; i < s->n; i++)
      k += s->m[i] * s->v[i] * s->v[i];
    if (kinetic)
      *kinetic = 0.5 * k;
    if (potential)
      *potential = s->model->spec.disc.frame == MFS_FRAME_LAGRANGIAN ? energy_lagrangian(s, s->u) : NAN;
    if (modified)
      *modified = NAN;
    return;
  }
  for (size_t i = 0; i < s->n; i++) {
    double mi = s->m[i];
    k += mi * s->v[i] * s->v[i];
    p -= mi * s->u[i] * s->a[i]; /* u^T K u = -u^T M a */
    aa += mi * s->a[i] * s->a[i];
  }
  k *= 0.5;
  p *= 0.5;
  if (kinetic)
    *kinetic = k;
  if (potential)
    *potential = p;
  if (modified)
    *modified = k + p - 0.125 * s->dt * s->dt * aa;
}

/* Nearest lattice index of coordinate x for nodes at i h, i = 0 .. n-1,
 * wrapped when periodic (period n h), clamped otherwise. */
static int nearest1(double x, double h, int n, int periodic)
{
  double r = floor(x / h + 0.5);
  if (periodic) {
    r = fmod(r, (double)n);
    if (r < 0)
      r += n;
  }
  if (!(r >= 0)) /* also NaN */
    r = 0;
  if (r > n - 1)
    r = n - 1;
  return (int)r;
}

size_t mfs_solver2d_nearest(const mfs_solver2d *s, double x, double y)
{
  const mfs_model *md = s->model;
  const mfs_source *sp = &md->spec.disc.source;
  size_t i = (size_t)nearest1(x, md->dx, sp->nx, sp->periodic);
  if (md->spec.disc.dim == 1)
    return i;
  size_t j = (size_t)nearest1(y, md->dy, sp->ny, sp->periodic);
  return j * (size_t)sp->nx + i; /* mfs_lattice_alloc's order */
}

long mfs_solver2d_dof(const mfs_solver2d *s, size_t particle, int comp)
{
  const mfs_model *md = s->model;
  if (comp < 0 || comp >= md->ndof || particle >= md->p->n)
    return -1;
  size_t f = particle * (size_t)md->ndof + (size_t)comp, lo = 0, hi = md->n;
  while (lo < hi) { /* model->dof is increasing */
    size_t mid = lo + (hi - lo) / 2;
    if (md->dof[mid] < f)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < md->n && md->dof[lo] == f ? (long)lo : -1;
}
