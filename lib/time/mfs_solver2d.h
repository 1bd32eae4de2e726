/* Reference explicit solver for linear Lagrangian models: the assembled
 * finite model of mfs_model.h (1D bar or 2D rectangle, periodic, free or
 * fixed boundary, any kernel, shape function, dilation and quadrature) under
 *
 *   M u'' = -K u,
 *
 * K the linear stiffness on the free degrees of freedom (2D anti-plane shear,
 * paper 003 eq. 113: K_IJ = mu sum_Q w_Q grad phi_I . grad phi_J; 2D plane
 * strain: K_IJ = sum_Q w_Q B_I^T D B_J; 1D bar), M the lumped (row-sum) mass
 * m_I = rho sum_Q w_Q phi_I(Q) (eq. 131).  The consistent mass is refused:
 * an explicit method with it would need a solve per step.  Degrees of
 * freedom are those of the model: free ones only, plane strain interleaved
 * (u_x, u_y) per particle as in model->dof.  The internal force K u is one
 * CSR product (mfs_csr_matvec), O(nnz) per evaluation.  1D models are
 * accepted too (Y = 0); for the nonlinear 1D rod see mfs_solver.h.
 * Step-level API as mfs_solver.h: alloc, set_state, set_dt, step, reset,
 * free; the caller owns the loop.
 *
 * Time integration (mfs_scheme of mfs_solver.h): central difference
 * (leapfrog, eq. 120 with xi = 0, kick-drift-kick with velocities at whole
 * steps: one K product per step), forward Euler, RK2 (midpoint), RK4.
 *
 * Stable step of the central difference: dt_crit = 2 / sqrt(lambda), lambda
 * from the linearized operator at u = 0 by a rule of mfs_dt_rule
 * (mfs_explicit.h; mfs_solver2d_choose_step): by default the Gershgorin
 * bound max_i sum_j |K_ij| / m_i (proven, one pass over the nonzeros);
 * `certified` factors sigma M - K (mfs_eig_certify_search); `power` (the
 * rule before these) is 1.05 times a power-iteration estimate (the Rayleigh
 * quotient after 300 iterations on the symmetric M^-1/2 K M^-1/2 from a fixed
 * pseudo-random start: a lower bound, short of lambda_max by at most
 * lambda_max / (2 e 300) times the start's weight off the top eigenvector
 * relative to on it), or the element bound (eqs 124, 132, mfs_bound.h) where
 * it is proven (every phi_I > 0 at the quadrature points) and smaller.  The
 * exact lambda_max is at hand for a check (mfs_eig_max, mfs_eig_dense on
 * model->K, model->m).
 *
 * Energy: kinetic 1/2 v^T M v, potential 1/2 u^T K u.  Their sum E is what
 * the exact dynamics conserves.  The leapfrog conserves exactly (a linear
 * system; up to rounding) the modified energy
 *   H = 1/2 v^T M v + 1/2 u^T K u - dt^2/8 a^T M a,   a = -M^-1 K u,
 * which is 1/2 v_{n-1/2}^T M v_{n+1/2} + 1/2 u_n^T K u_n, the energy with
 * the kinetic part from the half-step velocities v_{n+-1/2} = v_n +- dt/2 a_n;
 * E >= H oscillates above it by O((omega dt)^2) of the excited frequencies.
 *
 * Initially stressed plates (mfs_solver2d_alloc_stressed; plane strain): a
 * homogeneous initial Cauchy stress sigma0 and the St Venant-Kirchhoff
 * material with it, S = sigma0 + lambda tr(E) I + 2 mu E (the 2D form of the
 * rod's S = E (F^2 - 1)/2 + S0, mfs_solver.h), integrated as the nonlinear
 *   M u'' = f_int(0) - f_int(u)
 * (the load f_int(0) makes u = 0 an equilibrium; it vanishes to rounding on a
 * periodic lattice).  Its linearization at u = 0 has the tangent
 * a = c + delta (x) sigma0 of the dispersion analysis (mfs_dispersion.h).
 *   Lagrangian kernel: the model's table at the reference points,
 *     F_Q = I + sum_K u_K (x) grad0 phi_K(X_Q),  f_K = sum_Q w_Q F S grad0 phi_K;
 *   Eulerian kernel: shape functions re-evaluated at the current points among
 *     the current particles, radius a = D dx (sph: phi_I = V0_I W(x - x_I));
 *     points at particles move with them, stress and Gauss points with
 *     sum_K phi_K(X_Q) u_K;  F_Q^-1 = I - sum_K u_K (x) grad phi_K(x_Q) (eq. 68 in
 *     2D), sigma = J^-1 F S F^T, V_Q = J w_Q,  f_K = sum_Q V_Q sigma grad phi_K.
 *     Its linearization is the consistent one (`eulerian-consistent` of the
 *     dispersion analysis; for sph with nodal integration also eq. 71's).
 *     Candidate neighbours within a + skin, searched again when a point
 *     moved more than skin/2 (counted in `searches`).
 * The stable step of the stressed plate: Lagrangian kernel, the Gershgorin
 * bound of the tangent stiffness at u = 0 (the gradient products A^{jl}
 * contracted with dP/dH = delta sigma0 + C, streamed from the table: proven);
 * no certificate (the tangent is not assembled: `certified` falls back to
 * Gershgorin); Eulerian kernel with sigma0 != 0: `power` (the kernel motion's
 * terms are not bounded), from the unstressed K as above with lambda scaled by
 * 1 + |sigma0|_max / mu (an estimate: the initial-stress terms of the
 * linearized operator are O(sigma0/mu) of it).  Energy: kinetic always; the
 * Lagrangian plate's potential sum_Q w_Q (sigma0:E + lambda/2 tr(E)^2 + mu E:E)
 * - f_int(0).u (conserved by the exact dynamics); none (NAN) for the
 * Eulerian kernel, which has no energy; the modified energy is NAN. */
