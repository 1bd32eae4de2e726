/* The materials of the finite-deformation analyses (mfs_hyper.h): stresses
 * against the printed eq. 18 of paper 000 and against central differences of
 * the strain energies; every tangent against central differences of the
 * stress it derives from (C_SE from S, A from P, the Truesdell modulus from
 * the rate of sigma along F' = L F); the push-forward identities; the
 * acoustic tensor against the closed forms of docs/finite-deformation.md;
 * the PDE domain of the eq. 18 material on [0.3, 2]^2 by three independent
 * tests; the linear material under stress; the error returns. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

#define T4(i, j, k, l) ((((i)*3 + (j)) * 3 + (k)) * 3 + (l))
#define P4(i, j, k, l) ((((i)*2 + (j)) * 2 + (k)) * 2 + (l))

static double det3(const double *M)
{
  return M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
         M[2] * (M[3] * M[7] - M[4] * M[6]);
}

static void matmul(const double *A, const double *B, double *C)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++)
        s += A[i * 3 + k] * B[k * 3 + j];
      C[i * 3 + j] = s;
    }
}

static void transpose(const double *A, double *At)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      At[j * 3 + i] = A[i * 3 + j];
}

/* The strain energies, written from their definitions (3D invariants). */
static double energy(const mfs_hyper *m, const double *F)
{
  double Ft[9], C[9], C2[9];
  transpose(F, Ft);
  matmul(Ft, F, C);
  matmul(C, C, C2);
  double I1 = C[0] + C[4] + C[8], I2 = 0.5 * (I1 * I1 - (C2[0] + C2[4] + C2[8]));
  double J = det3(F), lnJ = log(J);
  if (m->type == &mfs_hyper_neo_hookean)
    return m->c[0] / 2 * (I1 - 3) - m->c[0] * lnJ + m->c[1] / 2 * lnJ * lnJ;
  return m->c[0] / 2 * (I1 - 3 * pow(J, 2.0 / 3.0)) + m->c[1] / 2 * (I2 - 3 * pow(J, 4.0 / 3.0)) +
         m->c[2] * lnJ * lnJ;
}

/* Eq. 18 of paper 000 as printed (invariants of B, I3 = det B). */
static void eq18(const mfs_hyper *m, const double *F, double *sig)
{
  double Ft[9], B[9], B2[9];
  transpose(F, Ft);
  matmul(F, Ft, B);
  matmul(B, B, B2);
  double I1 = B[0] + B[4] + B[8], I3 = det3(B), c1 = m->c[0], c2 = m->c[1], lam = m->c[2];
  double s = c1 * pow(I3, 1.0 / 3.0) + 2 * c2 * pow(I3, 2.0 / 3.0) - lam * log(I3);
  for (int i = 0; i < 9; i++)
    sig[i] = ((c1 + c2 * I1) * B[i] - c2 * B2[i] - (i % 4 == 0 ? s : 0.0)) / sqrt(I3);
}

static double maxabs(const double *x, int n)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fabs(x[i]) > m ? fabs(x[i]) : m;
  return m;
}

/* The deformations of the checks: identity, stretches, compression, shear, general. */
static const double Fs[][9] = {
  {1, 0, 0, 0, 1, 0, 0, 0, 1},           {1.3, 0, 0, 0, 0.8, 0, 0, 0, 1},
  {0.5, 0, 0, 0, 1.7, 0, 0, 0, 1},       {2, 0, 0, 0, 2, 0, 0, 0, 1},
  {0.3, 0, 0, 0, 0.3, 0, 0, 0, 1},       {1.6487, 0, 0, 0, 1.6487, 0, 0, 0, 1},
  {1.1, 0.35, 0, -0.05, 0.92, 0, 0, 0, 1}, {1.12, 0.13, -0.07, 0.09, 0.87, 0.11, -0.04, 0.06, 1.21}};
enum { NF = sizeof Fs / sizeof Fs[0] };

static void materials(mfs_hyper *m)
{
  m[0] = mfs_hyper_paper000_constants();
  m[1] = mfs_hyper_isotropic(&mfs_hyper_neo_hookean, 1.0, 0.3, 1.0);
  m[2] = (mfs_hyper){.type = &mfs_hyper_neo_hookean, .c = {1.3662e5, 2.024e7 - 2.0 / 3.0 * 1.3662e5}, .density = 125.4};
}

