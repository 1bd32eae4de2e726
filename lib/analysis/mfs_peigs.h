/* Distributed finite models (MPI): lambda_max by PARPACK and the Gershgorin
 * and element bounds over ranks, for models larger than one machine.
 *
 * Partition.  The particles are bucketed into the cells of a grid of side
 * a little over a/2 (mfs_grid, the neighbour search's own cells, numbered
 * with x fastest); rank r owns a contiguous block of that cell order, cut at
 * the cell boundary nearest to r N / P particles.  On a lattice the blocks
 * are slabs across the last coordinate (rows of cells in 2D, segments of the
 * line in 1D).  Every rank computes the same partition from the same
 * particles: no communication.
 *
 * Rows of a rank.  A rank keeps the quadrature points within the support
 * radius a of one of its particles, and the particles within a of those
 * points (its own and a halo of neighbours' particles, within 2a of its
 * own), both in the global order, and builds on them the ordinary plan
 * (mfs_plan_alloc, mfs_plan_tabulate) and rows (mfs_row_assemble): every
 * point it keeps sees exactly the particles it sees in the whole model, in
 * the same order, so the shape functions, the lumped masses and the rows of
 * its particles are the whole model's, bit for bit, whatever the number of
 * ranks.  The rows of its free degrees of freedom are kept as CSR with the
 * columns sorted by global degree of freedom; columns of other ranks'
 * particles are the halo, received before each product.
 *
 * What is computed, collectively (every rank calls, every rank gets the
 * same result):
 *   mfs_pmodel_gershgorin  max_i sum_j |K_ij| / m_i from the local rows:
 *                          bit for bit mfs_gershgorin_csr of the whole
 *                          model's K (assembled) or mfs_gershgorin_plan
 *                          (streamed, not assembled)
 *   mfs_pmodel_bound       the element bound max_Q lambda^Q over the kept
 *                          points, each counted on one rank: bit for bit
 *                          mfs_bound_plan of the whole model
 *   mfs_peig_max           lambda_max of M^-1/2 K M^-1/2 (lumped mass) by
 *                          PARPACK's pdsaupd / pdseupd, each rank holding its
 *                          rows of the Lanczos vectors; the product exchanges
 *                          the halo values (point-to-point) before the local
 *                          rows.  The start vector is mfs_eig_max's, by global
 *                          degree of freedom; the dot products are reduced
 *                          over ranks, so the value agrees with one process
 *                          to rounding (about 1e-15 relative), not bit for bit.
 *
 * Not distributed: the consistent mass (its solves need a factorization),
 * zero modes and certification (factorizations of K - sigma M).  Every rank
 * builds the whole geometry (particles and quadrature points, O(N) per
 * rank, freed once its part is extracted); the plan, the shape table and
 * the rows, which hold most of the memory, are distributed.
 *
 * Communicators are passed as Fortran handles (MPI_Comm_c2f), so this header
 * needs no mpi.h.  Without MPI (the library built without it) every
 * function returns MFS_ENOTSUP and mfs_peigs_available() is 0.  Statuses are
 * agreed over the ranks: when one rank fails, all return the same status.
 * Collective calls must be made in the same order on every rank. */
#ifndef MFS_PEIGS_H
#define MFS_PEIGS_H

#include <stddef.h>

#include "mfs_bound.h"
#include "mfs_eigen.h"
#include "mfs_model.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 if the library was built with MPI and PARPACK. */
int mfs_peigs_available(void);

typedef struct mfs_pmodel mfs_pmodel;

/* What a rank holds (mfs_pmodel_sizes). */
typedef struct {
  int rank, size;          /* of the communicator */
  size_t particles;        /* of the whole model */
  size_t points;           /* quadrature points of the whole model */
  size_t dofs;             /* free degrees of freedom of the whole model */
  size_t own_particles;    /* owned by this rank */
  size_t local_particles;  /* owned and halo: the particles of the local plan */
  size_t local_points;     /* quadrature points of the local plan */
  size_t rows;             /* owned free degrees of freedom */
  size_t halo;             /* halo degrees of freedom received before each product */
  size_t sent;             /* degrees of freedom sent to other ranks in each product */
  int neighbours;          /* ranks exchanged with */
  size_t nnz;              /* stored entries of the local rows (0 when not assembled) */
  size_t plan_nnz;         /* neighbour entries of the local plan */
} mfs_pmodel_info;

