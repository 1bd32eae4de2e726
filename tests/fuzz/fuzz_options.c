/* libFuzzer target: the option parser (tools/cli.c) with the shared
 * discretization and physics options and options of every other kind (lists
 * of numbers, integers, flags, a positional argument), then the descriptor
 * built from them (cli_disc_build, mfs_disc_check) and, when the work is
 * small, the stencil of the rule (mfs_stencil), checked finite, and a
 * finite model of its lattice (small_model).
 *
 * The input is the command line, one argument per line (at most 32).  A
 * refusal (cli_die) returns to the fuzzer through cli_die_hook; a crash, a
 * sanitizer report or a leak is a finding. */
#include "fuzz_common.h" /* first: it defines _GNU_SOURCE (memfd_create) */

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_alloc.h"
#include "mfstab.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc, (void)argv;
  fuzz_catch_refusals("fuzz");
  return 0;
}

typedef struct {
  cli_list stress, kappa;
  double tol;
  long points;
  int flag;
  const char *text;
} extra_opts;

#define OFF(f) offsetof(extra_opts, f)
static const cli_opt extra[] = {
  {.name = "--stress", .type = CLI_REALS, .arg = "S", .help = "", .offset = OFF(stress),
   .bounds = CLI_GE | CLI_LE, .lo = -1e6, .hi = 1e6},
  {.name = "--kappa", .type = CLI_REALS, .arg = "K", .help = "", .offset = OFF(kappa),
   .bounds = CLI_GE | CLI_LE, .lo = 0.0, .hi = 1e6},
  {.name = "--tol", .type = CLI_REAL, .arg = "T", .help = "", .offset = OFF(tol),
   .bounds = CLI_GT | CLI_LE, .lo = 0.0, .hi = 1.0},
  {.name = "--points", .type = CLI_INT, .arg = "N", .help = "", .offset = OFF(points),
   .bounds = CLI_GE | CLI_LE, .lo = 2, .hi = 100000},
  {.name = "--flag", .type = CLI_FLAG, .help = "", .offset = OFF(flag)},
  {.name = NULL, .type = CLI_TEXT, .arg = "FILE", .help = "", .offset = OFF(text)},
  {.type = CLI_END},
};

#define MAX_ARGS 32

static cli_disc o;
static extra_opts e;

static void free_lists(void)
{
  mfs_free(o.dilation.v);
  mfs_free(e.stress.v);
  mfs_free(e.kappa.v);
  o.dilation.v = e.stress.v = e.kappa.v = NULL;
}

/* A finite box of the descriptor's lattice (1D: 13 particles, 2D: 7 x 7,
 * perturbed by 0.3 dx for inputs of odd length), built as eigs builds one
 * and checked (fuzz_check_model): finite, symmetric, and with positive
 * lumped masses a spectrum within [0, lambda_gershgorin]. */
static void small_model(const mfs_disc *d, size_t size)
{
  mfs_model_spec sp = {.disc = *d, .fixed = MFS_FIX_NONE};
  mfs_source *src = &sp.disc.source;
  double dx = src->spacing > 0.0 ? src->spacing : 1.0, g = src->gamma > 0.0 ? src->gamma : 1.0;
  int nx = d->dim == 1 ? 13 : 7;
  src->nx = nx;
  src->ny = d->dim == 1 ? 0 : 7;
  src->lx = dx * (nx - 1);
  src->ly = d->dim == 1 ? 0.0 : dx * g * 6.0;
  src->perturb = size % 2 ? 0.3 : 0.0;
  src->seed = 2385;
  if (mfs_model_spec_check(&sp, NULL) != MFS_OK ||
      mfs_disc_plan_entries(&sp.disc, (double)nx * (d->dim == 1 ? 1.0 : 7.0), NULL) > 2e4)
    return;
  mfs_status st;
  mfs_model *m = mfs_model_alloc(&sp, &st, NULL);
  if (!m)
    return; /* a refusal: a status the tools name */
  fuzz_check_model(m);
  mfs_model_free(m);
}

static void small_work(const mfs_disc *d)
{
  double side = 4.0 * ceil(2.0 * d->dilation) + 4.0; /* the periodic box of mfs_stencil */
  if (mfs_disc_plan_entries(d, d->dim == 1 ? side : side * side, NULL) > 2e4)
    return;
  mfs_stencil_entry *s = NULL;
  size_t n = 0, bad = 0;
  if (mfs_stencil(d, &s, &n, &bad) == MFS_OK) {
    double sum = 0.0;
    for (size_t k = 0; k < n; k++)
      sum += s[k].K;
    if (!isfinite(sum))
      abort(); /* a stencil that was computed is finite */
  }
  mfs_free(s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (size > 4096)
    return 0;
  char *buf = mfs_malloc(size + 1);
  if (!buf)
    return 0;
  memcpy(buf, data, size);
  buf[size] = '\0';
  char *argv[MAX_ARGS + 1] = {"fuzz"};
  int argc = 1;
  for (char *s = buf; argc < MAX_ARGS;) {
    char *nl = strchr(s, '\n');
    if (nl)
      *nl = '\0';
    argv[argc++] = s;
    if (!nl)
      break;
    s = nl + 1;
  }
  argv[argc] = NULL;
  static unsigned char seen_disc[CLI_DISC_NOPTS], seen_phys[CLI_PHYSICS_NOPTS], seen_extra[8];
  memset(seen_disc, 0, sizeof seen_disc);
  memset(seen_phys, 0, sizeof seen_phys);
  memset(seen_extra, 0, sizeof seen_extra);
  cli_disc_defaults(&o);
  memset(&e, 0, sizeof e);
  cli_group groups[] = {{cli_disc_opts, &o, seen_disc},
                        {cli_physics_opts, &o, seen_phys},
                        {extra, &e, seen_extra}};
  if (setjmp(fuzz_back) == 0) {
    cli_parse(argc, argv, "usage: fuzz [OPTIONS]", "", groups, 3);
    mfs_disc d = cli_disc_build(&o, seen_disc);
    const char *field = NULL;
    if (mfs_disc_check(&d, &field) == MFS_OK) {
      small_work(&d);
      small_model(&d, size);
    }
  }
  free_lists();
  mfs_free(buf);
  return 0;
}
