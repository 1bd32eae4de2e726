#include "mfs_shape.h"
#include "mfs_mls1d.h"

#include <math.h>
#include <string.h>

#include "mfs_status.h"

#define MAXD 3
#define MAXM 4

size_t mfs_shape_work_len(int dim, int nn)
{
  /* kernel values (1 + dim + dim^2, at least 5) and a Shepard scratch (1 + dim) per neighbour */
  return (size_t)nn * (size_t)(5 + 2 + 2 * dim + dim * dim) + 8;
}

/* W, grad W, Hessian W with respect to X, per neighbour: kw[J*(1+dim+dim^2)]. */
static void kernel_values(const mfs_shape_ctx *c, int nn, const double *d, int order, double *kw)
{
  int dim = c->dim, st = 1 + dim + dim * dim;
  for (int J = 0; J < nn; J++) {
    const double *dj = d + J * dim;
    double r2 = 0.0;
    for (int k = 0; k < dim; k++)
      r2 += dj[k] * dj[k];
    double r = sqrt(r2);
    mfs_kernel_value kv = mfs_kernel_radial(c->kernel, dim, c->a, r);
    double *o = kw + J * st;
    o[0] = kv.W;
    for (int k = 0; k < dim; k++) /* grad_X W(|X - X_J|) = W'(r) (X - X_J)/r */
      o[1 + k] = -kv.dW_r * dj[k];
    if (order >= 2) {
      double t = r2 > 0.0 ? (kv.d2W - kv.dW_r) / r2 : 0.0;
      for (int k = 0; k < dim; k++)
        for (int l = 0; l < dim; l++)
          o[1 + dim + k * dim + l] = (k == l ? kv.dW_r : 0.0) + t * dj[k] * dj[l];
    }
  }
}

/* Cholesky of the m x m SPD matrix A (row-major) into L; 0 on success. */
static int cholesky(int m, const double *A, double *L)
{
  for (int i = 0; i < m; i++)
    for (int j = 0; j <= i; j++) {
      double s = A[i * m + j];
      for (int k = 0; k < j; k++)
        s -= L[i * m + k] * L[j * m + k];
      if (i == j) {
        if (!(s > 0.0))
          return -1;
        L[i * m + i] = sqrt(s);
      } else {
        L[i * m + j] = s / L[j * m + j];
      }
    }
  return 0;
}

static void chol_solve(int m, const double *L, double *b)
{
  for (int i = 0; i < m; i++) {
    double s = b[i];
    for (int k = 0; k < i; k++)
      s -= L[i * m + k] * b[k];
    b[i] = s / L[i * m + i];
  }
  for (int i = m - 1; i >= 0; i--) {
    double s = b[i];
    for (int k = i + 1; k < m; k++)
      s -= L[k * m + i] * b[k];
    b[i] = s / L[i * m + i];
  }
}

/* 1-norm reciprocal condition number from A and the explicit inverse. */
static double rcond_from(int m, const double *A, const double *Ainv)
{
  double na = 0.0, ni = 0.0;
  for (int j = 0; j < m; j++) {
    double sa = 0.0, si = 0.0;
    for (int i = 0; i < m; i++) {
      sa += fabs(A[i * m + j]);
      si += fabs(Ainv[i * m + j]);
    }
    na = sa > na ? sa : na;
    ni = si > ni ? si : ni;
  }
  double rc = 1.0 / (na * ni);
  return isfinite(rc) ? rc : 0.0;
}

/* Cholesky factor L (lower triangle written) and explicit inverse of the
 * m x m SPD moment matrix A, with its 1-norm reciprocal condition number;
 * MFS_ESINGULAR when A is not positive definite or *rcond < rcond_min. */
static mfs_status moment_inverse(int m, const double *A, double rcond_min, double *L, double *Ainv,
                                 double *rcond)
{
  *rcond = 0.0;
  if (cholesky(m, A, L))
    return MFS_ESINGULAR;
  for (int j = 0; j < m; j++) {
    double e[MAXM] = {0};
    e[j] = 1.0;
    chol_solve(m, L, e);
    for (int i = 0; i < m; i++)
      Ainv[i * m + j] = e[i];
  }
  *rcond = rcond_from(m, A, Ainv);
  return *rcond < rcond_min || *rcond == 0.0 ? MFS_ESINGULAR : MFS_OK;
}

/* Moving least squares with basis [1] (m = 1, Shepard) or [1, (Y - X)/a]
 * (m = 1 + dim), weights mult_J W_J.  Derivatives by differentiating
 * A gamma = p(X) (Belytschko et al. 1996): gamma' = A^-1 (p' - A' gamma), ...
 * Output in out[J*os + ...] up to `order` (0, 1, 2). */
static int mls_core(const mfs_shape_ctx *c, int m, int nn, const double *d, const double *kw,
                    const double *mult, int order, double *out, int os, double *rcond)
{
  int dim = c->dim, st = 1 + dim + dim * dim;
  double A[MAXM * MAXM] = {0}, dA[MAXD][MAXM * MAXM] = {{0}}, d2A[MAXD * MAXD][MAXM * MAXM] = {{0}};
  double p[MAXM];
  double ia = 1.0 / c->a;
  for (int J = 0; J < nn; J++) {
    const double *k = kw + J * st;
    double s = mult ? mult[J] : 1.0;
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    for (int i = 0; i < m; i++)
      for (int j = 0; j <= i; j++) {
        double pp = s * p[i] * p[j];
        A[i * m + j] += pp * k[0];
        if (order >= 1)
          for (int q = 0; q < dim; q++)
            dA[q][i * m + j] += pp * k[1 + q];
        if (order >= 2)
          for (int q = 0; q < dim * dim; q++)
            d2A[q][i * m + j] += pp * k[1 + dim + q];
      }
  }
  for (int i = 0; i < m; i++) /* symmetric fill */
    for (int j = i + 1; j < m; j++) {
      A[i * m + j] = A[j * m + i];
      for (int q = 0; q < dim; q++)
        dA[q][i * m + j] = dA[q][j * m + i];
      for (int q = 0; q < dim * dim; q++)
        d2A[q][i * m + j] = d2A[q][j * m + i];
    }
  double L[MAXM * MAXM] = {0}, Ainv[MAXM * MAXM];
  if (moment_inverse(m, A, c->rcond_min, L, Ainv, rcond) != MFS_OK)
    return MFS_ESINGULAR;

  double g[MAXM], dg[MAXD][MAXM], d2g[MAXD * MAXD][MAXM];
  for (int i = 0; i < m; i++)
    g[i] = Ainv[i * m];
  for (int q = 0; q < dim && order >= 1; q++) {
    double r[MAXM];
    for (int i = 0; i < m; i++) {
      double s = (m > 1 && i == q + 1) ? ia : 0.0;
      for (int j = 0; j < m; j++)
        s -= dA[q][i * m + j] * g[j];
      r[i] = s;
    }
    chol_solve(m, L, r);
    memcpy(dg[q], r, sizeof r);
  }
  for (int q = 0; q < dim && order >= 2; q++)
    for (int t = 0; t < dim; t++) {
      double r[MAXM];
      for (int i = 0; i < m; i++) {
        double s = 0.0;
        for (int j = 0; j < m; j++)
          s -= dA[q][i * m + j] * dg[t][j] + dA[t][i * m + j] * dg[q][j] +
               d2A[q * dim + t][i * m + j] * g[j];
        r[i] = s;
      }
      chol_solve(m, L, r);
      memcpy(d2g[q * dim + t], r, sizeof r);
    }

  for (int J = 0; J < nn; J++) {
    const double *k = kw + J * st;
    double s = mult ? mult[J] : 1.0;
    double w = s * k[0], dw[MAXD], gp = 0.0, dgp[MAXD] = {0};
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    for (int i = 0; i < m; i++)
      gp += g[i] * p[i];
    double *o = out + (size_t)J * os;
    o[0] = gp * w;
    if (order < 1)
      continue;
    for (int q = 0; q < dim; q++) {
      dw[q] = s * k[1 + q];
      for (int i = 0; i < m; i++)
        dgp[q] += dg[q][i] * p[i];
      o[1 + q] = dgp[q] * w + gp * dw[q];
    }
    if (order < 2)
      continue;
    for (int q = 0; q < dim; q++)
      for (int t = 0; t < dim; t++) {
        double d2gp = 0.0;
        for (int i = 0; i < m; i++)
          d2gp += d2g[q * dim + t][i] * p[i];
        o[1 + dim + q * dim + t] = d2gp * w + dgp[q] * dw[t] + dgp[t] * dw[q] +
                                   gp * s * k[1 + dim + q * dim + t];
      }
  }
  return MFS_OK;
}

