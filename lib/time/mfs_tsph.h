/* Taylor-SPH (TSPH, paper 001: Herreros & Mabssout 2011, section 3) for the
 * 1D bar in stress-velocity form, step-level API (alloc, set_state, set_dt,
 * step, reset, free; the caller owns the loop).
 *
 * Model (paper 001 eqs 1-12 in 1D, small strain, unit section):
 *   rho v_t = sigma_x,
 *   sigma_t = E (v_x - evp_t),   evp_t = gamma sgn(sigma) <phi>,
 *   phi = ((|sigma| - sy) / sy)^N  for |sigma| > sy, else 0   (eq. 4),
 *   sy_t = H gamma <phi>                                       (eq. 6),
 * i.e. U_t + F_x = S with U = (sigma, v, sy), F = (-E v, -sigma/rho, 0),
 * S = (-E gamma sgn(sigma) phi, 0, H gamma phi) (eqs 14-15).  yield_stress
 * = INFINITY (or fluidity = 0) is the elastic bar.
 *
 * Space: corrected SPH with a Lagrangian kernel (eqs 30-36): the function
 * approximation is the Shepard-normalized kernel sum (eq. 30), the gradient
 * the Randles-Libersky normalized one (eqs 32-35),
 *   f'(X_I) = sum_J (f_J - f_I) g_IJ,
 *   g_IJ = Omega_J dW_IJ / sum_K (X_K - X_I) Omega_K dW_IK,
 * exact for linear fields.  The kernel and its weights are built once (a
 * plan; Lagrangian: neighbours never change).  Volumes Omega are Voronoi
 * lengths on [0, L].
 *
 * Time, MFS_TSPH_TAYLOR (section 3.1, 3.2.4): n real particles at
 * X_I = I dx, dx = L/(n-1), and n-1 virtual particles at the midpoints.
 *   step 1, eq. (38): U_V^{n+1/2} = U_V^n + dt/2 (S - F_x)^n at the virtual
 *     particles from the real ones (U_V^n, S^n interpolated by eq. 30);
 *   step 2, eq. (40): U_R^{n+1} = U_R^n + dt (S - F_x)^{n+1/2} at the real
 *     particles from the virtual ones.
 * In f_I of eq. (35) a boundary particle uses its prescribed value (v at a
 * velocity or fixed end, sigma = 0 at a free end; the essential conditions
 * of the stress-velocity form, end of section 3.2.4); elsewhere the eq.-30
 * interpolant (zero weight where the neighbourhood is symmetric).
 * Support radius a = 2 h0 = D s with s = dx/2 the spacing of the combined
 * real + virtual lattice: D = 2 (h0 = s) reaches the two nearest particles
 * of the other set only, and the scheme is then Richtmyer's two-step
 * Lax-Wendroff (exact at c dt = dx for the elastic bar).
 * MFS_TSPH_EULER, _RK2 (midpoint), _RK4: the semi-discrete system of the
 * same corrected SPH on the real particles only (support a = D dx, h0 = dx at
 * D = 2), integrated by the standard schemes (the comparison of paper 001
 * section 4.1.1, Figs 5-6).  Boundary values are imposed at every stage.
 *
 * Artificial viscosity (not in paper 001; spec.viscosity = alpha, 0 gives
 * the paper's scheme): the momentum equation uses sigma + q with the viscous
 * stress q = alpha rho c dx v_x (Landshoff's linear viscosity, both signs of
 * v_x), q evaluated where the stress is: at the virtual particles at t^n
 * for the Taylor step, at the real particles for the others; q = 0 where
 * the stress is prescribed (free end).  The paper's scheme overshoots 19%
 * at the fixed end of the elastic bar (docs/errata.md E8); alpha = 0.03
 * brings it to 4.4% at c dt/dx = 0.970, and to 0.0% with the linear
 * interpolation (the shipped scene).
 *
 * Stable step (mfs_tsph_dt_stable): the von Neumann limit of the interior
 * scheme on the uniform lattice, the largest dt for which every eigenvalue
 * of the 2 x 2 amplification matrix G(theta) of (sigma, v) has modulus
 * <= 1 + 1e-12 for all theta.  Taylor step, with the staggered symbols P
 * (interpolation, eq. 30) and Ds (gradient, eq. 35) and A = [0 E; 1/rho 0]:
 *   G = I + dt Ds (P A + dt/2 Ds A^2 + [0 0; 0 eta Ds/rho]),  eta = alpha rho c dx;
 * at D = 2 and alpha = 0 this is Lax-Wendroff, stable for c dt <= dx.  The
 * others: G = R(dt L) with L = [0 E D; D/rho eta D^2/rho], D the collocated
 * gradient symbol and R the scheme's stability polynomial.  Without
 * viscosity L has imaginary eigenvalues, so forward Euler and the midpoint
 * RK2 are unstable for every dt (dt_stable = 0) and RK4 is stable for
 * c dt |D| <= 2 sqrt(2).  Boundaries are not part of this analysis: the limit is
 * necessary, not sufficient (the collocated operator has growing boundary
 * modes at any step, docs/errata.md E8). */
#ifndef MFS_TSPH_H
#define MFS_TSPH_H

#include <stddef.h>

#include "mfs_disc.h"
#include "mfs_explicit.h"
#include "mfs_kernel.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { MFS_TSPH_TAYLOR, MFS_TSPH_EULER, MFS_TSPH_RK2, MFS_TSPH_RK4 } mfs_tsph_scheme;

/* Name ("tsph", "euler", "rk2", "rk4"); parse: MFS_EINVAL if unknown. */
const char *mfs_tsph_scheme_name(mfs_tsph_scheme s);
mfs_status mfs_tsph_scheme_parse(const char *name, mfs_tsph_scheme *s);

/* The bar: disc with a finite 1D source (disc.source.nx >= 3 real
 * particles on [0, disc.source.lx], m), disc.material (density rho, modulus
 * E; kg/m^3, Pa), disc.kernel (the cubic B-spline of eq. 24 in the paper)
 * and disc.dilation (D > 0: a = D dx/2 (taylor), D dx (others)); the shape,
 * quadrature and frame of disc do not enter (the scheme fixes them).  Plus: */
typedef struct {
  mfs_disc disc;
  double yield_stress;    /* initial sy > 0 (Pa); INFINITY: elastic */
  double fluidity;        /* gamma >= 0 (1/s) */
  double exponent;        /* Perzyna N >= 0 */
  double hardening;       /* H (Pa); < 0 softening */
  mfs_tsph_scheme scheme;
  double viscosity;       /* artificial viscosity alpha >= 0 (0: the paper) */
  int linear_interpolation; /* 0: eq. 30 (Shepard, the paper); 1: eq. 30 plus
                          the first-order term it drops (exact for linear
                          fields; differs only next to the ends, where the
                          Voronoi volumes are dx/2) */
  mfs_bc bc[2];           /* left, right */
  double bc_velocity[2];  /* MFS_BC_VELOCITY: v (m/s) for t <= bc_until, then 0 */
  double bc_until[2];
} mfs_tsph_spec;

typedef struct mfs_tsph_work mfs_tsph_work;

/* Fields are read-only for the caller except through the functions below. */
typedef struct {
  size_t n, nv;        /* real and virtual particles (nv = n-1; 0 if not taylor) */
  double dx;
  const double *X;     /* n real coordinates */
  const double *Xv;    /* nv virtual coordinates (midpoints) */
  const double *vol;   /* n real Voronoi lengths (m) */
  double *sigma, *v;   /* stress (Pa, tension > 0) and velocity (m/s) at t */
  double *sy;          /* current yield stress (Pa) */
  double *evp;         /* accumulated equivalent viscoplastic strain */
  double t, dt;
  double dt_cfl;       /* dx / c, c = sqrt(E/rho) */
  long steps;
  mfs_tsph_spec spec;
  mfs_tsph_work *w;    /* private */
} mfs_tsph;

/* Build the particles and the kernel plan; state sigma = v = evp = 0,
 * sy = yield_stress, t = 0, dt = dt_cfl.  NULL with *status on failure
 * (MFS_EINVAL bad spec; MFS_ESINGULAR a particle whose support holds no
 * particle of the other set, or no neighbour on two sides for the
 * gradient normalization; MFS_ENOMEM). */
mfs_tsph *mfs_tsph_alloc(const mfs_tsph_spec *spec, mfs_status *status);
void mfs_tsph_free(mfs_tsph *s);

/* Back to the initial state at t = 0, steps = 0 (dt kept). */
mfs_status mfs_tsph_reset(mfs_tsph *s);

/* Copy a state of the real particles (NULL: zero) at t = 0 and impose the
 * boundary values.  MFS_OK or MFS_EDOMAIN (non-finite). */
mfs_status mfs_tsph_set_state(mfs_tsph *s, const double *sigma, const double *v);

/* MFS_EINVAL if dt <= 0 or not finite.  No stability check: the caller
 * decides (Taylor step: c dt <= dx at D = 2; forward Euler is unstable
 * for any dt on this central operator). */
mfs_status mfs_tsph_set_dt(mfs_tsph *s, double dt);

/* The von Neumann stable step of the interior scheme (see above), in
 * seconds; 0 when no positive step is stable (euler, rk2 without
 * viscosity).  Found by a scan in steps of dt_cfl/100 up to 16 dt_cfl and
 * bisection to 1e-10 relative; a scheme stable beyond 16 dt_cfl gets
 * 16 dt_cfl. */
double mfs_tsph_dt_stable(const mfs_tsph *s);

/* One step of spec.scheme.  MFS_OK; MFS_EDOMAIN on a non-finite value or a
 * yield stress driven to <= 0 by softening. */
mfs_status mfs_tsph_step(mfs_tsph *s);

/* Velocity at coordinate X by linear interpolation between real particles. */
double mfs_tsph_velocity_at(const mfs_tsph *s, double X);

/* Kinetic 1/2 sum rho Omega v^2 and elastic sum Omega sigma^2 / (2E) (J per
 * unit section). */
void mfs_tsph_energy(const mfs_tsph *s, double *kinetic, double *potential);

#ifdef __cplusplus
}
#endif

#endif
