/* Tests of the closed-form 1D dispersion relations (mfs_closed.h).
 *
 *   - API: every error status provoked; scheme names round-trip.
 *   - Tables: phi, phi', phi'' against an independent 1D MLS evaluator
 *     written here (moments in closed form, analytic first derivative, finite
 *     differences for the second) and against the kernel for sph; MLS sum
 *     rules (partition of unity, linear reproduction) at nodes and midpoints.
 *   - Brute force: each closed form against a direct linearization of the
 *     discrete equations it comes from (Eulerian: eqs 65-73 and 83-92 with
 *     perturbed particle positions and the stress points solved from eq. 90,
 *     differentiated by central differences; Lagrangian: eqs 79-81, 99-102 as
 *     direct lattice sums).  This settles the sign conventions of eq. 74 and
 *     the sign of the (F-1) Q_S Y_S term of eq. 93 (printed: +, model: -).
 *   - Continuum limit for every scheme, kernel, several D and sbar.
 *   - Table II, Figs 3, 9, 10 and 11 facts; eq. 108 printed vs derived. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "mfs_closed.h"
#include "mfs_disc.h"
#include "mfs_kernel.h"
#include "mfs_shape.h"
#include "mfs_status.h"

static const mfs_kernel_type *const kernels[] = {&mfs_kernel_cubic, &mfs_kernel_quartic};

static mfs_disc disc1(const mfs_kernel_type *k, const mfs_shape_type *s, double D)
{
  mfs_disc d = mfs_disc_default();
  d.kernel = k;
  d.shape = s;
  d.dilation = D;
  return d;
}

static mfs_cf_plan *make(const mfs_kernel_type *k, const mfs_shape_type *s, double D, double sb,
                         double F, double beta)
{
  mfs_cf_spec sp = {.disc = disc1(k, s, D), .sbar = sb, .stretch = F, .beta = beta};
  mfs_status st = -1;
  mfs_cf_plan *p = mfs_cf_plan_alloc(&sp, &st);
  CHECK(p && st == MFS_OK, "plan %s %s D=%g sbar=%g F=%g beta=%g: status %d", k->name, s->name,
        D, sb, F, beta, st);
  return p;
}

static double om2(const mfs_cf_plan *p, mfs_cf_scheme s, double kappa)
{
  double w = NAN;
  mfs_status st = mfs_cf_omega2(p, s, 1, &kappa, &w);
  CHECK(st == MFS_OK, "omega2 %s at kappa %g: status %d", mfs_cf_scheme_name(s), kappa, st);
  return w;
}

/* ---------------------------------------------------------------------- */
/* An independent shape-function profile: phi of the particle at 0 on the
 * unit lattice, evaluated at any x. */

typedef struct {
  const mfs_kernel_type *k;
  int mls; /* 1: linear MLS, 0: sph (phi = W) */
  double D;
} profile;

/* W(|x - j|) and its x-derivative. */
static void wj(const profile *p, double x, int j, double *w, double *dw)
{
  double d = x - j;
  mfs_kernel_value kv = mfs_kernel_radial(p->k, 1, p->D, fabs(d));
  *w = kv.W;
  *dw = d > 0 ? kv.dW : (d < 0 ? -kv.dW : 0.0);
}

/* phi(x) and phi'(x).  MLS with basis [1, y - x]: phi_0 = W_0 (m2 + m1 x) /
 * (m0 m2 - m1^2), m_k = sum_j W_j (j - x)^k (the shift cancels the scale). */
static void prof_phi1(const profile *p, double x, double *f, double *df)
{
  if (!p->mls) {
    wj(p, x, 0, f, df);
    return;
  }
  double m[3] = {0, 0, 0}, dm[3] = {0, 0, 0};
  for (int j = (int)floor(x - p->D) - 1; j <= (int)ceil(x + p->D) + 1; j++) {
    double w, dw, d = j - x;
    wj(p, x, j, &w, &dw);
    m[0] += w;
    m[1] += w * d;
    m[2] += w * d * d;
    dm[0] += dw;
    dm[1] += dw * d - w;
    dm[2] += dw * d * d - 2.0 * w * d;
  }
  double w0, dw0;
  wj(p, x, 0, &w0, &dw0);
  double N = w0 * (m[2] + m[1] * x), dN = dw0 * (m[2] + m[1] * x) + w0 * (dm[2] + dm[1] * x + m[1]);
  double Dn = m[0] * m[2] - m[1] * m[1], dDn = dm[0] * m[2] + m[0] * dm[2] - 2.0 * m[1] * dm[1];
  *f = N / Dn;
  *df = (dN * Dn - N * dDn) / (Dn * Dn);
}

static double prof_f(const profile *p, double x)
{
  double f, df;
  prof_phi1(p, x, &f, &df);
  return f;
}

static double prof_df(const profile *p, double x)
{
  double f, df;
  prof_phi1(p, x, &f, &df);
  return df;
}

/* ---------------------------------------------------------------------- */

