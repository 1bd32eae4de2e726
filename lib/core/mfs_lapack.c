#include "mfs_lapack.h"

#include <stddef.h>
#include <string.h>

static _Thread_local mfs_lapack_record record;

void mfs_lapack_reset(void)
{
  memset(&record, 0, sizeof record);
}

const mfs_lapack_record *mfs_lapack_last(void)
{
  return &record;
}

static void note(const char *name, size_t len, int info)
{
  record.count++;
  record.info = info;
  size_t n = len < sizeof record.routine - 1 ? len : sizeof record.routine - 1;
  memcpy(record.routine, name, n);
  record.routine[n] = '\0';
  while (n > 0 && record.routine[n - 1] == ' ') /* Fortran strings are blank-padded */
    record.routine[--n] = '\0';
}

/* LAPACK's handler (gfortran's calling convention: the hidden string length
 * last).  Records and returns: the caller checks. */
void xerbla_(const char *srname, const int *info, size_t srname_len);
void xerbla_(const char *srname, const int *info, size_t srname_len)
{
  note(srname, srname_len, info ? *info : 0);
}

/* LAPACKE's handler (lapacke.h: void LAPACKE_xerbla(const char *name, lapack_int info)). */
void LAPACKE_xerbla(const char *name, int info);
void LAPACKE_xerbla(const char *name, int info)
{
  note(name, name ? strlen(name) : 0, info);
}