/* Inverse of a dim x dim matrix by Gauss-Jordan with partial pivoting. */
static int small_inverse(int n, const double *A, double *Ai)
{
  double M[MAXD * 2 * MAXD];
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 2 * n; j++)
      M[i * 2 * n + j] = j < n ? A[i * n + j] : (j - n == i ? 1.0 : 0.0);
  for (int col = 0; col < n; col++) {
    int piv = col;
    for (int i = col + 1; i < n; i++)
      if (fabs(M[i * 2 * n + col]) > fabs(M[piv * 2 * n + col]))
        piv = i;
    if (M[piv * 2 * n + col] == 0.0)
      return -1;
    for (int j = 0; j < 2 * n; j++) {
      double t = M[col * 2 * n + j];
      M[col * 2 * n + j] = M[piv * 2 * n + j];
      M[piv * 2 * n + j] = t;
    }
    double inv = 1.0 / M[col * 2 * n + col];
    for (int j = 0; j < 2 * n; j++)
      M[col * 2 * n + j] *= inv;
    for (int i = 0; i < n; i++)
      if (i != col) {
        double f = M[i * 2 * n + col];
        for (int j = 0; j < 2 * n; j++)
          M[i * 2 * n + j] -= f * M[col * 2 * n + j];
      }
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      Ai[i * n + j] = M[i * 2 * n + n + j];
  return 0;
}

/* Correct the gradient vectors h_J stored in the gradient slots of out so
 * that sum_J G_J (X_J - X)^T = I (paper 000 eqs 29-31): G_J = a h_J with
 * a = C^-1, C = sum_J h_J (X_J - X)^T; with order 2 also d_n G_J from the
 * stored d_n h_J.  In place. */
static int correct_gradient(const mfs_shape_ctx *c, int nn, const double *d, int order,
                            double *out, int os, double *rcond)
{
  int dim = c->dim;
  double C[MAXD * MAXD] = {0}, a[MAXD * MAXD], S[MAXD] = {0};
  double dC[MAXD][MAXD * MAXD] = {{0}}, da[MAXD][MAXD * MAXD];
  for (int J = 0; J < nn; J++) {
    const double *o = out + (size_t)J * os;
    for (int l = 0; l < dim; l++) {
      S[l] += o[1 + l];
      for (int mm = 0; mm < dim; mm++) {
        C[l * dim + mm] += o[1 + l] * d[J * dim + mm];
        if (order >= 2)
          for (int n = 0; n < dim; n++)
            dC[n][l * dim + mm] += o[1 + dim + l * dim + n] * d[J * dim + mm];
      }
    }
  }
  *rcond = 0.0;
  if (small_inverse(dim, C, a))
    return MFS_ESINGULAR;
  *rcond = rcond_from(dim, C, a);
  if (*rcond < c->rcond_min || *rcond == 0.0)
    return MFS_ESINGULAR;
  if (order >= 2)
    for (int n = 0; n < dim; n++) {
      double t[MAXD * MAXD];
      for (int l = 0; l < dim; l++) /* d(X_J - X)/dX_n = -e_n */
        dC[n][l * dim + n] -= S[l];
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++) {
          double s = 0.0;
          for (int k = 0; k < dim; k++)
            s += dC[n][i * dim + k] * a[k * dim + j];
          t[i * dim + j] = s;
        }
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++) {
          double s = 0.0;
          for (int k = 0; k < dim; k++)
            s -= a[i * dim + k] * t[k * dim + j];
          da[n][i * dim + j] = s;
        }
    }
  for (int J = 0; J < nn; J++) {
    double *o = out + (size_t)J * os;
    double h[MAXD], dh[MAXD * MAXD];
    memcpy(h, o + 1, dim * sizeof *h);
    if (order >= 2)
      memcpy(dh, o + 1 + dim, dim * dim * sizeof *dh);
    for (int k = 0; k < dim; k++) {
      double s = 0.0;
      for (int l = 0; l < dim; l++)
        s += a[k * dim + l] * h[l];
      o[1 + k] = s;
      if (order < 2)
        continue;
      for (int n = 0; n < dim; n++) {
        double t = 0.0;
        for (int l = 0; l < dim; l++)
          t += da[n][k * dim + l] * h[l] + a[k * dim + l] * dh[l * dim + n];
        o[1 + dim + k * dim + n] = t;
      }
    }
  }
  return MFS_OK;
}


/* The fast paths' kernel at the scaled offset (px, py) = d / a: W and its
 * gradient with respect to X (grad_X W = -W'(r) d / r, with W'(r) / r =
 * cn w'(z) / (z a^2)); cn is the kernel's normalization over a^dim. */
static inline double fast_cn(const mfs_shape_ctx *c, double ia)
{
  double cn = c->kernel->norm[c->dim - 1] * ia;
  return c->dim == 2 ? cn * ia : cn;
}

static inline double fast_w(const mfs_shape_ctx *c, double cn, double ia, double px, double py,
                            double *gx, double *gy)
{
  double z = sqrt(px * px + py * py), w = 0.0, dw = 0.0, d2w;
  if (z < 1.0)
    c->kernel->eval(z, &w, &dw, &d2w);
  double t = z > 0.0 ? -cn * dw / z * ia : -cn * d2w * ia;
  *gx = t * px;
  *gy = t * py;
  return cn * w;
}

