/* libFuzzer target: the particle file reader (tools/particles_csv.c), the
 * users' own input to eigs, bound and check.  The input is the file (at most
 * 64 KB, written to an anonymous in-memory file and read by its
 * /proc/self/fd path, as the tools read theirs); the reader then completes
 * the set (particle_file_volumes: the dual volumes of the intervals or of the
 * Delaunay triangles by Qhull), and a file with groups gives the fix mask of
 * its first group.  A refusal (cli_die) returns to the fuzzer through
 * cli_die_hook and particle_file_free releases what the reader held; a
 * crash, a sanitizer report or a leak is a finding, and so is a set accepted
 * with a volume or spacing that is not finite and positive (every result
 * that needs masses would be wrong: mfstab must refuse such a set).  A set
 * of at most FUZZ_MAX_MODEL particles then becomes a model as eigs builds
 * one (mfs_model_alloc: plane strain in 2D, support 2.3 spacings, the
 * quadrature chosen by the input's length: nodal, stress points or Gauss
 * points): a refusal is a status, and a model that is built must have a
 * finite, symmetric stiffness and finite masses; with positive lumped
 * masses its spectrum (dense, LAPACK) must lie in [0, lambda_gershgorin],
 * and with a mass <= 0 the Gershgorin bound must say it does not apply. */
#include "fuzz_common.h" /* first: it defines _GNU_SOURCE (memfd_create) */

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "mfs_alloc.h"
#include "particles_csv.h"

static int fd = -1;
static char path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc, (void)argv;
  fuzz_catch_refusals("fuzz");
  fd = fuzz_file_open("particles.csv", path);
  return 0;
}

static particle_file pf;

#define FUZZ_MAX_MODEL 120

static void try_model(size_t size)
{
  static const char *const rules[2][3] = {{"nodal", "stress", "gauss2"},
                                          {"nodal", "stress-tri", "gauss2"}};
  mfs_model_spec sp = mfs_model_spec_default();
  mfs_disc *d = &sp.disc;
  d->dim = pf.dim;
  d->source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &pf.set};
  d->quadrature = mfs_quad_find(rules[pf.dim - 1][size % 3]);
  if (pf.dim == 2) {
    d->material.physics = MFS_PHYS_PLANE_STRAIN;
    d->material.poisson = 0.3;
  }
  d->support = 2.3 * pf.set.spacing;
  d->dilation = d->support / mfs_disc_dx(d);
  sp.fixed = MFS_FIX_NONE;
  mfs_status st;
  mfs_model *m = mfs_model_alloc(&sp, &st, NULL);
  if (!m)
    return; /* a refusal: the tools name it */
  fuzz_check_model(m);
  mfs_model_free(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (size > 65536)
    return 0;
  fuzz_file_write(fd, data, size);
  if (setjmp(fuzz_back) == 0) {
    particle_file_read(&pf, path, 1e-10);
    particle_file_volumes(&pf);
    if (!(pf.n >= (size_t)pf.dim + 1) || !(pf.set.spacing > 0.0) || !isfinite(pf.set.spacing))
      __builtin_trap();
    double sum = 0.0;
    for (size_t I = 0; I < pf.n; I++) {
      if (!(pf.vol[I] > 0.0) || !isfinite(pf.vol[I]))
        __builtin_trap();
      sum += pf.vol[I];
    }
    if (!isfinite(sum))
      __builtin_trap();
    if (pf.group && pf.ngroups > 0) {
      unsigned char *mask = particle_file_fix_mask(&pf, pf.names[0]);
      size_t fixed = 0;
      for (size_t I = 0; I < pf.n; I++)
        fixed += mask[I];
      if (fixed == 0) /* the first group names at least one particle */
        __builtin_trap();
      mfs_free(mask);
    }
    double c[2] = {pf.x[0], pf.dim == 2 ? pf.x[1] : 0.0};
    if (particle_file_line(&pf, particle_file_nearest(&pf, c)) == 0)
      __builtin_trap();
    if (pf.n <= FUZZ_MAX_MODEL)
      try_model(size);
  }
  particle_file_free(&pf);
  return 0;
}
