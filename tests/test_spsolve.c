/* Sparse direct solves (mfs_spsolve.h): CHOLMOD and UMFPACK agree with each
 * other and with the known solution of a symmetric positive definite system
 * (a 2D Laplacian plus a diagonal), UMFPACK solves a non-symmetric one, the
 * constrained (saddle-point) solve by CHOLMOD's Schur complement agrees with
 * UMFPACK on the whole matrix and satisfies the constraints, and every status
 * is provoked: a singular matrix, a non-positive pivot, an rcond threshold,
 * bad arguments. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

/* The n^2 x n^2 five-point Laplacian plus shift on the diagonal, times s on
 * the off-diagonal (s = 1 symmetric); asym adds asym to the entry right of
 * the diagonal. */
static mfs_csr *laplacian(int n, double shift, double asym)
{
  int N = n * n;
  mfs_csr *A = mfs_csr_alloc((size_t)N, (size_t)N, (size_t)N * 5);
  size_t e = 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      int r = j * n + i;
      /* unsorted on purpose: the diagonal last */
      if (i > 0)
        A->idx[e] = r - 1, A->val[e++] = -1.0;
      if (j > 0)
        A->idx[e] = r - n, A->val[e++] = -1.0;
      if (i < n - 1)
        A->idx[e] = r + 1, A->val[e++] = -1.0 + asym;
      if (j < n - 1)
        A->idx[e] = r + n, A->val[e++] = -1.0;
      A->idx[e] = r, A->val[e++] = 4.0 + shift;
      A->ptr[r + 1] = e;
    }
  return A;
}

