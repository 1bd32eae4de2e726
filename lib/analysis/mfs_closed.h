/* Closed-form 1D dispersion relations (paper 003 sections 2.2 and 4.1-4.3),
 * written independently of the assembly code: "path (b)" of the dispersion
 * analysis, to be compared with the Fourier symbol of assembled operators.
 *
 * Setting.  An infinite uniform 1D lattice of spacing dx (the current
 * spacing for Eulerian kernels, the reference spacing for Lagrangian ones);
 * all lengths are in units of dx.  Every relation is written with the
 * interior shape function of the particle at the origin, phi(x), and its
 * derivatives phi'(x), phi''(x) with respect to the evaluation point x,
 * sampled at the particles x = j and at the midpoints x = j + 1/2:
 *   mls  phi(x) = the linear MLS shape function of particle 0 at x
 *        (mfs_shape_mls, neighbours: all j with |j - x| < a = D), the entry
 *        of particle 0 with its first and second X-derivatives;
 *   sph  phi(x) = dx W(|x|), W the normalized 1D kernel (eq. 41, and the
 *        paper's simplification eq. 134 for MLS).
 * phi is even, phi' odd, phi'' even (symmetric kernel).  By translation
 * invariance phi_I(x) = phi(x - x_I), so phi'_I(x_J) = phi'(x_J - x_I):
 * phi' of particle 0 evaluated AT particle j.  With this convention
 * S below is negative for small kappa (S ~ -kappa for mls).
 *
 * Perturbation u_K = g exp(i kappa x_K) (eq. 69).  Lattice sums
 * (eqs 94-98; Nodes: x = j, Midpoints / Stress points: x = j + 1/2):
 *   S_M = sum phi'(j) sin(kappa j)        S_S = sum phi'(x) sin(kappa x)
 *   P_M = sum phi''(j) (1 - cos(kappa j)) R_S = sum phi''(x)
 *   Q_M = sum phi''(j) cos(kappa j)       Q_S = sum phi''(x) cos(kappa x)
 *   H_M = sum phi(j) cos(kappa j)         H_S = sum phi(x) cos(kappa x)
 *   Y_S = sum x phi'(x) cos(kappa x)      Z_S = sum x phi''(x) sin(kappa x)
 *
 * Normalization.  sbar = sigma / C (C the tangent modulus: C^{sigma T} for
 * Eulerian kernels, C^{SE} for Lagrangian ones; for Lagrangian kernels sigma
 * is read as the PK2 stress S), c^2 = C / rho, and the output is
 * omega2 = (omega dx / c)^2, a function of the wave number given as
 * kappa dx / pi (usually in [0, 1]; larger values are accepted).
 * omega2 < 0 means instability with growth rate sqrt(-omega2) c / dx.
 * Mass is lumped (rho dx per particle) except for the least-squares scheme,
 * whose mass matrix (eq. 106) is not a plain mass matrix.
 *
 * Schemes (F the uniform stretch, default 1):
 *   EULER_NODAL          eq. 74-75:
 *                        omega2 = (1 + sbar) S_M^2 - sbar (P_M - S_M^2)
 *   LAGR_NODAL           eq. 81-82: omega2 = (F^2 + sbar) S_M^2
 *   EULER_STRESS         eqs 83-92 re-derived (see mfs_closed.c):
 *                        omega2 = (1+sbar)/2 (S_M^2 + S_S^2)
 *                          - sbar/2 { P_M - S_M^2 + R_S - S_S^2 - F Q_S H_S
 *                                     - (F-1) Q_S Y_S + (F-1) Z_S S_S }
 *   EULER_STRESS_PRINTED eq. 93 exactly as printed: as above but with
 *                        + (F-1) Q_S Y_S.  The two agree at F = 1.
 *   LAGR_STRESS          eq. 103: omega2 = (F^2 + sbar)/2 (S_M^2 + S_S^2)
 *   LS_NODAL             Beissel-Belytschko least squares, nodal
 *                        integration, from the lattice rows of M and K of
 *                        eqs 106-107 (V_J = dx, sigma = 0):
 *                        omega2 = Khat / Mhat, Khat = sum_K K_0K cos(kappa K),
 *                        Mhat = sum_K M_0K cos(kappa K)
 *   LS_NODAL_PRINTED     eq. 108 as printed:
 *                        omega2 = (S_M^2 + beta Q_M^2) / (H_M^2 - beta Q_M H_M)
 *                        (identical to LS_NODAL: the symbols factor as
 *                        Khat = S_M^2 + beta Q_M^2, Mhat = H_M^2 - beta Q_M H_M)
 *   FEM_LINEAR           two-node linear elements, lumped mass (Fig. 10):
 *                        omega2 = (F^2 + sbar) 4 sin^2(kappa / 2) (Cbar^SE of
 *                        eq. 29 scaling K; 4 sin^2 at sigma = 0, F = 1)
 * beta = alpha_s l_c^2 in units of dx^2 (eq. 104); the least-squares schemes
 * are defined only for sbar = 0 and F = 1 (MFS_ENOTSUP otherwise).
 *
 * Limits of the paper's model, kept as they are (tests/test_closed.c):
 *   - eq. 71 / 89 move each Eulerian shape function rigidly with its
 *     particle.  For MLS this is consistent only where the error e(x) of the
 *     MLS interpolant of x^2 has e'' = 0 on the lattice, so for sbar != 0 the
 *     Eulerian schemes do not tend to the continuum 1 + sbar (eq. 34): e.g.
 *     quartic, D = 1.5: EULER_NODAL -> 1 + 0.281 sbar, EULER_STRESS ->
 *     1 + 1.140 sbar (limits of omega2 / (kappa dx)^2 as kappa -> 0).
 *   - eq. 91-92 make EULER_STRESS depend on which particle is held fixed;
 *     at F != 1 its long-wave limit is 1 + sbar F (cubic, D = 2), while the
 *     printed eq. 93 gives 1 + sbar.
 *   - sph is not linearly consistent, so no scheme tends to the continuum
 *     with it (cubic, D = 1.5: LAGR_NODAL -> 0.624 (1 + sbar)). */
