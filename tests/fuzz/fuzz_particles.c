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
 * that needs masses would be wrong: mfstab must refuse such a set). */
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
  }
  particle_file_free(&pf);
  return 0;
}
