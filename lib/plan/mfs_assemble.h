/* Plans and assembly.
 *
 * A plan is built once from particles, a quadrature set, a kernel, a
 * dilation and a shape-function type: neighbour lists of the quadrature
 * points (cell lists, radius a = dilation * dx) and the table of shape
 * functions and derivatives there.  Second derivatives are tabulated only
 * when asked for (order 2).  Assembly of stiffness and mass reuses it.
 *
 * Stiffness (linearized, zero initial stress):
 *   scalar        K_IJ = C sum_Q w_Q grad phi_I . grad phi_J      1D bar (C = E),
 *                 2D anti-plane (C = shear modulus, paper 003 eq. 113)
 *   plane strain  K_IJ = sum_Q w_Q B_I^T D B_J, D from lambda and mu, dofs (2I, 2I+1)
 * Mass: consistent M_IJ = rho sum_Q w_Q phi_I phi_J (eq. 112); lumped
 * m_I = rho sum_Q w_Q phi_I(Q), the row sum of the consistent mass (eq. 131)
 * for partition-of-unity shapes, and the particle mass rho V_I (eq. 51) for
 * sph, which is not a partition of unity. */
#ifndef MFS_ASSEMBLE_H
#define MFS_ASSEMBLE_H

#include <stddef.h>

#include "mfs_csr.h"
#include "mfs_kernel.h"
#include "mfs_neighbor.h"
#include "mfs_particles.h"
#include "mfs_quad.h"
#include "mfs_shape.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const mfs_kernel_type *kernel;
  const mfs_shape_type *shape;
  double dilation;  /* D: support radius a = D * dx */
  int order;        /* 1: values and gradients; 2: also second derivatives */
  double rcond_min; /* threshold for a singular moment matrix (e.g. 1e-12) */
} mfs_plan_spec;

typedef struct {
  int dim;
  const mfs_particles *p; /* borrowed */
  const mfs_quad *q;      /* borrowed */
  mfs_shape_ctx ctx;
  const mfs_shape_type *shape;
  int order, ncomp;
  mfs_nlist *nl;  /* quadrature point -> particles within a */
  double *tab;    /* nl->ptr[nq] * ncomp: shape functions at the quadrature points */
  double rcond;   /* smallest reciprocal condition number met */
  size_t bad;     /* the quadrature point where building failed, if it did */
} mfs_plan;

/* Build a plan.  On failure returns NULL, sets *status (MFS_ESINGULAR:
 * singular moment matrix at quadrature point *bad; MFS_ETOOSMALL; MFS_EINVAL;
 * MFS_ENOMEM) and, if bad is not NULL, the failing point. */
mfs_plan *mfs_plan_alloc(const mfs_plan_spec *spec, const mfs_particles *p, const mfs_quad *q,
                         int *status, size_t *bad);
void mfs_plan_free(mfs_plan *pl);

typedef enum { MFS_PHYS_SCALAR, MFS_PHYS_PLANE_STRAIN } mfs_physics_kind;

typedef struct {
  mfs_physics_kind kind;
  double modulus; /* E (1D), shear modulus (anti-plane, plane strain) */
  double lambda;  /* Lame lambda (plane strain) */
  double density;
} mfs_material;

/* Degrees of freedom per particle of a physics kind. */
int mfs_physics_ndof(mfs_physics_kind kind);

/* Assemble the stiffness; *K is allocated (free with mfs_csr_free). */
int mfs_assemble_stiffness(const mfs_plan *pl, const mfs_material *mat, mfs_csr **K);

/* Consistent mass (CSR, per dof) or lumped mass (vector of n*ndof). */
int mfs_assemble_mass_consistent(const mfs_plan *pl, const mfs_material *mat, mfs_csr **M);
int mfs_assemble_mass_lumped(const mfs_plan *pl, const mfs_material *mat, double *m);

/* Stencil of an interior node of an infinite lattice: the row of node 0 of a
 * periodic lattice large enough that no entry aliases. */
typedef struct {
  int dim;
  mfs_lattice_kind lattice;
  double dx, gamma;
  const char *quadrature; /* rule name */
  mfs_plan_spec plan;
  mfs_material mat;
  int consistent_mass;
} mfs_stencil_spec;

typedef struct {
  int j, k;     /* offset in lattice coordinates (a1, a2); k = 0 in 1D */
  double K, M;  /* stiffness and mass (lumped: M only at (0, 0)) */
} mfs_stencil_entry;

/* *entries is allocated (free()); sorted by (k, j).  Scalar physics only. */
int mfs_stencil(const mfs_stencil_spec *spec, mfs_stencil_entry **entries, size_t *n,
                size_t *bad);

#ifdef __cplusplus
}
#endif

#endif
