/* Stability classification of a discretization on the infinite lattice,
 * from its dispersion relation (mfs_dispersion.h): for each normalized
 * initial stress sbar, the smallest omega^2 over the sampled Brillouin zone
 * and where, the unstable wave numbers and the largest growth rate, the
 * spurious zero-energy modes (omega^2 = 0 away from the reciprocal lattice),
 * the onset stresses in tension and compression, and the labels
 *
 *   material         some wave is unstable and so is the continuum: the acoustic
 *                    tensor with the initial-stress term is not positive definite
 *                    at the analysed state (mfs_disp_pde: 1D C + sbar, Lagrangian
 *                    F^2 + sbar; anti-plane 1 + sbar; plane strain the strong
 *                    ellipticity of a_ijkl); never where no wave is unstable
 *   tensile          some wave is unstable while the continuum is not, under
 *                    tension: sigma_nn > 0 along the worst mode's current wave
 *                    direction n (1D and anti-plane: sbar > 0; sigma_nn = 0: the
 *                    mean stress decides)
 *   compressive      the same under compression (sigma_nn < 0), e.g. the long-wave
 *                    instability of Eulerian SPH with stress points
 *   rank-deficiency  spurious zero-energy modes at sbar = 0
 *   stable           none of these
 *
 * Thresholds are relative to the largest |omega^2| at sbar = 0 over 201
 * samples per ray (scale): omega^2 < -1e-10 scale is unstable, |omega^2| <=
 * 1e-10 scale a zero, a growth |Im sqrt(omega^2)| > sqrt(1e-10 scale)
 * unstable.  The continuum is unstable where q_min < -1e-12 (units of the
 * modulus); q_min = 0 (e.g. sbar = -1 in 1D, paper 003 Fig. 4) is marginal.
 * Onsets: bisection (50 halvings) of the smallest |sbar| with some omega^2 <
 * -tol, searched up to sbar = 10 in tension and 1 in compression (none for a
 * finite material, whose state is the plan's).  The long-wave check:
 * omega^2 / kappa^2 of the ndof lowest branches, Richardson-extrapolated from
 * kappa dx = 1e-3 and 2e-3 on every sampled ray, against mfs_disp_longwave. */
#ifndef MFS_CLASSIFY_H
#define MFS_CLASSIFY_H

#include <stddef.h>

#include "mfs_dispersion.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
  MFS_LABEL_MATERIAL = 1,
  MFS_LABEL_TENSILE = 2,
  MFS_LABEL_RANK_DEFICIENCY = 4,
  MFS_LABEL_COMPRESSIVE = 8
};

/* The continuum at a state is stable (no perturbation grows) unless q_min <
 * -1e-12 (units of the modulus): marginal states (q_min = 0) count as stable. */
static inline int mfs_pde_stable(const mfs_ellipticity *e)
{
  return !(e->q_min < -1e-12);
}

/* The labels of a state: unstable (some sampled wave grows), the PDE check,
 * the normal stress along the worst mode's current direction and the mean
 * stress (tie-break), spurious zeros at zero stress. */
unsigned mfs_class_labels(int unstable, const mfs_ellipticity *pde, double sigma_nn,
                          double sigma_mean, int spurious_zeros);

/* Where the relation is sampled: angles theta[0..ntheta) (radians; 1D: one
 * angle, ignored), and on each ray either the kappa values given (kappa dx
 * / pi, kappa != NULL) or npoints uniform on [0, kappa_max(theta)]. */
typedef struct {
  const double *theta;
  size_t ntheta;
  const double *kappa;
  size_t nkappa;
  int npoints;
} mfs_sampling;

/* The classification at one stress.  NAN marks an undefined value (no
 * unstable wave, no zero, no onset); *_theta are indices into
 * mfs_sampling.theta (-1 where undefined).  min_omega2 and max_growth are
 * the exact extremes; their places (kappa_at_*, theta_at_*) the first sample
 * in order that no later one beats by more than 1e-12 of the scale (max
 * |omega^2| at sbar = 0; its square root for the growth), so that samples
 * equal but for rounding give the same place on every machine. */
typedef struct {
  double sbar;
  double min_omega2, kappa_at_min;
  int theta_at_min;
  int unstable;
  double unstable_kappa_from, unstable_kappa_to;
  double max_growth, kappa_at_max_growth;
  int theta_at_max_growth;
  int spurious_zeros;        /* zeros counted over the samples at this stress */
  double zero_kappa;
  int zero_theta;
  double onset_tension, onset_compression;
  mfs_ellipticity pde;       /* the continuum at this stress (q_min in units of the modulus) */
  double sigma_nn;           /* normal stress along the worst mode's current direction
                                (NAN when no wave is unstable) */
  double longwave_deviation; /* max |omega^2/kappa^2 - q| / max |q| of the acoustic branches */
  unsigned labels;           /* MFS_LABEL_* bits; 0 is stable */
} mfs_class;

/* Classify at the stresses sbar[0..nsbar) into out[0..nsbar).  MFS_OK, or
 * the status of mfs_disp_omega2 (MFS_EDOMAIN, MFS_ELAPACK) at a sample,
 * MFS_EINVAL, MFS_ENOMEM. */
mfs_status mfs_classify(const mfs_disp_plan *pl, const mfs_sampling *smp, const double *sbar,
                        size_t nsbar, mfs_class *out);

/* "stable", or the labels joined by '+' in the order material, tensile,
 * compressive, rank-deficiency ("tensile+rank-deficiency"), into buf. */
const char *mfs_class_label(unsigned labels, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif
