/* Threads (internal, not installed): gcc's OpenMP where the library was built
 * with it (meson's openmp_dep), one thread otherwise.  OMP_NUM_THREADS sets
 * the count.  The library's parallel loops give the same bits for any count:
 * each output is computed by one thread in a fixed order (rows, points), and
 * reductions combine per-thread results in thread order with the ties of the
 * serial loop (the first index wins); per-thread workspaces are allocated
 * before a parallel region, never inside it, so that the allocations (and
 * tests/test_alloc.sh's count of them) do not depend on the scheduling. */
#ifndef MFS_THREADS_H
#define MFS_THREADS_H

#ifdef _OPENMP
#include <omp.h>
#endif

/* The most threads a loop whose per-thread results live on the stack uses. */
#define MFS_MAX_THREADS 64

/* The threads a parallel region will use (at least 1). */
static inline int mfs_threads(void)
{
#ifdef _OPENMP
  int n = omp_get_max_threads();
  return n > 0 ? n : 1;
#else
  return 1;
#endif
}

/* The calling thread's number in its region, 0 .. mfs_threads() - 1. */
static inline int mfs_thread_id(void)
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

#endif