static void stresses(void)
{
  mfs_hyper m[3];
  materials(m);
  double e18 = 0.0, ew = 0.0;
  for (int im = 0; im < 3; im++)
    for (int f = 0; f < NF; f++) {
      const double *F = Fs[f];
      double sig[9], P[9], S[9];
      CHECK(mfs_hyper_eval(&m[im], F, sig, P, S, NULL, NULL) == MFS_OK, "eval");
      /* sigma = J^-1 P F^T and P = F S hold by construction; P = dW/dF is the check */
      double scale = fmax(maxabs(P, 9), 1e-3 * m[im].type->mu0(m[im].c));
      for (int i = 0; i < 9; i++) { /* Richardson-extrapolated central differences */
        double D[2];
        for (int r = 0; r < 2; r++) {
          double Fp[9], Fm[9], h = r ? 5e-5 : 1e-4;
          memcpy(Fp, F, sizeof Fp);
          memcpy(Fm, F, sizeof Fm);
          Fp[i] += h;
          Fm[i] -= h;
          D[r] = (energy(&m[im], Fp) - energy(&m[im], Fm)) / (2 * h);
        }
        double d = (4 * D[1] - D[0]) / 3;
        ew = fmax(ew, fabs(d - P[i]) / scale);
      }
      if (im == 0) {
        double s18[9];
        eq18(&m[0], F, s18);
        for (int i = 0; i < 9; i++)
          e18 = fmax(e18, fabs(s18[i] - sig[i]) / maxabs(s18, 9));
      }
      if (f == 0) /* the reference state is stress-free */
        CHECK(maxabs(sig, 9) < 1e-9 * m[im].type->mu0(m[im].c), "stress-free at F = I: %g",
              maxabs(sig, 9));
    }
  CHECK(e18 < 1e-13, "paper000 sigma vs printed eq. 18: rel. diff %.3g", e18);
  CHECK(ew < 1e-7, "P vs central differences of W: rel. diff %.3g", ew);
  printf("stresses: eq. 18 %.2g, P = dW/dF %.2g\n", e18, ew);
}

