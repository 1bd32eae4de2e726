/* Cheap upper bounds on the largest eigenvalue lambda_max = omega_max^2 of
 * K v = lambda M v with the lumped (row-sum) mass, and the critical time
 * step of the central difference method (paper 003 section 5).
 *
 * Element eigenvalue inequality (eqs 121-124).  K = sum_Q K^Q and
 * M = sum_Q M^Q over the quadrature points Q, with
 *   K^Q = w_Q C sum grad phi_I . grad phi_J          (eqs 126, 140)
 *   M^Q = w_Q rho diag(phi_I S_Q),  S_Q = sum_J phi_J  (eqs 131, 139; the row
 *         sums of the consistent M^Q, whose sum over Q is the assembled lumped
 *         mass; S_Q = 1 for shape functions with the partition of unity)
 * so that lambda_max <= max_Q lambda^Q, lambda^Q the largest eigenvalue of
 * (K^Q, M^Q), provided every M^Q is positive definite, i.e. every phi_I > 0.
 * K^Q has rank dim (scalar problems), so lambda^Q is the largest eigenvalue
 * of a dim x dim matrix (w_Q cancels):
 *   1D (eq. 132)      lambda^Q = c^2 sum_I phi_I,x^2 / (phi_I S_Q)
 *   2D anti-plane     lambda^Q = c^2 lambda_max( sum_I g_I g_I^T / (phi_I S_Q) ),
 *                     g_I = grad phi_I: exact, eq. 141 (the off-diagonal sum
 *                     vanishes) is not assumed, so eq. 144 is its special case
 *   2D plane strain   lambda^Q = lambda_max( D^1/2 sum_I B_I B_I^T / (phi_I S_Q) D^1/2 ) / rho
 *                     (3 x 3), B_I the strain-displacement matrix of particle I
 * with c^2 = C / rho.  Particles whose degrees of freedom are removed (fixed)
 * are left out of the sums: the restriction of (K^Q, M^Q) to the free degrees
 * of freedom has no larger eigenvalue, so this is still a bound, and tighter.
 *
 * Negative shape functions.  Eq. 132 assumes phi_I > 0.  MLS shape
 * functions can be negative (near boundaries, at small dilations); then M^Q
 * is indefinite and the inequality does not hold.  Such terms are left out
 * of the sums and the quadrature points where they occur are counted
 * (negative_phi): where the count is not zero the bound is not guaranteed.
 *
 * Closed forms (eqs 134-137, 145-146).  On a uniform lattice without
 * boundary, phi_I = dx W_I (eq. 134), so in 1D lambda^Q = c^2 dx sum_I
 * W'_I^2 / W_I.  With W(r) = (norm / h) w(r / h) (h = a = D dx the support
 * radius, norm = 2 for the cubic spline of docs/user-guide.md), W'^2/W = (norm / h^3)
 * w'(z)^2 / w(z).  For the cubic spline on z <= 1/2, w = (2/3)(1 - 6 z^2 +
 * 6 z^3), and the algebra gives W'^2/W = (48 / h^3) g(z) with
 *   g(z) = z^2 (2 - 3 z)^2 / (1 - 6 z^2 + 6 z^3),  max g = 0.2587 at z = 0.4627:
 * this is the 0.2587 and the 48 of the line before eq. 136.  Counting N/2
 * terms of the sum at this maximum with N = 2 h / dx neighbours gives
 *   alpha = 48 * 0.2587 = norm * max_z w'(z)^2 / w(z) = 12.42        (eq. 136).
 * That step is a heuristic, not a bound: the Riemann sum of the interior
 * lambda^Q tends to c^2 int W'^2/W dx = 2 norm int_0^1 w'^2/w dz c^2/h^2
 * = 12.46 c^2/h^2 for the cubic spline.  In 2D the same limit is
 * lambda^Q = pi norm_2 int_0^1 w'^2/w z dz c^2/h^2 = 13.38 c^2/h^2 (cubic;
 * norm_2 = 2.7284), the eq. 145 constant printed as alpha_1 = 13.30. */
#ifndef MFS_BOUND_H
#define MFS_BOUND_H

#include <stddef.h>

