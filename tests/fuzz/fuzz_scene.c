/* libFuzzer target: the scene parser of `mfstab run` (tools/scene.c) and,
 * for a scene small enough, the solver it builds and ten steps of it.
 *
 * The input is the text of a scene file.  A refusal (cli_die: one line,
 * exit 2 or 1) returns to the fuzzer through cli_die_hook; a crash, a
 * sanitizer report, a leak or a non-finite energy after a successful build
 * is a finding.  Built with -Dfuzz=true by clang (tests/fuzz/meson.build);
 * run by scripts/fuzz.sh. */
#include "fuzz_common.h" /* first: it defines _GNU_SOURCE (memfd_create) */

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "scene.h"

static int fd = -1;
static char path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc, (void)argv;
  fd = fuzz_file_open("scene.ini", path);
  fuzz_catch_refusals("run");
  return 0;
}

/* a scene the fuzzer may build: at most this many particles and entries */
#define FUZZ_MAX_NODES 400
#define FUZZ_MAX_ENTRIES 2e4

static void try_steps(scene *sc)
{
  double n = (double)sc->spec.disc.source.nx * (sc->dim == 2 ? (double)sc->ny : 1.0);
  if (n > FUZZ_MAX_NODES)
    return;
  sc->max_entries = FUZZ_MAX_ENTRIES; /* scene_build refuses a larger plan */
  mfs_integrator in = scene_build(sc);
  double dt = in.type->stable_dt(in.solver);
  if (isfinite(dt) && dt > 0.0 && in.type->set_dt(in.solver, 0.5 * dt, 0) == MFS_OK) {
    for (int k = 0; k < 10; k++)
      if (in.type->step(in.solver, sc->scheme) != MFS_OK)
        break;
    double kin, pot, mod;
    if (in.type->energy(in.solver, &kin, &pot, &mod) == MFS_OK && !(isfinite(kin) && isfinite(pot)))
      abort(); /* a stable step of a finite start must stay finite */
  }
  in.type->free(in.solver);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  fuzz_file_write(fd, data, size);
  static scene sc; /* static: it survives the longjmp */
  if (setjmp(fuzz_back) == 0) {
    scene_load(&sc, path);
    scene_finish(&sc);
    try_steps(&sc);
  }
  return 0;
}