static void test_api(void)
{
  mfs_status st = -1;
  mfs_cf_spec good = {.disc = disc1(&mfs_kernel_quartic, &mfs_shape_mls, 1.5)};
  mfs_cf_spec s;
  CHECK(mfs_cf_plan_alloc(NULL, &st) == NULL && st == MFS_EINVAL, "NULL spec: status %d", st);
  s = good, s.disc.kernel = NULL;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "NULL kernel: status %d", st);
  s = good, s.disc.shape = NULL;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "NULL shape: status %d", st);
  s = good, s.disc.dilation = -1.5;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "D < 0: status %d", st);
  s = good, s.disc.dilation = 0.0;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "D = 0: status %d", st);
  s = good, s.sbar = NAN;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "sbar NaN: status %d", st);
  s = good, s.stretch = -0.93;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "F < 0: status %d", st);
  s = good, s.beta = -0.013;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_EINVAL, "beta < 0: status %d", st);
  s = good, s.disc.shape = &mfs_shape_shepard;
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_ENOTSUP, "shepard: status %d", st);
  s = good, s.disc.dilation = 1.0; /* a node sees only itself: moment matrix singular */
  CHECK(mfs_cf_plan_alloc(&s, &st) == NULL && st == MFS_ESINGULAR, "mls D = 1: status %d", st);
  s = good, s.disc.dilation = 1.0, s.disc.shape = &mfs_shape_sph; /* sph has no moment matrix */
  mfs_cf_plan *q = mfs_cf_plan_alloc(&s, &st);
  CHECK(q && st == MFS_OK, "sph D = 1: status %d", st);
  mfs_cf_plan_free(q);
  mfs_cf_plan_free(NULL);

  mfs_cf_plan *p = mfs_cf_plan_alloc(&good, &st);
  CHECK(p && st == MFS_OK, "good spec: status %d", st);
  if (!p)
    return;
  double k[3] = {0.137, 0.5, 0.871}, w[3];
  CHECK(mfs_cf_omega2(NULL, MFS_CF_EULER_NODAL, 3, k, w) == MFS_EINVAL, "NULL plan");
  CHECK(mfs_cf_omega2(p, MFS_CF_NSCHEMES, 3, k, w) == MFS_EINVAL, "scheme out of range");
  CHECK(mfs_cf_omega2(p, (mfs_cf_scheme)-1, 3, k, w) == MFS_EINVAL, "negative scheme");
  CHECK(mfs_cf_omega2(p, MFS_CF_EULER_NODAL, 3, NULL, w) == MFS_EINVAL, "NULL kappa");
  CHECK(mfs_cf_omega2(p, MFS_CF_EULER_NODAL, 3, k, NULL) == MFS_EINVAL, "NULL omega2");
  CHECK(mfs_cf_omega2(p, MFS_CF_EULER_NODAL, 0, NULL, NULL) == MFS_OK, "n = 0");
  double kn[2] = {0.3, NAN};
  CHECK(mfs_cf_omega2(p, MFS_CF_EULER_NODAL, 2, kn, w) == MFS_EINVAL, "NaN kappa");
  mfs_cf_sums sm;
  CHECK(mfs_cf_lattice_sums(NULL, 0.3, &sm) == MFS_EINVAL, "sums NULL plan");
  CHECK(mfs_cf_lattice_sums(p, INFINITY, &sm) == MFS_EINVAL, "sums inf kappa");
  size_t n;
  const double *x, *f;
  CHECK(mfs_cf_table(p, 0, &n, NULL, &f) == MFS_EINVAL, "table NULL x");
  CHECK(mfs_cf_table(NULL, 0, &n, &x, &f) == MFS_EINVAL, "table NULL plan");
  mfs_cf_plan_free(p);

  /* least squares: only at sigma = 0 and F = 1 */
  s = good, s.sbar = 0.2385;
  p = mfs_cf_plan_alloc(&s, &st);
  CHECK(mfs_cf_omega2(p, MFS_CF_LS_NODAL, 3, k, w) == MFS_ENOTSUP, "LS with sbar != 0");
  CHECK(mfs_cf_omega2(p, MFS_CF_LS_NODAL_PRINTED, 3, k, w) == MFS_ENOTSUP, "LS with sbar != 0");
  mfs_cf_plan_free(p);
  s = good, s.stretch = 1.07;
  p = mfs_cf_plan_alloc(&s, &st);
  CHECK(mfs_cf_omega2(p, MFS_CF_LS_NODAL, 3, k, w) == MFS_ENOTSUP, "LS with F != 1");
  mfs_cf_plan_free(p);
  /* a non-finite result: -sbar P_M(pi) overflows */
  s = good, s.sbar = 1e308;
  p = mfs_cf_plan_alloc(&s, &st);
  double one = 1.0;
  CHECK(mfs_cf_omega2(p, MFS_CF_EULER_NODAL, 1, &one, w) == MFS_EDOMAIN && isinf(w[0]),
        "overflow gives MFS_EDOMAIN, omega2 %g", w[0]);
  mfs_cf_plan_free(p);

  for (int i = 0; i < MFS_CF_NSCHEMES; i++) {
    mfs_cf_scheme sc = (mfs_cf_scheme)-1;
    const char *nm = mfs_cf_scheme_name((mfs_cf_scheme)i);
    CHECK(nm && mfs_cf_scheme_find(nm, &sc) == MFS_OK && sc == (mfs_cf_scheme)i,
          "scheme %d name round trip", i);
  }
  mfs_cf_scheme sc;
  CHECK(mfs_cf_scheme_name(MFS_CF_NSCHEMES) == NULL, "name out of range");
  CHECK(mfs_cf_scheme_find("euler-nodel", &sc) == MFS_EINVAL, "unknown scheme name");
  CHECK(mfs_cf_scheme_find(NULL, &sc) == MFS_EINVAL, "NULL scheme name");
}

/* Tables against the independent profile; MLS sum rules. */
static void test_tables(void)
{
  const double Ds[] = {1.5, 2.0, 2.5, 2.37, 3.1};
  for (size_t ik = 0; ik < 2; ik++)
    for (int mls = 0; mls < 2; mls++)
      for (size_t id = 0; id < sizeof Ds / sizeof *Ds; id++) {
        const mfs_kernel_type *k = kernels[ik];
        double D = Ds[id];
        mfs_cf_plan *p = make(k, mls ? &mfs_shape_mls : &mfs_shape_sph, D, 0.0, 1.0, 0.0);
        if (!p)
          continue;
        profile pr = {k, mls, D};
        for (int mid = 0; mid < 2; mid++) {
          size_t n;
          const double *x, *f;
          CHECK(mfs_cf_table(p, mid, &n, &x, &f) == MFS_OK, "table");
          double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
          for (size_t i = 0; i < n; i++) {
            const double *g = f + 3 * i;
            /* phi''' jumps at lattice points (w''' at r = 0 and r = a): the
             * central difference has an O(h) error there, Richardson removes it */
            double h = 2e-5;
            double d2h = (prof_df(&pr, x[i] + h) - prof_df(&pr, x[i] - h)) / (2 * h);
            double d2q = (prof_df(&pr, x[i] + h / 2) - prof_df(&pr, x[i] - h / 2)) / h;
            double d2 = 2 * d2q - d2h;
            CHECK_NEAR(g[0], prof_f(&pr, x[i]), 1e-13, "%s %s D=%g phi(%g)", k->name,
                       mls ? "mls" : "sph", D, x[i]);
            CHECK_NEAR(g[1], prof_df(&pr, x[i]), 1e-12, "%s %s D=%g phi'(%g)", k->name,
                       mls ? "mls" : "sph", D, x[i]);
            CHECK_NEAR(g[2], d2, 1e-6, "%s %s D=%g phi''(%g)", k->name, mls ? "mls" : "sph",
                       D, x[i]);
            /* symmetry: phi even, phi' odd, phi'' even */
            const double *m = f + 3 * (n - 1 - i);
            CHECK(x[n - 1 - i] == -x[i] && fabs(g[0] - m[0]) <= 1e-14 &&
                    fabs(g[1] + m[1]) <= 1e-13 && fabs(g[2] - m[2]) <= 1e-12,
                  "%s D=%g symmetry at %g", k->name, D, x[i]);
            s0 += g[0], s1 += g[1], s2 += x[i] * g[1], s3 += g[2];
          }
          if (mls) { /* sum_K phi_K(x) = 1, sum_K phi'_K(x) x_K = 1 (x_K = x - y) */
            CHECK_NEAR(s0, 1.0, 1e-13, "%s D=%g mid=%d partition of unity", k->name, D, mid);
            CHECK_NEAR(s1, 0.0, 1e-13, "%s D=%g mid=%d sum phi'", k->name, D, mid);
            CHECK_NEAR(s2, -1.0, 1e-13, "%s D=%g mid=%d linear reproduction", k->name, D, mid);
            CHECK_NEAR(s3, 0.0, 1e-12, "%s D=%g mid=%d sum phi''", k->name, D, mid);
          }
        }
        mfs_cf_plan_free(p);
      }
}

