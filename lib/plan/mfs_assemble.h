/* Assembly: one machinery for finite models and periodic unit cells.
 *
 * The row of particle I is accumulated over the quadrature points that see
 * it (the plan's transposed lists), and for each point over the particles J
 * it sees, with a marker array (as in CSparse's cs_multiply); columns come
 * in order of first appearance.  What a row accumulates is a set of forms
 * (mfs_forms):
 *
 *   stiffness, scalar        K_IJ = C sum_Q w_Q grad phi_I . grad phi_J
 *                            (1D bar, C = E; 2D anti-plane, C = mu: paper 003 eq. 113)
 *   stiffness, plane strain  K_IJ = sum_Q w_Q B_I^T D B_J (2 x 2 blocks),
 *                            D from lambda and mu
 *   mass                     M_IJ = rho sum_Q w_Q phi_I phi_J (eq. 112)
 *   Eulerian, paper          G_IJ = sum_Q w_Q phi_I''(Q) (T_QJ - delta_IJ) with the
 *                            kernel motion of eqs 71, 89-92 (1D, mfs_dispersion.h)
 *   Eulerian, consistent     G_IJ = sum_Q w_Q [phi_I''(Q) T_QJ + d phi_I'(Q) / d x_J]
 *   gradient products        A^{jl}_IJ = sum_Q w_Q d_j phi_I(Q) d_l phi_J(Q) (2 x 2 blocks
 *                            in place of K; plane strain: a tangent contracts them)
 *   2D Eulerian terms        G^{jk}_IJ = sum_Q w_Q (D^IQ_J)_jk (2 x 2 blocks) with
 *                            D = H^I_Q (T_QJ - delta_IJ I) (paper) or
 *                            D = d grad phi_I(Q) / d x_J + H^I_Q T_QJ (consistent),
 *                            H^I_Q_jm = d_m d_j phi_I(Q), T_QJ the motion of the point:
 *                            delta at a particle; at a stress or Gauss point
 *                            F [phi_J I - u_J (x) grad phi_J], u_J = (I - F^-1)(x_J - x_I)
 *                            (paper) or phi_J I (consistent); F = diag(stretch, stretch_y)
 *   least squares            K += beta sum_Q w phi_I'' phi_J'', M -= beta sum_Q w phi_I'' phi_J
 *                            (Beissel-Belytschko, eqs 104-107)
 *
 * Finite models assemble every row into CSR (mfs_assemble_stiffness,
 * mfs_assemble_mass_consistent); the unit-cell analyses (mfs_stencil,
 * mfs_dispersion.h) assemble the rows of the particles of one cell of a
 * periodic box.  The lumped mass is m_I = rho sum_Q w_Q phi_I(Q), the row
 * sum of the consistent mass (eq. 131) for partition-of-unity shapes, and
 * the particle mass rho V_I (eq. 51) for sph. */
#ifndef MFS_ASSEMBLE_H
#define MFS_ASSEMBLE_H

#include <stddef.h>

#include "mfs_csr.h"
#include "mfs_disc.h"
#include "mfs_eval.h"
#include "mfs_material.h"
#include "mfs_plan.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { MFS_EULER_NONE, MFS_EULER_PAPER, MFS_EULER_CONSISTENT } mfs_euler_form;

/* The forms a row accumulates. */
typedef struct {
  int stiffness;            /* K blocks (ndof x ndof) */
  mfs_physics_kind physics; /* scalar or plane strain */
  double c[3];              /* scalar: c[0] = C; plane strain: lambda + 2 mu, lambda, mu */
  double density;           /* rho of the consistent mass M (0: no mass) */
  mfs_euler_form euler;     /* the Eulerian term G (1D scalar; the plan needs order 2) */
  double stretch;           /* F of the Eulerian analysis (1 if 0); 2D: F_11 */
  double stretch_y;         /* 2D: F_22 of the paper-style Eulerian term (1 if 0) */
  double ls_beta;           /* least-squares stabilization beta (0: none; order 2) */
  int outer;                /* plane strain: K holds the gradient products A^{jl} */
  double lumped_density;    /* rho of the row's lumped mass, mfs_row.lump = rho sum_Q w_Q
                               phi_I(Q) (0: none; eq. 131, partition-of-unity shapes) */
} mfs_forms;

