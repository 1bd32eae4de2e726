/* Reference explicit solver: a 1D rod of particles, displacement form,
 * step-level API (alloc, set_state, set_dt, step, reset, free; the caller
 * owns the loop).
 *
 * Material: 1D St Venant-Kirchhoff with initial stress (paper 003 eqs 27-29,
 * 81):  S = E (F^2 - 1)/2 + S0,  P = F S,  tangent Cbar = E F^2 + S.
 *
 * Lagrangian kernel (eqs 77-79): the shape table phi_J(X_Q), phi_J'(X_Q) at
 * the quadrature points is built ONCE by mfs_plan_alloc;
 *   F_Q = 1 + sum_J phi_J'(X_Q) u_J,   f_I = sum_Q w_Q phi_I'(X_Q) P_Q.
 * Eulerian kernel (eqs 64-68): shape functions re-evaluated every force
 * evaluation at the current positions x = X + u (support radius a = D dX
 * fixed); quadrature points at particles move with them, stress and Gauss
 * points with the interpolated displacement sum_J phi_J(X_Q) u_J;
 *   F_Q = 1 / (1 - sum_J phi_J'(x_Q) u_J)   (eq. 68),
 *   f_I = sum_Q V_Q phi_I'(x_Q) sigma_Q,  V_Q = w_Q F_Q,  sigma = P (1D).
 * Candidate neighbours are searched with radius a + skin and searched again
 * only when some point moved more than skin/2 since the last search (the only
 * allocation after alloc; counted in `searches`).  For sph the volumes in
 * phi = V W are the reference volumes V^0 = m / rho0, so phi_I is a fixed
 * function of x - x_I: exactly the kernel motion eq. 71 linearizes.
 *
 * Mass: lumped, m_I = rho0 V_I (eq. 51).  Equilibration: the discrete
 * divergence of a uniform initial stress is not zero near a boundary (a
 * quadrature error); with `equilibrate` the internal force at u = 0 is
 * applied as a constant external load, so u = 0 is an equilibrium.
 *
 * Time integration: central difference (leapfrog, kick-drift-kick form with
 * velocities at whole steps: one force evaluation per step), forward Euler,
 * RK2 (midpoint), RK4, all with the same force routine.  Stable step:
 * dt_crit = 2 / sqrt(lambda) (eq. 120), lambda from the linearized operator
 * at u = 0 by a rule of mfs_dt_rule (mfs_explicit.h): by default the
 * Gershgorin bound max_I sum_J |K_IJ| / m_I of K(Cbar), Cbar = E + S0 (the
 * linearization of P = F S at F = 1, eq. 81), streamed from the plan: proven,
 * one pass over the rows; `certified` factors sigma M - K(Cbar); `power`
 * (the rule before these) is 1.05 times a 300-step power-iteration estimate
 * of lambda_max (it converges from below: not proven), or the element bound
 * (eqs 124, 132, with Cbar in place of E) when that is proven (every
 * phi_I > 0 at the quadrature points) and smaller; the element bound alone
 * can be useless: MLS phi_I nearly vanish at free ends.  K(Cbar) is the
 * linearization of the Lagrangian kernel, and of the Eulerian one without
 * initial stress; for the Eulerian rod with S0 != 0 (kernel-motion terms,
 * eqs 71-75) and where some m_I <= 0 or Cbar <= 0 the Gershgorin and
 * certified rules fall back to `power`, said in step.fallback. */
#ifndef MFS_SOLVER_H
#define MFS_SOLVER_H

#include <stddef.h>

#include "mfs_disc.h"
#include "mfs_explicit.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The rod: disc with a finite 1D source (disc.source.nx particles on
 * [0, disc.source.lx], spacing lx/(nx-1), periodic lx/nx), disc.material
 * (modulus E, density rho0, initial_stress S0), kernel, dilation, shape,
 * frame (lagrangian or eulerian), quadrature (nodal, stress, gaussN), plus: */
typedef struct {
  mfs_disc disc;
  mfs_bc bc[2];          /* left, right (ignored when periodic) */
  double bc_velocity[2]; /* prescribed velocity of MFS_BC_VELOCITY */
  double bc_until[2];    /* ... applied for t <= until, then 0 (use INFINITY for always) */
  int equilibrate;       /* apply -f_int(u = 0) as a constant load */
  double skin;           /* Eulerian neighbour skin, in dX (0: 0.5) */
} mfs_solver_spec;