#include "mfs_assemble.h"
#include "mfs_dispersion.h"
#include "mfs_material.h"
#include "mfs_model.h"
#include "mfs_plan.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  double lambda;        /* max_Q lambda^Q (eq. 124), 1/time^2 */
  size_t argmax;        /* a quadrature point where it is attained */
  double xmax[2];       /* its coordinates */
  size_t points;        /* quadrature points */
  size_t negative_phi;  /* points where some phi_I <= 0 (or S_Q <= 0): no guarantee there */
  size_t evaluated;     /* points at which shape functions were evaluated */
} mfs_bound_result;

/* lambda^Q at one point from its shape-table row: nn neighbours, ncomp
 * components each (mfs_shape.h layout), active[J] != 0 for free neighbours
 * (NULL: all).  dim 1 or 2; mat gives the physics, C (mat->modulus), nu and
 * rho.  Sets
 * *negative to 1 if some phi_J <= 0 or S <= 0.  Returns lambda^Q. */
double mfs_bound_point(int dim, const mfs_material *mat, int nn, const double *tab, int ncomp,
                       const unsigned char *active, int *negative);

/* The bound from a plan's shape table, or without one the points evaluated
 * one by one (the table's values, no table held), O(table size) time.
 * fixed: p->n flags (NULL: none fixed).  In parallel, the same result for
 * any number of threads.  MFS_OK, MFS_EINVAL, MFS_ESINGULAR (a point's
 * evaluation), MFS_ENOMEM. */
mfs_status mfs_bound_plan(const mfs_plan *pl, const mfs_material *mat,
                          const unsigned char *fixed, mfs_bound_result *r);

/* The bound of the model a spec describes, without assembling it or storing
 * a shape table: streams over the quadrature points, and evaluates the
 * shape functions only at points whose neighbourhood has not been met
 * before (on a lattice, points at the same place in their cell with the
 * same position relative to the boundary are equivalent: translates of each
 * other, with the same neighbour offsets, volumes and fixed flags).  O(N)
 * time for N particles, O(N) memory for the particles and quadrature points
 * only.  Equals mfs_bound_plan on the assembled model up to rounding.
 * Particle sets, perturbed lattices and masks of fixed particles have no
 * equivalent points: their bound goes through a plan and its shape table
 * (O(N) time and memory).  Returns MFS_OK, or the statuses of
 * mfs_model_alloc (MFS_ESINGULAR with *bad the failing quadrature point). */
mfs_status mfs_bound_model(const mfs_model_spec *spec, mfs_bound_result *r, size_t *bad);

/* The bound of an assembled model (its plan must not have been released). */
mfs_status mfs_bound_of_model(const mfs_model *m, mfs_bound_result *r);

/* The Gershgorin bound with the lumped mass: every eigenvalue of M^-1 K
 * lies in a disc centred at K_ii / m_i of radius sum_{j != i} |K_ij| / m_i,
 * so lambda_max <= max_i sum_j |K_ij| / m_i: a proven upper bound, one pass
 * over the nonzeros, provided every m_i > 0.  It does not apply to a
 * consistent mass (M^-1 K is then not available row by row) nor where some
 * m_i <= 0 (MLS on strongly disordered sets): lambda is then NAN and the
 * offending masses are counted. */
typedef struct {
  double lambda;            /* the bound (1/time^2), NAN where it does not apply */
  size_t argmax;            /* the degree of freedom (particle * ndof + component) of the row */
  size_t nonpositive;       /* degrees of freedom with m_i <= 0 */
  size_t first_nonpositive; /* the first of them (as argmax) */
  double min_mass;          /* the smallest m_i (kg, per unit thickness in 2D) */
  size_t argmin_mass;       /* its degree of freedom */
} mfs_gershgorin_result;

/* From an assembled K (n x n, CSR) and lumped mass m (n); dof (n, or NULL:
 * the identity) the full degree of freedom of each row.  MFS_OK, MFS_EINVAL. */
mfs_status mfs_gershgorin_csr(const mfs_csr *K, const double *m, const size_t *dof,
                              mfs_gershgorin_result *r);

/* Streamed from a plan row by row (mfs_row_sweep: its table, or the points
 * evaluated block by block), without storing K: the stiffness of mat
 * restricted to the particles not fixed (fixed: p->n flags, or NULL) with
 * the lumped mass (mfs_assemble_mass_lumped).  The same value as
 * mfs_gershgorin_csr on the assembled model up to the order of the sums;
 * the same for any number of threads.  MFS_OK, MFS_EINVAL, MFS_ESINGULAR,
 * MFS_ENOMEM. */
mfs_status mfs_gershgorin_plan(const mfs_plan *pl, const mfs_material *mat,
                               const unsigned char *fixed, mfs_gershgorin_result *r);