/* ---------------------------------------------------------------------- */
/* Brute force: the discrete equations linearized directly.  Units: current
 * spacing 1 (Eulerian) or reference spacing 1 (Lagrangian), C = 1, rho = 1,
 * so omega2 = dF/de of the internal force on particle 0 for u~_K = cos(t K). */

typedef struct {
  const profile *p;
  int stress;       /* 0 nodal, 1 stress points */
  double F, sb, t;  /* stretch, sigma / C, kappa dx */
  int use_sin;
} bf_case;

static double ut(const bf_case *c, int K) { return c->use_sin ? sin(c->t * K) : cos(c->t * K); }

/* G_Q = sum_K phi'_K(x_Q) u~_K at the unperturbed point x_Q (eqs 73, 88). */
static double bf_grad(const bf_case *c, double xq)
{
  double g = 0.0;
  int R = (int)ceil(c->p->D) + 1;
  for (int K = (int)floor(xq) - R; K <= (int)ceil(xq) + R; K++)
    g += prof_df(c->p, xq - K) * ut(c, K);
  return g;
}

/* Internal force on particle 0, Eulerian kernel, perturbation amplitude e:
 * f_0 = sum_Q V_Q phi'(x_Q - x_0) sigma_Q (eqs 66, 83) with
 * x_K = K + e u~_K, V_Q / V_Q^0 = F_Q / F = 1 + e G_Q (eqs 66, 84, 88),
 * sigma_Q = sigma + (C + sigma) e G_Q (eqs 72, 87, 75), and stress points at
 * x^S = X^S + sum_K phi(x^S - x_K) u_K (eq. 90), u_K = x_K - K / F (eq. 92:
 * particle 0 does not move), X^S chosen so that x^S = J + 1/2 at e = 0. */
static double bf_force_euler(const bf_case *c, double e)
{
  const profile *p = c->p;
  int R = (int)ceil(p->D) + 1, RK = 2 * R + 2;
  double x0 = e * ut(c, 0), f = 0.0, wq = c->stress ? 0.5 : 1.0;
  for (int J = -R; J <= R; J++) {
    double G = bf_grad(c, J), xq = J + e * ut(c, J);
    f += wq * (1.0 + e * G) * prof_df(p, xq - x0) * (c->sb + (1.0 + c->sb) * e * G);
  }
  if (!c->stress)
    return f;
  for (int J = -R - 1; J <= R; J++) {
    double xs0 = J + 0.5, XS = xs0;
    for (int K = J - RK; K <= J + RK; K++) /* X^S from the unperturbed state */
      XS -= prof_f(p, xs0 - K) * (K - K / c->F);
    double xs = xs0;
    for (int it = 0; it < 80; it++) { /* eq. 90, a contraction for F near 1 */
      double s = XS;
      for (int K = J - RK; K <= J + RK; K++) {
        double xK = K + e * ut(c, K);
        s += prof_f(p, xs - xK) * (xK - K / c->F);
      }
      xs = s;
    }
    double G = bf_grad(c, xs0);
    f += 0.5 * (1.0 + e * G) * prof_df(p, xs - x0) * (c->sb + (1.0 + c->sb) * e * G);
  }
  return f;
}

/* d f_0 / d e at 0.  phi''' jumps at lattice points, so the central
 * difference has an O(e) error term; Richardson removes it. */
static double bf_euler(const bf_case *c)
{
  double e = 1e-5;
  double d1 = (bf_force_euler(c, e) - bf_force_euler(c, -e)) / (2 * e);
  double d2 = (bf_force_euler(c, e / 2) - bf_force_euler(c, -e / 2)) / e;
  return 2 * d2 - d1;
}

/* Lagrangian kernel (eqs 79-81, 99-102): f_0 = sum_Q V0_Q phi'(X_Q) Cbar G_Q. */
static double bf_lagr(const bf_case *c)
{
  int R = (int)ceil(c->p->D) + 1;
  double cbar = c->F * c->F + c->sb, f = 0.0, wq = c->stress ? 0.5 : 1.0;
  for (int J = -R; J <= R; J++)
    f += wq * prof_df(c->p, J) * cbar * bf_grad(c, J);
  if (c->stress)
    for (int J = -R - 1; J <= R; J++)
      f += 0.5 * prof_df(c->p, J + 0.5) * cbar * bf_grad(c, J + 0.5);
  return f;
}

