/* The plane-strain plate of the lambda_max benchmarks (not a test):
 * bench_lambda, bench_peigs and bench_phases time the same model.  NX x NY
 * nodes on a square lattice of [0, NX-1] x [0, NY-1] (spacing 1 m), cubic
 * MLS, D = 2, stress-quad, lumped mass, nu = 0.3, the rest mfstab's defaults
 * (E = 1, rho = 1), free edges. */
#ifndef MFS_BENCH_PLATE_H
#define MFS_BENCH_PLATE_H

#include <stdio.h>

#include "mfstab.h"

static inline mfs_model_spec bench_plate_spec(int nx, int ny)
{
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.dim = 2;
  s.disc.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .nx = nx, .ny = ny,
                               .lx = (double)(nx - 1), .ly = (double)(ny - 1)};
  s.disc.dilation = 2.0;
  s.disc.quadrature = &mfs_quad_stress_quad;
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.disc.material.poisson = 0.3;
  return s;
}

/* The plate assembled, its plan released (as mfstab eigs does before its
 * eigensolver); NULL after a line on stderr naming who failed. */
static inline mfs_model *bench_plate_model(int nx, int ny, const char *who)
{
  mfs_model_spec s = bench_plate_spec(nx, ny);
  mfs_status st;
  mfs_model *m = mfs_model_alloc(&s, &st, NULL);
  if (!m) {
    fprintf(stderr, "%s: model: %s\n", who, mfs_strerror(st));
    return NULL;
  }
  mfs_model_release_plan(m);
  return m;
}

#endif