/* Linear MLS with gradients only, in 1D or 2D: the case every assembly of a
 * stiffness needs, written with scalars so that it unrolls (about twice as
 * fast as mls_core; same formulas).  The moment matrix is inverted by its
 * adjugate; a non-positive determinant or a small rcond is singular. */
static int mls_fast_order1(const mfs_shape_ctx *c, int nn, const double *d, double *out,
                           double *work, double *rcond)
{
  const int dim = c->dim, os = 1 + dim;
  const double ia = 1.0 / c->a, cn = fast_cn(c, ia);
  /* W, grad W (wrt X) and the scaled offsets p = d/a per neighbour */
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b00[2] = {0, 0}, b01[2] = {0, 0}, b02[2] = {0, 0}, b11[2] = {0, 0}, b12[2] = {0, 0},
         b22[2] = {0, 0};
  for (int J = 0; J < nn; J++) {
    double px = d[J * dim] * ia, py = dim == 2 ? d[J * dim + 1] * ia : 0.0, gx, gy;
    double W = fast_w(c, cn, ia, px, py, &gx, &gy);
    double *o = work + 5 * J;
    o[0] = W;
    o[1] = gx;
    o[2] = gy;
    o[3] = px;
    o[4] = py;
    a00 += W;
    a01 += W * px;
    a02 += W * py;
    a11 += W * px * px;
    a12 += W * px * py;
    a22 += W * py * py;
    b00[0] += gx;
    b01[0] += gx * px;
    b02[0] += gx * py;
    b11[0] += gx * px * px;
    b12[0] += gx * px * py;
    b22[0] += gx * py * py;
    b00[1] += gy;
    b01[1] += gy * px;
    b02[1] += gy * py;
    b11[1] += gy * px * px;
    b12[1] += gy * px * py;
    b22[1] += gy * py * py;
  }
  *rcond = 0.0;
  double g[3], dg[2][3];
  if (dim == 1) {
    double det = a00 * a11 - a01 * a01;
    if (!(det > 0.0))
      return MFS_ESINGULAR;
    double i00 = a11 / det, i01 = -a01 / det, i11 = a00 / det;
    double na = fmax(fabs(a00) + fabs(a01), fabs(a01) + fabs(a11));
    double ni = fmax(fabs(i00) + fabs(i01), fabs(i01) + fabs(i11));
    *rcond = 1.0 / (na * ni);
    if (!(*rcond >= c->rcond_min) || *rcond == 0.0)
      return MFS_ESINGULAR;
    g[0] = i00;
    g[1] = i01;
    /* dg = A^-1 (e1/a - dA g) */
    double r0 = -(b00[0] * g[0] + b01[0] * g[1]);
    double r1 = ia - (b01[0] * g[0] + b11[0] * g[1]);
    dg[0][0] = i00 * r0 + i01 * r1;
    dg[0][1] = i01 * r0 + i11 * r1;
    for (int J = 0; J < nn; J++) {
      const double *k = work + 5 * J;
      double gp = g[0] + g[1] * k[3], dgp = dg[0][0] + dg[0][1] * k[3];
      out[J * os] = gp * k[0];
      out[J * os + 1] = dgp * k[0] + gp * k[1];
    }
    return MFS_OK;
  }
  /* 3 x 3 symmetric inverse by the adjugate */
  double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22, c02 = a01 * a12 - a02 * a11;
  double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12, c22 = a00 * a11 - a01 * a01;
  double det = a00 * c00 + a01 * c01 + a02 * c02;
  if (!(det > 0.0))
    return MFS_ESINGULAR;
  double id = 1.0 / det;
  double i00 = c00 * id, i01 = c01 * id, i02 = c02 * id, i11 = c11 * id, i12 = c12 * id,
         i22 = c22 * id;
  double na = fmax(fabs(a00) + fabs(a01) + fabs(a02),
                   fmax(fabs(a01) + fabs(a11) + fabs(a12), fabs(a02) + fabs(a12) + fabs(a22)));
  double ni = fmax(fabs(i00) + fabs(i01) + fabs(i02),
                   fmax(fabs(i01) + fabs(i11) + fabs(i12), fabs(i02) + fabs(i12) + fabs(i22)));
  *rcond = 1.0 / (na * ni);
  if (!(*rcond >= c->rcond_min) || *rcond == 0.0)
    return MFS_ESINGULAR;
  g[0] = i00;
  g[1] = i01;
  g[2] = i02;
  for (int q = 0; q < 2; q++) {
    double r0 = -(b00[q] * g[0] + b01[q] * g[1] + b02[q] * g[2]);
    double r1 = (q == 0 ? ia : 0.0) - (b01[q] * g[0] + b11[q] * g[1] + b12[q] * g[2]);
    double r2 = (q == 1 ? ia : 0.0) - (b02[q] * g[0] + b12[q] * g[1] + b22[q] * g[2]);
    dg[q][0] = i00 * r0 + i01 * r1 + i02 * r2;
    dg[q][1] = i01 * r0 + i11 * r1 + i12 * r2;
    dg[q][2] = i02 * r0 + i12 * r1 + i22 * r2;
  }
  for (int J = 0; J < nn; J++) {
    const double *k = work + 5 * J;
    double gp = g[0] + g[1] * k[3] + g[2] * k[4];
    double dx = dg[0][0] + dg[0][1] * k[3] + dg[0][2] * k[4];
    double dy = dg[1][0] + dg[1][1] * k[3] + dg[1][2] * k[4];
    double *o = out + (size_t)J * os;
    o[0] = gp * k[0];
    o[1] = dx * k[0] + gp * k[1];
    o[2] = dy * k[0] + gp * k[2];
  }
  return MFS_OK;
}

/* The corrected Shepard gradient (kb) with gradients only, in 1D or 2D,
 * written with scalars as mls_fast_order1 (same formulas as kb_eval: the
 * Shepard functions, then G = C^-1 h with C = sum_J h_J (X_J - X)^T). */
