/* LAPACK's error handlers, replaced so that nothing prints and nothing stops.
 *
 * The reference LAPACK calls xerbla_ on an illegal argument, which prints
 * "Parameter N to routine NAME was incorrect" and STOPs the program; LAPACKE
 * calls LAPACKE_xerbla, which prints "Wrong parameter" or "Not enough
 * memory".  libmfstab defines both symbols (they take precedence over the
 * libraries loaded after it, as dynamic symbol lookup goes): each records
 * the routine and the argument, and returns.  The library's calls reset
 * the record before a LAPACK, LAPACKE or ARPACK call and check it after,
 * returning MFS_ELAPACK / MFS_EARPACK (or MFS_ENOMEM for LAPACKE's work
 * memory).  A client that calls LAPACK itself can read the record too. */
#ifndef MFS_LAPACK_H
#define MFS_LAPACK_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  int count;        /* errors since the last reset */
  int info;         /* the last one's argument number (LAPACK), or LAPACKE's code */
  char routine[16]; /* the last one's routine name */
} mfs_lapack_record;

/* Clear the record (this thread's). */
void mfs_lapack_reset(void);

/* The record of this thread. */
const mfs_lapack_record *mfs_lapack_last(void);

#ifdef __cplusplus
}
#endif

#endif
