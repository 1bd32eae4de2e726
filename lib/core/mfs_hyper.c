#include "mfs_hyper.h"

#include <math.h>
#include <string.h>

/* Index of a fourth-order 3D tensor. */
#define T4(i, j, k, l) ((((i)*3 + (j)) * 3 + (k)) * 3 + (l))
/* Index of a fourth-order in-plane tensor. */
#define P4(i, j, k, l) ((((i)*2 + (j)) * 2 + (k)) * 2 + (l))

static double det3(const double *M)
{
  return M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
         M[2] * (M[3] * M[7] - M[4] * M[6]);
}

static void inv3(const double *M, double d, double *Mi)
{
  Mi[0] = (M[4] * M[8] - M[5] * M[7]) / d;
  Mi[1] = (M[2] * M[7] - M[1] * M[8]) / d;
  Mi[2] = (M[1] * M[5] - M[2] * M[4]) / d;
  Mi[3] = (M[5] * M[6] - M[3] * M[8]) / d;
  Mi[4] = (M[0] * M[8] - M[2] * M[6]) / d;
  Mi[5] = (M[2] * M[3] - M[0] * M[5]) / d;
  Mi[6] = (M[3] * M[7] - M[4] * M[6]) / d;
  Mi[7] = (M[1] * M[6] - M[0] * M[7]) / d;
  Mi[8] = (M[0] * M[4] - M[1] * M[3]) / d;
}

/* CSE += f X(x)X + g II_X, II_X_IJKL = (X_IK X_JL + X_IL X_JK) / 2. */
static void add_xx_iix(double *CSE, const double *X, double f, double g)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
          CSE[T4(i, j, k, l)] += f * X[i * 3 + j] * X[k * 3 + l] +
                                 g * 0.5 * (X[i * 3 + k] * X[j * 3 + l] + X[i * 3 + l] * X[j * 3 + k]);
}

/* ---- linear: S = 0 and C_SE = lambda I(x)I + 2 mu II at C = I ---- */

static void linear_pk2(const double *c, const double *C, double *S, double *CSE)
{
  (void)C; /* F = I only (the type has finite = 0) */
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  memset(S, 0, 9 * sizeof *S);
  if (CSE) {
    memset(CSE, 0, 81 * sizeof *CSE);
    add_xx_iix(CSE, I3, c[1], 2.0 * c[0]);
  }
}

static double lame_mu0(const double *c)
{
  return c[0];
}

static double lame_k0(const double *c)
{
  return c[1] + 2.0 * c[0] / 3.0;
}

/* ---- neo-Hookean: S = mu (I - C^-1) + lambda ln J C^-1,
 *      C_SE = lambda C^-1(x)C^-1 + 2 (mu - lambda ln J) II_{C^-1} ---- */

static void neo_pk2(const double *c, const double *C, double *S, double *CSE)
{
  double I3 = det3(C), Ci[9];
  inv3(C, I3, Ci);
  double mu = c[0], lam = c[1], lnJ = 0.5 * log(I3);
  for (int i = 0; i < 9; i++)
    S[i] = mu * ((i % 4 == 0 ? 1.0 : 0.0) - Ci[i]) + lam * lnJ * Ci[i];
  if (CSE) {
    memset(CSE, 0, 81 * sizeof *CSE);
    add_xx_iix(CSE, Ci, lam, 2.0 * (mu - lam * lnJ));
  }
}

/* ---- paper 000 eq. 18: with beta = -c1 J^(2/3) - 2 c2 J^(4/3) + 2 lambda ln J and
 *      gamma = J dbeta/dJ = -(2/3) c1 J^(2/3) - (8/3) c2 J^(4/3) + 2 lambda,
 *      S = c1 I + c2 (I1 I - C) + beta C^-1,
 *      C_SE = 2 c2 (I(x)I - II) + gamma C^-1(x)C^-1 - 2 beta II_{C^-1} ---- */