typedef struct mfs_solver_work mfs_solver_work;

/* Fields are read-only for the caller except through the functions below. */
typedef struct {
  size_t n, nq;
  double dX;
  const double *X;     /* n reference coordinates */
  double *u, *v, *a;   /* displacement, velocity, acceleration at time t */
  double *m;           /* n lumped masses */
  const double *xq0;   /* nq reference quadrature points */
  const double *wq;    /* nq reference weights */
  double *F, *sigma;   /* nq deformation gradient and Cauchy stress (= P in 1D)
                          of the last force evaluation (see mfs_solver_fields) */
  double t, dt;
  double dt_crit;      /* 2 / sqrt(lambda_max) */
  double lambda_bound; /* element bound (eq. 132 with Cbar) */
  double lambda_power; /* power-iteration estimate */
  size_t negative_phi; /* points where eq. 132 is not guaranteed */
  mfs_dt_info step;  /* the rule that chose dt_crit and what it found */
  long steps;
  long searches;       /* Eulerian neighbour searches */
  mfs_solver_spec spec;
  mfs_solver_work *w;  /* private */
} mfs_solver;

/* Build the particles, quadrature, plan, masses and the stable step;
 * state u = v = 0, t = 0, dt = 0.9 dt_crit.  NULL with *status on failure
 * (MFS_EINVAL bad spec, MFS_ESINGULAR singular moment matrix at quadrature
 * point *bad, MFS_ETOOSMALL, MFS_ENOMEM). */
mfs_solver *mfs_solver_alloc(const mfs_solver_spec *spec, mfs_status *status, size_t *bad);
void mfs_solver_free(mfs_solver *s);

/* Choose dt_crit (and dt = 0.9 dt_crit) again by `rule` (mfs_solver_alloc
 * uses MFS_DT_GERSHGORIN), filling s->step; the linearization is at u = 0,
 * so call it before mfs_solver_set_state.  MFS_OK, MFS_EINVAL (unknown
 * rule), MFS_EDOMAIN (no positive finite lambda), MFS_ENOMEM, the statuses of
 * the force (MFS_ESINGULAR, Eulerian). */
mfs_status mfs_solver_choose_step(mfs_solver *s, mfs_dt_rule rule);

/* Back to u = v = 0, t = 0, steps = 0 (dt kept). */
mfs_status mfs_solver_reset(mfs_solver *s);

/* Copy a state (NULL: zero) and evaluate the acceleration; the boundary
 * conditions are imposed.  MFS_OK, MFS_EDOMAIN, MFS_ESINGULAR. */
mfs_status mfs_solver_set_state(mfs_solver *s, const double *u, const double *v);

/* Set the step.  MFS_EINVAL if dt <= 0, or dt > dt_crit and !force. */
mfs_status mfs_solver_set_dt(mfs_solver *s, double dt, int force);

/* One step of the scheme.  MFS_OK; MFS_EDOMAIN on a non-finite value or an
 * inverted deformation (F <= 0); MFS_ESINGULAR (Eulerian MLS at a collapsed
 * configuration); MFS_ENOMEM (neighbour search). */
mfs_status mfs_solver_step(mfs_solver *s, mfs_scheme scheme);

/* Recompute F and sigma at the quadrature points for the current u. */
mfs_status mfs_solver_fields(mfs_solver *s);

/* Kinetic energy 1/2 sum m v^2 and the potential: strain energy
 * sum_Q w_Q psi(F_Q), psi = S0 (F^2-1)/2 + E (F^2-1)^2 / 8 (dpsi/dF = P),
 * minus the work of the equilibration load.  Conserved by the exact
 * Lagrangian dynamics with free or fixed ends.  Uses F from the current u. */
mfs_status mfs_solver_energy(mfs_solver *s, double *kinetic, double *potential);

/* Index of the particle nearest to coordinate X. */
size_t mfs_solver_nearest(const mfs_solver *s, double X);

#ifdef __cplusplus
}
#endif

#endif
