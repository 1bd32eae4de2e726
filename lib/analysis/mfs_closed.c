/* Closed-form 1D dispersion relations (paper 003 sections 4.1-4.3).
 *
 * Derivation of EULER_STRESS (eqs 83-92), lengths in units of the current
 * spacing dx, particle I = 0, masters x_J = J, stress points x_J^S = J + 1/2,
 * quadrature volumes dx/2 each (eq. 84), lumped mass rho dx, sigma the
 * initial Cauchy stress, Ct = C + sigma (eq. 75), G_J = sum_K phi'_K(x_J) u~_K
 * the perturbed velocity-gradient-like quantity (so F~_J / F_J = G_J, eq. 88).
 * Eq. 86, divided by dx/2:
 *   2 rho u~''_0 = - sum_{Q in M,S} [ (Ct + sigma) phi'(x_Q) G_Q
 *                                     + sigma phi''(x_Q) (u~_Q - u~_0) ]
 * (the sigma G term is the volume change V~/V = F~/F, eq. 84).  With
 * u~_K = g e^{i kappa x_K} and phi' odd:
 *   G_Q = -i S g e^{i kappa x_Q}   (S = S_M at masters, S_S at stress points)
 *   sum_Q phi'(x_Q) G_Q = S^2 g, each set.
 * Stress-point displacement, eq. 91 with u_K = (F-1)/F x_K (eq. 92, I = 0);
 * with y = x_J^S - x_K:
 *   u~_J^S = F sum_K [phi(y) - phi'(y) (F-1)/F (x_J^S - y)] g e^{i kappa x_K}
 *          = g e^{i kappa x_J^S} [F H_S + (F-1) Y_S + i (F-1) x_J^S S_S]
 * The last term grows with x_J^S: the perturbation is not of Bloch form
 * because of the "node I fixed" convention of eq. 92.  Then, phi'' even and
 * x phi''(x) odd,
 *   sum_J phi''(x_J^S) (u~_J^S - u~_0)
 *     = g [ (F H_S + (F-1) Y_S) Q_S + i (F-1) S_S (i Z_S) - R_S ]
 *     = g [ F H_S Q_S + (F-1) Y_S Q_S - (F-1) S_S Z_S - R_S ].
 * The master part gives sum_J phi''(j)(u~_J - u~_0) = -P_M g.  Collecting,
 * with omega2 = rho omega^2 dx^2 / C:
 *   omega2 = (1 + sbar)/2 (S_M^2 + S_S^2)
 *          - sbar/2 { P_M - S_M^2 + R_S - S_S^2 - F Q_S H_S
 *                     - (F-1) Q_S Y_S + (F-1) Z_S S_S }.
 * Eq. 93 as printed has + (F-1) Q_S Y_S: the sign of that term differs.  The
 * test suite checks this formula against a direct finite-difference
 * linearization of the discrete model (83)-(92), which confirms the minus.
 * (Flipping the sign convention of phi' flips both S_S and Y_S, which would
 * make the Y term agree and the Z term disagree instead: no convention makes
 * the printed signs consistent.)
 *
 * Derivation of LS_NODAL (eqs 104-108): nodal quadrature V_J = dx,
 *   M_0K = rho dx sum_J [phi(J) - beta phi''(J)] phi(J - K)
 *   K_0K = E dx sum_J [phi'(J) phi'(J - K) + beta phi''(J) phi''(J - K)]
 * (phi_K(x_J) = phi(x_J - x_K), phi'_K(x_J) = phi'(x_J - x_K)).  The rows are
 * even in K, so the symbols are real: Mhat = sum_K M_0K cos(kappa K) and
 * Khat likewise, and they factor as H_M^2 - beta Q_M H_M and
 * S_M^2 + beta Q_M^2: eq. 108 follows from (106)-(107).  The plan builds the
 * rows and this file evaluates their symbols directly, a path independent of
 * the factored form. */
#include "mfs_closed.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_eval.h"
#include "mfs_status.h"

struct mfs_cf_plan {
  double D, sbar, F, beta;
  int jm;          /* particles j = -jm..jm, midpoints j + 1/2, j = -jm-1..jm */
  size_t nn, nm;   /* number of particles and midpoints tabulated */
  double *xn, *xm; /* positions */
  double *tn, *tm; /* 3 per point: phi, phi', phi'' */
  int nrow;        /* least-squares rows: K = -(nrow-1)/2 .. (nrow-1)/2 */
  double *Mrow, *Krow;
};