static int kb_fast_order1(const mfs_shape_ctx *c, int nn, const double *d, double *out,
                          double *work, double *rcond)
{
  const int dim = c->dim, os = 1 + dim;
  const double ia = 1.0 / c->a, cn = fast_cn(c, ia);
  double S = 0.0, Sx = 0.0, Sy = 0.0;
  for (int J = 0; J < nn; J++) {
    double px = d[J * dim] * ia, py = dim == 2 ? d[J * dim + 1] * ia : 0.0;
    double *o = work + 3 * J;
    o[0] = fast_w(c, cn, ia, px, py, &o[1], &o[2]);
    S += o[0];
    Sx += o[1];
    Sy += o[2];
  }
  *rcond = 0.0;
  if (!(S > 0.0))
    return MFS_ESINGULAR;
  double iS = 1.0 / S, c00 = 0, c01 = 0, c10 = 0, c11 = 0;
  for (int J = 0; J < nn; J++) { /* Shepard values and gradients h_J; C = sum h d^T */
    double *o = work + 3 * J, *r = out + (size_t)J * os;
    double phi = o[0] * iS;
    r[0] = phi;
    o[1] = (o[1] - phi * Sx) * iS;
    o[2] = (o[2] - phi * Sy) * iS;
    double dx = d[J * dim], dy = dim == 2 ? d[J * dim + 1] : 0.0;
    c00 += o[1] * dx;
    c01 += o[1] * dy;
    c10 += o[2] * dx;
    c11 += o[2] * dy;
  }
  double i00, i01 = 0.0, i10 = 0.0, i11 = 0.0, na, ni;
  if (dim == 1) {
    if (c00 == 0.0)
      return MFS_ESINGULAR;
    i00 = 1.0 / c00;
    na = fabs(c00);
    ni = fabs(i00);
  } else {
    double det = c00 * c11 - c01 * c10;
    if (det == 0.0)
      return MFS_ESINGULAR;
    i00 = c11 / det;
    i01 = -c01 / det;
    i10 = -c10 / det;
    i11 = c00 / det;
    na = fmax(fabs(c00) + fabs(c10), fabs(c01) + fabs(c11));
    ni = fmax(fabs(i00) + fabs(i10), fabs(i01) + fabs(i11));
  }
  double rc = 1.0 / (na * ni);
  *rcond = isfinite(rc) ? rc : 0.0;
  if (*rcond < c->rcond_min || *rcond == 0.0)
    return MFS_ESINGULAR;
  for (int J = 0; J < nn; J++) {
    const double *o = work + 3 * J;
    double *r = out + (size_t)J * os;
    if (dim == 1) {
      r[1] = i00 * o[1];
    } else {
      r[1] = i00 * o[1] + i01 * o[2];
      r[2] = i10 * o[1] + i11 * o[2];
    }
  }
  return MFS_OK;
}

/* 1D linear MLS fused with the gather (mfs_shape_type.gather_1d): the body
 * is mfs_mls1d_gather (mfs_mls1d.h), specialized for each built-in kernel
 * (MFS_KERNEL_LIST) with the kernel's inline formula in place of the call
 * through its table. */
#define GATHER_ARGS                                                                          \
  const mfs_shape_ctx *c, const mfs_box *box, double x, const double *xp, const int *cand,   \
    size_t nc, int *idx, double *out, double *work, int *nn, double *rcond, const double *field, \
    double *grad
#define MFS_X_GATHER(name)                                                                   \
  static int mls_gather_1d_##name(GATHER_ARGS)                                               \
  {                                                                                          \
    return mfs_mls1d_gather(mfs_kernel_##name##_w, c, box, x, xp, cand, nc, idx, out, work, \
                              nn, rcond, field, grad, 1);                                    \
  }
MFS_KERNEL_LIST(MFS_X_GATHER)
#undef MFS_X_GATHER

static int mls_gather_1d_any(GATHER_ARGS)
{
  return mfs_mls1d_gather(c->kernel->eval, c, box, x, xp, cand, nc, idx, out, work, nn, rcond,
                            field, grad, 1);
}

static int (*const gather_by_kernel[MFS_KERNEL_NIDS])(GATHER_ARGS) = {
  [MFS_KERNEL_ID_NONE] = mls_gather_1d_any,
#define MFS_X_ENTRY(name) [MFS_KERNEL_ID_##name] = mls_gather_1d_##name,
  MFS_KERNEL_LIST(MFS_X_ENTRY)
#undef MFS_X_ENTRY
};

static mfs_shape_gather_1d_fn mls_gather_1d(const mfs_kernel_type *k)
{
  int id = k ? k->id : 0;
  return gather_by_kernel[id > 0 && id < MFS_KERNEL_NIDS ? id : 0];
}
#undef GATHER_ARGS

mfs_status mfs_shape_dpos_1d(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn, const double *d,
                      const double *v, int K, double *dphi, double *dgrad)
{
  if (!t->dpos_1d)
    return MFS_ENOTSUP;
  return t->dpos_1d(c, nn, d, v, K, dphi, dgrad);
}

/* sph: phi_J = V_J W(x_J - x), only J = K moves. */
static int sph_dpos(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int K,
                    double *dphi, double *dgrad)
{
  if (c->dim != 1 || nn < 1 || K < 0 || K >= nn)
    return MFS_EINVAL;
  for (int J = 0; J < nn; J++)
    dphi[J] = dgrad[J] = 0.0;
  mfs_kernel_value kv = mfs_kernel_radial(c->kernel, 1, c->a, fabs(d[K]));
  double sg = d[K] > 0.0 ? 1.0 : (d[K] < 0.0 ? -1.0 : 0.0);
  dphi[K] = v[K] * kv.dW * sg;
  dgrad[K] = -v[K] * kv.d2W;
  return MFS_OK;
}

