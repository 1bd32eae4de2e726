#include "par.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#ifdef MFS_HAVE_MPI
#include <mpi.h>
#endif

static int active = 0, rank = 0, size = 1;

/* The number of ranks an MPI launcher announced (Open MPI, MPICH's hydra,
 * PMIx), or 0 when not launched by one. */
static int launched_size(void)
{
  static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", NULL};
  for (int k = 0; vars[k]; k++) {
    const char *v = getenv(vars[k]);
    if (v && *v)
      return atoi(v) > 0 ? atoi(v) : 1;
  }
  return getenv("PMIX_RANK") ? 1 : 0;
}

/* This process's rank as the launcher announced it (0 if none). */
static int launched_rank(void)
{
  static const char *const vars[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", NULL};
  for (int k = 0; vars[k]; k++) {
    const char *v = getenv(vars[k]);
    if (v && *v)
      return atoi(v);
  }
  return 0;
}

/* Before dying on every rank of a launch without MPI: rank 0 alone says why. */
static void quiet_others(void)
{
  if (launched_rank() > 0 && !freopen("/dev/null", "w", stderr))
    exit(2);
}

#ifdef MFS_HAVE_MPI
static int failing = 0; /* leaving through cli_die with a code other than 0 */

static void finish(void)
{
  int fin = 0;
  if (active && !failing && MPI_Finalized(&fin) == MPI_SUCCESS && !fin)
    MPI_Finalize();
}

static void die_hook(int code)
{
  if (code != 0)
    failing = 1; /* no MPI_Finalize: the other ranks may never reach it */
  fflush(stdout);
  exit(code);
}
#endif

void par_init(int *argc, char ***argv, const char *cmd)
{
  int n = launched_size();
  if (n == 0)
    return;
  int distributed = strcmp(cmd, "eigs") == 0 || strcmp(cmd, "bound") == 0;
#ifndef MFS_HAVE_MPI
  (void)argc;
  (void)argv;
  if (n > 1)
    quiet_others();
  if (n > 1)
    cli_die(2, "launched on %d MPI ranks, but this mfstab was built without MPI: every rank would "
               "run the whole command; install libopenmpi-dev and libparpack2-dev and rebuild, or "
               "run it without mpirun",
            n);
  (void)distributed;
#else
  if (!distributed) {
    if (n > 1)
      quiet_others();
    if (n > 1)
      cli_die(2, "runs in one process; under mpirun (%d ranks) only eigs and bound are "
                 "distributed: run it without mpirun",
              n);
    return;
  }
  if (MPI_Init(argc, argv) != MPI_SUCCESS)
    cli_die(1, "MPI_Init failed");
  active = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  atexit(finish);
  cli_die_hook = die_hook;
  if (rank > 0) { /* rank 0 alone talks */
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
      cli_die(1, "rank %d: cannot redirect its output to /dev/null", rank);
  }
#endif
}

int par_active(void)
{
  return active;
}

int par_rank(void)
{
  return rank;
}

int par_size(void)
{
  return size;
}

int par_comm(void)
{
#ifdef MFS_HAVE_MPI
  return active ? (int)MPI_Comm_c2f(MPI_COMM_WORLD) : 0;
#else
  return 0;
#endif
}

const char *par_out_path(const char *path)
{
  return rank > 0 ? "/dev/null" : path;
}

void par_need_one(const char *what)
{
  if (size > 1)
    cli_die(2, "%s: not distributed (it needs one process); run it without mpirun or with -np 1",
            what);
}