static void test_bruteforce(void)
{
  struct {
    const mfs_kernel_type *k;
    int mls;
    double D, F, sb;
  } cs[] = {
    {&mfs_kernel_quartic, 1, 2.5, 1.15, 0.3517},  {&mfs_kernel_cubic, 1, 2.2, 0.915, -0.2731},
    {&mfs_kernel_quartic, 1, 1.5, 1.0, 0.6183},   {&mfs_kernel_cubic, 1, 3.05, 1.083, 0.4471},
    {&mfs_kernel_quartic, 0, 2.0, 1.0, 0.4129},   {&mfs_kernel_cubic, 0, 2.5, 1.0, -0.3377},
  };
  const double kap[] = {0.0371, 0.3719, 0.6602, 0.9473};
  for (size_t ic = 0; ic < sizeof cs / sizeof *cs; ic++) {
    profile pr = {cs[ic].k, cs[ic].mls, cs[ic].D};
    double F = cs[ic].F, sb = cs[ic].sb;
    mfs_cf_plan *p = make(pr.k, pr.mls ? &mfs_shape_mls : &mfs_shape_sph, pr.D, sb, F, 0.0);
    if (!p)
      continue;
    const char *nm = pr.mls ? "mls" : "sph";
    for (size_t i = 0; i < sizeof kap / sizeof *kap; i++) {
      double t = M_PI * kap[i];
      for (int stress = 0; stress < 2; stress++) {
        bf_case c = {&pr, stress, F, sb, t, 0}, cs_ = c;
        cs_.use_sin = 1;
        mfs_cf_scheme se = stress ? MFS_CF_EULER_STRESS : MFS_CF_EULER_NODAL;
        mfs_cf_scheme sl = stress ? MFS_CF_LAGR_STRESS : MFS_CF_LAGR_NODAL;
        double be = bf_euler(&c), bl = bf_lagr(&c);
        double we = om2(p, se, kap[i]), wl = om2(p, sl, kap[i]);
        if (stress || F == 1.0) /* eq. 74 has no F: the brute force only at F = 1 */
          CHECK_NEAR(we, be, 1e-7 * (1 + fabs(be)),
                     "%s %s D=%g F=%g sbar=%g kappa=%g: %s vs brute force",
                     pr.k->name, nm, pr.D, F, sb, kap[i], mfs_cf_scheme_name(se));
        CHECK_NEAR(bf_euler(&cs_), 0.0, 1e-7, "%s %s D=%g: sin part of the Eulerian symbol",
                   pr.k->name, nm, pr.D);
        CHECK_NEAR(wl, bl, 1e-12 * (1 + fabs(bl)), "%s %s D=%g F=%g kappa=%g: %s vs direct sum",
                   pr.k->name, nm, pr.D, F, kap[i], mfs_cf_scheme_name(sl));
        CHECK_NEAR(bf_lagr(&cs_), 0.0, 1e-12, "sin part of the Lagrangian symbol");
      }
      /* eq. 93 as printed differs from the model by the sign of (F-1) Q_S Y_S */
      mfs_cf_sums s;
      mfs_cf_lattice_sums(p, kap[i], &s);
      double dprinted = om2(p, MFS_CF_EULER_STRESS_PRINTED, kap[i]) -
                        om2(p, MFS_CF_EULER_STRESS, kap[i]);
      CHECK_NEAR(dprinted, -sb * (F - 1.0) * s.QS * s.YS, 1e-13,
                 "%s D=%g F=%g kappa=%g: printed - derived eq. 93", pr.k->name, pr.D, F, kap[i]);
    }
    mfs_cf_plan_free(p);
  }
  /* The difference is real, e.g. quartic MLS D = 2.5, F = 1.15, sbar = 0.3517:
   * kappa = 0.3719: derived 0.751033, printed 0.746699, brute force 0.751033;
   * kappa = 0.75: derived -0.00767 (unstable), printed +0.01447 (stable). */
  profile pr = {&mfs_kernel_quartic, 1, 2.5};
  mfs_cf_plan *p = make(pr.k, &mfs_shape_mls, 2.5, 0.3517, 1.15, 0.0);
  bf_case c = {&pr, 1, 1.15, 0.3517, M_PI * 0.3719, 0};
  double bf = bf_euler(&c), dv = om2(p, MFS_CF_EULER_STRESS, 0.3719),
         pv = om2(p, MFS_CF_EULER_STRESS_PRINTED, 0.3719);
  CHECK(fabs(pv - bf) > 1e-3 && fabs(dv - bf) < 1e-7,
        "eq. 93 printed %.6f vs brute force %.6f vs derived %.6f", pv, bf, dv);
  mfs_cf_plan_free(p);
}

/* ---------------------------------------------------------------------- */
/* Continuum limit.  From the tables: s1 = -sum j phi'(j), p2 = sum j^2
 * phi''(j) / 2, m0 = sum phi(j), r0 = sum phi''(j), and over midpoints y:
 * t1 = -sum y phi'(y), q2 = sum y^2 phi''(y) / 2, H0 = sum phi(y),
 * h2 = sum y^2 phi(y) / 2, RS = sum phi''(y).  For small t = kappa dx:
 *   S_M ~ -s1 t, P_M ~ p2 t^2, S_S ~ -t1 t, Q_S ~ RS - q2 t^2, H_S ~ H0 - h2 t^2
 * so omega2 ~ c0 + c2 t^2 with (F = 1)
 *   euler-nodal   c2 = (1+sb) s1^2 - sb (p2 - s1^2)
 *   lagr-nodal    c2 = (1+sb) s1^2
 *   euler-stress  c0 = -sb/2 RS (1 - H0)
 *                 c2 = (1+sb)(s1^2+t1^2)/2 - sb/2 (p2 - s1^2 - t1^2 + q2 H0 + RS h2)
 *   lagr-stress   c2 = (1+sb)(s1^2+t1^2)/2
 *   ls (sb = 0)   c0 = beta r0^2 / (m0 (m0 - beta r0)); c2 = s1^2 / m0^2 if beta r0 = 0
 *   fem           c2 = 1 + sb.
 * MLS: s1 = t1 = m0 = H0 = 1, r0 = RS = 0, so every Lagrangian scheme, FEM
 * and LS tend to the continuum 1 + sbar (eq. 32/34).  The Eulerian ones do
 * NOT unless sbar = 0: p2 = 1 + e''(0)/2 and q2 = 1 + e''(1/2)/2 where
 * e(x) = sum_K phi_K(x) (x_K - x)^2 is the (periodic) error of the MLS
 * interpolant of x^2, whose curvature does not vanish on the lattice: eq. 71
 * moves each shape function rigidly with its particle, which is consistent
 * only if e'' = 0 (e.g. cubic spline with D = 2, the B-spline case, where
 * MLS = SPH and e is constant).  Stress points help: e''(0) + e''(1/2) nearly
 * cancels.  Numbers (quartic MLS, D = 1.5): p2 = 1.7190, q2 = 0; euler-nodal
 * tends to 1 + 0.2810 sbar, euler-stress to 1 + 1.1405 sbar, continuum 1 + sbar.
 * SPH is not linearly consistent: s1 != 1 (cubic D = 1.5: 0.790), so no
 * scheme tends to the continuum; with RS != 0 (quartic D = 2: 0.469) the
 * Eulerian stress-point omega2 does not even vanish at kappa = 0 (the "F"
 * in eq. 91 and partition of unity are assumed there), and LS with beta > 0
 * has omega2(0) = c0 != 0 (r0 != 0). */