/* Shepard (m = 1) and linear MLS (m = 2): dual numbers through the MLS formulas. */
static int mls_dpos_m(int m, const mfs_shape_ctx *c, int nn, const double *d, int K, double *dphi,
                      double *dgrad)
{
  if (c->dim != 1 || nn < 1 || K < 0 || K >= nn)
    return MFS_EINVAL;
  for (int J = 0; J < nn; J++)
    dphi[J] = dgrad[J] = 0.0;
  /* values (W, W_x = dW/dx, p) and their duals (derivatives wrt x_K) */
  double A[4] = {0}, At[4] = {0}, B[4] = {0}, Bt[4] = {0};
  double ia = 1.0 / c->a;
  for (int J = 0; J < nn; J++) {
    mfs_kernel_value kv = mfs_kernel_radial(c->kernel, 1, c->a, fabs(d[J]));
    double sg = d[J] > 0.0 ? 1.0 : (d[J] < 0.0 ? -1.0 : 0.0), e = J == K ? 1.0 : 0.0;
    double W = kv.W, Wt = kv.dW * sg * e, Wx = -kv.dW * sg, Wxt = -kv.d2W * e;
    double p[2] = {1.0, d[J] * ia}, pt[2] = {0.0, e * ia};
    for (int i = 0; i < m; i++)
      for (int j = 0; j < m; j++) {
        double pp = p[i] * p[j], ppt = pt[i] * p[j] + p[i] * pt[j];
        A[i * m + j] += W * pp;
        At[i * m + j] += Wt * pp + W * ppt;
        B[i * m + j] += Wx * pp;
        Bt[i * m + j] += Wxt * pp + Wx * ppt;
      }
  }
  double Ai[4];
  if (m == 1) {
    if (!(A[0] > 0.0))
      return MFS_ESINGULAR;
    Ai[0] = 1.0 / A[0];
  } else {
    double det = A[0] * A[3] - A[1] * A[2];
    if (!(det > 0.0))
      return MFS_ESINGULAR;
    Ai[0] = A[3] / det, Ai[1] = -A[1] / det, Ai[2] = -A[2] / det, Ai[3] = A[0] / det;
  }
#define MV(M, x, i) ((M)[(i) * m] * (x)[0] + (m > 1 ? (M)[(i) * m + 1] * (x)[1] : 0.0))
  double g[2], gt[2], gx[2], gxt[2], r[2], rt[2];
  for (int i = 0; i < m; i++)
    g[i] = Ai[i * m];
  for (int i = 0; i < m; i++) /* gamma~ = -A^-1 A~ gamma */
    r[i] = -MV(At, g, i);
  for (int i = 0; i < m; i++)
    gt[i] = MV(Ai, r, i);
  for (int i = 0; i < m; i++) /* gamma_x = A^-1 (e1/a - B gamma) */
    r[i] = (i == 1 ? ia : 0.0) - MV(B, g, i);
  for (int i = 0; i < m; i++)
    gx[i] = MV(Ai, r, i);
  for (int i = 0; i < m; i++) /* gamma_x~ = A^-1 (-A~ gamma_x - B~ gamma - B gamma~) */
    rt[i] = -MV(At, gx, i) - MV(Bt, g, i) - MV(B, gt, i);
  for (int i = 0; i < m; i++)
    gxt[i] = MV(Ai, rt, i);
#undef MV
  for (int J = 0; J < nn; J++) {
    mfs_kernel_value kv = mfs_kernel_radial(c->kernel, 1, c->a, fabs(d[J]));
    double sg = d[J] > 0.0 ? 1.0 : (d[J] < 0.0 ? -1.0 : 0.0), e = J == K ? 1.0 : 0.0;
    double W = kv.W, Wt = kv.dW * sg * e, Wx = -kv.dW * sg, Wxt = -kv.d2W * e;
    double p[2] = {1.0, d[J] * ia}, pt[2] = {0.0, e * ia};
    double gp = 0, gpt = 0, gxp = 0, gxpt = 0;
    for (int i = 0; i < m; i++) {
      gp += g[i] * p[i];
      gpt += gt[i] * p[i] + g[i] * pt[i];
      gxp += gx[i] * p[i];
      gxpt += gxt[i] * p[i] + gx[i] * pt[i];
    }
    dphi[J] = gpt * W + gp * Wt;
    dgrad[J] = gxpt * W + gxp * Wt + gpt * Wx + gp * Wxt;
  }
  return MFS_OK;
}

static int shepard_dpos(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int K,
                        double *dphi, double *dgrad)
{
  (void)v;
  return mls_dpos_m(1, c, nn, d, K, dphi, dgrad);
}

static int mls_dpos(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int K,
                    double *dphi, double *dgrad)
{
  (void)v;
  return mls_dpos_m(2, c, nn, d, K, dphi, dgrad);
}

mfs_status mfs_shape_dpos(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn, const double *d,
                          const double *v, int K, int l, double *dphi, double *dgrad)
{
  if (!t->dpos)
    return MFS_ENOTSUP;
  return t->dpos(c, nn, d, v, K, l, dphi, dgrad);
}

/* W, its gradient Wx and Hessian Wxx with respect to the evaluation point x,
 * for the offset d = x_J - x (the kernel_values formulas for one neighbour). */
static void kernel_one(const mfs_shape_ctx *c, const double *dj, double *W, double *Wx,
                       double *Wxx)
{
  int dim = c->dim;
  double r2 = 0.0;
  for (int k = 0; k < dim; k++)
    r2 += dj[k] * dj[k];
  mfs_kernel_value kv = mfs_kernel_radial(c->kernel, dim, c->a, sqrt(r2));
  double t = r2 > 0.0 ? (kv.d2W - kv.dW_r) / r2 : 0.0;
  *W = kv.W;
  for (int k = 0; k < dim; k++) {
    Wx[k] = -kv.dW_r * dj[k];
    for (int q = 0; q < dim; q++)
      Wxx[k * dim + q] = (k == q ? kv.dW_r : 0.0) + t * dj[k] * dj[q];
  }
}

/* sph, any dimension: phi_J = V_J W(x_J - x), only J = K moves:
 * d phi_K / d x_K,l = -V_K W_x,l, d g_K,m / d x_K,l = -V_K W_xx,ml. */
static int sph_dpos_dim(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int K,
                        int l, double *dphi, double *dgrad)
{
  int dim = c->dim;
  if (nn < 1 || K < 0 || K >= nn || l < 0 || l >= dim || dim > MAXD)
    return MFS_EINVAL;
  for (int J = 0; J < nn; J++) {
    dphi[J] = 0.0;
    for (int m = 0; m < dim; m++)
      dgrad[J * dim + m] = 0.0;
  }
  double W, Wx[MAXD], Wxx[MAXD * MAXD];
  kernel_one(c, d + K * dim, &W, Wx, Wxx);
  dphi[K] = -v[K] * Wx[l];
  for (int m = 0; m < dim; m++)
    dgrad[K * dim + m] = -v[K] * Wxx[m * dim + l];
  return MFS_OK;
}

/* Shepard (m = 1) and linear MLS (m = 1 + dim), any dimension: the 1D dual
 * numbers of mls_dpos_m with the basis p_J = [1, d_J / a], the dual unit on
 * d_K,l: W~_J = -delta_JK W_x,l, (W_x,q)~ = -delta_JK W_xx,ql, p~_K = e_{1+l}/a;
 * A = sum W p p^T, B_q = sum W_x,q p p^T, gamma = A^-1 e_0,
 * gamma_q = A^-1 (e_{1+q}/a - B_q gamma), and their duals. */
