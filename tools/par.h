/* MPI in the program (tools/par.c).  `mpirun -np N mfstab eigs|bound ...`
 * distributes the model (lib/analysis/mfs_peigs.h): main() calls par_init,
 * which starts MPI only when the process was launched by an MPI launcher
 * (its environment says so) and the program was built with MPI; otherwise
 * everything runs in one process as without MPI.  Rank 0 alone talks: the
 * other ranks' standard output and error go to /dev/null, and they write no
 * file (par_out_path).  A failure (cli_die with a code other than 0) leaves
 * without MPI_Finalize, so that a rank that fails alone does not wait for
 * the others; the launcher then ends the job with that exit code. */
#ifndef MFSTAB_PAR_H
#define MFSTAB_PAR_H

/* Start MPI for command cmd if launched by mpirun.  Commands other than
 * eigs and bound on more than one rank, and a program built without MPI
 * launched on more than one rank, die with one line (exit 2). */
void par_init(int *argc, char ***argv, const char *cmd);

int par_active(void); /* MPI was started (any number of ranks) */
int par_rank(void);   /* 0 without MPI */
int par_size(void);   /* 1 without MPI */
int par_comm(void);   /* MPI_COMM_WORLD as a Fortran handle (mfs_peigs.h), 0 without MPI */

/* The output path of this rank: path on rank 0, "/dev/null" on the others. */
const char *par_out_path(const char *path);

/* Die (exit 2) when more than one rank runs and `what` (an option) needs one
 * process; with one rank it runs there. */
void par_need_one(const char *what);

#endif