typedef struct {
  double s1, p2, m0, r0, t1, q2, H0, h2, RS;
} moments;

static moments get_moments(const mfs_cf_plan *p)
{
  moments m = {0};
  size_t n;
  const double *x, *f;
  mfs_cf_table(p, 0, &n, &x, &f);
  for (size_t i = 0; i < n; i++) {
    m.s1 -= x[i] * f[3 * i + 1];
    m.p2 += 0.5 * x[i] * x[i] * f[3 * i + 2];
    m.m0 += f[3 * i];
    m.r0 += f[3 * i + 2];
  }
  mfs_cf_table(p, 1, &n, &x, &f);
  for (size_t i = 0; i < n; i++) {
    m.t1 -= x[i] * f[3 * i + 1];
    m.q2 += 0.5 * x[i] * x[i] * f[3 * i + 2];
    m.H0 += f[3 * i];
    m.h2 += 0.5 * x[i] * x[i] * f[3 * i];
    m.RS += f[3 * i + 2];
  }
  return m;
}

/* omega2 ~ c0 + c2 t^2 near t = 0; c2 = NAN where not predicted. */
static void limit_coeffs(const moments *m, mfs_cf_scheme s, double sb, double beta, double *c0,
                         double *c2)
{
  double s1 = m->s1, t1 = m->t1;
  *c0 = 0.0;
  switch (s) {
  case MFS_CF_EULER_NODAL:
    *c2 = (1 + sb) * s1 * s1 - sb * (m->p2 - s1 * s1);
    break;
  case MFS_CF_LAGR_NODAL:
    *c2 = (1 + sb) * s1 * s1;
    break;
  case MFS_CF_EULER_STRESS:
  case MFS_CF_EULER_STRESS_PRINTED:
    *c0 = -0.5 * sb * m->RS * (1 - m->H0);
    *c2 = 0.5 * (1 + sb) * (s1 * s1 + t1 * t1) -
          0.5 * sb * (m->p2 - s1 * s1 - t1 * t1 + m->q2 * m->H0 + m->RS * m->h2);
    break;
  case MFS_CF_LAGR_STRESS:
    *c2 = 0.5 * (1 + sb) * (s1 * s1 + t1 * t1);
    break;
  case MFS_CF_LS_NODAL:
  case MFS_CF_LS_NODAL_PRINTED:
    *c0 = beta * m->r0 * m->r0 / (m->m0 * (m->m0 - beta * m->r0));
    *c2 = (beta * m->r0 == 0.0) ? s1 * s1 / (m->m0 * m->m0) : NAN;
    break;
  default:
    *c2 = 1 + sb;
  }
}

static void check_limit(const mfs_cf_plan *p, const moments *m, mfs_cf_scheme s, double sb,
                        double beta, const char *what)
{
  double k = 1e-3, t = M_PI * k, c0, c2;
  limit_coeffs(m, s, sb, beta, &c0, &c2);
  double w1 = om2(p, s, k), w2 = om2(p, s, 2 * k);
  if (c0 == 0.0) { /* omega2 / (kappa dx)^2 at kappa dx / pi = 1e-3 */
    CHECK_NEAR(w1 / (t * t), c2, 1e-4 * fmax(fabs(c2), 1.0), "%s %s: omega2/(kappa dx)^2", what,
               mfs_cf_scheme_name(s));
    return;
  }
  /* Richardson: omega2 = c0 + c2 t^2 + O(t^4) */
  double e0 = (4 * w1 - w2) / 3, e2 = (w2 - w1) / (3 * t * t);
  CHECK_NEAR(e0, c0, 1e-9 + 1e-6 * fabs(c0), "%s %s: omega2(0)", what, mfs_cf_scheme_name(s));
  if (!isnan(c2))
    CHECK_NEAR(e2, c2, 1e-4 * fabs(c2) + 1e-6, "%s %s: d omega2 / d(kappa dx)^2", what,
               mfs_cf_scheme_name(s));
}

