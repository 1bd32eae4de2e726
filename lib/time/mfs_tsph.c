/* Taylor-SPH for the 1D stress-velocity bar (see mfs_tsph.h). */
#include "mfs_tsph.h"
#include "mfs_alloc.h"

#include <complex.h>
#undef I /* particle indices are I, J; the imaginary unit is _Complex_I */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

/* A corrected-SPH operator from a set of source points to a set of target
 * points (compressed rows): interpolation weights wi (eq. 30), gradient
 * weights wg (eq. 35 with eq. 33 in 1D) and gsum = sum_J wg_IJ, so that
 *   f(Y_I) = sum_J wi_IJ f_J,  f'(Y_I) = sum_J wg_IJ f_J - gsum_I f_I. */
typedef struct {
  size_t rows;
  size_t *ptr, *col;
  double *wi, *wg, *gsum;
} op;

struct mfs_tsph_work {
  double *X, *Xv, *vol, *volv;
  double *U;          /* 4n: sigma, v, sy, evp */
  double *U0;         /* 4n: initial state (set_state) for reset */
  double *tmp;        /* 5 * 4n + 6 nv: stages and Taylor half-step values */
  double *q;          /* 2n: sigma + viscous stress where the stress lives, v_x */
  op rv, vr, rr;      /* real->virtual, virtual->real (taylor); real->real (others) */
};

static const char *const scheme_names[] = {"tsph", "euler", "rk2", "rk4"};

const char *mfs_tsph_scheme_name(mfs_tsph_scheme s)
{
  return (unsigned)s < 4 ? scheme_names[s] : "?";
}