static void tangents(void)
{
  mfs_hyper m[3];
  materials(m);
  double eA = 0.0, eC = 0.0, eT = 0.0, ec = 0.0;
  for (int im = 0; im < 3; im++)
    for (int f = 0; f < NF; f++) {
      const double *F = Fs[f];
      double sig[9], S[9], A[81], a[81];
      CHECK(mfs_hyper_eval(&m[im], F, sig, NULL, S, A, a) == MFS_OK, "eval");
      double sA = maxabs(A, 81), h = 1e-6;
      /* A = dP/dF */
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          double Fp[9], Fm[9], Pp[9], Pm[9];
          memcpy(Fp, F, sizeof Fp);
          memcpy(Fm, F, sizeof Fm);
          Fp[k * 3 + L] += h;
          Fm[k * 3 + L] -= h;
          mfs_hyper_eval(&m[im], Fp, NULL, Pp, NULL, NULL, NULL);
          mfs_hyper_eval(&m[im], Fm, NULL, Pm, NULL, NULL, NULL);
          for (int i = 0; i < 3; i++)
            for (int J = 0; J < 3; J++)
              eA = fmax(eA, fabs((Pp[i * 3 + J] - Pm[i * 3 + J]) / (2 * h) - A[T4(i, J, k, L)]) / sA);
        }
      /* C_SE = dS/dE from A: C_SE_MJNL = F^-1_Mi F^-1_Nk (A_iJkL - delta_ik S_JL), against
       * dS along C + 2 h sym(e_K (x) e_L) (F changed by a right stretch) */
      double Ft[9], C[9];
      transpose(F, Ft);
      matmul(Ft, F, C);
      for (int K = 0; K < 3; K++)
        for (int L = 0; L < 3; L++) {
          /* S depends on C only: central differences of the type's pk2 at C +- 2 h E,
           * E = sym(e_K (x) e_L), give C_SE : E (C = I + 2 E) */
          double E[9] = {0};
          E[K * 3 + L] += 0.5;
          E[L * 3 + K] += 0.5;
          double Cp[9], Cm[9], Sp[9], Sm[9];
          for (int i = 0; i < 9; i++) {
            Cp[i] = C[i] + 2 * h * E[i];
            Cm[i] = C[i] - 2 * h * E[i];
          }
          m[im].type->pk2(m[im].c, Cp, Sp, NULL);
          m[im].type->pk2(m[im].c, Cm, Sm, NULL);
          /* C_SE from A (the library's) */
          double Fi[9], dF = det3(F);
          Fi[0] = (F[4] * F[8] - F[5] * F[7]) / dF;
          Fi[1] = (F[2] * F[7] - F[1] * F[8]) / dF;
          Fi[2] = (F[1] * F[5] - F[2] * F[4]) / dF;
          Fi[3] = (F[5] * F[6] - F[3] * F[8]) / dF;
          Fi[4] = (F[0] * F[8] - F[2] * F[6]) / dF;
          Fi[5] = (F[2] * F[3] - F[0] * F[5]) / dF;
          Fi[6] = (F[3] * F[7] - F[4] * F[6]) / dF;
          Fi[7] = (F[1] * F[6] - F[0] * F[7]) / dF;
          Fi[8] = (F[0] * F[4] - F[1] * F[3]) / dF;
          for (int M = 0; M < 3; M++)
            for (int J = 0; J < 3; J++) {
              double cse = 0.0; /* C_SE_MJKL from A, contracted with E: sum over N, L2 */
              for (int N = 0; N < 3; N++)
                for (int L2 = 0; L2 < 3; L2++) {
                  double v = 0.0;
                  for (int i = 0; i < 3; i++)
                    for (int k = 0; k < 3; k++)
                      v += Fi[M * 3 + i] * Fi[N * 3 + k] *
                           (A[T4(i, J, k, L2)] - (i == k ? S[J * 3 + L2] : 0.0));
                  cse += v * E[N * 3 + L2];
                }
              double fd = (Sp[M * 3 + J] - Sm[M * 3 + J]) / (2 * h);
              eC = fmax(eC, fabs(fd - cse) / sA);
            }
        }
      /* the Truesdell rate: d sigma(F + h L F)/dh = c:D + L sigma + sigma L^T - tr(L) sigma,
       * c_ijkl = a_ijkl - delta_ik sigma_jl */
      const double L[9] = {0.31, -0.17, 0.05, 0.23, -0.11, 0.07, -0.02, 0.13, 0.19};
      double LF[9], Fp[9], Fm[9], sp[9], sm[9];
      matmul(L, F, LF);
      for (int i = 0; i < 9; i++) {
        Fp[i] = F[i] + h * LF[i];
        Fm[i] = F[i] - h * LF[i];
      }
      mfs_hyper_eval(&m[im], Fp, sp, NULL, NULL, NULL, NULL);
      mfs_hyper_eval(&m[im], Fm, sm, NULL, NULL, NULL, NULL);
      double trL = L[0] + L[4] + L[8];
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          double r = -trL * sig[i * 3 + j];
          for (int k = 0; k < 3; k++) {
            r += L[i * 3 + k] * sig[k * 3 + j] + sig[i * 3 + k] * L[j * 3 + k];
            for (int l = 0; l < 3; l++) {
              double c = a[T4(i, j, k, l)] - (i == k ? sig[j * 3 + l] : 0.0);
              r += c * 0.5 * (L[k * 3 + l] + L[l * 3 + k]);
            }
          }
          eT = fmax(eT, fabs((sp[i * 3 + j] - sm[i * 3 + j]) / (2 * h) - r) / sA);
        }
      /* a = c + delta sigma, c the push-forward of C_SE (A.5 closed form for paper000) */
      if (im == 0) {
        double Ft2[9], B[9], J = det3(F);
        transpose(F, Ft2);
        matmul(F, Ft2, B);
        double c1 = m[0].c[0], c2 = m[0].c[1], lam = m[0].c[2];
        double j23 = pow(J, 2.0 / 3.0), j43 = j23 * j23;
        double beta = -c1 * j23 - 2 * c2 * j43 + 2 * lam * log(J);
        double gamma = -2.0 / 3.0 * c1 * j23 - 8.0 / 3.0 * c2 * j43 + 2 * lam;
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
              for (int l = 0; l < 3; l++) {
                double Iik = i == k, Ijl = j == l, Iil = i == l, Ijk = j == k, Iij = i == j, Ikl = k == l;
                double c = (2 * c2 * (B[i * 3 + j] * B[k * 3 + l] -
                                      0.5 * (B[i * 3 + k] * B[j * 3 + l] + B[i * 3 + l] * B[j * 3 + k])) +
                            gamma * Iij * Ikl - beta * (Iik * Ijl + Iil * Ijk)) / J;
                ec = fmax(ec, fabs(c + Iik * sig[j * 3 + l] - a[T4(i, j, k, l)]) / sA);
              }
      }
    }
  CHECK(eA < 1e-7, "A vs central differences of P: rel. diff %.3g", eA);
  CHECK(eC < 1e-7, "C_SE vs central differences of S: rel. diff %.3g", eC);
  CHECK(eT < 1e-7, "Truesdell modulus vs the rate of sigma along F' = L F: rel. diff %.3g", eT);
  CHECK(ec < 1e-13, "paper000 a = c (eq. A5) + delta sigma: rel. diff %.3g", ec);
  printf("tangents: A %.2g, C_SE %.2g, Truesdell %.2g, closed c %.2g\n", eA, eC, eT, ec);

  /* small-strain moduli at F = I */
  double A[81];
  mfs_hyper_eval(&m[0], Fs[0], NULL, NULL, NULL, A, NULL);
  double mu0 = 1.3662e5, K0 = 2.024e7;
  CHECK_NEAR(A[T4(0, 0, 0, 0)], K0 + 4 * mu0 / 3, 1e-6, "paper000 c_1111 at F = I");
  CHECK_NEAR(A[T4(0, 0, 1, 1)], K0 - 2 * mu0 / 3, 1e-6, "paper000 c_1122 at F = I");
  CHECK_NEAR(A[T4(0, 1, 0, 1)], mu0, 1e-6, "paper000 c_1212 at F = I");
  CHECK_NEAR(mfs_hyper_paper000.mu0(m[0].c), mu0, 1e-9, "mu0 = c1 + c2");
}

