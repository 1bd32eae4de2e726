/* Reference explicit solver for linear Lagrangian models (see mfs_solver2d.h). */
#include "mfs_solver2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_bound.h"
#include "mfs_status.h"

struct mfs_solver2d_work {
  double *u0, *v0; /* n: RK stage base */
  double *ku, *kv; /* 4n each: RK stage derivatives */
  double *tu;      /* n: stage displacement */
  int *comp;       /* n: s->comp */
};

enum { POWER_ITERATIONS = 300 };

/* a = -M^-1 K u; MFS_EDOMAIN if some a_i is not finite. */
static int accel(const mfs_solver2d *s, const double *u, double *a)
{
  mfs_csr_matvec(s->model->K, u, a);
  int bad = 0;
  for (size_t i = 0; i < s->n; i++) {
    a[i] = -a[i] / s->m[i];
    bad |= !isfinite(a[i]);
  }
  return bad ? MFS_EDOMAIN : MFS_OK;
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
  free(s->u); /* the block of every vector */
  if (s->w)
    free(s->w->comp);
  free(s->w);
  free(s);
}

mfs_solver2d *mfs_solver2d_alloc(const mfs_model_spec *spec, mfs_status *status, size_t *bad)
{
  mfs_status st = MFS_EINVAL;
  mfs_solver2d *s = NULL;
  if (!spec || spec->disc.consistent_mass)
    goto fail;
  st = MFS_ENOMEM;
  if (!(s = calloc(1, sizeof *s)) || !(s->w = calloc(1, sizeof *s->w)))
    goto fail;
  if (!(s->model = mfs_model_alloc(spec, &st, bad)))
    goto fail;
  st = MFS_ENOMEM;
  const mfs_model *md = s->model;
  size_t n = md->n;
  s->n = n;
  s->m = md->m;
  /* one block: u v a u0 v0 ku(4) kv(4) tu X Y */
  double *blk = calloc(16 * n, sizeof *blk);
  int *comp = s->w->comp = malloc(n * sizeof *comp);
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
  /* stable step: the rule of mfs_step_lambda (mfs_bound.h) */
  mfs_bound_result br;
  if (mfs_bound_of_model(md, &br) == MFS_OK) {
    s->lambda_bound = br.lambda;
    s->negative_phi = br.negative_phi;
  }
  s->lambda_power = power_lambda(s);
  double lam = mfs_step_lambda(s->lambda_power, s->lambda_bound, s->negative_phi);
  if (isnan(lam)) {
    st = MFS_EDOMAIN;
    goto fail;
  }
  s->lambda = lam;
  s->dt_crit = mfs_dt_crit(lam); /* eq. 120 */
  s->dt = 0.9 * s->dt_crit;
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
  mfs_status st = mfs_explicit_check_dt(dt, s->dt_crit, force);
  if (st == MFS_OK)
    s->dt = dt;
  return st;
}

/* Central difference, eq. 120, in kick-drift-kick form. */
static int accel_cb(void *ctx, const double *u, double *a)
{
  return accel(ctx, u, a);
}

mfs_status mfs_solver2d_step(mfs_solver2d *s, mfs_scheme scheme)
{
  mfs_solver2d_work *w = s->w;
  mfs_explicit_work rk = {w->u0, w->v0, w->ku, w->kv, w->tu};
  mfs_status st = mfs_explicit_step(scheme, s->n, s->u, s->v, s->a, s->t, s->dt, &rk, accel_cb, NULL, s);
  if (st == MFS_OK || st == MFS_EDOMAIN) { /* the step was taken */
    s->t += s->dt;
    s->steps++;
  }
  return st;
}

void mfs_solver2d_energy(const mfs_solver2d *s, double *kinetic, double *potential,
                         double *modified)
{
  double k = 0.0, p = 0.0, aa = 0.0;
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