/* The same for any operator whose ndof x ndof blocks come from rows of
 * forms: the linearization of a solver's force at its state (the stiffness
 * with a tangent modulus; the gradient products A^{jl} contracted with a
 * tangent by `block`; Eulerian terms), with the lumped mass or given
 * masses.  Gershgorin's theorem holds for any square matrix, so the result
 * bounds |lambda| of every eigenvalue of M^-1 A, symmetric or not. */
typedef struct {
  const mfs_forms *forms; /* what a row accumulates (its physics gives ndof) */
  int ndof;
  /* the block of column k of the row (ndof x ndof, row-major) from the
   * row's accumulators; NULL: the stiffness block row->K + k ndof^2 */
  void (*block)(const void *ctx, const mfs_row *row, size_t k, double *blk);
  const void *ctx;
  const double *mass;     /* p->n ndof masses; NULL: the lumped mass with density */
  double density;
} mfs_gershgorin_op;

/* MFS_OK, MFS_EINVAL (forms and ndof disagree), the statuses of
 * mfs_row_sweep (*bad the failing point). */
mfs_status mfs_gershgorin_op_plan(const mfs_plan *pl, const mfs_gershgorin_op *op,
                                  const unsigned char *fixed, mfs_gershgorin_result *r,
                                  size_t *bad);

/* Closed-form constants, lambda <= alpha c^2 / h^2 with h = a the support radius:
 *   dim 1: alpha = norm_1 max_z w'(z)^2/w(z)           (eq. 136; 12.42 for the cubic spline)
 *   dim 2: alpha_1 = pi norm_2 int_0^1 w'^2/w z dz     (eqs 145-146; 13.38 cubic, printed 13.30)
 * computed numerically from the kernel table. */
double mfs_bound_alpha(const mfs_kernel_type *k, int dim);

/* The continuum limit of the interior lambda^Q h^2 / c^2 on a uniform
 * lattice (dx/h -> 0): 1D 2 norm_1 int_0^1 w'^2/w dz (12.46 cubic); 2D equal
 * to mfs_bound_alpha. */
double mfs_bound_alpha_continuum(const mfs_kernel_type *k, int dim);

/* The paper's printed constants: alpha = 12.42 (eq. 136), alpha_1 = 13.30
 * (eq. 145), alpha_2 = 15.00 (eq. 147). */
#define MFS_PAPER_ALPHA 12.42
#define MFS_PAPER_ALPHA1 13.30
#define MFS_PAPER_ALPHA2 15.00

/* The Fourier (von Neumann) estimate: the largest omega^2 of plane waves on
 * the infinite uniform lattice (of a particle set: the line or square lattice
 * of its mean spacing; of a perturbed lattice: the unperturbed one) with the
 * spec's kernel, shape functions,
 * quadrature, dilation, mass and physics (mfs_dispersion.h), over kappa in
 * [0, kappa_max(theta)] sampled at npts points (then refined around the
 * largest sample by golden section), at nangles angles theta evenly
 * spaced in [0, 90] degrees (2D; 1D ignores it), converted to
 * 1/time^2 with c^2 = modulus/density and dx:  lambda = max omega2 c^2/dx^2.
 * The wave number where the maximum is attained is returned in *kappa
 * (kappa dx/pi) and *theta (radians), either may be NULL.  Returns MFS_OK,
 * or the statuses of mfs_disp_plan_alloc and mfs_disp_omega2. */
mfs_status mfs_bound_fourier(const mfs_model_spec *spec, int npts, int nangles, double *lambda,
                             double *kappa, double *theta);

/* The stable-step rule of the reference solvers: the lambda_max estimate
 * their step dt_crit = 2 / sqrt(lambda) uses, from a power-iteration
 * estimate (it converges to lambda_max from below) and the element bound
 * (proven only where negative_phi == 0, and useless where some phi_I is tiny:
 * MLS at free ends with nodal integration gives 1e16 times lambda_max):
 * 1.05 lambda_power, or the proven bound where it is smaller.  NAN when
 * neither is positive and finite. */
double mfs_step_lambda(double lambda_power, double lambda_bound, size_t negative_phi);

/* Critical time step of the undamped central difference method,
 * 2 / omega_max = 2 / sqrt(lambda_max) (eq. 120 with xi = 0, eq. 124). */
double mfs_dt_crit(double lambda_max);

#ifdef __cplusplus
}
#endif

#endif
