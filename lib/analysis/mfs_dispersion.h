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
 * 2D plane strain under a homogeneous state (docs/finite-deformation.md C):
 * the rows hold the gradient products A^{jl}_IK = sum_Q w_Q d_j phi_I d_l phi_K
 * and, for an Eulerian kernel, G^{jk}_IK = sum_Q w_Q (D^IQ_K)_jk (mfs_assemble.h);
 * a state (mfs_hyper.h: sigma, a, A divided by mu0) contracts them:
 *   Lagrangian kernel:  K_IK,ik = A_ijkl A^{jl}_IK        (reference lattice,
 *       gradients, volumes; A the first elasticity tensor with the initial-stress
 *       term: the geometric stiffness; theory C.1-C.2)
 *   Eulerian kernel:    K_IK,ik = a_ijkl A^{jl} + sigma_im A^{km} + sigma_ij G^{jk}
 *       (current lattice x = F X, current volumes J V0, eq. C6): paper style
 *       (`eulerian`, the 2D eq. 71: phi_I a fixed function of x - x_I, stress
 *       points moved as eqs 90-92) or consistent (`eulerian-consistent`: shape
 *       functions re-solved at the moved particles, stress points moved with
 *       sum_K phi_K u~_K)
 *   M = rho0 V0 (lumped row sum) in both frames.
 * The state is the linear material (shear modulus 1, the Poisson ratio of
 * disc.material) under sigma/mu = (sbar, stress_yy, stress_xy) at F = I, or a
 * finite material (spec.material) at F = diag(stretch, stretch_y), normalized
 * by its small-strain shear modulus mu0, reference spacing and density: then
 * omega2 = omega^2 rho0 dx0^2 / mu0.  Wave vectors are in 1/dx0 in the frame's
 * configuration: reference (Lagrangian) or current (Eulerian; k = F^-T k0).
 * Anti-plane (scalar) physics: the kernel frame does not enter (in-plane
 * positions do not move), and sbar is the equibiaxial in-plane stress. */
#ifndef MFS_DISPERSION_H
#define MFS_DISPERSION_H

#include <stddef.h>

#include "mfs_assemble.h"
#include "mfs_disc.h"
#include "mfs_hyper.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The analysis: the discretization d (an infinite lattice: d.source.lattice
 * and, for the square lattice, d.source.gamma; the spacing, modulus and
 * density are normalized to 1, so d.source.spacing and d.material.modulus
 * and density do not enter; d.material.poisson does for plane strain),
 * plus the pre-stretch and the least-squares stabilization. */
/* How the radius of an Eulerian kernel follows a stretch F = diag(l1, l2)
 * (2D): with the particle volume, a = D dx0 sqrt(J) (the 1D rule for an
 * isotropic stretch; SPH codes with h ~ (m/rho)^(1/2)), or fixed, a = D dx0. */
typedef enum { MFS_SUPPORT_VOLUME, MFS_SUPPORT_REFERENCE } mfs_support_rule;

/* "volume", "reference"; parse: MFS_EINVAL if unknown. */
const char *mfs_support_rule_name(mfs_support_rule r);
mfs_status mfs_support_rule_parse(const char *name, mfs_support_rule *r);

typedef struct {
  mfs_disc disc;
  double stretch;   /* 1D: pre-stretch F of the Eulerian analysis; 2D plane strain: the
                       principal stretch l1 of F = diag(l1, l2) (1 if 0) */
  double ls_beta;   /* least-squares stabilization beta in dx^2 (0: none) */
  /* 2D plane strain */
  double stretch_y; /* l2 (1 if 0) */
  double stress_yy, stress_xy; /* linear material: sigma_yy / mu, sigma_xy / mu */
  mfs_hyper material;          /* a finite material (type NULL: the linear material) */
  mfs_support_rule support;    /* Eulerian kernel radius under a stretch */
} mfs_disp_spec;

typedef struct mfs_disp_plan mfs_disp_plan;

