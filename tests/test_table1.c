/* Paper 003 Table I: stiffness stencil K_jk of the 2D anti-plane problem,
 * cubic spline, MLS, D = 2, gamma = 1, lumped mass, for nodal, 2x2 cell,
 * one-point cell and quadrilateral stress-point quadrature.  Every printed
 * entry to its printed digits (4 significant); blank entries zero (to
 * roundoff where they are zero by symmetry, exactly where no quadrature
 * point couples the two particles). */
#include <stdlib.h>

#include "check.h"
#include "mfstab.h"

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
    const char *rule = mfs_paper_table1_rules[c];
    mfs_disc s = mfs_disc_default();
    s.dim = 2;
    s.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = 1.0, .gamma = 1.0};
    s.quadrature = mfs_quad_find(rule);
    s.kernel = &mfs_kernel_cubic;
    s.dilation = 2.0;
    mfs_stencil_entry *e;
    size_t n, bad;
    mfs_status st = mfs_stencil(&s, &e, &n, &bad);
    CHECK(st == MFS_OK, "%s: mfs_stencil status %d", rule, st);
    if (st != MFS_OK)
      continue;
    double k00 = 0.0;
    for (size_t t = 0; t < mfs_paper_table1_len; t++)
      for (int sj = -1; sj <= 1; sj += 2)
        for (int sk = -1; sk <= 1; sk += 2) {
          int j = sj * mfs_paper_table1[t].j, k = sk * mfs_paper_table1[t].k, found;
          double got = lookup(e, n, j, k, &found), want = mfs_paper_table1[t].K[c];
          if (j == 0 && k == 0)
            k00 = got;
          if (want != 0.0) {
            /* printed to 4 significant digits: half a unit of the 4th digit */
            CHECK(found, "%s (%d,%d): entry missing", rule, j, k);
            CHECK_NEAR(got, want, mfs_paper_table1_tol(want), "%s K(%d,%d)", rule, j, k);
          } else {
            CHECK(fabs(got) <= 1e-15 * 0.5, "%s K(%d,%d) = %.3g: blank entry not zero", rule,
                  j, k, got);
          }
        }
    /* every other entry of the stencil is zero; the row sums to zero (K times a constant) */
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
      sum += e[i].K;
      int listed = 0;
      for (size_t t = 0; t < mfs_paper_table1_len; t++)
        listed |= abs(e[i].j) == mfs_paper_table1[t].j && abs(e[i].k) == mfs_paper_table1[t].k;
      if (!listed)
        CHECK(fabs(e[i].K) <= 1e-15, "%s K(%d,%d) = %.3g not in Table I", rule, e[i].j,
              e[i].k, e[i].K);
      if (e[i].j == 0 && e[i].k == 0)
        CHECK_NEAR(e[i].M, 1.0, 1e-14, "%s lumped mass = dx dy (eq. 119)", rule);
      else
        CHECK(e[i].M == 0.0, "%s lumped mass off the diagonal", rule);
    }
    CHECK_NEAR(sum, 0.0, 1e-14 * k00, "%s row sum of K", rule);
    /* stress points on quadrilateral centres = half nodal + half one-point cells (section 4.4) */
    free(e);
  }
  return check_summary("test_table1");
}