static double maxdiff(size_t n, const double *a, const double *b)
{
  double d = 0.0;
  for (size_t i = 0; i < n; i++)
    d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

int main(void)
{
  const int n = 23;
  const size_t N = (size_t)n * n;
  double *x = malloc(N * sizeof *x), *b = malloc(N * sizeof *b), *y1 = malloc(N * sizeof *y1),
         *y2 = malloc(N * sizeof *y2);
  for (size_t i = 0; i < N; i++)
    x[i] = sin(0.37 * (double)i) + 0.2385;
  /* symmetric positive definite: both solvers find x */
  mfs_csr *A = laplacian(n, 0.0137, 0.0);
  mfs_csr_matvec(A, x, b);
  mfs_spsolve_info i1, i2;
  CHECK(mfs_spsolve(&mfs_spsolve_cholmod, A, b, y1, 1e-15, &i1) == MFS_OK, "cholmod SPD");
  CHECK(mfs_spsolve(&mfs_spsolve_umfpack, A, b, y2, 1e-15, &i2) == MFS_OK, "umfpack SPD");
  CHECK(maxdiff(N, y1, x) < 1e-11 && maxdiff(N, y2, x) < 1e-11, "SPD solutions: %.3g %.3g",
        maxdiff(N, y1, x), maxdiff(N, y2, x));
  CHECK(i1.backward < 1e-15 && i2.backward < 1e-15, "backward errors %.3g %.3g", i1.backward,
        i2.backward);
  CHECK(i1.rcond > 0.0 && i1.rcond <= 1.0 && i2.rcond > 0.0 && i2.rcond <= 1.0, "rcond %g %g",
        i1.rcond, i2.rcond);
  CHECK(mfs_spsolve_find("cholmod") == &mfs_spsolve_cholmod && !mfs_spsolve_find("lapack"),
        "lookup");
  /* the rcond threshold: above the estimate is singular */
  CHECK(mfs_spsolve(&mfs_spsolve_umfpack, A, b, y2, 0.999, &i2) == MFS_ESYSTEM,
        "umfpack rcond_min 0.999");
  CHECK(mfs_spsolve(&mfs_spsolve_cholmod, A, b, y2, 0.999, &i2) == MFS_ESYSTEM,
        "cholmod rcond_min 0.999");
  mfs_csr_free(A);
  /* non-symmetric: UMFPACK */
  A = laplacian(n, 0.5, 0.3183);
  mfs_csr_matvec(A, x, b);
  CHECK(mfs_spsolve(&mfs_spsolve_umfpack, A, b, y2, 1e-15, &i2) == MFS_OK &&
          maxdiff(N, y2, x) < 1e-11,
        "umfpack non-symmetric: %.3g", maxdiff(N, y2, x));
  mfs_csr_free(A);
  /* indefinite: shift -4 makes the diagonal 0 */
  A = laplacian(n, -4.0, 0.0);
  CHECK(mfs_spsolve(&mfs_spsolve_cholmod, A, b, y1, 1e-15, &i1) == MFS_ESYSTEM,
        "cholmod: a non-positive pivot");
  mfs_csr_free(A);
  A = mfs_csr_alloc(3, 3, 3); /* [[1, 1, 0], [0, 1, 0], [0, 0, 0]]: a zero row */
  A->idx[0] = 0, A->val[0] = 1.0, A->idx[1] = 1, A->val[1] = 1.0;
  A->ptr[1] = 2;
  A->idx[2] = 1, A->val[2] = 1.0;
  A->ptr[2] = 3;
  A->ptr[3] = 3;
  double b3[3] = {1, 1, 0}, x3[3];
  CHECK(mfs_spsolve(&mfs_spsolve_umfpack, A, b3, x3, 1e-15, &i2) == MFS_ESYSTEM,
        "umfpack: a singular matrix");
  mfs_csr_free(A);
  /* bad arguments */
  A = mfs_csr_alloc(3, 4, 1);
  CHECK(mfs_spsolve(&mfs_spsolve_umfpack, A, b3, x3, 0.0, NULL) == MFS_EINVAL, "not square");
  CHECK(mfs_spsolve(NULL, A, b3, x3, 0.0, NULL) == MFS_EINVAL, "no solver");
  mfs_csr_free(A);
  /* constrained: [[A, C^T], [C, 0]] with A SPD and C = two rows */
  A = laplacian(n, 0.0, 0.0); /* the Dirichlet Laplacian: SPD */
  mfs_csr *C = mfs_csr_alloc(2, N, 4);
  C->idx[0] = 0, C->val[0] = 1.7, C->idx[1] = (int)N - 1, C->val[1] = -0.4;
  C->ptr[1] = 2;
  C->idx[2] = (int)N / 2, C->val[2] = 2.3, C->idx[3] = 5, C->val[3] = 0.9;
  C->ptr[2] = 4;
  double g[2] = {0.31, -0.77}, l1[2], l2[2];
  for (size_t i = 0; i < N; i++)
    b[i] = cos(0.11 * (double)i);
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_cholmod, A, C, NULL, b, g, y1, l1, 1e-15, &i1) == MFS_OK,
        "cholmod constrained");
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_umfpack, A, C, NULL, b, g, y2, l2, 1e-15, &i2) == MFS_OK,
        "umfpack constrained");
  double cx[2];
  mfs_csr_matvec(C, y1, cx);
  CHECK(fabs(cx[0] - g[0]) < 1e-13 && fabs(cx[1] - g[1]) < 1e-13, "constraints: %.3g %.3g",
        cx[0] - g[0], cx[1] - g[1]);
  CHECK(maxdiff(N, y1, y2) < 1e-12 && maxdiff(2, l1, l2) < 1e-12,
        "Schur complement and saddle-point matrix: x %.3g, lambda %.3g", maxdiff(N, y1, y2),
        maxdiff(2, l1, l2));
  CHECK(i1.backward < 1e-14 && i2.backward < 1e-14, "constrained backward %.3g %.3g", i1.backward,
        i2.backward);
  /* a non-symmetric constraint pair needs the saddle-point matrix: cholmod refuses */
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_cholmod, A, C, C, b, g, y1, NULL, 1e-15, NULL) ==
          MFS_EINVAL,
        "cholmod with C_test: EINVAL");
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_umfpack, A, C, C, b, g, y2, NULL, 1e-15, NULL) == MFS_OK &&
          maxdiff(N, y1, y2) < 1e-12,
        "umfpack with C_test = C");
  /* constraints that leave a null vector of A free: A = 0 with two constraints */
  mfs_csr *Z = mfs_csr_alloc(N, N, N);
  for (size_t i = 0; i < N; i++)
    Z->idx[i] = (int)i, Z->val[i] = 0.0, Z->ptr[i + 1] = i + 1;
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_cholmod, Z, C, NULL, b, g, y1, NULL, 1e-15, NULL) ==
          MFS_ESYSTEM,
        "cholmod constrained, singular");
  CHECK(mfs_spsolve_constrained(&mfs_spsolve_umfpack, Z, C, NULL, b, g, y1, NULL, 1e-15, NULL) ==
          MFS_ESYSTEM,
        "umfpack constrained, singular");
  mfs_csr_free(Z);
  mfs_csr_free(C);
  mfs_csr_free(A);
  free(x);
  free(b);
  free(y1);
  free(y2);
  return check_summary("test_spsolve");
}
