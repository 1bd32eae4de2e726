/* Shape functions at one evaluation point X from its neighbours J (the nodes
 * with |X_J - X| < a), with gradients and, on request, second derivatives.
 *
 *   sph      phi_J = V_J W_J                          (paper 003 eq. 41)
 *   shepard  phi_J = W_J / sum W                      (paper 000 eq. 43)
 *   mls      linear MLS, basis shifted to X, scaled by a   (003 eqs 36-39)
 *   kb       values Shepard; gradient Krongauz-Belytschko corrected (000 eqs 26-32)
 *   rl       values V-weighted Shepard; gradient Randles-Libersky normalized
 *            symmetrized SPH gradient (000 eqs 33-34; 004 eqs 68-69)
 *   sphs     values V-weighted Shepard; gradient the symmetrized SPH gradient
 *            without the normalization (004 eq. 47; 000 eq. 33)
 *   cd2      values MLS; gradient the diffuse (Nayroles) derivative of the
 *            linear MLS fit, corrected derivatives method 2 (004 eqs 63-64)
 *
 * kb is the corrected derivative method 1 of paper 004 (eqs 55-61, section
 * 4.4.3): the same correction of the Shepard gradient.
 * The RL (and sphs) symmetrization subtracts the value at X.  At a particle (`self` >= 0,
 * nodal quadrature) that is the particle's own value, exactly eq. 33; at any
 * other point it is the Shepard interpolant, which keeps the corrected
 * gradient exact for linear fields there too.
 *
 * Output layout, per neighbour J, ncomp = mfs_shape_ncomp(dim, order) doubles:
 *   [phi, d_1 phi .. d_dim phi, (order 2) G_kn = d_n (d_k phi), k-major]
 * Derivatives are with respect to the evaluation point X.  For kb and rl the
 * "gradient" is the corrected one and G its derivative (not symmetric). */
#ifndef MFS_SHAPE_H
#define MFS_SHAPE_H

#include <stddef.h>

#include "mfs_kernel.h"
#include "mfs_particles.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const mfs_kernel_type *kernel;
  int dim;          /* 1..3 */
  double a;         /* support radius */
  double rcond_min; /* moment matrices with a smaller reciprocal condition number are singular */
} mfs_shape_ctx;

/* 1D position derivatives, for the consistent linearization of an Eulerian
 * kernel: the derivatives of phi_J(x) and of its gradient g_J(x) = d phi_J
 * / dx with respect to the position of neighbour K (d[K] = x_K - x), all
 * other positions and x fixed, for every J: dphi[J] = d phi_J / d x_K,
 * dgrad[J] = d g_J / d x_K.  Exact (forward-mode dual numbers through the
 * MLS formulas).  MFS_OK, MFS_EINVAL, MFS_ESINGULAR as eval. */
typedef int (*mfs_shape_dpos_fn)(const mfs_shape_ctx *c, int nn, const double *d,
                                 const double *v, int K, double *dphi, double *dgrad);

/* Position derivatives in any dimension (the consistent linearization of
 * an Eulerian kernel in 2D): the derivatives of phi_J(x) and of its gradient
 * g_J(x) with respect to the position of neighbour K along axis l
 * (d[K*dim + l] = x_K,l - x_l moves), x and every other position fixed, for
 * every J: dphi[J] = d phi_J / d x_K,l, dgrad[J*dim + m] = d g_J,m / d x_K,l.
 * Exact (forward-mode dual numbers through the MLS formulas).  MFS_OK,
 * MFS_EINVAL, MFS_ESINGULAR as eval. */
typedef int (*mfs_shape_dpos_dim_fn)(const mfs_shape_ctx *c, int nn, const double *d,
                                     const double *v, int K, int l, double *dphi, double *dgrad);

/* The same for one gradient and every neighbour at once (what a row of the
 * consistent Eulerian operator needs, O(nn) instead of O(nn^2)):
 * out[(K*dim + l)*dim + m] = d g_J,m / d x_K,l for every K < nn and l, m < dim;
 * work: mfs_shape_work_len(dim, nn) doubles. */
typedef int (*mfs_shape_dpos_grad_fn)(const mfs_shape_ctx *c, int nn, const double *d,
                                      const double *v, int J, double *out, double *work);