static int mls_dpos_dim_m(int m, const mfs_shape_ctx *c, int nn, const double *d, int K, int l,
                          double *dphi, double *dgrad)
{
  const int dim = c->dim;
  if (nn < 1 || K < 0 || K >= nn || l < 0 || l >= dim || dim > MAXD || m > MAXM)
    return MFS_EINVAL;
  const double ia = 1.0 / c->a;
  double A[MAXM * MAXM] = {0}, At[MAXM * MAXM] = {0};
  double B[MAXD][MAXM * MAXM] = {{0}}, Bt[MAXD][MAXM * MAXM] = {{0}};
  for (int J = 0; J < nn; J++) {
    double W, Wx[MAXD], Wxx[MAXD * MAXD], p[MAXM], pt[MAXM] = {0};
    kernel_one(c, d + J * dim, &W, Wx, Wxx);
    int e = J == K;
    double Wt = e ? -Wx[l] : 0.0, Wxt[MAXD];
    for (int q = 0; q < dim; q++)
      Wxt[q] = e ? -Wxx[q * dim + l] : 0.0;
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    if (e && m > 1)
      pt[1 + l] = ia;
    for (int i = 0; i < m; i++)
      for (int j = 0; j < m; j++) {
        double pp = p[i] * p[j], ppt = pt[i] * p[j] + p[i] * pt[j];
        A[i * m + j] += W * pp;
        At[i * m + j] += Wt * pp + W * ppt;
        for (int q = 0; q < dim; q++) {
          B[q][i * m + j] += Wx[q] * pp;
          Bt[q][i * m + j] += Wxt[q] * pp + Wx[q] * ppt;
        }
      }
  }
  double L[MAXM * MAXM] = {0};
  if (cholesky(m, A, L))
    return MFS_ESINGULAR;
  double g[MAXM] = {0}, gt[MAXM], gx[MAXD][MAXM], gxt[MAXD][MAXM];
  g[0] = 1.0;
  chol_solve(m, L, g);
  for (int i = 0; i < m; i++) { /* gamma~ = -A^-1 A~ gamma */
    double s = 0.0;
    for (int j = 0; j < m; j++)
      s -= At[i * m + j] * g[j];
    gt[i] = s;
  }
  chol_solve(m, L, gt);
  for (int q = 0; q < dim; q++) {
    for (int i = 0; i < m; i++) { /* gamma_q = A^-1 (e_{1+q}/a - B_q gamma) */
      double s = (m > 1 && i == q + 1) ? ia : 0.0;
      for (int j = 0; j < m; j++)
        s -= B[q][i * m + j] * g[j];
      gx[q][i] = s;
    }
    chol_solve(m, L, gx[q]);
    for (int i = 0; i < m; i++) { /* gamma_q~ = A^-1 (-A~ gamma_q - B_q~ gamma - B_q gamma~) */
      double s = 0.0;
      for (int j = 0; j < m; j++)
        s -= At[i * m + j] * gx[q][j] + Bt[q][i * m + j] * g[j] + B[q][i * m + j] * gt[j];
      gxt[q][i] = s;
    }
    chol_solve(m, L, gxt[q]);
  }
  for (int J = 0; J < nn; J++) {
    double W, Wx[MAXD], Wxx[MAXD * MAXD], p[MAXM], pt[MAXM] = {0};
    kernel_one(c, d + J * dim, &W, Wx, Wxx);
    int e = J == K;
    double Wt = e ? -Wx[l] : 0.0;
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    if (e && m > 1)
      pt[1 + l] = ia;
    double gp = 0.0, gpt = 0.0;
    for (int i = 0; i < m; i++) {
      gp += g[i] * p[i];
      gpt += gt[i] * p[i] + g[i] * pt[i];
    }
    dphi[J] = gpt * W + gp * Wt;
    for (int q = 0; q < dim; q++) {
      double gxp = 0.0, gxpt = 0.0, Wxt = e ? -Wxx[q * dim + l] : 0.0;
      for (int i = 0; i < m; i++) {
        gxp += gx[q][i] * p[i];
        gxpt += gxt[q][i] * p[i] + gx[q][i] * pt[i];
      }
      dgrad[J * dim + q] = gxpt * W + gxp * Wt + gpt * Wx[q] + gp * Wxt;
    }
  }
  return MFS_OK;
}

/* sph: only K = J moves phi_J = V_J W(x_J - x). */
static int sph_dpos_grad(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int J,
                         double *out, double *work)
{
  (void)work;
  int dim = c->dim;
  if (nn < 1 || J < 0 || J >= nn || dim > MAXD)
    return MFS_EINVAL;
  memset(out, 0, (size_t)nn * dim * dim * sizeof *out);
  double W, Wx[MAXD], Wxx[MAXD * MAXD];
  kernel_one(c, d + J * dim, &W, Wx, Wxx);
  for (int l = 0; l < dim; l++)
    for (int m = 0; m < dim; m++)
      out[(J * dim + l) * dim + m] = -v[J] * Wxx[m * dim + l];
  return MFS_OK;
}

/* mls_dpos_dim_m for the gradient of neighbour J only, every (K, l): the
 * sums A, B_q, their factorization and gamma, gamma_q are shared, and each
 * dual (A~, B_q~) has the rank-two form of the one neighbour K. */
static int mls_dpos_grad_m(int m, const mfs_shape_ctx *c, int nn, const double *d, int J,
                           double *out, double *work)
{
  const int dim = c->dim, st = 1 + dim + dim * dim;
  if (nn < 1 || J < 0 || J >= nn || dim > MAXD || m > MAXM)
    return MFS_EINVAL;
  const double ia = 1.0 / c->a;
  double A[MAXM * MAXM] = {0}, B[MAXD][MAXM * MAXM] = {{0}};
  for (int K = 0; K < nn; K++) { /* kernel values into work: W, Wx, Wxx per neighbour */
    double *kw = work + (size_t)K * st, p[MAXM];
    kernel_one(c, d + K * dim, kw, kw + 1, kw + 1 + dim);
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[K * dim + i - 1] * ia;
    for (int i = 0; i < m; i++)
      for (int j = 0; j < m; j++) {
        double pp = p[i] * p[j];
        A[i * m + j] += kw[0] * pp;
        for (int q = 0; q < dim; q++)
          B[q][i * m + j] += kw[1 + q] * pp;
      }
  }
  double L[MAXM * MAXM] = {0};
  if (cholesky(m, A, L))
    return MFS_ESINGULAR;
  double g[MAXM] = {0}, gx[MAXD][MAXM];
  g[0] = 1.0;
  chol_solve(m, L, g);
  for (int q = 0; q < dim; q++) {
    for (int i = 0; i < m; i++) {
      double s = (m > 1 && i == q + 1) ? ia : 0.0;
      for (int j = 0; j < m; j++)
        s -= B[q][i * m + j] * g[j];
      gx[q][i] = s;
    }
    chol_solve(m, L, gx[q]);
  }
  /* neighbour J's own values */
  const double *kJ = work + (size_t)J * st;
  double pJ[MAXM];
  pJ[0] = 1.0;
  for (int i = 1; i < m; i++)
    pJ[i] = d[J * dim + i - 1] * ia;
  double gpJ = 0.0, gxpJ[MAXD] = {0};
  for (int i = 0; i < m; i++) {
    gpJ += g[i] * pJ[i];
    for (int q = 0; q < dim; q++)
      gxpJ[q] += gx[q][i] * pJ[i];
  }
  for (int K = 0; K < nn; K++) {
    const double *kw = work + (size_t)K * st;
    double p[MAXM];
    p[0] = 1.0;
    for (int i = 1; i < m; i++)
      p[i] = d[K * dim + i - 1] * ia;
    double pg = 0.0, pgx[MAXD] = {0}; /* p_K . gamma, p_K . gamma_q */
    for (int i = 0; i < m; i++) {
      pg += p[i] * g[i];
      for (int q = 0; q < dim; q++)
        pgx[q] += p[i] * gx[q][i];
    }
    for (int l = 0; l < dim; l++) {
      /* A~ v = Wt p (p.v) + W (pt (p.v) + p (pt.v)), pt = e_{1+l}/a (m > 1) */
      double Wt = -kw[1 + l];
      double gt[MAXM], r[MAXM];
      for (int i = 0; i < m; i++) {
        double ptv = m > 1 ? g[1 + l] * ia : 0.0, pti = (m > 1 && i == 1 + l) ? ia : 0.0;
        r[i] = -(Wt * p[i] * pg + kw[0] * (pti * pg + p[i] * ptv));
      }
      for (int i = 0; i < m; i++)
        gt[i] = r[i];
      chol_solve(m, L, gt);
      double gtpJ = 0.0, ptJ = (K == J && m > 1) ? g[1 + l] * ia : 0.0; /* gamma~.p_J, gamma.p~_J */
      for (int i = 0; i < m; i++)
        gtpJ += gt[i] * pJ[i];
      double WtJ = K == J ? Wt : 0.0;
      for (int q = 0; q < dim; q++) {
        /* gamma_q~ = A^-1 (-A~ gamma_q - B_q~ gamma - B_q gamma~) */
        double Wxt = -kw[1 + dim + q * dim + l], Wx = kw[1 + q];
        double ptgx = m > 1 ? gx[q][1 + l] * ia : 0.0, ptg = m > 1 ? g[1 + l] * ia : 0.0;
        double gxt[MAXM];
        for (int i = 0; i < m; i++) {
          double pti = (m > 1 && i == 1 + l) ? ia : 0.0;
          double s = -(Wt * p[i] * pgx[q] + kw[0] * (pti * pgx[q] + p[i] * ptgx));
          s -= Wxt * p[i] * pg + Wx * (pti * pg + p[i] * ptg);
          for (int j = 0; j < m; j++)
            s -= B[q][i * m + j] * gt[j];
          gxt[i] = s;
        }
        chol_solve(m, L, gxt);
        double gxtpJ = 0.0, ptgxJ = (K == J && m > 1) ? gx[q][1 + l] * ia : 0.0;
        for (int i = 0; i < m; i++)
          gxtpJ += gxt[i] * pJ[i];
        double WxtJ = K == J ? Wxt : 0.0;
        /* d g_J,q = gx~.p_J W_J + gx.p~_J W_J + gx.p_J W~_J + g~.p_J Wx_J + g.p~_J Wx_J + g.p_J Wx~_J */
        out[(K * dim + l) * dim + q] = (gxtpJ + ptgxJ) * kJ[0] + gxpJ[q] * WtJ +
                                       (gtpJ + ptJ) * kJ[1 + q] + gpJ * WxtJ;
      }
    }
  }
  return MFS_OK;
}