static void test_continuum(void)
{
  const double Ds[] = {1.5, 2.0, 2.5};
  const double sbs[] = {0.0, 0.2385, -0.4137, 0.7311, 1.9};
  const double betas[] = {0.0, 0.0137, 0.4};
  char what[128];
  for (size_t ik = 0; ik < 2; ik++)
    for (int mls = 0; mls < 2; mls++)
      for (size_t id = 0; id < 3; id++) {
        const mfs_kernel_type *k = kernels[ik];
        const mfs_shape_type *sh = mls ? &mfs_shape_mls : &mfs_shape_sph;
        double D = Ds[id];
        for (size_t ib = 0; ib < sizeof sbs / sizeof *sbs; ib++) {
          double sb = sbs[ib];
          mfs_cf_plan *p = make(k, sh, D, sb, 1.0, 0.0);
          if (!p)
            continue;
          moments m = get_moments(p);
          snprintf(what, sizeof what, "%s %s D=%g sbar=%g", k->name, sh->name, D, sb);
          for (int s = 0; s < MFS_CF_NSCHEMES; s++)
            if (s != MFS_CF_LS_NODAL && s != MFS_CF_LS_NODAL_PRINTED)
              check_limit(p, &m, (mfs_cf_scheme)s, sb, 0.0, what);
          if (mls) { /* the continuum 1 + sbar (eqs 32, 34) */
            double c0, c2;
            const mfs_cf_scheme to_continuum[] = {MFS_CF_LAGR_NODAL, MFS_CF_LAGR_STRESS,
                                                  MFS_CF_FEM_LINEAR};
            for (int i = 0; i < 3; i++) {
              limit_coeffs(&m, to_continuum[i], sb, 0.0, &c0, &c2);
              CHECK_NEAR(c2, 1 + sb, 1e-12 * (1 + fabs(sb)), "%s %s tends to the continuum",
                         what, mfs_cf_scheme_name(to_continuum[i]));
            }
            if (sb == 0.0)
              for (int s = MFS_CF_EULER_NODAL; s <= MFS_CF_EULER_STRESS_PRINTED; s++) {
                limit_coeffs(&m, (mfs_cf_scheme)s, sb, 0.0, &c0, &c2);
                CHECK_NEAR(c2, 1.0, 1e-12, "%s %s at sbar = 0", what,
                           mfs_cf_scheme_name((mfs_cf_scheme)s));
              }
          }
          mfs_cf_plan_free(p);
        }
        for (size_t ib = 0; ib < sizeof betas / sizeof *betas; ib++) {
          mfs_cf_plan *p = make(k, sh, D, 0.0, 1.0, betas[ib]);
          if (!p)
            continue;
          moments m = get_moments(p);
          snprintf(what, sizeof what, "%s %s D=%g beta=%g", k->name, sh->name, D, betas[ib]);
          check_limit(p, &m, MFS_CF_LS_NODAL, 0.0, betas[ib], what);
          check_limit(p, &m, MFS_CF_LS_NODAL_PRINTED, 0.0, betas[ib], what);
          if (mls) {
            double w = om2(p, MFS_CF_LS_NODAL, 1e-3), t = M_PI * 1e-3;
            CHECK_NEAR(w / (t * t), 1.0, 1e-4, "%s ls-nodal tends to the continuum", what);
          }
          mfs_cf_plan_free(p);
        }
      }

  /* Where the Eulerian closed forms (eq. 71) miss the continuum, and why. */
  mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 1.5, 0.2385, 1.0, 0.0);
  moments m = get_moments(p);
  double c0, c2n, c2s;
  limit_coeffs(&m, MFS_CF_EULER_NODAL, 0.2385, 0, &c0, &c2n);
  limit_coeffs(&m, MFS_CF_EULER_STRESS, 0.2385, 0, &c0, &c2s);
  CHECK_NEAR(m.p2, 1.719008, 1e-6, "quartic mls D=1.5: p2 = 1 + e''(0)/2");
  CHECK_NEAR(m.q2, 0.0, 1e-12, "quartic mls D=1.5: q2 (phi linear between 0 and 1)");
  CHECK_NEAR(c2n, 1 + 0.2385 * (2 - 1.719008), 1e-6, "euler-nodal limit 1 + sbar (2 - p2)");
  CHECK(fabs(c2n - 1.2385) > 0.1 && fabs(c2s - 1.2385) > 0.01,
        "eq. 74 / 93 limits %.5f %.5f vs continuum 1.2385 (expected to differ)", c2n, c2s);
  mfs_cf_plan_free(p);
  p = make(&mfs_kernel_cubic, &mfs_shape_mls, 2.0, 0.2385, 1.0, 0.0); /* B-spline: e'' = 0 */
  m = get_moments(p);
  CHECK(fabs(m.p2 - 1) < 1e-12 && fabs(m.q2 - 1) < 1e-12, "cubic mls D=2: p2 %.15g q2 %.15g",
        m.p2, m.q2);
  mfs_cf_plan_free(p);
  /* Stretched (F != 1) Eulerian stress points, MLS (RS = 0, H0 = t1 = 1):
   *   derived  c2 = 1 + sb - sb/2 (p2 - 2 + q2 (3 - 2F))
   *   printed  c2 = 1 + sb - sb/2 (p2 - 2 + q2)
   * With p2 = q2 = 1 (cubic, D = 2) the model (86)-(92) tends to 1 + sbar F,
   * not to the continuum 1 + sbar (eq. 34); the printed eq. 93 does.  The
   * cause is eq. 91-92: the rigidly moved shape functions of eq. 89-91 lose
   * the partition of unity under perturbation, so the result depends on
   * which particle is held fixed; with particle I fixed, u~^S_J gains
   * i (F-1) x^S_J S_S, growing with the distance to I (the Z_S term). */
  const double Fs[] = {1.2, 0.87};
  for (int i = 0; i < 2; i++) {
    const double sb = 0.3137, F = Fs[i], k = 1e-3, t = M_PI * k;
    p = make(&mfs_kernel_cubic, &mfs_shape_mls, 2.0, sb, F, 0.0);
    CHECK_NEAR(om2(p, MFS_CF_EULER_STRESS, k) / (t * t), 1 + sb * F, 1e-4,
               "cubic mls D=2 F=%g: eq. 86-92 limit 1 + sbar F", F);
    CHECK_NEAR(om2(p, MFS_CF_EULER_STRESS_PRINTED, k) / (t * t), 1 + sb, 1e-4,
               "cubic mls D=2 F=%g: eq. 93 printed limit 1 + sbar", F);
    mfs_cf_plan_free(p);
    p = make(&mfs_kernel_quartic, &mfs_shape_mls, 2.5, sb, F, 0.0);
    m = get_moments(p);
    CHECK_NEAR(om2(p, MFS_CF_EULER_STRESS, k) / (t * t),
               1 + sb - 0.5 * sb * (m.p2 - 2 + m.q2 * (3 - 2 * F)), 1e-4,
               "quartic mls D=2.5 F=%g: eq. 86-92 limit", F);
    CHECK_NEAR(om2(p, MFS_CF_EULER_STRESS_PRINTED, k) / (t * t),
               1 + sb - 0.5 * sb * (m.p2 - 2 + m.q2), 1e-4,
               "quartic mls D=2.5 F=%g: eq. 93 printed limit", F);
    mfs_cf_plan_free(p);
  }

  p = make(&mfs_kernel_cubic, &mfs_shape_sph, 1.5, 0.0, 1.0, 0.0);
  m = get_moments(p);
  CHECK_NEAR(m.s1, 64.0 / 81.0, 1e-12, "cubic sph D=1.5: s1 = -sum j phi'(j)");
  mfs_cf_plan_free(p);
}

/* ---------------------------------------------------------------------- */

#define NGRID 20000