#ifndef MFS_SOLVER2D_H
#define MFS_SOLVER2D_H

#include <stddef.h>

#include "mfs_explicit.h"
#include "mfs_model.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mfs_solver2d_work mfs_solver2d_work;

/* Fields are read-only for the caller except through the functions below. */
typedef struct {
  mfs_model *model;    /* owned: particles, plan, K, lumped m (its spec's
                          quadrature name is borrowed from the caller's spec) */
  size_t n;            /* free degrees of freedom (model->n) */
  double *u, *v, *a;   /* n: displacement, velocity, acceleration -M^-1 K u at time t */
  const double *m;     /* n lumped masses (model->m) */
  const double *X, *Y; /* n: reference coordinates of each dof's particle (Y = 0 in 1D) */
  const int *comp;     /* n: its component: 0 (u_x, or the scalar), 1 (u_y) */
  double t, dt;
  double dt_crit;      /* 2 / sqrt(lambda) */
  double lambda;       /* the lambda_max estimate dt_crit uses, 1/time^2 */
  double lambda_power; /* power-iteration estimate (a lower bound) */
  double lambda_bound; /* element bound (eq. 124); proven where negative_phi == 0 */
  size_t negative_phi; /* quadrature points where the bound is not guaranteed */
  mfs_dt_info step;  /* the rule that chose dt_crit and what it found */
  long steps;
  int stressed;        /* the initially stressed (nonlinear) plate */
  long searches;       /* Eulerian neighbour searches */
  mfs_solver2d_work *w; /* private */
} mfs_solver2d;

/* Build the model (mfs_model_alloc), its state u = v = a = 0, t = 0, and
 * the stable step; dt = 0.9 dt_crit.  NULL with *status on failure:
 * MFS_EINVAL (NULL spec, consistent mass, or as mfs_model_spec_check),
 * MFS_ETOOSMALL, MFS_ESINGULAR (singular moment matrix at quadrature point
 * *bad, if bad is not NULL), MFS_EDOMAIN (no positive finite lambda_max:
 * K = 0), MFS_ENOMEM. */
mfs_solver2d *mfs_solver2d_alloc(const mfs_model_spec *spec, mfs_status *status, size_t *bad);

/* The same under the homogeneous initial Cauchy stress sigma0 = (sigma_xx,
 * sigma_yy, sigma_xy) in Pa (NULL: zero) with the kernel frame of
 * spec->disc.frame (lagrangian or eulerian); skin: the Eulerian neighbour
 * skin in dx (0: 0.5).  A Lagrangian plate without stress is the linear one.
 * Further statuses: MFS_ENOTSUP (a stressed or Eulerian plate that is not
 * plane strain; frame eulerian-consistent: the time-domain Eulerian kernel is
 * `eulerian`, whose linearization that frame describes), MFS_EINVAL (a
 * non-finite stress, skin < 0). */
mfs_solver2d *mfs_solver2d_alloc_stressed(const mfs_model_spec *spec, const double *sigma0,
                                          double skin, mfs_status *status, size_t *bad);
void mfs_solver2d_free(mfs_solver2d *s);

/* Choose dt_crit (and dt = 0.9 dt_crit) again by `rule` (the allocs use
 * MFS_DT_GERSHGORIN), filling s->step; from the operator at u = 0, before
 * any step.  MFS_OK, MFS_EINVAL (unknown rule), MFS_EDOMAIN (no positive
 * finite lambda), MFS_ENOMEM. */
mfs_status mfs_solver2d_choose_step(mfs_solver2d *s, mfs_dt_rule rule);

/* Back to u = v = a = 0, t = 0, steps = 0 (dt kept). */
void mfs_solver2d_reset(mfs_solver2d *s);

/* Copy a state (NULL: zero; n values each) and evaluate a = -M^-1 K u.
 * MFS_OK, or MFS_EDOMAIN for a non-finite value (the state is then left
 * unchanged). */
mfs_status mfs_solver2d_set_state(mfs_solver2d *s, const double *u, const double *v);

/* Set the step.  MFS_EINVAL if dt <= 0 or not finite, or dt > dt_crit and
 * !force. */
mfs_status mfs_solver2d_set_dt(mfs_solver2d *s, double dt, int force);

/* One step of the scheme.  MFS_OK; MFS_EINVAL for an unknown scheme;
 * MFS_EDOMAIN on a non-finite value (an unstable run that overflowed) or an
 * inverted configuration; the shape functions' status (MFS_ESINGULAR) and
 * MFS_ENOMEM (a neighbour search) for the Eulerian kernel. */
mfs_status mfs_solver2d_step(mfs_solver2d *s, mfs_scheme scheme);

/* Kinetic 1/2 v^T M v and potential 1/2 u^T K u energies, and the modified
 * energy kinetic + potential - dt^2/8 a^T M a that the leapfrog conserves;
 * O(n) (K u = -M a is kept).  Any pointer may be NULL. */
void mfs_solver2d_energy(mfs_solver2d *s, double *kinetic, double *potential, double *modified);

/* Index of the particle nearest to (x, y) (y ignored in 1D; a periodic box
 * wraps the point into the box first), fixed particles included.  O(1). */
size_t mfs_solver2d_nearest(const mfs_solver2d *s, double x, double y);

/* The free degree of freedom of component comp of particle `particle` (an
 * index into u, v, a), or -1 if the particle is fixed or the arguments are
 * out of range.  O(log n). */
long mfs_solver2d_dof(const mfs_solver2d *s, size_t particle, int comp);

#ifdef __cplusplus
}
#endif

#endif