mfs_status mfs_tsph_scheme_parse(const char *name, mfs_tsph_scheme *s)
{
  for (int k = 0; k < 4; k++)
    if (name && strcmp(name, scheme_names[k]) == 0) {
      *s = (mfs_tsph_scheme)k;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

static void op_free(op *o)
{
  mfs_free(o->ptr);
  mfs_free(o->col);
  mfs_free(o->wi);
  mfs_free(o->wg);
  mfs_free(o->gsum);
  memset(o, 0, sizeof *o);
}

/* Build the operator from ns sources xs (volumes vs, sorted) to nt targets
 * yt (sorted) with support radius a.  MFS_ESINGULAR when a target sees no
 * source with a nonzero kernel or kernel slope. */
static int op_build(op *o, const mfs_kernel_type *k, double a, const double *yt, size_t nt,
                    const double *xs, const double *vs, size_t ns, int linear)
{
  memset(o, 0, sizeof *o);
  o->rows = nt;
  o->ptr = mfs_malloc((nt + 1) * sizeof *o->ptr);
  o->gsum = mfs_malloc((nt ? nt : 1) * sizeof *o->gsum);
  if (!o->ptr || !o->gsum)
    return MFS_ENOMEM;
  size_t lo = 0, nnz = 0;
  o->ptr[0] = 0;
  for (size_t i = 0; i < nt; i++) {
    while (lo < ns && xs[lo] <= yt[i] - a)
      lo++;
    for (size_t j = lo; j < ns && xs[j] < yt[i] + a; j++)
      nnz++;
    o->ptr[i + 1] = nnz;
  }
  o->col = mfs_malloc((nnz ? nnz : 1) * sizeof *o->col);
  o->wi = mfs_malloc((nnz ? nnz : 1) * sizeof *o->wi);
  o->wg = mfs_malloc((nnz ? nnz : 1) * sizeof *o->wg);
  if (!o->col || !o->wi || !o->wg)
    return MFS_ENOMEM;
  lo = 0;
  for (size_t i = 0; i < nt; i++) {
    while (lo < ns && xs[lo] <= yt[i] - a)
      lo++;
    double sw = 0.0, sg = 0.0;
    size_t p = o->ptr[i];
    for (size_t j = lo; p < o->ptr[i + 1]; j++, p++) {
      double d = xs[j] - yt[i];
      mfs_kernel_value kv = mfs_kernel_radial(k, 1, a, fabs(d));
      o->col[p] = j;
      o->wi[p] = vs[j] * kv.W;
      /* d W(X_J - X_I) / d X_I: odd in d, >= 0 for d > 0 (W decreasing) */
      o->wg[p] = vs[j] * (d > 0 ? -kv.dW : d < 0 ? kv.dW : 0.0);
      sw += o->wi[p];
      sg += d * o->wg[p];
    }
    if (!(sw > 0.0) || !(sg > 0.0))
      return MFS_ESINGULAR;
    double gs = 0.0, xc = 0.0;
    for (p = o->ptr[i]; p < o->ptr[i + 1]; p++) {
      o->wi[p] /= sw; /* eq. 31 */
      o->wg[p] /= sg; /* eqs 33, 36 */
      gs += o->wg[p];
      xc += o->wi[p] * xs[o->col[p]];
    }
    o->gsum[i] = gs;
    /* linear: keep the first-order Taylor term eq. 30 drops,
     * f_I = f_shepard + (Y_I - Xc) f'_I with f'_I = G - gsum f_I, solved for
     * f_I (exact for linear fields); Shepard where a single neighbour
     * cannot fix a slope (1 + shift gsum = 0). */
    double shift = yt[i] - xc, den = 1.0 + shift * gs;
    if (linear && o->ptr[i + 1] - o->ptr[i] >= 2 && fabs(den) > 1e-8)
      for (p = o->ptr[i]; p < o->ptr[i + 1]; p++)
        o->wi[p] = (o->wi[p] + shift * o->wg[p]) / den;
  }
  return MFS_OK;
}

static inline double op_interp(const op *o, size_t i, const double *f)
{
  double r = 0.0;
  for (size_t p = o->ptr[i]; p < o->ptr[i + 1]; p++)
    r += o->wi[p] * f[o->col[p]];
  return r;
}

static inline double op_grad(const op *o, size_t i, const double *f, double fi)
{
  double r = -o->gsum[i] * fi;
  for (size_t p = o->ptr[i]; p < o->ptr[i + 1]; p++)
    r += o->wg[p] * f[o->col[p]];
  return r;
}

void mfs_tsph_free(mfs_tsph *s)
{
  if (!s)
    return;
  if (s->w) {
    mfs_tsph_work *w = s->w;
    mfs_free(w->X);
    mfs_free(w->Xv);
    mfs_free(w->vol);
    mfs_free(w->volv);
    mfs_free(w->U);
    mfs_free(w->U0);
    mfs_free(w->tmp);
    mfs_free(w->q);
    op_free(&w->rv);
    op_free(&w->vr);
    op_free(&w->rr);
    mfs_free(w);
  }
  mfs_free(s);
}

static int spec_ok(const mfs_tsph_spec *sp)
{
  if (sp->disc.source.nx < 3 || sp->disc.source.nx > 100000000 || !(sp->disc.source.lx > 0) || !(sp->disc.material.density > 0) ||
      !(sp->disc.material.modulus > 0) || !(sp->yield_stress > 0) || !(sp->fluidity >= 0) ||
      !isfinite(sp->fluidity) || !(sp->exponent >= 0) || !isfinite(sp->hardening) ||
      !(sp->disc.dilation > 0) || !isfinite(sp->disc.dilation) || (unsigned)sp->scheme > MFS_TSPH_RK4 ||
      !(sp->viscosity >= 0) || !isfinite(sp->viscosity))
    return 0;
  for (int k = 0; k < 2; k++)
    if ((unsigned)sp->bc[k] > MFS_BC_VELOCITY || !isfinite(sp->bc_velocity[k]))
      return 0;
  return 1;
}

mfs_tsph *mfs_tsph_alloc(const mfs_tsph_spec *spec, mfs_status *status)
{
  mfs_status st = MFS_ENOMEM;
  mfs_tsph *s = NULL;
  if (!spec || !spec_ok(spec)) {
    st = MFS_EINVAL;
    goto fail;
  }
  s = mfs_calloc(1, sizeof *s);
  if (!s || !(s->w = mfs_calloc(1, sizeof *s->w)))
    goto fail;
  mfs_tsph_work *w = s->w;
  s->spec = *spec;
  if (!s->spec.disc.kernel)
    s->spec.disc.kernel = &mfs_kernel_cubic; /* eq. 24 */
  size_t n = (size_t)spec->disc.source.nx;
  int taylor = spec->scheme == MFS_TSPH_TAYLOR;
  size_t nv = taylor ? n - 1 : 0;
  s->n = n;
  s->nv = nv;
  s->dx = spec->disc.source.lx / (double)(n - 1);
  w->X = mfs_malloc(n * sizeof *w->X);
  w->vol = mfs_malloc(n * sizeof *w->vol);
  w->Xv = mfs_malloc((n - 1) * sizeof *w->Xv);
  w->volv = mfs_malloc((n - 1) * sizeof *w->volv);
  w->U = mfs_calloc(4 * n, sizeof *w->U);
  w->U0 = mfs_calloc(4 * n, sizeof *w->U0);
  w->tmp = mfs_calloc(20 * n + 6 * (n - 1), sizeof *w->tmp);
  w->q = mfs_calloc(2 * n, sizeof *w->q);
  if (!w->X || !w->vol || !w->Xv || !w->volv || !w->U || !w->U0 || !w->tmp || !w->q)
    goto fail;
  for (size_t I = 0; I < n; I++) {
    w->X[I] = spec->disc.source.lx * (double)I / (double)(n - 1);
    w->vol[I] = (I == 0 || I == n - 1) ? 0.5 * s->dx : s->dx; /* Voronoi on [0, L] */
  }
  for (size_t J = 0; J + 1 < n; J++) {
    w->Xv[J] = 0.5 * (w->X[J] + w->X[J + 1]);
    w->volv[J] = s->dx; /* Voronoi of the midpoints on [0, L] */
  }
  if (taylor) {
    double a = spec->disc.dilation * 0.5 * s->dx;
    int lin = spec->linear_interpolation;
    if ((st = op_build(&w->rv, s->spec.disc.kernel, a, w->Xv, nv, w->X, w->vol, n, lin)) != MFS_OK ||
        (st = op_build(&w->vr, s->spec.disc.kernel, a, w->X, n, w->Xv, w->volv, nv, lin)) != MFS_OK)
      goto fail;
  } else {
    double a = spec->disc.dilation * s->dx;
    if ((st = op_build(&w->rr, s->spec.disc.kernel, a, w->X, n, w->X, w->vol, n,
                       spec->linear_interpolation)) != MFS_OK)
      goto fail;
  }
  s->X = w->X;
  s->Xv = w->Xv;
  s->vol = w->vol;
  s->sigma = w->U;
  s->v = w->U + n;
  s->sy = w->U + 2 * n;
  s->evp = w->U + 3 * n;
  for (size_t I = 0; I < n; I++)
    w->U0[2 * n + I] = spec->yield_stress;
  s->dt_cfl = s->dx / sqrt(spec->disc.material.modulus / spec->disc.material.density);
  s->dt = s->dt_cfl;
  mfs_tsph_reset(s);
  *status = MFS_OK;
  return s;
fail:
  mfs_tsph_free(s);
  *status = st;
  return NULL;
}

/* Essential end values of the stress-velocity form at time t on state U. */
static void apply_bc(const mfs_tsph *s, double *U, double t)
{
  size_t n = s->n;
  for (int k = 0; k < 2; k++) {
    size_t I = k ? n - 1 : 0;
    switch (s->spec.bc[k]) {
    case MFS_BC_FREE: U[I] = 0.0; break;
    case MFS_BC_FIXED: U[n + I] = 0.0; break;
    case MFS_BC_VELOCITY:
      U[n + I] = t <= s->spec.bc_until[k] ? s->spec.bc_velocity[k] : 0.0;
      break;
    }
  }
}

/* Prescribed value of the velocity (which = 1) or stress (which = 0) at the
 * end particle I at time t, in *val; 0 if that value is not prescribed. */
static int prescribed(const mfs_tsph *s, size_t I, int which, double t, double *val)
{
  int k;
  if (I == 0)
    k = 0;
  else if (I == s->n - 1)
    k = 1;
  else
    return 0;
  mfs_bc b = s->spec.bc[k];
  if (which == 0 && b == MFS_BC_FREE) {
    *val = 0.0;
    return 1;
  }
  if (which == 1 && b == MFS_BC_FIXED) {
    *val = 0.0;
    return 1;
  }
  if (which == 1 && b == MFS_BC_VELOCITY) {
    *val = t <= s->spec.bc_until[k] ? s->spec.bc_velocity[k] : 0.0;
    return 1;
  }
  return 0;
}

mfs_status mfs_tsph_reset(mfs_tsph *s)
{
  if (!s)
    return MFS_EINVAL;
  memcpy(s->w->U, s->w->U0, 4 * s->n * sizeof *s->w->U);
  s->t = 0.0;
  s->steps = 0;
  apply_bc(s, s->w->U, 0.0);
  return MFS_OK;
}

mfs_status mfs_tsph_set_state(mfs_tsph *s, const double *sigma, const double *v)
{
  if (!s)
    return MFS_EINVAL;
  size_t n = s->n;
  for (size_t I = 0; I < n; I++) {
    double a = sigma ? sigma[I] : 0.0, b = v ? v[I] : 0.0;
    if (!isfinite(a) || !isfinite(b))
      return MFS_EDOMAIN;
    s->w->U0[I] = a;
    s->w->U0[n + I] = b;
    s->w->U0[2 * n + I] = s->spec.yield_stress;
    s->w->U0[3 * n + I] = 0.0;
  }
  return mfs_tsph_reset(s);
}

mfs_status mfs_tsph_set_dt(mfs_tsph *s, double dt)
{
  if (!s || !(dt > 0.0) || !isfinite(dt))
    return MFS_EINVAL;
  s->dt = dt;
  return MFS_OK;
}

/* Perzyna source at one point (eqs 3-6 in 1D): the stress source, the yield
 * stress source and the equivalent viscoplastic strain rate. */
static int source(const mfs_tsph_spec *sp, double sigma, double sy, double *ss, double *ssy,
                  double *sev)
{
  *ss = *ssy = *sev = 0.0;
  if (sp->fluidity == 0.0 || isinf(sp->yield_stress))
    return MFS_OK;
  if (!(sy > 0.0))
    return MFS_EDOMAIN;
  double f = fabs(sigma);
  if (!(f > sy))
    return MFS_OK;
  double phi = sp->exponent == 0.0 ? 1.0 : pow((f - sy) / sy, sp->exponent);
  double rate = sp->fluidity * phi;
  *sev = rate;
  *ss = -sp->disc.material.modulus * (sigma > 0 ? rate : -rate);
  *ssy = sp->hardening * rate;
  return MFS_OK;
}

static int taylor_step(mfs_tsph *s)
{
  mfs_tsph_work *w = s->w;
  const mfs_tsph_spec *sp = &s->spec;
  size_t n = s->n, nv = s->nv;
  double *sig = w->U, *v = w->U + n, *sy = w->U + 2 * n, *ev = w->U + 3 * n;
  double E = sp->disc.material.modulus, rho = sp->disc.material.density, dt = s->dt;
  double eta = sp->viscosity * rho * sqrt(E / rho) * s->dx;
  /* real-particle sources at t^n */
  double *Ss = w->tmp, *Ssy = Ss + n, *Sev = Ssy + n;
  for (size_t I = 0; I < n; I++)
    if (source(sp, sig[I], sy[I], &Ss[I], &Ssy[I], &Sev[I]) != MFS_OK)
      return MFS_EDOMAIN;
  /* step 1, eq. (38): virtual particles at t^{n+1/2} */
  double *hs = Sev + n, *hv = hs + nv, *hy = hv + nv;
  double *Vs = hy + nv, *Vsy = Vs + nv, *Vev = Vsy + nv;
  for (size_t J = 0; J < nv; J++) {
    double s0 = op_interp(&w->rv, J, sig), v0 = op_interp(&w->rv, J, v);
    double y0 = op_interp(&w->rv, J, sy);
    double sx = op_grad(&w->rv, J, sig, s0), vx = op_grad(&w->rv, J, v, v0);
    hs[J] = s0 + 0.5 * dt * (E * vx + op_interp(&w->rv, J, Ss));
    hv[J] = v0 + 0.5 * dt * sx / rho;
    hy[J] = y0 + 0.5 * dt * op_interp(&w->rv, J, Ssy);
    w->q[J] = hs[J] + eta * vx; /* the stress of the momentum equation */
  }
  for (size_t J = 0; J < nv; J++)
    if (source(sp, hs[J], hy[J], &Vs[J], &Vsy[J], &Vev[J]) != MFS_OK)
      return MFS_EDOMAIN;
  /* step 2, eq. (40): real particles at t^{n+1} */
  double th = s->t + 0.5 * dt;
  for (size_t I = 0; I < n; I++) {
    double fs, fv;
    if (!prescribed(s, I, 0, th, &fs))
      fs = op_interp(&w->vr, I, w->q);
    if (!prescribed(s, I, 1, th, &fv))
      fv = op_interp(&w->vr, I, hv);
    double sx = op_grad(&w->vr, I, w->q, fs), vx = op_grad(&w->vr, I, hv, fv);
    sig[I] += dt * (E * vx + op_interp(&w->vr, I, Vs));
    v[I] += dt * sx / rho;
    sy[I] += dt * op_interp(&w->vr, I, Vsy);
    ev[I] += dt * op_interp(&w->vr, I, Vev);
  }
  return MFS_OK;
}

/* Semi-discrete right-hand side on the real particles: Y holds the state
 * (boundary values imposed), K receives dY/dt. */
static int rhs(const mfs_tsph *s, const double *Y, double *K)
{
  const mfs_tsph_spec *sp = &s->spec;
  size_t n = s->n;
  const op *o = &s->w->rr;
  double eta = sp->viscosity * sp->disc.material.density * sqrt(sp->disc.material.modulus / sp->disc.material.density) * s->dx;
  double *q = s->w->q, *vxs = q + n, dummy;
  for (size_t I = 0; I < n; I++) {
    vxs[I] = op_grad(o, I, Y + n, Y[n + I]);
    q[I] = prescribed(s, I, 0, 0.0, &dummy) ? Y[I] : Y[I] + eta * vxs[I];
  }
  for (size_t I = 0; I < n; I++) {
    double ss, ssy, sev;
    if (source(sp, Y[I], Y[2 * n + I], &ss, &ssy, &sev) != MFS_OK)
      return MFS_EDOMAIN;
    double sx = op_grad(o, I, q, q[I]), vx = vxs[I];
    K[I] = prescribed(s, I, 0, 0.0, &dummy) ? 0.0 : sp->disc.material.modulus * vx + ss;
    K[n + I] = prescribed(s, I, 1, 0.0, &dummy) ? 0.0 : sx / sp->disc.material.density;
    K[2 * n + I] = ssy;
    K[3 * n + I] = sev;
  }
  return MFS_OK;
}

/* One Runge-Kutta stage: Y = U + h k with the boundary values at time t,
 * and its right-hand side kout. */
static int stage(mfs_tsph *s, const double *U, const double *k, double h, double t, double *Y,
                 double *kout)
{
  for (size_t i = 0; i < 4 * s->n; i++)
    Y[i] = U[i] + h * k[i];
  apply_bc(s, Y, t);
  return rhs(s, Y, kout);
}

static int rk_step(mfs_tsph *s)
{
  size_t m = 4 * s->n;
  double *U = s->w->U, *Y = s->w->tmp, *k1 = Y + m, *k2 = k1 + m, *k3 = k2 + m, *k4 = k3 + m;
  double t = s->t, dt = s->dt;
  mfs_status st;
  if ((st = rhs(s, U, k1)) != MFS_OK)
    return st;
  switch (s->spec.scheme) {
  case MFS_TSPH_EULER:
    for (size_t i = 0; i < m; i++)
      U[i] += dt * k1[i];
    break;
  case MFS_TSPH_RK2:
    if ((st = stage(s, U, k1, 0.5 * dt, t + 0.5 * dt, Y, k2)) != MFS_OK)
      return st;
    for (size_t i = 0; i < m; i++)
      U[i] += dt * k2[i];
    break;
  default: /* RK4 */
    if ((st = stage(s, U, k1, 0.5 * dt, t + 0.5 * dt, Y, k2)) != MFS_OK ||
        (st = stage(s, U, k2, 0.5 * dt, t + 0.5 * dt, Y, k3)) != MFS_OK ||
        (st = stage(s, U, k3, dt, t + dt, Y, k4)) != MFS_OK)
      return st;
    for (size_t i = 0; i < m; i++)
      U[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    break;
  }
  return MFS_OK;
}

mfs_status mfs_tsph_step(mfs_tsph *s)
{
  if (!s)
    return MFS_EINVAL;
  int st = s->spec.scheme == MFS_TSPH_TAYLOR ? taylor_step(s) : rk_step(s);
  if (st != MFS_OK)
    return st;
  s->steps++;
  s->t = (double)s->steps * s->dt;
  apply_bc(s, s->w->U, s->t);
  for (size_t i = 0; i < 2 * s->n; i++)
    if (!isfinite(s->w->U[i]))
      return MFS_EDOMAIN;
  return MFS_OK;
}

double mfs_tsph_velocity_at(const mfs_tsph *s, double X)
{
  return mfs_lerp_uniform(s->v, s->n, s->dx, X);
}

void mfs_tsph_energy(const mfs_tsph *s, double *kinetic, double *potential)
{
  double k = 0.0, p = 0.0;
  for (size_t I = 0; I < s->n; I++) {
    k += 0.5 * s->spec.disc.material.density * s->vol[I] * s->v[I] * s->v[I];
    p += 0.5 * s->vol[I] * s->sigma[I] * s->sigma[I] / s->spec.disc.material.modulus;
  }
  *kinetic = k;
  *potential = p;
}

/* Symbols of the corrected-SPH interpolation (eq. 30) and gradient (eq. 35)
 * on the uniform lattice at wavenumber theta (per dx): sources at offsets
 * (j + off) dx, |offset| < a.  The weights sum_J g_IJ vanish on the
 * symmetric lattice, so the value f_I used in eq. 35 drops out. */
static void symbols(const mfs_kernel_type *k, double a, double dx, double off, double th,
                    double complex *P, double complex *D)
{
  double sw = 0.0, sg = 0.0;
  double complex pi = 0.0, gi = 0.0;
  int jmax = (int)ceil(a / dx) + 1;
  for (int j = -jmax; j <= jmax; j++) {
    double d = ((double)j + off) * dx;
    if (!(fabs(d) < a))
      continue;
    mfs_kernel_value kv = mfs_kernel_radial(k, 1, a, fabs(d));
    double wg = d > 0 ? -kv.dW : d < 0 ? kv.dW : 0.0;
    double complex e = cexp(_Complex_I * th * d / dx);
    sw += kv.W;
    sg += d * wg;
    pi += kv.W * e;
    gi += wg * e;
  }
  *P = pi / sw;
  *D = gi / sg;
}

/* Eigenvalues of the complex 2 x 2 matrix [a b; c d], as m +- sqrt(delta^2
 * + bc) with m and delta the half sum and half difference of the diagonal:
 * no cancellation between the squared trace and the determinant. */
static void eig2(double complex a, double complex b, double complex c, double complex d,
                 double complex *l1, double complex *l2)
{
  double complex m = 0.5 * (a + d), h = 0.5 * (a - d), r = csqrt(h * h + b * c);
  *l1 = m + r;
  *l2 = m - r;
}

/* Stability polynomial of a Runge-Kutta scheme of degree deg at z. */
static double complex rk_poly(int deg, double complex z)
{
  double complex r = 1.0, t = 1.0;
  for (int k = 1; k <= deg; k++) {
    t *= z / (double)k;
    r += t;
  }
  return r;
}

/* max over theta of the spectral radius of G(theta) at step dt. */
static double growth(const mfs_tsph *s, double dt)
{
  const mfs_tsph_spec *sp = &s->spec;
  double E = sp->disc.material.modulus, rho = sp->disc.material.density, dx = s->dx;
  double eta = sp->viscosity * rho * sqrt(E / rho) * dx;
  int taylor = sp->scheme == MFS_TSPH_TAYLOR;
  int deg = sp->scheme == MFS_TSPH_EULER ? 1 : sp->scheme == MFS_TSPH_RK2 ? 2 : 4;
  double a = taylor ? sp->disc.dilation * 0.5 * dx : sp->disc.dilation * dx;
  double gmax = 0.0;
  const int nth = 512;
  for (int i = 0; i <= nth; i++) {
    double th = M_PI * (double)i / nth;
    double complex P, D, l1, l2, g1, g2;
    if (taylor) {
      /* real -> virtual and virtual -> real: the same half-integer offsets;
       * G = I + Mt, Mt = dt D (P A + dt/2 D A^2 + [0 0; 0 eta D/rho]) */
      symbols(sp->disc.kernel, a, dx, 0.5, th, &P, &D);
      double complex h = 0.5 * dt * D * E / rho;
      eig2(dt * D * h, dt * D * P * E, dt * D * P / rho, dt * D * (h + eta * D / rho), &l1, &l2);
      g1 = 1.0 + l1;
      g2 = 1.0 + l2;
    } else {
      /* G = R(dt L), L = [0 E D; D/rho eta D^2/rho] */
      symbols(sp->disc.kernel, a, dx, 0.0, th, &P, &D);
      eig2(0.0, dt * E * D, dt * D / rho, dt * eta * D * D / rho, &l1, &l2);
      g1 = rk_poly(deg, l1);
      g2 = rk_poly(deg, l2);
    }
    gmax = fmax(gmax, fmax(cabs(g1), cabs(g2)));
  }
  return gmax;
}

double mfs_tsph_dt_stable(const mfs_tsph *s)
{
  const double tol = 1e-12, h = s->dt_cfl / 100.0;
  double lo = 0.0, hi = 0.0;
  for (int k = 1; k <= 1600; k++) {
    if (growth(s, h * k) > 1.0 + tol) {
      hi = h * k;
      break;
    }
    lo = h * k;
  }
  if (hi == 0.0)
    return lo;
  if (lo == 0.0)
    return 0.0;
  while (hi - lo > 1e-10 * hi) {
    double mid = 0.5 * (lo + hi);
    if (growth(s, mid) > 1.0 + tol)
      hi = mid;
    else
      lo = mid;
  }
  return lo;
}
