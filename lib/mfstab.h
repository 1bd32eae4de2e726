/* libmfstab: stability and dispersion analysis of meshfree particle methods. */
#ifndef MFSTAB_H
#define MFSTAB_H

/* core */
#include "mfs_status.h"
#include "mfs_alloc.h"
#include "mfs_kernel.h"
#include "mfs_lapack.h"
#include "mfs_convention.h"
#include "mfs_material.h"
#include "mfs_hyper.h"
#include "mfs_shape.h"
#include "mfs_particles.h"
#include "mfs_neighbor.h"
#include "mfs_voronoi.h"
#include "mfs_delaunay.h"
#include "mfs_quad.h"
#include "mfs_csr.h"
/* plan */
#include "mfs_disc.h"
#include "mfs_eval.h"
#include "mfs_plan.h"
#include "mfs_assemble.h"
#include "mfs_model.h"
/* analysis */
#include "mfs_classify.h"
#include "mfs_closed.h"
#include "mfs_dispersion.h"
#include "mfs_eigen.h"
#include "mfs_lanczos.h"
#include "mfs_peigs.h"
#include "mfs_bound.h"
#include "mfs_spsolve.h"
#include "mfs_static.h"
/* time */
#include "mfs_explicit.h"
#include "mfs_integrator.h"
#include "mfs_solver.h"
#include "mfs_solver2d.h"
#include "mfs_tsph.h"
/* paper */
#include "mfs_paper.h"

#ifdef __cplusplus
extern "C" {
#endif



#ifdef __cplusplus
}
#endif

#endif