/* The stiffness forms of a material (K only). */
mfs_forms mfs_forms_stiffness(const mfs_material *m);

/* One row's accumulators and workspace, reused row after row. */
typedef struct {
  size_t len;     /* columns of the last row */
  int *col;       /* len particle indices, in order of first appearance */
  double *K;      /* len * ndof^2: the stiffness block of each column, row-major */
  double *M;      /* len: consistent mass (if the forms have a density) */
  double *G;      /* len * gsz: the Eulerian term (if the forms have one) */
  int gsz;        /* doubles of G per column: 1 (1D), 4 (2D plane strain, row-major 2 x 2) */
  double lump;    /* the row's lumped mass (if the forms have a lumped_density) */
  /* private */
  int ndof;
  size_t cap;     /* columns a row can have; the accumulators hold one more (a discard slot) */
  const double *ctab; /* a chunk of the table (mfs_row_sweep without a plan table), */
  const int *cslot;   /* the entry of each point's row in it, */
  size_t cq0;         /* by point number less this (the block's smallest point) */
  int *mark;      /* particles: position in the row, or -1 */
  int *pcol;      /* a point's neighbours: their positions in the row */
  const size_t *tptr; /* the plan's table (mfs_plan_table) and points */
  const int *tidx;
  const double *ttab, *qw, *qx;
  const int *qnode;
  int nc, dim;
  mfs_eval ev;    /* consistent Eulerian form: the point's offsets */
  int *eidx;
  double *dphi, *dgrad, *dwork;
} mfs_row;

/* A row for plan pl and forms f.  MFS_OK, MFS_EINVAL (forms the plan's table
 * cannot give: second derivatives for the Eulerian and least-squares terms;
 * Eulerian terms other than 1D scalar or 2D plane strain; the outer form
 * without plane strain), MFS_ENOTSUP (the consistent term for a shape without
 * position derivatives), MFS_ENOMEM. */
mfs_status mfs_row_init(mfs_row *r, const mfs_plan *pl, const mfs_forms *f);
void mfs_row_free(mfs_row *r);

/* Accumulate the row of particle I.  MFS_OK, MFS_ENOMEM, or the shape
 * functions' status for the consistent Eulerian form (MFS_ESINGULAR). */
mfs_status mfs_row_assemble(mfs_row *r, const mfs_plan *pl, const mfs_forms *f, size_t particle);

/* Sort the columns of the last row by particle index (with their values). */
void mfs_row_sort(mfs_row *r);

/* Rows in parallel (gcc's OpenMP, mfs_threads.h): fn(ctx, r, I, thread)
 * once for every particle I with skip[I] == 0 (skip NULL: all), with r the
 * accumulated row of I as mfs_row_assemble leaves it (columns in order of
 * first appearance); rows go in blocks of consecutive particles, each block
 * to one thread (0 .. mfs_threads() - 1), its rows in increasing order; fn
 * may be called concurrently for rows of different blocks and writes only
 * what belongs to its row (or to its thread).  The plan's table is used if it
 * has one (of the order the forms need); without one, each block evaluates
 * the points its rows need (mfs_plan_eval_point, the same values), so that no
 * table is held: O(block) memory instead of O(table).  Values do not depend
 * on the number of threads.  MFS_OK; the status of mfs_row_init; of a point's
 * evaluation (MFS_ESINGULAR, *bad the smallest such point, as
 * mfs_plan_tabulate reports it); of mfs_row_assemble or fn at the first
 * failing row; MFS_ENOMEM. */
typedef mfs_status (*mfs_row_fn)(void *ctx, const mfs_row *r, size_t particle, int thread);
mfs_status mfs_row_sweep(const mfs_plan *pl, const mfs_forms *f, const unsigned char *skip,
                         mfs_row_fn fn, void *ctx, size_t *bad);

