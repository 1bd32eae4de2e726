/* Von Neumann (Bloch) dispersion analysis of a particle discretization on an
 * infinite uniform lattice: "path (a)".  The linearized operators are
 * assembled with the core machinery (shape tables, quadrature, assembly) on a
 * periodic box, the rows of one unit cell are kept with the lattice offset of
 * every coupling, and their Fourier symbols K(kappa), M(kappa) give
 * omega^2 as the eigenvalues of K v = omega^2 M v (one per branch).
 *
 * Normalization: spacing dx = 1, tangent modulus C = 1, density rho = 1, so
 * omega2 = (omega dx / c)^2 with c^2 = C / rho; kappa is given as
 * kappa dx / pi; sbar = sigma / C.
 *
 * Linearized internal force (scalar problems, paper 003 eqs 65-103):
 *   Lagrangian kernel:  K = (F^2 + sbar) A,                   A_IK = sum_Q w_Q phi_I'(Q) phi_K'(Q)
 *   Eulerian kernel:    K = A + sbar (2 A + G),                (eqs 70-75, 86-92)
 *       G_IK = sum_Q w_Q phi_I''(Q) (T_QK - delta_IK),  u~_Q = sum_K T_QK u~_K:
 *       T_QK = delta at a particle (eq. 71); at a stress or Gauss point
 *       T_QK = F (phi_K(Q) - phi_K'(Q) u_K), u_K = (1 - 1/F)(x_K - x_I) (eqs 90-92).
 *   Eulerian, consistent: G_IK = sum_Q w_Q [phi_I''(Q) T_QK + d phi_I'(Q) / d x_K],
 *       T_QK = delta at a particle, phi_K(Q) elsewhere (exact for linearly complete shapes).
 *   Least squares (Beissel-Belytschko, eqs 104-107): A += beta sum_Q w phi_I'' phi_K'',
 *       M_IK -= beta sum_Q w phi_I'' phi_K.
 * 2D anti-plane: K = (1 + sbar) A with A = sum_Q w grad phi_I . grad phi_K (eq. 113);
 * in-plane particle positions do not move, so both kernels give the same operator.
 * 2D plane strain: K_IJ = sum_Q w B_I^T D B_J with shear modulus 1 and the given
 * Poisson ratio; c is then the shear wave speed. */
#ifndef MFS_DISPERSION_H
#define MFS_DISPERSION_H

#include <stddef.h>

#include "mfs_assemble.h"
#include "mfs_disc.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The analysis: the discretization d (an infinite lattice: d.source.lattice
 * and, for the square lattice, d.source.gamma; the spacing, modulus and
 * density are normalized to 1, so d.source.spacing and d.material.modulus
 * and density do not enter; d.material.poisson does for plane strain),
 * plus the pre-stretch and the least-squares stabilization. */
typedef struct {
  mfs_disc disc;
  double stretch; /* pre-stretch F of the Eulerian 1D analysis (1 if 0) */
  double ls_beta; /* least-squares stabilization beta in dx^2 (0: none) */
} mfs_disp_spec;

typedef struct mfs_disp_plan mfs_disp_plan;

/* Build the unit-cell operators.  NULL with *status on failure
 * (MFS_ESINGULAR: singular moment matrix; MFS_ENOTSUP: a combination the
 * analysis does not cover: plane strain with least squares or a stretch,
 * the consistent frame outside 1D, for a shape without position derivatives
 * (mfs_shape_type.dpos_1d), or with a stretch for a shape that is not
 * linearly complete; MFS_EINVAL; MFS_ENOMEM). */
mfs_disp_plan *mfs_disp_plan_alloc(const mfs_disp_spec *spec, mfs_status *status);
void mfs_disp_plan_free(mfs_disp_plan *pl);

/* Number of branches (unit-cell particles times degrees of freedom). */
int mfs_disp_branches(const mfs_disp_plan *pl);

/* Reciprocal-lattice check: 1 if the wave vector k (2 components, in 1/dx)
 * is a reciprocal-lattice vector of the unit cell (the Bloch symbol equals
 * that at k = 0), within tol. */
int mfs_disp_is_reciprocal(const mfs_disp_plan *pl, const double *k, double tol);

/* omega^2 of every branch at wave vector k = kappa*pi*(cos theta, sin theta)
 * (theta in radians; 1D ignores it) and stress sbar, sorted by real part.
 * omega2 holds mfs_disp_branches() complex values; they are real for the
 * symmetric operators (Lagrangian) and may be complex otherwise.
 * Returns MFS_OK, MFS_ELAPACK, or MFS_EDOMAIN if the mass symbol is singular. */
mfs_status mfs_disp_omega2(const mfs_disp_plan *pl, double sbar, double kappa, double theta,
                           double _Complex *omega2);

/* Symbols at one wave vector, for checks: K(k) and M(k), nb x nb row-major. */
mfs_status mfs_disp_symbols(const mfs_disp_plan *pl, double sbar, const double *k,
                            double _Complex *K, double _Complex *M);

/* The spec the plan was built from. */
const mfs_disp_spec *mfs_disp_plan_spec(const mfs_disp_plan *pl);

/* The maximum wave number kappa dx / pi on the first Brillouin zone boundary
 * in direction theta: 1 along a lattice axis of the square lattice,
 * sqrt(2) at 45 degrees (paper section 4.4). */
double mfs_disp_kappa_max(const mfs_disp_plan *pl, double theta);

#ifdef __cplusplus
}
#endif

#endif