static const char *const scheme_names[MFS_CF_NSCHEMES] = {
  "euler-nodal",  "lagr-nodal", "euler-stress",     "euler-stress-printed",
  "lagr-stress", "ls-nodal",   "ls-nodal-printed", "fem-linear",
};

const char *mfs_cf_scheme_name(mfs_cf_scheme s)
{
  return ((int)s >= 0 && s < MFS_CF_NSCHEMES) ? scheme_names[s] : NULL;
}

mfs_status mfs_cf_scheme_find(const char *name, mfs_cf_scheme *s)
{
  if (!name || !s)
    return MFS_EINVAL;
  for (int i = 0; i < MFS_CF_NSCHEMES; i++)
    if (strcmp(name, scheme_names[i]) == 0) {
      *s = (mfs_cf_scheme)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

void mfs_cf_plan_free(mfs_cf_plan *p)
{
  if (!p)
    return;
  mfs_free(p->xn);
  mfs_free(p->xm);
  mfs_free(p->tn);
  mfs_free(p->tm);
  mfs_free(p->Mrow);
  mfs_free(p->Krow);
  mfs_free(p);
}

/* phi, phi', phi'' of particle 0 at the point x: the shape functions of all
 * lattice particles j with |j - x| < D evaluated at x (the point
 * evaluator), entry of j = 0.  xp, cand, idx, out: scratch for nmax
 * neighbours. */
static int eval_phi(mfs_eval *ev, double x, int nmax, double *xp, const double *ones, int *cand,
                    int *idx, double *out, double *res)
{
  res[0] = res[1] = res[2] = 0.0;
  double D = ev->ctx.a;
  if (!(fabs(x) < D))
    return MFS_OK; /* particle 0 is not a neighbour of x */
  int lo = (int)floor(x - D), hi = (int)ceil(x + D), nc = 0, self = -1;
  for (int j = lo; j <= hi && nc < nmax; j++) {
    xp[nc] = (double)j;
    if ((double)j == x)
      self = nc;
    cand[nc] = nc;
    nc++;
  }
  int nn; /* volumes V_J = dx */
  mfs_status st = mfs_eval_point(ev, &x, xp, ones, cand, (size_t)nc, self, idx, out, &nn, NULL);
  if (st != MFS_OK)
    return st;
  int zero = -1;
  for (int k = 0; k < nn; k++)
    if (xp[idx[k]] == 0.0)
      zero = k;
  if (zero < 0)
    return MFS_OK;
  for (int k = 0; k < 3; k++)
    res[k] = out[3 * zero + k];
  return (isfinite(res[0]) && isfinite(res[1]) && isfinite(res[2])) ? MFS_OK : MFS_EDOMAIN;
}

/* phi at the integer offset j (zero outside the table), component k. */
static double node_phi(const mfs_cf_plan *p, int j, int k)
{
  if (j < -p->jm || j > p->jm)
    return 0.0;
  return p->tn[3 * (size_t)(j + p->jm) + (size_t)k];
}

static void build_ls_rows(mfs_cf_plan *p)
{
  int h = (p->nrow - 1) / 2;
  for (int K = -h; K <= h; K++) {
    double m = 0.0, k = 0.0;
    for (int J = -p->jm; J <= p->jm; J++) {
      double f = node_phi(p, J, 0), df = node_phi(p, J, 1), d2f = node_phi(p, J, 2);
      m += (f - p->beta * d2f) * node_phi(p, J - K, 0);
      k += df * node_phi(p, J - K, 1) + p->beta * d2f * node_phi(p, J - K, 2);
    }
    p->Mrow[K + h] = m;
    p->Krow[K + h] = k;
  }
}

mfs_cf_plan *mfs_cf_plan_alloc(const mfs_cf_spec *spec, mfs_status *status)
{
  mfs_status st = MFS_OK;
  mfs_cf_plan *p = NULL;
  double *xp = NULL, *ones = NULL, *out = NULL;
  int *cand = NULL, *idx = NULL;
  mfs_eval ev = {0};
  const mfs_disc *d = spec ? &spec->disc : NULL;
  if (!spec || !d->kernel || !d->shape || !(d->dilation > 0.0) || !isfinite(d->dilation) ||
      !isfinite(spec->sbar) || !(spec->stretch >= 0.0) || !isfinite(spec->stretch) ||
      !(spec->beta >= 0.0) || !isfinite(spec->beta)) {
    st = MFS_EINVAL;
    goto done;
  }
  /* the paper's two families: linearly complete MLS (eqs 36-39) and the kernel
   * itself, phi = V W (eq. 41); not Shepard, nor a corrected gradient */
  const mfs_shape_type *t = d->shape;
  if (!t->gradient_is_derivative || (!t->linear_complete && t->partition_of_unity)) {
    st = MFS_ENOTSUP;
    goto done;
  }
  if (d->dilation > 1e4) { /* tables of 2D+3 points; keep them sane */
    st = MFS_EINVAL;
    goto done;
  }
  p = mfs_calloc(1, sizeof *p);
  if (!p) {
    st = MFS_ENOMEM;
    goto done;
  }
  p->D = d->dilation;
  p->sbar = spec->sbar;
  p->F = spec->stretch == 0.0 ? 1.0 : spec->stretch;
  p->beta = spec->beta;
  p->jm = (int)ceil(p->D);
  p->nn = 2 * (size_t)p->jm + 1;
  p->nm = 2 * (size_t)p->jm + 2;
  p->nrow = 4 * p->jm + 1;
  int nmax = 2 * p->jm + 3;
  p->xn = mfs_malloc(p->nn * sizeof *p->xn);
  p->xm = mfs_malloc(p->nm * sizeof *p->xm);
  p->tn = mfs_malloc(3 * p->nn * sizeof *p->tn);
  p->tm = mfs_malloc(3 * p->nm * sizeof *p->tm);
  p->Mrow = mfs_malloc((size_t)p->nrow * sizeof *p->Mrow);
  p->Krow = mfs_malloc((size_t)p->nrow * sizeof *p->Krow);
  xp = mfs_malloc((size_t)nmax * sizeof *xp);
  ones = mfs_malloc((size_t)nmax * sizeof *ones);
  out = mfs_malloc(3 * (size_t)nmax * sizeof *out);
  cand = mfs_malloc((size_t)nmax * sizeof *cand);
  idx = mfs_malloc((size_t)nmax * sizeof *idx);
  if (!p->xn || !p->xm || !p->tn || !p->tm || !p->Mrow || !p->Krow || !xp || !ones || !out ||
      !cand || !idx) {
    st = MFS_ENOMEM;
    goto done;
  }
  for (int i = 0; i < nmax; i++)
    ones[i] = 1.0;
  /* the infinite lattice in units of dx: a = D, rcond threshold 1e-12 */
  static const mfs_box line = {.dim = 1};
  mfs_disc dd = *d;
  dd.dim = 1;
  dd.rcond_min = 1e-12;
  if ((st = mfs_eval_init(&ev, &dd, p->D, 2, &line, (size_t)nmax)) != MFS_OK)
    goto done;
  for (size_t i = 0; i < p->nn && st == MFS_OK; i++) {
    p->xn[i] = (double)((int)i - p->jm);
    st = eval_phi(&ev, p->xn[i], nmax, xp, ones, cand, idx, out, p->tn + 3 * i);
  }
  for (size_t i = 0; i < p->nm && st == MFS_OK; i++) {
    p->xm[i] = (double)((int)i - p->jm - 1) + 0.5;
    st = eval_phi(&ev, p->xm[i], nmax, xp, ones, cand, idx, out, p->tm + 3 * i);
  }
  if (st == MFS_OK)
    build_ls_rows(p);
done:
  mfs_eval_free(&ev);
  mfs_free(xp);
  mfs_free(ones);
  mfs_free(out);
  mfs_free(cand);
  mfs_free(idx);
  if (st != MFS_OK) {
    mfs_cf_plan_free(p);
    p = NULL;
  }
  if (status)
    *status = st;
  return p;
}

mfs_status mfs_cf_table(const mfs_cf_plan *p, int midpoints, size_t *n, const double **x,
                 const double **phi)
{
  if (!p || !n || !x || !phi)
    return MFS_EINVAL;
  *n = midpoints ? p->nm : p->nn;
  *x = midpoints ? p->xm : p->xn;
  *phi = midpoints ? p->tm : p->tn;
  return MFS_OK;
}

/* The sums of the header at t = kappa dx (radians). */
static void sums_at(const mfs_cf_plan *p, double t, mfs_cf_sums *s)
{
  memset(s, 0, sizeof *s);
  for (size_t i = 0; i < p->nn; i++) {
    const double *f = p->tn + 3 * i;
    double x = p->xn[i], c = cos(t * x);
    s->SM += f[1] * sin(t * x);
    s->PM += f[2] * (1.0 - c);
    s->QM += f[2] * c;
    s->HM += f[0] * c;
  }
  for (size_t i = 0; i < p->nm; i++) {
    const double *f = p->tm + 3 * i;
    double x = p->xm[i], c = cos(t * x), sn = sin(t * x);
    s->SS += f[1] * sn;
    s->RS += f[2];
    s->QS += f[2] * c;
    s->HS += f[0] * c;
    s->YS += x * f[1] * c;
    s->ZS += x * f[2] * sn;
  }
}

mfs_status mfs_cf_lattice_sums(const mfs_cf_plan *p, double kappa, mfs_cf_sums *out)
{
  if (!p || !out || !isfinite(kappa))
    return MFS_EINVAL;
  sums_at(p, M_PI * kappa, out);
  return MFS_OK;
}

/* Symbol of an even lattice row r[K + h], K = -h..h, at t = kappa dx. */
static double row_symbol(const double *r, int nrow, double t)
{
  int h = (nrow - 1) / 2;
  double s = r[h];
  for (int K = 1; K <= h; K++)
    s += (r[h + K] + r[h - K]) * cos(t * K);
  return s;
}

static double omega2_at(const mfs_cf_plan *p, mfs_cf_scheme sc, double t)
{
  double sb = p->sbar, F = p->F;
  mfs_cf_sums s;
  if (sc == MFS_CF_FEM_LINEAR) {
    double h = sin(0.5 * t);
    return (F * F + sb) * 4.0 * h * h;
  }
  if (sc == MFS_CF_LS_NODAL)
    return row_symbol(p->Krow, p->nrow, t) / row_symbol(p->Mrow, p->nrow, t);
  sums_at(p, t, &s);
  double SM2 = s.SM * s.SM, SS2 = s.SS * s.SS;
  switch (sc) {
  case MFS_CF_EULER_NODAL: /* eq. 74-75 */
    return (1.0 + sb) * SM2 - sb * (s.PM - SM2);
  case MFS_CF_LAGR_NODAL: /* eq. 82 with eq. 81 */
    return (F * F + sb) * SM2;
  case MFS_CF_EULER_STRESS: /* eqs 83-92, derived above */
    return 0.5 * (1.0 + sb) * (SM2 + SS2) -
           0.5 * sb *
             (s.PM - SM2 + s.RS - SS2 - F * s.QS * s.HS - (F - 1.0) * s.QS * s.YS +
              (F - 1.0) * s.ZS * s.SS);
  case MFS_CF_EULER_STRESS_PRINTED: /* eq. 93 as printed */
    return 0.5 * (1.0 + sb) * (SM2 + SS2) -
           0.5 * sb *
             (s.PM - SM2 + s.RS - SS2 - F * s.QS * s.HS + (F - 1.0) * s.QS * s.YS +
              (F - 1.0) * s.ZS * s.SS);
  case MFS_CF_LAGR_STRESS: /* eq. 103 */
    return 0.5 * (F * F + sb) * (SM2 + SS2);
  case MFS_CF_LS_NODAL_PRINTED: /* eq. 108 */
    return (SM2 + p->beta * s.QM * s.QM) / (s.HM * s.HM - p->beta * s.QM * s.HM);
  default:
    return NAN;
  }
}

mfs_status mfs_cf_omega2(const mfs_cf_plan *p, mfs_cf_scheme s, size_t n, const double *kappa,
                         double *omega2)
{
  if (!p || (n && (!kappa || !omega2)) || (int)s < 0 || s >= MFS_CF_NSCHEMES)
    return MFS_EINVAL;
  for (size_t i = 0; i < n; i++)
    if (!isfinite(kappa[i]))
      return MFS_EINVAL;
  if ((s == MFS_CF_LS_NODAL || s == MFS_CF_LS_NODAL_PRINTED) && (p->sbar != 0.0 || p->F != 1.0))
    return MFS_ENOTSUP;
  mfs_status st = MFS_OK;
  for (size_t i = 0; i < n; i++) {
    omega2[i] = omega2_at(p, s, M_PI * kappa[i]);
    if (!isfinite(omega2[i]))
      st = MFS_EDOMAIN;
  }
  return st;
}