/* Q(n) of the eq. 18 material (closed form, docs/finite-deformation.md B.4):
 * J^-1 [mu0 m I + (gamma - beta + c2 J^2) n (x) n], m = b1 n1^2 + b2 n2^2; the
 * in-plane condition g > 0 (B7). */
static double g_closed(double l1, double l2)
{
  const double c1 = 1.265e5, c2 = 1.012e4, lam = 1.012e7, mu0 = c1 + c2;
  double J = l1 * l2, lm = fmin(l1, l2);
  return mu0 * lm * lm + c1 / 3 * pow(J, 2.0 / 3.0) - 2 * c2 / 3 * pow(J, 4.0 / 3.0) +
         c2 * J * J + 2 * lam * (1 - log(J));
}

static void acoustic(void)
{
  mfs_hyper m = mfs_hyper_paper000_constants();
  const double c1 = 1.265e5, c2 = 1.012e4, lam = 1.012e7, mu0 = c1 + c2;
  double eq = 0.0, eqq = 0.0;
  const double st[][2] = {{1.3, 0.8}, {0.5, 1.7}, {1.9, 1.6}, {0.3, 0.35}, {1.05, 1.0}};
  for (size_t s = 0; s < sizeof st / sizeof st[0]; s++) {
    mfs_plane_state ps;
    CHECK(mfs_plane_state_stretch(&m, st[s][0], st[s][1], &ps) == MFS_OK, "state");
    double l1 = st[s][0], l2 = st[s][1], J = l1 * l2, b1 = l1 * l1, b2 = l2 * l2;
    double j23 = pow(J, 2.0 / 3.0), j43 = j23 * j23;
    double beta = -c1 * j23 - 2 * c2 * j43 + 2 * lam * log(J);
    double gamma = -2.0 / 3.0 * c1 * j23 - 8.0 / 3.0 * c2 * j43 + 2 * lam;
    for (int it = 0; it < 7; it++) {
      double th = 0.37 * it, n[2] = {cos(th), sin(th)}, Q[4];
      mfs_acoustic_tensor(ps.a, th, Q);
      double mm = b1 * n[0] * n[0] + b2 * n[1] * n[1];
      for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
          double want = (mu0 * mm * (i == k) + (gamma - beta + c2 * J * J) * n[i] * n[k]) / J / mu0;
          eq = fmax(eq, fabs(Q[i * 2 + k] - want) / fmax(1.0, fabs(want)));
        }
      /* Q0(N) = J |F^-T N|^2 Q(n), n = F^-T N / |F^-T N| */
      double N[2] = {cos(th + 0.1), sin(th + 0.1)}, Q0[4], Qn[4];
      mfs_acoustic_tensor(ps.A, th + 0.1, Q0);
      double v[2] = {N[0] / l1, N[1] / l2}, nv = hypot(v[0], v[1]);
      mfs_acoustic_tensor(ps.a, atan2(v[1], v[0]), Qn);
      for (int i = 0; i < 4; i++)
        eqq = fmax(eqq, fabs(Q0[i] - J * nv * nv * Qn[i]) / fmax(1.0, fabs(Q0[i])));
    }
  }
  CHECK(eq < 1e-12, "paper000 Q(n) vs closed form: rel. diff %.3g", eq);
  CHECK(eqq < 1e-12, "Q0(N) = J |F^-T N|^2 Q(n): rel. diff %.3g", eqq);

  /* The PDE domain on [0.3, 2]^2, 35 x 35: the library's test, the orthotropic
   * exact test (B5) and the closed form (B7) agree everywhere; 1128 stable. */
  int n1 = 0, n2 = 0, n3 = 0, disagree = 0;
  double jmin_unstable = INFINITY, jmax_stable = 0.0;
  for (int i = 0; i < 35; i++)
    for (int j = 0; j < 35; j++) {
      double l1 = 0.3 + 1.7 * i / 34.0, l2 = 0.3 + 1.7 * j / 34.0;
      mfs_plane_state ps;
      mfs_plane_state_stretch(&m, l1, l2, &ps);
      mfs_ellipticity e;
      CHECK(mfs_ellipticity_check(ps.a, 0, &e) == MFS_OK, "ellipticity");
      const double *a = ps.a;
      double p = a[P4(0, 0, 0, 0)], q = a[P4(0, 1, 0, 1)], r = a[P4(1, 0, 1, 0)],
             t = a[P4(1, 1, 1, 1)], u = a[P4(0, 0, 1, 1)] + a[P4(0, 1, 1, 0)];
      int s2 = p > 0 && q > 0 && r > 0 && t > 0 && p * t + q * r - u * u > -2 * sqrt(p * q * r * t);
      int s3 = g_closed(l1, l2) > 0;
      n1 += e.stable;
      n2 += s2;
      n3 += s3;
      disagree += (e.stable != s2) || (s2 != s3);
      if (!e.stable)
        jmin_unstable = fmin(jmin_unstable, l1 * l2);
      else
        jmax_stable = fmax(jmax_stable, l1 * l2);
    }
  CHECK(n1 == 1128 && n2 == 1128 && n3 == 1128 && disagree == 0,
        "PDE domain: %d, %d, %d stable of 1225 (want 1128), %d disagree", n1, n2, n3, disagree);
  CHECK(jmin_unstable > 2.77 && jmin_unstable < 2.85, "smallest unstable J %g (near e)", jmin_unstable);

  /* neo-Hookean closed form: lambda (1 - ln J) + mu (1 + min l^2) > 0 */
  mfs_hyper nh = mfs_hyper_isotropic(&mfs_hyper_neo_hookean, 1.0, 0.45, 1.0);
  int bad = 0;
  for (int i = 0; i < 30; i++)
    for (int j = 0; j < 30; j++) {
      double l1 = 0.3 + 4.0 * i / 29.0, l2 = 0.3 + 4.0 * j / 29.0, J = l1 * l2, lm = fmin(l1, l2);
      mfs_plane_state ps;
      mfs_plane_state_stretch(&nh, l1, l2, &ps);
      mfs_ellipticity e;
      mfs_ellipticity_check(ps.a, 0, &e);
      bad += e.stable != (nh.c[1] * (1 - log(J)) + nh.c[0] * (1 + lm * lm) > 0);
    }
  CHECK(bad == 0, "neo-Hookean ellipticity vs closed form: %d disagree", bad);

  /* the linear material: Q(n) = c(n) + sigma_nn I; sigma_xx = -1.5 mu makes the
   * transverse wave along x unstable: q_min = 1 - 1.5 at theta = 0 */
  mfs_plane_state ls;
  mfs_plane_state_linear(0.3, -1.5, 0.0, 0.0, &ls);
  mfs_ellipticity e;
  mfs_ellipticity_check(ls.a, 0, &e);
  CHECK(!e.stable, "linear, sigma_xx = -1.5: unstable");
  CHECK_NEAR(e.q_min, -0.5, 1e-12, "linear, sigma_xx = -1.5: q_min");
  CHECK(fabs(sin(e.theta)) < 1e-6, "linear, sigma_xx = -1.5: worst theta %g", e.theta);
  /* a shear stress: sigma = tau (e1 e2 + e2 e1) has sigma_nn = tau sin 2 theta, least -tau at
   * theta = 3 pi/4; with mu = 1 stable iff tau < 1 */
  mfs_plane_state_linear(0.25, 0.0, 0.0, 0.8, &ls);
  mfs_ellipticity_check(ls.a, 0, &e);
  CHECK(e.stable && fabs(e.q_min - 0.2) < 1e-12, "linear, tau = 0.8: q_min %g (want 0.2)", e.q_min);
  CHECK(fabs(e.theta - 0.75 * M_PI) < 1e-6, "linear, tau = 0.8: theta %g (want 3 pi/4)", e.theta);
  mfs_plane_state_linear(0.25, 0.0, 0.0, 1.2, &ls);
  mfs_ellipticity_check(ls.a, 0, &e);
  CHECK(!e.stable && fabs(e.q_min + 0.2) < 1e-12, "linear, tau = 1.2: q_min %g", e.q_min);
  /* and the linear plane state from the table equals mfs_plane_state_linear */
  mfs_hyper lin = mfs_hyper_isotropic(&mfs_hyper_linear, 1.0, 0.3, 1.0);
  mfs_plane_state a1, a2;
  mfs_plane_state_stretch(&lin, 1.0, 1.0, &a1);
  mfs_plane_state_linear(0.3, 0, 0, 0, &a2);
  double dl = 0.0;
  for (int i = 0; i < 16; i++)
    dl = fmax(dl, fabs(a1.a[i] - a2.a[i]));
  CHECK(maxabs(a1.a, 16) > 0 && dl < 1e-14, "linear table state: %g", dl);
  /* neo-Hookean at F = I is the linear material */
  mfs_plane_state_stretch(&nh, 1.0, 1.0, &a1);
  mfs_plane_state_linear(0.45, 0, 0, 0, &a2);
  dl = 0.0;
  for (int i = 0; i < 16; i++)
    dl = fmax(dl, fabs(a1.a[i] - a2.a[i]));
  CHECK(dl < 1e-13, "neo-Hookean at F = I = linear: %g", dl);
}

