/* libmfstab: stability and dispersion analysis of meshfree particle methods. */
#ifndef MFSTAB_H
#define MFSTAB_H

#include "mfs_assemble.h"
#include "mfs_closed.h"
#include "mfs_csr.h"
#include "mfs_dispersion.h"
#include "mfs_kernel.h"
#include "mfs_neighbor.h"
#include "mfs_paper.h"
#include "mfs_model.h"
#include "mfs_eigen.h"
#include "mfs_explicit.h"
#include "mfs_bound.h"
#include "mfs_particles.h"
#include "mfs_quad.h"
#include "mfs_shape.h"
#include "mfs_solver.h"
#include "mfs_solver2d.h"
#include "mfs_status.h"
#include "mfs_tsph.h"
#include "mfs_voronoi.h"

#ifdef __cplusplus
extern "C" {
#endif



#ifdef __cplusplus
}
#endif

#endif