#ifndef MFS_CLOSED_H
#define MFS_CLOSED_H

#include <stddef.h>

#include "mfs_disc.h"
#include "mfs_kernel.h"
#include "mfs_shape.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  MFS_CF_EULER_NODAL,
  MFS_CF_LAGR_NODAL,
  MFS_CF_EULER_STRESS,
  MFS_CF_EULER_STRESS_PRINTED,
  MFS_CF_LAGR_STRESS,
  MFS_CF_LS_NODAL,
  MFS_CF_LS_NODAL_PRINTED,
  MFS_CF_FEM_LINEAR,
  MFS_CF_NSCHEMES
} mfs_cf_scheme;

/* Name of a scheme ("euler-nodal", "lagr-nodal", "euler-stress",
 * "euler-stress-printed", "lagr-stress", "ls-nodal", "ls-nodal-printed",
 * "fem-linear"), or NULL if out of range. */
const char *mfs_cf_scheme_name(mfs_cf_scheme s);

/* The scheme called `name` in *s; MFS_OK or MFS_EINVAL. */
mfs_status mfs_cf_scheme_find(const char *name, mfs_cf_scheme *s);

/* The analysis: the kernel, shape (mls or sph: linearly complete, or the
 * kernel itself) and dilation of a 1D discretization, plus
 * the scheme's state.  The rest of disc (source, quadrature, frame, mass,
 * material) does not enter: the scheme chooses them. */
typedef struct {
  mfs_disc disc;
  double sbar;    /* sigma / C (or S / C^SE, Lagrangian) */
  double stretch; /* F > 0; 0 means 1 */
  double beta;    /* alpha_s l_c^2 in dx^2, >= 0 (least squares) */
} mfs_cf_spec;

typedef struct mfs_cf_plan mfs_cf_plan;

/* Tabulate phi, phi', phi'' at the particles j and the midpoints j + 1/2
 * inside the support (by the point evaluator, mfs_eval.h), and the lattice
 * rows of the least-squares M and K.  On failure returns NULL and sets
 * *status: MFS_EINVAL (NULL kernel or shape, D <= 0 or D > 1e4, non-finite
 * sbar, F < 0, beta < 0), MFS_ENOTSUP (a shape other than mls and sph),
 * MFS_ESINGULAR (a moment matrix with reciprocal condition number
 * below 1e-12, e.g. mls with D <= 1), MFS_ENOMEM. */
mfs_cf_plan *mfs_cf_plan_alloc(const mfs_cf_spec *spec, mfs_status *status);

/* Free a plan; NULL is accepted. */
void mfs_cf_plan_free(mfs_cf_plan *p);

/* omega2[i] = (omega dx / c)^2 of scheme s at kappa[i] (given as
 * kappa dx / pi), i < n.  Returns MFS_OK; MFS_EINVAL (NULL pointers, scheme
 * out of range, non-finite kappa); MFS_ENOTSUP (least squares with sbar != 0
 * or F != 1); MFS_EDOMAIN if some omega2 is not finite (least squares where
 * the mass symbol vanishes) -- every entry is still written. */
mfs_status mfs_cf_omega2(const mfs_cf_plan *p, mfs_cf_scheme s, size_t n, const double *kappa,
                         double *omega2);

/* The lattice sums at one wave number (kappa dx / pi), for cross-checks and
 * for other paths; names as in the comment at the top of this file. */
typedef struct {
  double SM, SS, PM, RS, QM, QS, HM, HS, YS, ZS;
} mfs_cf_sums;

mfs_status mfs_cf_lattice_sums(const mfs_cf_plan *p, double kappa, mfs_cf_sums *out);

/* The tabulated shape function: n points x[i] (in dx; particles j if
 * midpoints == 0, else j + 1/2), ascending and symmetric about 0, and
 * phi[3 i + 0..2] = phi, phi', phi'' there.  Pointers are into the plan. */
mfs_status mfs_cf_table(const mfs_cf_plan *p, int midpoints, size_t *n, const double **x,
                 const double **phi);

#ifdef __cplusplus
}
#endif

#endif