static void test_table2(void)
{
  /* Table II: sigma = 0, quartic MLS, D = 1.5, max over kappa of omega2. */
  mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 1.5, 0.0, 1.0, 0.0);
  if (!p)
    return;
  double mx[MFS_CF_NSCHEMES] = {0}, at[MFS_CF_NSCHEMES] = {0}, mx4 = 0;
  for (int i = 0; i <= NGRID; i++) {
    double k = (double)i / NGRID;
    for (int s = 0; s <= MFS_CF_LAGR_STRESS; s++) {
      double w = om2(p, (mfs_cf_scheme)s, k);
      if (w > mx[s])
        mx[s] = w, at[s] = k;
    }
    mfs_cf_sums sm;
    mfs_cf_lattice_sums(p, k, &sm);
    double w4 = sm.SM * sm.SM + sm.SS * sm.SS;
    mx4 = w4 > mx4 ? w4 : mx4;
    CHECK_NEAR(om2(p, MFS_CF_EULER_STRESS, k), om2(p, MFS_CF_LAGR_STRESS, k), 1e-14,
               "sigma = 0: eq. 93 = eq. 103 at kappa %g", k);
  }
  CHECK_NEAR(mx[MFS_CF_EULER_NODAL], 1.0, 1e-10, "Table II nodal (Eulerian)");
  CHECK_NEAR(mx[MFS_CF_LAGR_NODAL], 1.0, 1e-10, "Table II nodal (Lagrangian)");
  CHECK_NEAR(at[MFS_CF_LAGR_NODAL], 0.5, 1e-4, "Table II nodal max attained at");
  CHECK_NEAR(om2(p, MFS_CF_LAGR_NODAL, 0.5), 1.0, 1e-12, "nodal omega2 at kappa dx/pi = 1/2");
  CHECK_NEAR(mx[MFS_CF_LAGR_STRESS], 2.0, 1e-10, "Table II stress points, Lagrangian");
  CHECK_NEAR(at[MFS_CF_LAGR_STRESS], 1.0, 1e-4, "Table II stress max attained at");
  /* The paper prints 4.0 for Eulerian stress points; eq. 93 (both forms)
   * gives 2.0 at sigma = 0, where it coincides with eq. 103.  4.0 is the max
   * of S_M^2 + S_S^2, i.e. eq. 93 without the half volumes of eq. 84. */
  CHECK_NEAR(mx[MFS_CF_EULER_STRESS], 2.0, 1e-10, "Eulerian stress points (derived) max");
  CHECK_NEAR(mx[MFS_CF_EULER_STRESS_PRINTED], 2.0, 1e-10, "Eulerian stress points (printed)");
  CHECK_NEAR(mx4, 4.0, 1e-10, "max of S_M^2 + S_S^2");
  mfs_cf_plan_free(p);
}

/* First grid kappa where omega2 < 0, or -1. */
static double onset(const mfs_cf_plan *p, mfs_cf_scheme s, int n)
{
  for (int i = 1; i <= n; i++)
    if (om2(p, s, (double)i / n) < 0.0)
      return (double)i / n;
  return -1.0;
}

static double min_omega2(const mfs_cf_plan *p, mfs_cf_scheme s, int n)
{
  double mn = INFINITY;
  for (int i = 0; i <= n; i++) {
    double w = om2(p, s, (double)i / n);
    mn = w < mn ? w : mn;
  }
  return mn;
}

static void test_fig3(void)
{
  /* Fig. 3: Eulerian kernel, nodal integration, quartic MLS. */
  const double Ds[] = {1.5, 2.5};
  for (int id = 0; id < 2; id++) {
    double D = Ds[id];
    mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, D, 0.0, 1.0, 0.0);
    CHECK_NEAR(om2(p, MFS_CF_EULER_NODAL, 1.0), 0.0, 1e-12,
               "D=%g sbar=0: spurious mode at cut-off", D);
    CHECK(min_omega2(p, MFS_CF_EULER_NODAL, 2000) > -1e-14, "D=%g sbar=0: omega2 >= 0", D);
    mfs_cf_plan_free(p);
    const double sbs[] = {0.01, 0.0237, 0.05, 0.1};
    double prev = 2.0;
    for (int ib = 0; ib < 4; ib++) {
      p = make(&mfs_kernel_quartic, &mfs_shape_mls, D, sbs[ib], 1.0, 0.0);
      double kc = onset(p, MFS_CF_EULER_NODAL, 4000);
      CHECK(kc > 0.6 && kc < 1.0 && kc < prev, "D=%g sbar=%g: tensile onset at %g (prev %g)", D,
            sbs[ib], kc, prev);
      for (int i = 0; i <= 100 && kc > 0; i++) { /* unstable from the onset to the cut-off */
        double k = kc + (1.0 - kc) * i / 100;
        CHECK(om2(p, MFS_CF_EULER_NODAL, k) < 0.0, "D=%g sbar=%g: unstable at %g", D, sbs[ib], k);
      }
      prev = kc;
      mfs_cf_plan_free(p);
    }
  }
  /* No threshold stress: at the cut-off omega2 = -sbar P_M(pi) for any
   * sbar > 0; P_M(pi) = 6.876 (D = 1.5), 0.647 (D = 2.5): D = 2.5 only makes
   * the growth slower. */
  mfs_cf_plan *a = make(&mfs_kernel_quartic, &mfs_shape_mls, 1.5, 1e-3, 1.0, 0.0);
  mfs_cf_plan *b = make(&mfs_kernel_quartic, &mfs_shape_mls, 2.5, 1e-3, 1.0, 0.0);
  CHECK_NEAR(om2(a, MFS_CF_EULER_NODAL, 1.0), -6.876033e-3, 1e-8, "D=1.5 omega2 at cut-off");
  CHECK_NEAR(om2(b, MFS_CF_EULER_NODAL, 1.0), -6.47256e-4, 1e-8, "D=2.5 omega2 at cut-off");
  mfs_cf_plan_free(a);
  mfs_cf_plan_free(b);
  /* Lagrangian kernel, nodal: no tensile instability for sbar in (-1, 2]. */
  const double sl[] = {-0.97, -0.5137, 0.0, 0.7311, 2.0};
  for (int ib = 0; ib < 5; ib++)
    for (int id = 0; id < 2; id++) {
      mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, Ds[id], sl[ib], 1.0, 0.0);
      CHECK(min_omega2(p, MFS_CF_LAGR_NODAL, 2000) >= 0.0, "lagr-nodal D=%g sbar=%g stable",
            Ds[id], sl[ib]);
      mfs_cf_plan_free(p);
    }
}