static void p000_pk2(const double *c, const double *C, double *S, double *CSE)
{
  static const double Id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double I3 = det3(C), Ci[9];
  inv3(C, I3, Ci);
  double c1 = c[0], c2 = c[1], lam = c[2], J = sqrt(I3), I1 = C[0] + C[4] + C[8];
  double j23 = pow(J, 2.0 / 3.0), j43 = j23 * j23;
  double beta = -c1 * j23 - 2.0 * c2 * j43 + 2.0 * lam * log(J);
  double gamma = -2.0 / 3.0 * c1 * j23 - 8.0 / 3.0 * c2 * j43 + 2.0 * lam;
  for (int i = 0; i < 9; i++)
    S[i] = c1 * Id[i] + c2 * (I1 * Id[i] - C[i]) + beta * Ci[i];
  if (CSE) {
    memset(CSE, 0, 81 * sizeof *CSE);
    add_xx_iix(CSE, Id, 2.0 * c2, -2.0 * c2);
    add_xx_iix(CSE, Ci, gamma, -2.0 * beta);
  }
}

static double p000_mu0(const double *c)
{
  return c[0] + c[1];
}

static double p000_k0(const double *c)
{
  return 2.0 * c[2];
}

const mfs_hyper_type mfs_hyper_linear = {.name = "linear",
                                         .constants = "shear modulus mu, Lame lambda",
                                         .finite = 0,
                                         .pk2 = linear_pk2,
                                         .mu0 = lame_mu0,
                                         .k0 = lame_k0};
const mfs_hyper_type mfs_hyper_neo_hookean = {.name = "neo-hookean",
                                              .constants = "shear modulus mu, Lame lambda",
                                              .finite = 1,
                                              .pk2 = neo_pk2,
                                              .mu0 = lame_mu0,
                                              .k0 = lame_k0};
const mfs_hyper_type mfs_hyper_paper000 = {.name = "paper000",
                                           .constants = "c1, c2, lambda of paper 000 eq. 18",
                                           .finite = 1,
                                           .pk2 = p000_pk2,
                                           .mu0 = p000_mu0,
                                           .k0 = p000_k0};

const mfs_hyper_type *const mfs_hyper_types[] = {&mfs_hyper_linear, &mfs_hyper_neo_hookean,
                                                 &mfs_hyper_paper000, NULL};

const mfs_hyper_type *mfs_hyper_find(const char *name)
{
  for (int i = 0; name && mfs_hyper_types[i]; i++)
    if (strcmp(mfs_hyper_types[i]->name, name) == 0)
      return mfs_hyper_types[i];
  return NULL;
}

mfs_hyper mfs_hyper_paper000_constants(void)
{
  return (mfs_hyper){.type = &mfs_hyper_paper000, .c = {1.265e5, 1.012e4, 1.012e7}, .density = 125.4};
}

mfs_hyper mfs_hyper_isotropic(const mfs_hyper_type *t, double mu, double nu, double rho)
{
  return (mfs_hyper){.type = t, .c = {mu, 2.0 * mu * nu / (1.0 - 2.0 * nu), 0.0}, .density = rho};
}

mfs_status mfs_hyper_eval(const mfs_hyper *m, const double *F, double *sigma, double *P, double *S,
                          double *A, double *a)
{
  if (!m || !m->type || !m->type->finite || !F)
    return MFS_EINVAL;
  double J = det3(F);
  if (!(J > 0.0) || !isfinite(J))
    return MFS_EINVAL;
  double C[9], Sl[9], Pl[9], CSE[81];
  for (int I = 0; I < 3; I++)
    for (int K = 0; K < 3; K++) {
      double s = 0.0;
      for (int i = 0; i < 3; i++)
        s += F[i * 3 + I] * F[i * 3 + K];
      C[I * 3 + K] = s;
    }
  m->type->pk2(m->c, C, Sl, (A || a) ? CSE : NULL);
  for (int i = 0; i < 3; i++)
    for (int J2 = 0; J2 < 3; J2++) {
      double s = 0.0;
      for (int M = 0; M < 3; M++)
        s += F[i * 3 + M] * Sl[M * 3 + J2];
      Pl[i * 3 + J2] = s;
    }
  for (int i = 0; i < 9; i++)
    if (!isfinite(Sl[i]))
      return MFS_EINVAL;
  if (S)
    memcpy(S, Sl, sizeof Sl);
  if (P)
    memcpy(P, Pl, sizeof Pl);
  if (sigma)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (int K = 0; K < 3; K++)
          s += Pl[i * 3 + K] * F[j * 3 + K];
        sigma[i * 3 + j] = s / J;
      }
  if (!A && !a)
    return MFS_OK;
  double Al[81];
  /* A_iJkL = delta_ik S_JL + F_iM F_kN C_SE_MJNL; first G_MJkL = F_kN C_SE_MJNL */
  double G[81];
  for (int M = 0; M < 3; M++)
    for (int J2 = 0; J2 < 3; J2++)
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          double s = 0.0;
          for (int N = 0; N < 3; N++)
            s += F[k * 3 + N] * CSE[T4(M, J2, N, L)];
          G[T4(M, J2, k, L)] = s;
        }
  for (int i = 0; i < 3; i++)
    for (int J2 = 0; J2 < 3; J2++)
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          double s = i == k ? Sl[J2 * 3 + L] : 0.0;
          for (int M = 0; M < 3; M++)
            s += F[i * 3 + M] * G[T4(M, J2, k, L)];
          Al[T4(i, J2, k, L)] = s;
        }
  if (A)
    memcpy(A, Al, sizeof Al);
  if (a) /* a_ijkl = J^-1 F_jJ F_lL A_iJkL */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
          for (int l = 0; l < 3; l++) {
            double s = 0.0;
            for (int J2 = 0; J2 < 3; J2++)
              for (int L = 0; L < 3; L++)
                s += F[j * 3 + J2] * F[l * 3 + L] * Al[T4(i, J2, k, L)];
            a[T4(i, j, k, l)] = s / J;
          }
  return MFS_OK;
}

