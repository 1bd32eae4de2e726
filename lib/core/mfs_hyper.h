/* Materials of the finite-deformation and initial-stress analyses: const
 * type tables (as kernels and shape functions are), their stresses, their
 * tangent moduli derived from the stress, and the acoustic tensor's strong
 * ellipticity (the PDE's own stability).  docs/finite-deformation.md derives
 * every formula; tests/test_hyper.c checks the tangents against central
 * differences of the stresses.
 *
 *   linear       the linear isotropic material under a given initial Cauchy
 *                stress sigma0 (paper 003 eq. 75 in 2D): F = I, Truesdell
 *                modulus c = lambda I(x)I + 2 mu II, a = c + delta(x)sigma0
 *   neo-hookean  W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
 *   paper000     paper 000 eq. 18, which gives only the Cauchy stress
 *                sigma = J^-1 [(c1 + c2 I1) B - c2 B^2 - (c1 J^(2/3) + 2 c2 J^(4/3)
 *                - 2 lambda ln J) I]; it is the stress of
 *                W = c1/2 (I1 - 3 J^(2/3)) + c2/2 (I2 - 3 J^(4/3)) + lambda (ln J)^2
 *                (3D invariants; small-strain mu0 = c1 + c2, bulk modulus 2 lambda;
 *                the paper's lambda is not a Lame constant)
 *
 * Conventions.  F = dx/dX, J = det F, C = F^T F, B = F F^T; S the second and
 * P = F S the first Piola-Kirchhoff stress, sigma = J^-1 P F^T.  Tensors are
 * row-major 3 x 3 (F[i*3+J]); fourth-order ones are X[((i*3+j)*3+k)*3+l].
 *   C_SE_IJKL = dS_IJ / dE_KL                    (material tangent)
 *   A_iJkL    = dP_iJ / dF_kL = delta_ik S_JL + F_iM F_kN C_SE_MJNL
 *   a_ijkl    = J^-1 F_jJ F_lL A_iJkL = c_ijkl + delta_ik sigma_jl
 *               (c the Truesdell modulus; a is paper 003's C + sigma of eq. 75)
 *   Q(n)_ik   = a_ijkl n_j n_l,  Q0(N)_ik = A_iJkL N_J N_L  (acoustic tensors)
 * Units: stresses and moduli in Pa, density in kg/m^3. */
#ifndef MFS_HYPER_H
#define MFS_HYPER_H

#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const char *name;        /* "linear", "neo-hookean", "paper000" */
  const char *constants;   /* the constants c[0..2] in words, for messages and docs */
  int finite;              /* the stress follows from F (0: linear, F = I, stress given) */
  /* S and C_SE (81 doubles, or NULL) at the right Cauchy-Green tensor C
   * (3 x 3, det C > 0) for the constants c */
  void (*pk2)(const double *c, const double *C, double *S, double *CSE);
  double (*mu0)(const double *c);  /* small-strain shear modulus (Pa) */
  double (*k0)(const double *c);   /* small-strain bulk modulus (Pa) */
} mfs_hyper_type;

extern const mfs_hyper_type mfs_hyper_linear;      /* c = {mu, lambda (Lame)} */
extern const mfs_hyper_type mfs_hyper_neo_hookean; /* c = {mu, lambda (Lame)} */
extern const mfs_hyper_type mfs_hyper_paper000;    /* c = {c1, c2, lambda} of eq. 18 */
extern const mfs_hyper_type *const mfs_hyper_types[]; /* NULL-terminated */

/* The material called `name`, or NULL. */
const mfs_hyper_type *mfs_hyper_find(const char *name);

/* A material: its type, constants (Pa) and reference density. */
typedef struct {
  const mfs_hyper_type *type;
  double c[3];
  double density; /* rho0 (kg/m^3) */
} mfs_hyper;

/* Paper 000's eq. 18 material: c1 = 1.265e5, c2 = 1.012e4, lambda = 1.012e7 N/m^2,
 * rho = 125.4 kg/m^3. */
mfs_hyper mfs_hyper_paper000_constants(void);

/* A material of type t with shear modulus mu (Pa), Poisson's ratio nu (small
 * strain) and density rho: linear and neo-hookean (paper000 has its own
 * constants: use mfs_hyper_paper000_constants). */
mfs_hyper mfs_hyper_isotropic(const mfs_hyper_type *t, double mu, double nu, double rho);

/* Stresses and tangents at a deformation gradient F (3 x 3, det F > 0) of a
 * material with `finite` set: sigma, P, S (9 each), A and a (81 each); any
 * output may be NULL.  MFS_OK; MFS_EINVAL (not a finite material, det F <=
 * 0, a non-finite value). */
mfs_status mfs_hyper_eval(const mfs_hyper *m, const double *F, double *sigma, double *P, double *S,
                          double *A, double *a);

/* ---- plane strain: the in-plane state of a homogeneous deformation ---- */

/* The in-plane components (indices 0, 1) of a homogeneous plane-strain
 * state F = diag(l1, l2, 1): Cauchy stress, spatial and reference tangents
 * with the stress term, divided by the normalization modulus mu0 (the
 * small-strain shear modulus), so that dispersion analyses use them as
 * they are.  a and A are indexed ((i*2+j)*2+k)*2+l. */
typedef struct {
  double l[2];      /* principal stretches */
  double J;         /* l1 l2 */
  double sigma[4];  /* sigma / mu0, 2 x 2 row-major */
  double a[16];     /* a_ijkl / mu0 (current configuration) */
  double A[16];     /* A_iJkL / mu0 (reference configuration) */
  double mu0;       /* Pa */
} mfs_plane_state;

/* The state of a finite material at the stretches l1, l2 > 0.  MFS_OK,
 * MFS_EINVAL (a stretch <= 0 or not finite, or the linear material with a
 * stretch other than 1: it is defined at F = I under a given stress). */
mfs_status mfs_plane_state_stretch(const mfs_hyper *m, double l1, double l2, mfs_plane_state *s);

/* The state of the linear material (mu = 1, Poisson's ratio nu, normalized)
 * under the normalized initial Cauchy stress sigma/mu = (sxx, syy, sxy), F = I:
 * a = A = c + delta (x) sigma (paper 003 eq. 75 in 2D).  MFS_OK, MFS_EINVAL. */
mfs_status mfs_plane_state_linear(double nu, double sxx, double syy, double sxy,
                                  mfs_plane_state *s);

/* Q(n)_ik = t_ijkl n_j n_l for the in-plane tangent t (16) and n = (cos theta,
 * sin theta): 2 x 2 row-major. */
void mfs_acoustic_tensor(const double *t, double theta, double *Q);

/* The smallest eigenvalue of the symmetric part of the 2 x 2 matrix Q. */
double mfs_sym2_min_eig(const double *Q);

/* Strong ellipticity of an in-plane tangent t (16): the minimum over unit n
 * of the smallest eigenvalue of Q(n), and where.  Q(theta) is a quadratic
 * trigonometric polynomial with period pi: it is sampled at `samples`
 * angles on [0, pi) (0: 720) and every local minimum refined by golden
 * section to 1e-13 rad.  stable = q_min > 0 (strongly elliptic: no
 * perturbation of the PDE grows); q_min = 0 is marginal. */
typedef struct {
  int stable;
  double q_min;   /* in the units of t */
  double theta;   /* the worst direction n (radians, [0, pi)) */
} mfs_ellipticity;

mfs_status mfs_ellipticity_check(const double *t, int samples, mfs_ellipticity *e);

#ifdef __cplusplus
}
#endif

#endif