/* Build the unit-cell operators.  NULL with *status on failure
 * (MFS_ESINGULAR: singular moment matrix; MFS_ENOTSUP: a combination the
 * analysis does not cover: plane strain with least squares, a stretch in 2D
 * without a finite material or with anti-plane physics, stress_yy or
 * stress_xy without plane strain or with a finite material, the consistent
 * frame for a shape without position derivatives (mfs_shape_type.dpos_1d,
 * dpos) or with a stretch for a shape that is not linearly complete;
 * MFS_EINVAL (a bad spec: a stretch <= 0, a material that is not finite);
 * MFS_ENOMEM). */
mfs_disp_plan *mfs_disp_plan_alloc(const mfs_disp_spec *spec, mfs_status *status);
void mfs_disp_plan_free(mfs_disp_plan *pl);

/* Number of branches (unit-cell particles times degrees of freedom). */
int mfs_disp_branches(const mfs_disp_plan *pl);

/* The size of a plan's folded lattice sums, the work of one wave vector:
 * *offsets lattice offsets times *components symbol components (the real
 * parts, and the imaginary parts where the evaluation needs them), one
 * multiply and one add each; the phases and the eigen solve come on top. */
void mfs_disp_plan_work(const mfs_disp_plan *pl, size_t *offsets, int *components);

/* Reciprocal-lattice check: 1 if the wave vector k (2 components, in 1/dx)
 * is a reciprocal-lattice vector of the unit cell (the Bloch symbol equals
 * that at k = 0), within tol. */
int mfs_disp_is_reciprocal(const mfs_disp_plan *pl, const double *k, double tol);

/* omega^2 of every branch at wave vector k = kappa*pi*(cos theta, sin theta)
 * (theta in radians; 1D ignores it) and stress sbar, sorted by real part.
 * omega2 holds mfs_disp_branches() complex values; they are real for the
 * symmetric operators (Lagrangian) and may be complex otherwise.  With a
 * finite material the state is the plan's and sbar must be 0.
 * Returns MFS_OK, MFS_ELAPACK, MFS_EINVAL (sbar with a finite material), or
 * MFS_EDOMAIN if the mass symbol is singular (omega2 is then NaN).
 * How: the plan keeps the lattice sums folded over pairs of opposite offsets
 * d = i a1 + j a2, sum_t c_t e^{ik.d_t} = sum_t c_t - sum_o (c_o + c_-o)
 * (1 - cos k.d_o) + i sum_o (c_o - c_-o) sin k.d_o, with 1 - cos(m k.a) and
 * sin(m k.a) from tables built by the addition theorem per wave vector; the
 * 1 x 1 and lumped 2 x 2 eigenproblems in closed form. */
mfs_status mfs_disp_omega2(const mfs_disp_plan *pl, double sbar, double kappa, double theta,
                           double _Complex *omega2);

/* omega^2 along a ray: at the wave numbers kappa[0..n) (kappa dx / pi) in
 * direction theta and each stress sbar[0..nsbar), into omega2[s ld + i nb +
 * b] (nb = mfs_disp_branches; ld >= n nb, or 0 for n nb), the same values as
 * mfs_disp_omega2 point by point, bit for bit; the lattice sums of a wave
 * vector serve all the stresses.  Every point is computed on its own from the plan (which is only
 * read; nothing is allocated), so calls may run in parallel on one plan and
 * a ray split into pieces gives the same bits.  MFS_OK, or the status of the
 * first failing point in the order (stress, kappa) (MFS_EDOMAIN, MFS_ELAPACK:
 * the values of failing points are NaN, the others are computed), or of a
 * stress (MFS_EINVAL, as mfs_disp_omega2: nothing computed). */
mfs_status mfs_disp_ray(const mfs_disp_plan *pl, const double *sbar, size_t nsbar, double theta,
                        const double *kappa, size_t n, double _Complex *omega2, size_t ld);

/* Symbols at one wave vector, for checks: K(k) and M(k), nb x nb row-major,
 * summed term by term with a sincos per lattice offset (the reference the
 * folded sums of mfs_disp_omega2 are tested against). */