mfs_status mfs_plane_state_stretch(const mfs_hyper *m, double l1, double l2, mfs_plane_state *s)
{
  if (!m || !m->type || !s || !(l1 > 0.0) || !(l2 > 0.0) || !isfinite(l1) || !isfinite(l2))
    return MFS_EINVAL;
  double mu0 = m->type->mu0(m->c);
  if (!(mu0 > 0.0) || !isfinite(mu0))
    return MFS_EINVAL;
  if (!m->type->finite) {
    if (l1 != 1.0 || l2 != 1.0)
      return MFS_EINVAL;
    double nu = m->c[1] / (2.0 * (m->c[0] + m->c[1])); /* lambda = 2 mu nu / (1 - 2 nu) */
    return mfs_plane_state_linear(nu, 0.0, 0.0, 0.0, s);
  }
  double F[9] = {l1, 0, 0, 0, l2, 0, 0, 0, 1}, sig[9], A[81], a[81];
  mfs_status st = mfs_hyper_eval(m, F, sig, NULL, NULL, A, a);
  if (st != MFS_OK)
    return st;
  *s = (mfs_plane_state){.l = {l1, l2}, .J = l1 * l2, .mu0 = mu0};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) {
      s->sigma[i * 2 + j] = sig[i * 3 + j] / mu0;
      for (int k = 0; k < 2; k++)
        for (int l = 0; l < 2; l++) {
          s->a[P4(i, j, k, l)] = a[T4(i, j, k, l)] / mu0;
          s->A[P4(i, j, k, l)] = A[T4(i, j, k, l)] / mu0;
        }
    }
  for (int i = 0; i < 16; i++)
    if (!isfinite(s->a[i]) || !isfinite(s->A[i]))
      return MFS_EINVAL;
  return MFS_OK;
}

mfs_status mfs_plane_state_linear(double nu, double sxx, double syy, double sxy, mfs_plane_state *s)
{
  if (!s || !(nu > -1.0 && nu < 0.5) || !isfinite(sxx) || !isfinite(syy) || !isfinite(sxy))
    return MFS_EINVAL;
  double lam = 2.0 * nu / (1.0 - 2.0 * nu);
  *s = (mfs_plane_state){.l = {1.0, 1.0}, .J = 1.0, .sigma = {sxx, sxy, sxy, syy}, .mu0 = 1.0};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      for (int k = 0; k < 2; k++)
        for (int l = 0; l < 2; l++) {
          double c = (i == j && k == l ? lam : 0.0) + (i == k && j == l ? 1.0 : 0.0) +
                     (i == l && j == k ? 1.0 : 0.0);
          s->a[P4(i, j, k, l)] = c + (i == k ? s->sigma[j * 2 + l] : 0.0);
        }
  memcpy(s->A, s->a, sizeof s->A);
  return MFS_OK;
}

void mfs_acoustic_tensor(const double *t, double theta, double *Q)
{
  double n[2] = {cos(theta), sin(theta)};
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 2; k++) {
      double s = 0.0;
      for (int j = 0; j < 2; j++)
        for (int l = 0; l < 2; l++)
          s += t[P4(i, j, k, l)] * n[j] * n[l];
      Q[i * 2 + k] = s;
    }
}