/* The fused 1D gather and evaluation (mfs_shape_type.gather_1d): the
 * candidates cand[0..nc) of the particles xp within a of x, their indices
 * to idx[0..*nn) and their values and derivatives to out (2 per neighbour);
 * with field (a nodal field, indexed like xp) not NULL also *grad = sum_J
 * phi_J'(x) field[idx_J], the field's gradient at x, in the same pass. */
typedef int (*mfs_shape_gather_1d_fn)(const mfs_shape_ctx *c, const mfs_box *box, double x,
                                      const double *xp, const int *cand, size_t nc, int *idx,
                                      double *out, double *work, int *nn, double *rcond,
                                      const double *field, double *grad);

typedef struct {
  const char *name;
  /* capabilities */
  int uses_volumes;           /* reads v[] */
  int partition_of_unity;     /* sum_J phi_J = 1 (all but sph) */
  int linear_complete;        /* the values reproduce linear fields (mls) */
  int gradient_is_derivative; /* the gradient is d phi / dX, not a corrected gradient
                                 (sph, shepard, mls; not kb, rl, sphs, cd2) */
  int gradient_linear;        /* the gradient reproduces the gradient of linear fields:
                                 sum_J G_J (X_J - X)^T = I (mls, kb, rl, cd2) */
  int uses_self;              /* the result depends on `self` (rl, sphs: the reference
                                 value of the symmetrized gradient) */
  /* d: nn*dim offsets X_J - X; v: nn volumes (may be NULL if !uses_volumes);
   * self: index in 0..nn-1 of the neighbour located at X, or -1;
   * order: 1 or 2; out: nn*ncomp; work: mfs_shape_work_len(dim, nn) doubles;
   * rcond: set to the reciprocal condition number of the moment matrix (1 if none).
   * Returns MFS_OK or MFS_ESINGULAR. */
  int (*eval)(const mfs_shape_ctx *c, int nn, const double *d, const double *v, int self,
              int order, double *out, double *work, double *rcond);
  mfs_shape_dpos_fn dpos_1d;  /* NULL where not available (kb, rl) */
  /* Optional fast path (NULL: none): 1D, order 1, fused with the gather of
   * the neighbours, the values of eval; gather_1d(kernel) gives the function
   * for that kernel (specialized for the built-in ones).  It takes the
   * candidates cand[0..nc) at positions xp (the minimum image of box) and
   * keeps the neighbours with |x_J - x| < a: their indices to idx[0..*nn),
   * (phi, phi') to out; work: 3 nc doubles.  The rod solver's Eulerian force
   * calls it every step. */
  mfs_shape_gather_1d_fn (*gather_1d)(const mfs_kernel_type *kernel);
  int gather_1d_is_mls1d;     /* gather_1d is mfs_mls1d_gather (mfs_mls1d.h) with the kernel's
                                 formula: a caller may inline that one instead (mls) */
  mfs_shape_dpos_dim_fn dpos; /* any dimension; NULL where not available (kb, rl) */
  mfs_shape_dpos_grad_fn dpos_grad; /* one gradient, every neighbour; NULL as dpos */
} mfs_shape_type;

extern const mfs_shape_type mfs_shape_sph;
extern const mfs_shape_type mfs_shape_shepard;
extern const mfs_shape_type mfs_shape_mls;
extern const mfs_shape_type mfs_shape_kb;
extern const mfs_shape_type mfs_shape_rl;
extern const mfs_shape_type mfs_shape_sphs;
extern const mfs_shape_type mfs_shape_cd2;
extern const mfs_shape_type *const mfs_shape_types[];

const mfs_shape_type *mfs_shape_find(const char *name);

static inline int mfs_shape_ncomp(int dim, int order)
{
  return 1 + dim + (order >= 2 ? dim * dim : 0);
}

size_t mfs_shape_work_len(int dim, int nn);

/* t->dpos_1d, or MFS_ENOTSUP where the shape type has none. */
mfs_status mfs_shape_dpos_1d(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn, const double *d,
                      const double *v, int K, double *dphi, double *dgrad);

/* t->dpos_grad, or MFS_ENOTSUP where the shape type has none. */
mfs_status mfs_shape_dpos_grad(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn,
                               const double *d, const double *v, int J, double *out, double *work);

/* t->dpos, or MFS_ENOTSUP where the shape type has none. */
mfs_status mfs_shape_dpos(const mfs_shape_type *t, const mfs_shape_ctx *c, int nn, const double *d,
                          const double *v, int K, int l, double *dphi, double *dgrad);

#ifdef __cplusplus
}
#endif

#endif