/* Symbolic assembly: the pattern of the matrices of the particles not fixed
 * (fixed: p->n flags, NULL: none), ndof degrees of freedom per particle
 * interleaved, numbered over the free particles in order (as mfs_model's
 * free dofs); the columns of each row sorted.  *A (mfs_csr_free) has ptr and
 * idx set and val allocated, not set.  From the plan's lists alone (no
 * table).  MFS_OK, MFS_EINVAL (ndof < 1), MFS_ENOMEM. */
mfs_status mfs_assemble_pattern(const mfs_plan *pl, int ndof, const unsigned char *fixed,
                                mfs_csr **A);

/* Numeric assembly into that pattern, in one sweep (mfs_row_sweep, so with
 * the plan's table or, without one, evaluating the points block by block):
 * the stiffness of mat into K, the consistent mass into M, the lumped mass
 * into m (n_free ndof), each that is not NULL; K and M must have the pattern
 * of mfs_assemble_pattern(pl, ndof of mat, fixed).  The values equal those
 * of the entries of mfs_assemble_stiffness, mfs_assemble_mass_consistent and
 * mfs_assemble_mass_lumped (the same terms added in the same order).
 * MFS_OK, MFS_EINVAL (plane strain in 1D, a pattern of another size),
 * MFS_ESINGULAR (at point *bad, as mfs_plan_tabulate), MFS_ENOMEM. */
mfs_status mfs_assemble_fill(const mfs_plan *pl, const mfs_material *mat,
                             const unsigned char *fixed, mfs_csr *K, mfs_csr *M, double *m,
                             size_t *bad);

/* Symbolic and numeric assembly in one sweep (the one-shot path of finite
 * models): *K (the stiffness of mat, if K is not NULL) and *M (the
 * consistent mass, if M is not NULL) allocated (mfs_csr_free), with the
 * pattern of mfs_assemble_pattern(pl, ndof of mat, fixed) and the values
 * mfs_assemble_fill writes into it, bit for bit; m (if not NULL) the lumped
 * mass as there.  Each row is accumulated once (mfs_row_sweep), its columns
 * sorted and appended in row order: no separate pass for the pattern, no
 * count pass (with threads, each thread appends the rows of a contiguous
 * range of blocks to its own arrays, reserved at the bound of their entries
 * and touched only where written, and the ranges are appended to the first
 * one's in order at the end, a chunk at a time).
 * MFS_OK, MFS_EINVAL (K and M both NULL, plane strain in 1D), MFS_ESINGULAR
 * (at point *bad), MFS_ENOMEM. */
mfs_status mfs_assemble(const mfs_plan *pl, const mfs_material *mat, const unsigned char *fixed,
                        mfs_csr **K, mfs_csr **M, double *m, size_t *bad);

/* The stiffness of a material over every particle, CSR of order n ndof
 * (plane strain dofs interleaved (u_x, u_y) per particle); *K is allocated
 * (mfs_csr_free). */
mfs_status mfs_assemble_stiffness(const mfs_plan *pl, const mfs_material *mat, mfs_csr **K);

/* Consistent mass (CSR, per dof) or lumped mass (vector of n ndof).  These
 * three take a plan with or without a table (mfs_assemble_fill); the columns
 * of each row come sorted. */
mfs_status mfs_assemble_mass_consistent(const mfs_plan *pl, const mfs_material *mat,
                                        mfs_csr **M);
mfs_status mfs_assemble_mass_lumped(const mfs_plan *pl, const mfs_material *mat, double *m);

/* Stencil of an interior particle of the infinite lattice of d (scalar
 * physics; d->source the infinite lattice): the row of particle 0 of a
 * periodic box large enough that no entry aliases. */
typedef struct {
  int j, k;     /* offset in lattice coordinates (a1, a2); k = 0 in 1D */
  double K, M;  /* stiffness and mass (lumped: M only at (0, 0)) */
} mfs_stencil_entry;

/* *entries is allocated (mfs_free()), sorted by (k, j).  MFS_OK; MFS_EINVAL
 * (not an infinite lattice, not scalar physics, a bad d); MFS_ESINGULAR at
 * quadrature point *bad; MFS_ENOMEM. */
mfs_status mfs_stencil(const mfs_disc *d, mfs_stencil_entry **entries, size_t *n, size_t *bad);

#ifdef __cplusplus
}
#endif

#endif
