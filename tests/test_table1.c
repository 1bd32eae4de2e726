/* Paper 003 Table I: stiffness stencil K_jk of the 2D anti-plane problem,
 * cubic spline, MLS, D = 2, gamma = 1, lumped mass, for nodal, 2x2 cell,
 * one-point cell and quadrilateral stress-point quadrature.  Every printed
 * entry to its printed digits (4 significant); blank entries zero (to
 * roundoff where they are zero by symmetry, exactly where no quadrature
 * point couples the two particles). */
#include <stdlib.h>

#include "check.h"
#include "mfstab.h"

typedef struct {
  int j, k;
  double v[4]; /* nodal, gauss2, gauss1, stress-quad; 0 = blank */
} row;

/* Table I as printed; the -0.9193e-5 at (3,2) is in the 2x2 column (DESIGN.md). */
static const row table[] = {
  {0, 0, {0.5062, 0.6507, 0.8142, 0.6602}},
  {1, 0, {0.1101, 0.1016, 0.9911e-1, 0.1046}},
  {0, 1, {0.1101, 0.1016, 0.9911e-1, 0.1046}},
  {1, 1, {0, -0.5933e-1, -0.1456, -0.7282e-1}},
  {2, 0, {-0.1132, -0.8733e-1, -0.4677e-1, -0.7997e-1}},
  {0, 2, {-0.1132, -0.8733e-1, -0.4677e-1, -0.7997e-1}},
  {2, 1, {-0.5504e-1, -0.5223e-1, -0.4677e-1, -0.5090e-1}},
  {1, 2, {-0.5504e-1, -0.5223e-1, -0.4677e-1, -0.5090e-1}},
  {2, 2, {-0.1338e-1, -0.8851e-2, -0.4173e-2, -0.8778e-2}},
  {3, 0, {0, -0.2663e-2, -0.5564e-2, -0.2782e-2}},
  {0, 3, {0, -0.2663e-2, -0.5564e-2, -0.2782e-2}},
  {3, 1, {0, -0.8141e-3, -0.3478e-2, -0.1739e-2}},
  {1, 3, {0, -0.8141e-3, -0.3478e-2, -0.1739e-2}},
  {3, 2, {0, -0.9193e-5, 0, 0}},
  {2, 3, {0, -0.9193e-5, 0, 0}},
};

static const char *rules[4] = {"nodal", "gauss2", "gauss1", "stress-quad"};

static double lookup(const mfs_stencil_entry *e, size_t n, int j, int k, int *found)
{
  for (size_t i = 0; i < n; i++)
    if (e[i].j == j && e[i].k == k) {
      *found = 1;
      return e[i].K;
    }
  *found = 0;
  return 0.0;
}

int main(void)
{
  for (int c = 0; c < 4; c++) {
    mfs_stencil_spec s = {.dim = 2,
                          .lattice = MFS_LATTICE_SQUARE,
                          .dx = 1.0,
                          .gamma = 1.0,
                          .quadrature = rules[c],
                          .plan = {&mfs_kernel_cubic, &mfs_shape_mls, 2.0, 1, 1e-12},
                          .mat = {MFS_PHYS_SCALAR, 1.0, 0.0, 1.0},
                          .consistent_mass = 0};
    mfs_stencil_entry *e;
    size_t n, bad;
    int st = mfs_stencil(&s, &e, &n, &bad);
    CHECK(st == MFS_OK, "%s: mfs_stencil status %d", rules[c], st);
    if (st != MFS_OK)
      continue;
    double k00 = 0.0;
    for (size_t t = 0; t < sizeof table / sizeof table[0]; t++)
      for (int sj = -1; sj <= 1; sj += 2)
        for (int sk = -1; sk <= 1; sk += 2) {
          int j = sj * table[t].j, k = sk * table[t].k, found;
          double got = lookup(e, n, j, k, &found), want = table[t].v[c];
          if (j == 0 && k == 0)
            k00 = got;
          if (want != 0.0) {
            /* printed to 4 significant digits: half a unit of the 4th digit */
            double ulp4 = pow(10.0, floor(log10(fabs(want))) - 3);
            CHECK(found, "%s (%d,%d): entry missing", rules[c], j, k);
            CHECK_NEAR(got, want, 0.5 * ulp4 * (1 + 1e-9), "%s K(%d,%d)", rules[c], j, k);
          } else {
            CHECK(fabs(got) <= 1e-15 * 0.5, "%s K(%d,%d) = %.3g: blank entry not zero", rules[c],
                  j, k, got);
          }
        }
    /* every other entry of the stencil is zero; the row sums to zero (K times a constant) */
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
      sum += e[i].K;
      int listed = 0;
      for (size_t t = 0; t < sizeof table / sizeof table[0]; t++)
        listed |= abs(e[i].j) == table[t].j && abs(e[i].k) == table[t].k;
      if (!listed)
        CHECK(fabs(e[i].K) <= 1e-15, "%s K(%d,%d) = %.3g not in Table I", rules[c], e[i].j,
              e[i].k, e[i].K);
      if (e[i].j == 0 && e[i].k == 0)
        CHECK_NEAR(e[i].M, 1.0, 1e-14, "%s lumped mass = dx dy (eq. 119)", rules[c]);
      else
        CHECK(e[i].M == 0.0, "%s lumped mass off the diagonal", rules[c]);
    }
    CHECK_NEAR(sum, 0.0, 1e-14 * k00, "%s row sum of K", rules[c]);
    /* stress points on quadrilateral centres = half nodal + half one-point cells (section 4.4) */
    free(e);
  }
  return check_summary("test_table1");
}