static int shepard_dpos_grad(const mfs_shape_ctx *c, int nn, const double *d, const double *v,
                             int J, double *out, double *work)
{
  (void)v;
  return mls_dpos_grad_m(1, c, nn, d, J, out, work);
}

static int mls_dpos_grad(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int J,
                         double *out, double *work)
{
  (void)v;
  return mls_dpos_grad_m(1 + c->dim, c, nn, d, J, out, work);
}

mfs_status mfs_shape_dpos_grad(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn,
                               const double *d, const double *v, int J, double *out, double *work)
{
  if (!t->dpos_grad)
    return MFS_ENOTSUP;
  return t->dpos_grad(c, nn, d, v, J, out, work);
}

static int shepard_dpos_dim(const mfs_shape_ctx *c, int nn, const double *d, const double *v,
                            int K, int l, double *dphi, double *dgrad)
{
  (void)v;
  return mls_dpos_dim_m(1, c, nn, d, K, l, dphi, dgrad);
}

static int mls_dpos_dim(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int K,
                        int l, double *dphi, double *dgrad)
{
  (void)v;
  return mls_dpos_dim_m(1 + c->dim, c, nn, d, K, l, dphi, dgrad);
}

static int sph_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                    int order, double *out, double *work, double *rcond)
{
  (void)self;
  int dim = c->dim, os = mfs_shape_ncomp(dim, order), st = 1 + dim + dim * dim;
  kernel_values(c, nn, d, order, work);
  for (int J = 0; J < nn; J++)
    for (int i = 0; i < os; i++)
      out[(size_t)J * os + i] = v[J] * work[J * st + i];
  *rcond = 1.0;
  return MFS_OK;
}

static int shepard_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v,
                        int self, int order, double *out, double *work, double *rcond)
{
  (void)v;
  (void)self;
  kernel_values(c, nn, d, order, work);
  return mls_core(c, 1, nn, d, work, NULL, order, out, mfs_shape_ncomp(c->dim, order), rcond);
}

static int mls_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                    int order, double *out, double *work, double *rcond)
{
  (void)v;
  (void)self;
  if (order == 1 && c->dim <= 2)
    return mls_fast_order1(c, nn, d, out, work, rcond);
  kernel_values(c, nn, d, order, work);
  return mls_core(c, 1 + c->dim, nn, d, work, NULL, order, out, mfs_shape_ncomp(c->dim, order),
                  rcond);
}

static int kb_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                   int order, double *out, double *work, double *rcond)
{
  (void)v;
  (void)self;
  if (order == 1 && c->dim <= 2)
    return kb_fast_order1(c, nn, d, out, work, rcond);
  int os = mfs_shape_ncomp(c->dim, order);
  kernel_values(c, nn, d, order, work);
  int st = mls_core(c, 1, nn, d, work, NULL, order, out, os, rcond);
  if (st != MFS_OK)
    return st;
  double rc2;
  st = correct_gradient(c, nn, d, order, out, os, &rc2);
  *rcond = rc2 < *rcond ? rc2 : *rcond;
  return st;
}

/* The symmetrized SPH gradient o_J = V_J grad W_J - psi_J sum_K V_K grad W_K
 * (paper 000 eq. 33, paper 004 eq. 47), psi_J the reference: delta at the
 * point's own particle, the V-weighted Shepard function elsewhere; values
 * the V-weighted Shepard functions.  correct: normalized by the
 * Randles-Libersky matrix (paper 000 eq. 34, paper 004 eqs 68-69). */
static int sym_gradient(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                        int order, double *out, double *work, double *rcond, int correct)
{
  int dim = c->dim, os = mfs_shape_ncomp(dim, order), st = 1 + dim + dim * dim;
  double *kw = work, *sh = work + (size_t)nn * st; /* sh: V-weighted Shepard, order <= 1 */
  kernel_values(c, nn, d, order, kw);
  int s1 = mls_core(c, 1, nn, d, kw, v, order >= 2 ? 1 : 0, sh, 1 + dim, rcond);
  if (s1 != MFS_OK)
    return s1;
  double s[MAXD] = {0}, ds[MAXD * MAXD] = {0}; /* s = sum V_J grad W_J, ds[l][n] = d_n s_l */
  for (int J = 0; J < nn; J++)
    for (int l = 0; l < dim; l++) {
      s[l] += v[J] * kw[J * st + 1 + l];
      if (order >= 2)
        for (int n = 0; n < dim; n++)
          ds[l * dim + n] += v[J] * kw[J * st + 1 + dim + l * dim + n];
    }
  for (int J = 0; J < nn; J++) {
    double *o = out + (size_t)J * os;
    double psi = self >= 0 ? (J == self ? 1.0 : 0.0) : sh[J * (1 + dim)];
    o[0] = sh[J * (1 + dim)];
    for (int l = 0; l < dim; l++) {
      o[1 + l] = v[J] * kw[J * st + 1 + l] - psi * s[l];
      if (order >= 2)
        for (int n = 0; n < dim; n++) {
          double dpsi = self >= 0 ? 0.0 : sh[J * (1 + dim) + 1 + n];
          o[1 + dim + l * dim + n] =
            v[J] * kw[J * st + 1 + dim + l * dim + n] - dpsi * s[l] - psi * ds[l * dim + n];
        }
    }
  }
  if (!correct)
    return MFS_OK;
  double rc2;
  int s2 = correct_gradient(c, nn, d, order, out, os, &rc2);
  *rcond = rc2 < *rcond ? rc2 : *rcond;
  return s2;
}

