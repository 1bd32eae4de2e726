/* OpenMP without a hard dependency (internal, not installed): MFS_OMP("omp
 * parallel for ...") is the pragma where the build has OpenMP and nothing
 * otherwise; mfs_omp_threads() and mfs_omp_thread() are the team's size and
 * the caller's index (1 and 0 without OpenMP).  Loops parallelized with it
 * compute every item on its own and combine in a fixed order, so results do
 * not depend on the number of threads (docs/design.md, Threads). */
#ifndef MFS_OMP_H
#define MFS_OMP_H

#ifdef _OPENMP
#include <omp.h>
#define MFS_OMP(x) _Pragma(x)
static inline int mfs_omp_threads(void)
{
  return omp_get_max_threads();
}
static inline int mfs_omp_thread(void)
{
  return omp_get_thread_num();
}
#else
#define MFS_OMP(x)
static inline int mfs_omp_threads(void)
{
  return 1;
}
static inline int mfs_omp_thread(void)
{
  return 0;
}
#endif

#endif