static void test_fig9(void)
{
  /* Fig. 9: Eulerian kernel, stress points, quartic MLS: no tensile
   * instability for D = 1.5; with D = 2.5 unstable at the cut-off for sbar = 1. */
  const double sbs[] = {0.0, 0.1, 0.5, 1.0};
  for (int ib = 0; ib < 4; ib++) {
    mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 1.5, sbs[ib], 1.0, 0.0);
    CHECK(min_omega2(p, MFS_CF_EULER_STRESS, 2000) >= -1e-15, "euler-stress D=1.5 sbar=%g stable",
          sbs[ib]);
    mfs_cf_plan_free(p);
  }
  mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 2.5, 1.0, 1.0, 0.0);
  CHECK(om2(p, MFS_CF_EULER_STRESS, 1.0) < -0.1, "euler-stress D=2.5 sbar=1 at cut-off: %g",
        om2(p, MFS_CF_EULER_STRESS, 1.0));
  mfs_cf_plan_free(p);
}

static void test_fig10(void)
{
  /* Fig. 10: Lagrangian kernel, stress points, cubic MLS, sigma = 0. */
  const double Ds[] = {1.5, 2.0, 2.5, 3.0};
  double prev = INFINITY;
  for (int id = 0; id < 4; id++) {
    mfs_cf_plan *p = make(&mfs_kernel_cubic, &mfs_shape_mls, Ds[id], 0.0, 1.0, 0.0);
    double w = om2(p, MFS_CF_LAGR_STRESS, 1.0);
    CHECK(w > 0.0 && w < prev, "D=%g: omega2 at cut-off %g (previous D %g)", Ds[id], w, prev);
    prev = w;
    for (int i = 1; i <= 200; i++) { /* below the linear finite element */
      double k = i / 200.0;
      CHECK(om2(p, MFS_CF_LAGR_STRESS, k) <= om2(p, MFS_CF_FEM_LINEAR, k) * (1 + 1e-12),
            "D=%g kappa=%g: particle frequency above FEM", Ds[id], k);
    }
    mfs_cf_plan_free(p);
  }
  CHECK(prev < 0.01, "D=3: omega2 at cut-off %g is very small", prev);
  mfs_cf_plan *p = make(&mfs_kernel_cubic, &mfs_shape_mls, 2.0, 0.2385, 1.17, 0.0);
  CHECK_NEAR(om2(p, MFS_CF_FEM_LINEAR, 0.6131),
             (1.17 * 1.17 + 0.2385) * 4 * pow(sin(M_PI * 0.6131 / 2), 2),
             1e-14, "fem-linear");
  mfs_cf_plan_free(p);
}

static void test_ls(void)
{
  /* eq. 108 as printed vs the symbols of the rows of (106)-(107). */
  const double Ds[] = {1.5, 2.0, 2.5, 3.3};
  const double betas[] = {0.0, 0.001, 0.0137, 0.1, 0.7};
  for (size_t ik = 0; ik < 2; ik++)
    for (int mls = 0; mls < 2; mls++)
      for (int id = 0; id < 4; id++)
        for (int ib = 0; ib < 5; ib++) {
          mfs_cf_plan *p = make(kernels[ik], mls ? &mfs_shape_mls : &mfs_shape_sph, Ds[id], 0.0,
                                1.0, betas[ib]);
          double maxd = 0.0;
          for (int i = 0; i <= 200; i++) {
            double k = i / 200.0 * 1.3, a = om2(p, MFS_CF_LS_NODAL, k),
                   b = om2(p, MFS_CF_LS_NODAL_PRINTED, k), d = fabs(a - b) / (1 + fabs(b));
            maxd = d > maxd ? d : maxd;
          }
          CHECK(maxd < 1e-11, "%s %s D=%g beta=%g: eq. 108 printed vs derived differ by %g",
                kernels[ik]->name, mls ? "mls" : "sph", Ds[id], betas[ib], maxd);
          mfs_cf_plan_free(p);
        }
  /* Fig. 11, D = 1.5: stabilization removes the spurious mode at the cut-off. */
  double prev = -1.0;
  const double bq[] = {0.0, 0.001, 0.01, 0.1};
  for (int ib = 0; ib < 4; ib++) {
    mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 1.5, 0.0, 1.0, bq[ib]);
    double w = om2(p, MFS_CF_LS_NODAL, 1.0);
    if (ib == 0)
      CHECK_NEAR(w, 0.0, 1e-14, "beta = 0: spurious mode");
    else
      CHECK(w > prev, "beta=%g: omega2 at cut-off %g (previous %g)", bq[ib], w, prev);
    prev = w;
    mfs_cf_plan_free(p);
  }
  /* D = 2.5: the paper says the mass term of eq. 108 turns positive at large
   * kappa and the denominator can vanish.  With MLS (cubic, quartic, D in
   * 1.1..4) Q_M H_M <= 0 and H_M > 0 at every kappa: the mass symbol
   * H_M^2 - beta Q_M H_M >= H_M^2 > 0 and omega2 >= 0 for every beta >= 0. */
  const double bl[] = {0.001, 0.0137, 0.1, 1.0, 10.0};
  for (int ib = 0; ib < 5; ib++) {
    mfs_cf_plan *p = make(&mfs_kernel_quartic, &mfs_shape_mls, 2.5, 0.0, 1.0, bl[ib]);
    double mh = INFINITY;
    for (int i = 0; i <= 1000; i++) {
      mfs_cf_sums s;
      mfs_cf_lattice_sums(p, i / 1000.0, &s);
      double m = s.HM * s.HM - bl[ib] * s.QM * s.HM;
      mh = m < mh ? m : mh;
      CHECK(s.QM * s.HM <= 1e-15 && s.HM > 0.0, "D=2.5 kappa=%g: Q_M H_M = %g, H_M = %g",
            i / 1000.0, s.QM * s.HM, s.HM);
    }
    CHECK(mh > 0.0 && min_omega2(p, MFS_CF_LS_NODAL, 1000) >= -1e-12, /* rounding at kappa = 0 */
          "D=2.5 beta=%g: mass symbol min %g", bl[ib], mh);
    mfs_cf_plan_free(p);
  }
}

int main(void)
{
  test_api();
  test_tables();
  test_bruteforce();
  test_continuum();
  test_table2();
  test_fig3();
  test_fig9();
  test_fig10();
  test_ls();
  return check_summary("test_closed");
}