static int rl_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                   int order, double *out, double *work, double *rcond)
{
  return sym_gradient(c, nn, d, v, self, order, out, work, rcond, 1);
}

static int sphs_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                     int order, double *out, double *work, double *rcond)
{
  return sym_gradient(c, nn, d, v, self, order, out, work, rcond, 0);
}

/* Corrected derivatives, method 2 (paper 004 eqs 63-64): with p_J = (1,
 * (X_J - X)/a) and A = sum_J W_J p_J p_J^T, q_J = A^-1 p_J, the values are
 * the MLS functions q_J[0] W_J (the Shepard factor of eq. 63 cancels) and
 * the gradient is the diffuse (Nayroles) derivative G_kJ = q_J[k+1] W_J / a,
 * which is not the derivative of the values.  Order 2: d_n G_kJ from
 * d_n q_J = A^-1 (d_n p_J - d_n A q_J), d_n p_J = -e_(n+1) / a. */
static int cd2_eval(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
                    int order, double *out, double *work, double *rcond)
{
  (void)v;
  (void)self;
  int dim = c->dim, m = 1 + dim, os = mfs_shape_ncomp(dim, order), st = 1 + dim + dim * dim;
  double ia = 1.0 / c->a, A[MAXM * MAXM] = {0}, dA[MAXD][MAXM * MAXM] = {{0}};
  kernel_values(c, nn, d, order, work);
  for (int J = 0; J < nn; J++) {
    const double *k = work + J * st;
    double p[MAXM] = {1.0};
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    for (int i = 0; i < m; i++)
      for (int j = 0; j < m; j++) {
        A[i * m + j] += k[0] * p[i] * p[j];
        for (int n = 0; n < dim && order >= 2; n++) {
          double dpi = i == n + 1 ? -ia : 0.0, dpj = j == n + 1 ? -ia : 0.0;
          dA[n][i * m + j] += k[1 + n] * p[i] * p[j] + k[0] * (dpi * p[j] + p[i] * dpj);
        }
      }
  }
  double L[MAXM * MAXM] = {0}, Ainv[MAXM * MAXM];
  if (moment_inverse(m, A, c->rcond_min, L, Ainv, rcond) != MFS_OK)
    return MFS_ESINGULAR;
  for (int J = 0; J < nn; J++) {
    const double *k = work + J * st;
    double p[MAXM] = {1.0}, q[MAXM] = {0};
    for (int i = 1; i < m; i++)
      p[i] = d[J * dim + i - 1] * ia;
    for (int i = 0; i < m; i++) {
      q[i] = 0.0;
      for (int j = 0; j < m; j++)
        q[i] += Ainv[i * m + j] * p[j];
    }
    double *o = out + (size_t)J * os;
    o[0] = q[0] * k[0];
    for (int l = 0; l < dim; l++)
      o[1 + l] = q[1 + l] * k[0] * ia;
    if (order < 2)
      continue;
    for (int n = 0; n < dim; n++) {
      double r[MAXM], dq[MAXM];
      for (int i = 0; i < m; i++) {
        r[i] = i == n + 1 ? -ia : 0.0;
        for (int j = 0; j < m; j++)
          r[i] -= dA[n][i * m + j] * q[j];
      }
      for (int i = 0; i < m; i++) {
        dq[i] = 0.0;
        for (int j = 0; j < m; j++)
          dq[i] += Ainv[i * m + j] * r[j];
      }
      for (int l = 0; l < dim; l++)
        o[1 + dim + l * dim + n] = (dq[1 + l] * k[0] + q[1 + l] * k[1 + n]) * ia;
    }
  }
  return MFS_OK;
}

const mfs_shape_type mfs_shape_sph = {.name = "sph",
                                      .uses_volumes = 1,
                                      .gradient_is_derivative = 1,
                                      .eval = sph_eval,
                                      .dpos_1d = sph_dpos,
                                      .dpos = sph_dpos_dim,
                                      .dpos_grad = sph_dpos_grad};
const mfs_shape_type mfs_shape_shepard = {.name = "shepard",
                                          .partition_of_unity = 1,
                                          .gradient_is_derivative = 1,
                                          .eval = shepard_eval,
                                          .dpos_1d = shepard_dpos,
                                          .dpos = shepard_dpos_dim,
                                          .dpos_grad = shepard_dpos_grad};
const mfs_shape_type mfs_shape_mls = {.name = "mls",
                                      .partition_of_unity = 1,
                                      .linear_complete = 1,
                                      .gradient_is_derivative = 1,
                                      .gradient_linear = 1,
                                      .eval = mls_eval,
                                      .dpos_1d = mls_dpos,
                                      .gather_1d = mls_gather_1d,
                                      .gather_1d_is_mls1d = 1,
                                      .dpos = mls_dpos_dim,
                                      .dpos_grad = mls_dpos_grad};
const mfs_shape_type mfs_shape_kb = {
  .name = "kb", .partition_of_unity = 1, .gradient_linear = 1, .eval = kb_eval};
const mfs_shape_type mfs_shape_rl = {.name = "rl",
                                     .uses_volumes = 1,
                                     .partition_of_unity = 1,
                                     .gradient_linear = 1,
                                     .uses_self = 1,
                                     .eval = rl_eval};
const mfs_shape_type mfs_shape_sphs = {
  .name = "sphs", .uses_volumes = 1, .partition_of_unity = 1, .uses_self = 1, .eval = sphs_eval};
const mfs_shape_type mfs_shape_cd2 = {
  .name = "cd2", .partition_of_unity = 1, .linear_complete = 1, .gradient_linear = 1,
  .eval = cd2_eval};

const mfs_shape_type *const mfs_shape_types[] = {
  &mfs_shape_sph, &mfs_shape_shepard, &mfs_shape_mls, &mfs_shape_kb,
  &mfs_shape_rl,  &mfs_shape_sphs,    &mfs_shape_cd2, NULL};

const mfs_shape_type *mfs_shape_find(const char *name)
{
  for (int i = 0; mfs_shape_types[i]; i++)
    if (strcmp(mfs_shape_types[i]->name, name) == 0)
      return mfs_shape_types[i];
  return NULL;
}