double mfs_sym2_min_eig(const double *Q)
{
  double a = Q[0], d = Q[3], b = 0.5 * (Q[1] + Q[2]);
  double h = 0.5 * (a - d);
  return 0.5 * (a + d) - hypot(h, b);
}

static double qmin_at(const double *t, double th)
{
  double Q[4];
  mfs_acoustic_tensor(t, th, Q);
  return mfs_sym2_min_eig(Q);
}

/* d lambda_min / d theta = v^T Q'(theta) v, v the unit eigenvector of the
 * smallest eigenvalue of sym Q (Hellmann-Feynman). */
static double qmin_slope(const double *t, double th)
{
  double Q[4], Qp[4], n[2] = {cos(th), sin(th)}, np[2] = {-sin(th), cos(th)};
  mfs_acoustic_tensor(t, th, Q);
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 2; k++) {
      double s = 0.0;
      for (int j = 0; j < 2; j++)
        for (int l = 0; l < 2; l++)
          s += t[(((i * 2 + j) * 2 + k) * 2) + l] * (np[j] * n[l] + n[j] * np[l]);
      Qp[i * 2 + k] = s;
    }
  double a = Q[0], d = Q[3], b = 0.5 * (Q[1] + Q[2]), lam = mfs_sym2_min_eig(Q);
  double v[2] = {b, lam - a}; /* (Q - lam I) v = 0 */
  if (fabs(a - lam) < fabs(d - lam)) {
    v[0] = lam - d;
    v[1] = b;
  }
  double nv = hypot(v[0], v[1]);
  if (!(nv > 0.0))
    return 0.0;
  v[0] /= nv;
  v[1] /= nv;
  return v[0] * v[0] * Qp[0] + v[0] * v[1] * (Qp[1] + Qp[2]) + v[1] * v[1] * Qp[3];
}

mfs_status mfs_ellipticity_check(const double *t, int samples, mfs_ellipticity *e)
{
  if (!t || !e || samples < 0)
    return MFS_EINVAL;
  int n = samples ? samples : 720;
  if (n < 8)
    return MFS_EINVAL;
  for (int i = 0; i < 16; i++)
    if (!isfinite(t[i]))
      return MFS_EINVAL;
  double h = M_PI / n, best = INFINITY, bth = 0.0;
  /* every sample that is a local minimum of the periodic sequence is refined */
  double prev = qmin_at(t, -h), cur = qmin_at(t, 0.0);
  for (int i = 0; i < n; i++) {
    double next = qmin_at(t, (i + 1) * h);
    if (cur <= prev && cur <= next) {
      double lo = (i - 1) * h, hi = (i + 1) * h, g = 0.5 * (sqrt(5.0) - 1.0);
      double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      double f1 = qmin_at(t, x1), f2 = qmin_at(t, x2);
      while (hi - lo > 1e-13) {
        if (f1 <= f2) {
          hi = x2;
          x2 = x1;
          f2 = f1;
          x1 = hi - g * (hi - lo);
          f1 = qmin_at(t, x1);
        } else {
          lo = x1;
          x1 = x2;
          f1 = f2;
          x2 = lo + g * (hi - lo);
          f2 = qmin_at(t, x2);
        }
      }
      /* then the zero of the slope by bisection: the argmin to rounding (the value is
       * flat there, so golden section alone fixes it only to sqrt(eps)) */
      double a0 = 0.5 * (lo + hi) - 1e-6, b0 = 0.5 * (lo + hi) + 1e-6;
      double sa = qmin_slope(t, a0), sb = qmin_slope(t, b0);
      if (sa < 0.0 && sb > 0.0) {
        for (int it = 0; it < 60 && b0 - a0 > 1e-16; it++) {
          double mid = 0.5 * (a0 + b0), sm = qmin_slope(t, mid);
          if (sm < 0.0)
            a0 = mid;
          else
            b0 = mid;
        }
        lo = a0;
        hi = b0;
      }
      double xm = 0.5 * (lo + hi), fm = qmin_at(t, xm);
      if (cur < fm) { /* the sample itself (a kink or a flat minimum) */
        fm = cur;
        xm = i * h;
      }
      if (fm < best) {
        best = fm;
        bth = xm;
      }
    }
    prev = cur;
    cur = next;
  }
  bth = fmod(bth, M_PI);
  if (bth < 0.0)
    bth += M_PI;
  *e = (mfs_ellipticity){.stable = best > 0.0, .q_min = best, .theta = bth};
  return MFS_OK;
}
