/* Values printed in Belytschko, Guo, Liu, Xiao (2000) that mfstab reproduces,
 * kept in one place for the tests and `mfstab reproduce`. */
#ifndef MFS_PAPER_H
#define MFS_PAPER_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Table I: stiffness K_jk of the 2D anti-plane problem, cubic spline, MLS,
 * D = 2, gamma = 1, for (j, k) >= 0 (the entries hold for all sign
 * combinations).  Columns: nodal, gauss2 (2x2 cells), gauss1 (one-point
 * cells), stress-quad.  0 marks a blank entry.  The -0.9193e-5 at (3, 2)
 * stands under the one-point column in the extracted text; it belongs to the
 * 2x2 column (docs/user-guide.md, Conventions). */
typedef struct {
  int j, k;
  double K[4];
} mfs_paper_table1_row;

extern const char *const mfs_paper_table1_rules[4];
extern const mfs_paper_table1_row mfs_paper_table1[];
extern const size_t mfs_paper_table1_len;

/* Half a unit in the last printed digit of v (4 significant digits). */
double mfs_paper_table1_tol(double v);

#ifdef __cplusplus
}
#endif

#endif