static void errors(void)
{
  mfs_hyper m = mfs_hyper_paper000_constants();
  mfs_plane_state s;
  CHECK(mfs_plane_state_stretch(&m, 0.0, 1.0, &s) == MFS_EINVAL, "stretch 0");
  CHECK(mfs_plane_state_stretch(&m, 1.0, -0.5, &s) == MFS_EINVAL, "stretch < 0");
  CHECK(mfs_plane_state_stretch(&m, NAN, 1.0, &s) == MFS_EINVAL, "stretch NaN");
  mfs_hyper lin = mfs_hyper_isotropic(&mfs_hyper_linear, 1.0, 0.3, 1.0);
  CHECK(mfs_plane_state_stretch(&lin, 1.1, 1.0, &s) == MFS_EINVAL, "linear with a stretch");
  const double F[9] = {1, 0, 0, 0, -1, 0, 0, 0, 1};
  CHECK(mfs_hyper_eval(&m, F, NULL, NULL, NULL, NULL, NULL) == MFS_EINVAL, "det F < 0");
  CHECK(mfs_hyper_eval(&lin, Fs[0], NULL, NULL, NULL, NULL, NULL) == MFS_EINVAL, "linear eval");
  CHECK(mfs_plane_state_linear(0.5, 0, 0, 0, &s) == MFS_EINVAL, "nu = 0.5");
  double t[16] = {0};
  t[0] = NAN;
  mfs_ellipticity e;
  CHECK(mfs_ellipticity_check(t, 0, &e) == MFS_EINVAL, "NaN tangent");
  CHECK(mfs_ellipticity_check(t, 4, &e) == MFS_EINVAL, "too few samples");
  CHECK(mfs_hyper_find("paper000") == &mfs_hyper_paper000 && !mfs_hyper_find("rubber"), "find");
}

int main(void)
{
  stresses();
  tangents();
  acoustic();
  errors();
  return check_summary("test_hyper");
}
