/* Transparent huge pages for a large block (internal, not installed).
 * mfs_advise_huge(p, bytes): on Linux, madvise MADV_HUGEPAGE over the whole
 * pages of a block of at least 8 MB that has not been touched yet, where the
 * system's setting is "madvise" or "always"; advice only (nothing happens
 * elsewhere, or if the kernel declines; the memory is the same either way).
 * For the arrays that are written once and then streamed many times: the
 * stored operator of the eigensolvers (lib/analysis/mfs_symop.c) and
 * ARPACK's Lanczos basis.  With 4 KB pages the first touch of the 2 x 2
 * operator's 58 MB took a page fault per page (its fill at 2 10^5 unknowns:
 * 68-110 ms with them, 38-54 ms with 2 MB pages) and the products were
 * slower by their TLB misses (4.9-9.3 ms per product against 4.7-6.1 ms;
 * bench_lambda 316 --lanczos, one thread, load 2.5-5, alternating). */
#ifndef MFS_HUGE_H
#define MFS_HUGE_H

#include <stddef.h>

void mfs_advise_huge(void *p, size_t bytes);

#endif
