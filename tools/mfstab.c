/* mfstab: stability and dispersion analysis of meshfree particle methods. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "par.h"

#ifndef MFSTAB_VERSION
#define MFSTAB_VERSION "unknown"
#endif

static const struct {
  const char *name;
  int (*run)(int, char **);
  const char *what;
} cmds[] = {
  {"stencil", cmd_stencil, "stiffness and mass stencil of an interior node of an infinite lattice"},
  {"dispersion", cmd_dispersion, "von Neumann dispersion curves and stability classification"},
  {"eigs", cmd_eigs,
   "extreme eigenvalues, zero-energy modes and critical time step of a finite model"},
  {"bound", cmd_bound, "cheap element eigenvalue bound and critical time step (eqs 123-146)"},
  {"run", cmd_run, "explicit reference solver on a scene file (INI)"},
  {"map", cmd_map, "stability over a grid of states (stretches, stresses): PDE and kernel frames"},
  {"check", cmd_check, "check your own discretization: stability, modes and time steps you can trust"},
  {"static", cmd_static, "static elasticity with the seven particle methods of paper 004"},
  {"reproduce", cmd_reproduce, "regenerate the reproduced tables and figures into notebooks-data/"},
};
enum { NCMDS = sizeof cmds / sizeof cmds[0] };

/* Testing hooks (tests/test_alloc.sh), not for users: MFSTAB_ALLOC_FAIL=k
 * makes the k-th allocation of the library and the program return NULL;
 * MFSTAB_ALLOC_COUNT=FILE writes the number of allocations made to FILE at
 * exit.  Through mfs_set_allocator (lib/core/mfs_alloc.h). */
static long alloc_made, alloc_fail;
static int alloc_abort; /* MFSTAB_ALLOC_ABORT=1: abort at the failing one (for a debugger) */
static const char *alloc_count_path;

static int fail_this(void)
{
  if (++alloc_made != alloc_fail)
    return 0;
  if (alloc_abort)
    abort();
  return 1;
}

static void *test_malloc(size_t n)
{
  return fail_this() ? NULL : malloc(n);
}

static void *test_calloc(size_t c, size_t n)
{
  return fail_this() ? NULL : calloc(c, n);
}

static void *test_realloc(void *p, size_t n)
{
  return fail_this() ? NULL : realloc(p, n);
}

static void write_alloc_count(void)
{
  FILE *f = fopen(alloc_count_path, "w");
  if (f) {
    fprintf(f, "%ld\n", alloc_made);
    fclose(f);
  }
}

static void alloc_hooks(void)
{
  const char *k = getenv("MFSTAB_ALLOC_FAIL");
  alloc_count_path = getenv("MFSTAB_ALLOC_COUNT");
  if (!k && !alloc_count_path)
    return;
  alloc_fail = k ? atol(k) : 0;
  alloc_abort = getenv("MFSTAB_ALLOC_ABORT") != NULL;
  static const mfs_allocator counting = {test_malloc, test_calloc, test_realloc, free};
  mfs_set_allocator(&counting);
  if (alloc_count_path)
    atexit(write_alloc_count);
}

static void usage(FILE *f)
{
  fputs("usage: mfstab COMMAND [options]    (mfstab COMMAND --help, or mfstab help COMMAND)\n"
        "       mfstab --version\n"
        "commands:\n",
        f);
  for (int i = 0; i < NCMDS; i++)
    fprintf(f, "  %-12s %s\n", cmds[i].name, cmds[i].what);
}

static int find(const char *name)
{
  for (int i = 0; i < NCMDS; i++)
    if (strcmp(name, cmds[i].name) == 0)
      return i;
  return -1;
}

static _Noreturn void unknown(const char *name)
{
  fprintf(stderr, "mfstab: '%s': unknown command; allowed:", name);
  for (int i = 0; i < NCMDS; i++)
    fprintf(stderr, "%s %s", i ? "," : "", cmds[i].name);
  fputc('\n', stderr);
  exit(2);
}

/* libgomp reads OMP_WAIT_POLICY once, when it is loaded (before main), and
 * by default its idle threads spin between parallel regions: on a shared
 * machine that doubled the CPU time of `mfstab reproduce` (6 s instead of
 * 2.7 s, 7 s wall instead of 2.7 s at a load of 5).  Without a policy in the
 * environment the program therefore runs itself again with
 * OMP_WAIT_POLICY=passive (same pid, arguments and environment otherwise);
 * not under valgrind (its preload), under mpirun, or with MFSTAB_NO_REEXEC
 * set; if the exec fails it goes on as it is. */
static void omp_passive(char **argv)
{
#ifdef _OPENMP
  const char *pre = getenv("LD_PRELOAD");
  if (getenv("OMP_WAIT_POLICY") || getenv("MFSTAB_NO_REEXEC") || (pre && strstr(pre, "vgpreload")) ||
      getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_RANK") || getenv("PMIX_RANK"))
    return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) == 0)
    execv("/proc/self/exe", argv);
#else
  (void)argv;
#endif
}

int main(int argc, char **argv)
{
  omp_passive(argv);
  gsl_set_error_handler_off();
  alloc_hooks();
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0) {
    printf("mfstab %s\n", MFSTAB_VERSION);
    return 0;
  }
  if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
      (strcmp(argv[1], "help") == 0 && argc == 2)) {
    usage(stdout);
    return 0;
  }
  if (strcmp(argv[1], "help") == 0) { /* mfstab help CMD: CMD --help */
    int k = find(argv[2]);
    if (k < 0)
      unknown(argv[2]);
    if (argc > 3) {
      fprintf(stderr, "mfstab help: '%s': unexpected argument; usage: mfstab help COMMAND\n",
              argv[3]);
      return 2;
    }
    char *av[3] = {argv[2], "--help", NULL};
    cli_command = cmds[k].name;
    return cmds[k].run(2, av);
  }
  int k = find(argv[1]);
  if (k < 0)
    unknown(argv[1]);
  cli_command = cmds[k].name;
  par_init(&argc, &argv, cli_command); /* MPI, when launched by mpirun (tools/par.h) */
  return cmds[k].run(argc - 1, argv + 1);
}