mfs_status mfs_disp_symbols(const mfs_disp_plan *pl, double sbar, const double *k,
                            double _Complex *K, double _Complex *M);

/* The normalized state of the analysis at stress sbar (plane strain): the
 * plan's finite state, or the linear material under (sbar, stress_yy,
 * stress_xy).  MFS_OK, MFS_EINVAL (not plane strain; sbar with a finite
 * material). */
mfs_status mfs_disp_state(const mfs_disp_plan *pl, double sbar, mfs_plane_state *s);

/* The same as mfs_disp_symbols and mfs_disp_omega2 for a given state s
 * (plane strain; an Eulerian plan holds the geometry of its own stretch,
 * so s must have the plan's stretches: MFS_EINVAL otherwise), and k in
 * 1/dx0 (2 components). */
mfs_status mfs_disp_symbols_state(const mfs_disp_plan *pl, const mfs_plane_state *s,
                                  const double *k, double _Complex *K, double _Complex *M);
mfs_status mfs_disp_omega2_state(const mfs_disp_plan *pl, const mfs_plane_state *s,
                                 const double *k, double _Complex *omega2);

/* mfs_disp_omega2_state at n wave vectors k[2 i .. 2 i + 1] into omega2[i nb
 * .. i nb + nb - 1], the same bits point by point, evaluated in blocks (as
 * mfs_disp_ray); reads the plan only.  MFS_OK, MFS_EINVAL as above, or the
 * status of the first failing point (its values NaN). */
mfs_status mfs_disp_omega2_states(const mfs_disp_plan *pl, const mfs_plane_state *s, size_t n,
                                  const double *k, double _Complex *omega2);

/* The continuum's long-wave limit: omega^2 / kappa^2 as kappa -> 0 along
 * theta, for each of the ndof polarizations (ascending): the eigenvalues of
 * the acoustic tensor with the initial-stress term over the density, in the
 * frame's wave vectors: Lagrangian Q0(N) / rho0, Eulerian J Q(n) / rho0;
 * 1D: F^2 + sbar (Lagrangian), 1 + sbar (Eulerian); anti-plane 1 + sbar.
 * A branch of a linearly complete Lagrangian (or consistent Eulerian)
 * discretization tends to one of them (tests/test_dispersion2d.c).
 * MFS_OK, MFS_EINVAL as mfs_disp_state. */
mfs_status mfs_disp_longwave(const mfs_disp_plan *pl, double sbar, double theta, double *q);

/* The PDE's stability at the analysed state: strong ellipticity of the
 * acoustic tensor (mfs_ellipticity_check on a; 1D and anti-plane the scalar
 * above), q_min in units of mu0 (theta the worst current direction). */
mfs_status mfs_disp_pde(const mfs_disp_plan *pl, double sbar, mfs_ellipticity *e);

/* The wave vector in the current configuration of a wave vector k of the
 * frame's lattice (Lagrangian: F^-T k; otherwise k itself), 1/dx0. */
void mfs_disp_current_k(const mfs_disp_plan *pl, const double *k, double *kc);

/* Lattice sums of a plane-strain plan at a fixed list of wave vectors, for
 * analyses that evaluate many states on one plan (a Lagrangian stretch or
 * stress map: the sums do not depend on the state): k[2 i .. 2 i + 1], i <
 * nk, in 1/dx0.  NULL with *status (MFS_EINVAL: not plane strain; MFS_ENOMEM). */
typedef struct mfs_disp_sample mfs_disp_sample;
mfs_disp_sample *mfs_disp_sample_alloc(const mfs_disp_plan *pl, size_t nk, const double *k,
                                       mfs_status *status);
void mfs_disp_sample_free(mfs_disp_sample *s);

/* omega^2 of every branch at wave vector i of the sample for state st (as
 * mfs_disp_omega2_state). */
mfs_status mfs_disp_sample_omega2(const mfs_disp_sample *s, size_t i, const mfs_plane_state *st,
                                  double _Complex *omega2);

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