/* Build this rank's part of the model of spec over communicator comm
 * (collective).  assemble: 1 keeps the rows of K (for mfs_peig_max and the
 * assembled Gershgorin bound), 0 keeps the plan only (the streamed
 * Gershgorin and element bounds: `mfstab bound`).  The spec is checked as
 * mfs_model_alloc checks it, and the same statuses are returned (NULL and
 * *status; MFS_ESINGULAR with *bad the global index of the failing
 * quadrature point, on every rank; MFS_EINVAL when every particle is
 * fixed); also MFS_ETOOSMALL when a rank owns no free degree of freedom
 * (more ranks than the model has cells for) and MFS_ENOTSUP without MPI.  spec->fix_mask is read during the call only. */
mfs_pmodel *mfs_pmodel_alloc(const mfs_model_spec *spec, int comm, int assemble,
                             mfs_status *status, size_t *bad);
void mfs_pmodel_free(mfs_pmodel *pm);

/* Drop the local plan (neighbour lists, shape table) and quadrature points,
 * which hold a good part of a rank's memory, once the element bound is
 * computed (as mfs_model_release_plan): the assembled rows, the masses and
 * mfs_peig_max stay; mfs_pmodel_bound and the streamed Gershgorin bound then
 * return MFS_EINVAL.  Local, no communication. */
void mfs_pmodel_release_plan(mfs_pmodel *pm);

/* Sizes of this rank's part (local to the rank, no communication). */
void mfs_pmodel_sizes(const mfs_pmodel *pm, mfs_pmodel_info *info);

/* The coordinates of global particle I, wherever it is owned (collective:
 * its owner broadcasts them); xy[1] = 0 in 1D.  MFS_OK, MFS_EINVAL. */
mfs_status mfs_pmodel_particle_x(const mfs_pmodel *pm, size_t particle, double *xy);

/* The Gershgorin bound with the lumped mass, as mfs_gershgorin_csr (assembled)
 * or mfs_gershgorin_plan (not assembled) on the whole model, with the same
 * global degrees of freedom in argmax, first_nonpositive and argmin_mass.
 * Collective.  MFS_OK, MFS_ENOMEM, MFS_ENOTSUP. */
mfs_status mfs_pmodel_gershgorin(const mfs_pmodel *pm, mfs_gershgorin_result *r);

/* The element bound, as mfs_bound_plan on the whole model (argmax the global
 * quadrature point).  Points with no particle within a are not counted.
 * Collective.  MFS_OK, MFS_EINVAL, MFS_ENOMEM, MFS_ENOTSUP. */
mfs_status mfs_pmodel_bound(const mfs_pmodel *pm, mfs_bound_result *r);

/* lambda_max of K v = lambda m v with the lumped mass m (every m_i > 0),
 * distributed (an assembled pmodel; collective).  opts as mfs_eig_max;
 * info->iterations, matvecs, nconv, runs and residual as there (the residual
 * of the returned pair ||K v - lambda M v|| / (lambda ||M v||) reduced over
 * ranks).  MFS_OK; MFS_EINVAL (not assembled, fewer than 2 dofs, a mass <= 0
 * on some rank); MFS_ENOCONV; MFS_EARPACK (info->routine "pdsaupd" or
 * "pdseupd"); MFS_ENOMEM; MFS_ENOTSUP. */
mfs_status mfs_peig_max(const mfs_pmodel *pm, const mfs_eig_opts *opts, double *lambda,
                        mfs_eig_info *info);

/* The halo exchange on its own, for tests and benchmarks: y (rows) = K x
 * with x the owned values of a global vector (rows), through the same
 * exchange as mfs_peig_max's products, scaled by nothing.  Collective.
 * MFS_OK, MFS_EINVAL (not assembled), MFS_ENOTSUP. */
mfs_status mfs_pmodel_matvec(const mfs_pmodel *pm, const double *x, double *y);

/* The global degree of freedom (free numbering, as mfs_model's K) of local
 * row i, or -1 for i out of range. */
long mfs_pmodel_row_dof(const mfs_pmodel *pm, size_t i);

#ifdef __cplusplus
}
#endif

#endif
