/* Benchmark (not a test): the first touch of fresh memory on this machine,
 * the cost under every new large array (the Lanczos storage build of
 * mfs_lanczos_max writes 68 MB it has just allocated; docs/benchmarks.md,
 * round 9).  For each size and page kind, a fresh anonymous mapping (2 MB
 * aligned), advised MADV_HUGEPAGE or not, then
 *   first_touch  one byte written per 4 KB page (the page faults: the kernel
 *                zeroes each page, and on a virtual machine the host may
 *                have to back it first);
 *   rewrite      memset of the whole block (the same pages, now mapped: the
 *                write bandwidth),
 * and the mapping is released; R rounds over all sizes and kinds, in turns
 * (the released pages go back to the guest's free lists, so a later round
 * may get pages the host has backed already: the rounds show how much of the
 * cost is the host's).
 *   bench_first_touch [--rounds R] [-o FILE] [MB ...]   (default 5 rounds, 68 256 MB)
 * CSV: size_mb,pages,round,first_touch_s,first_touch_gbs,rewrite_s,rewrite_gbs,load1
 *   (pages: huge = 2 MB advised, base = 4 KB); analysis/bench/limits.py adds
 *   the limit: the block's bytes at the one-thread bandwidth. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "bench_common.h"

static int one(FILE *f, size_t mb, int huge, int round)
{
  const size_t n = mb << 20, align = (size_t)2 << 20;
  char *p = mmap(NULL, n + align, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) {
    fprintf(stderr, "bench_first_touch: mmap of %zu MB failed\n", mb);
    return 1;
  }
  char *q = (char *)(((size_t)p + align - 1) & ~(align - 1));
  if (huge)
    madvise(q, n, MADV_HUGEPAGE);
  double l = bench_load1(), t0 = bench_now();
  for (size_t i = 0; i < n; i += 4096)
    q[i] = 1;
  double t1 = bench_now();
  memset(q, 2, n);
  double t2 = bench_now();
  volatile char keep = q[n / 2]; /* the memset is not dead */
  (void)keep;
  munmap(p, n + align);
  fprintf(f, "%zu,%s,%d,%.6f,%.3f,%.6f,%.3f,%.2f\n", mb, huge ? "huge" : "base", round, t1 - t0,
          1e-9 * (double)n / (t1 - t0), t2 - t1, 1e-9 * (double)n / (t2 - t1), l);
  return 0;
}

int main(int argc, char **argv)
{
  int rounds = 5;
  const char *out = NULL;
  size_t sizes[16], ns = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--rounds") && i + 1 < argc)
      rounds = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-o") && i + 1 < argc)
      out = argv[++i];
    else if (ns < 16 && atol(argv[i]) > 0)
      sizes[ns++] = (size_t)atol(argv[i]);
    else {
      fprintf(stderr, "usage: bench_first_touch [--rounds R] [-o FILE] [MB ...]\n");
      return 2;
    }
  }
  if (rounds < 1) {
    fprintf(stderr, "bench_first_touch: --rounds %d: at least 1\n", rounds);
    return 2;
  }
  if (ns == 0) {
    sizes[ns++] = 68;
    sizes[ns++] = 256;
  }
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f) {
    fprintf(stderr, "bench_first_touch: cannot write %s\n", out);
    return 1;
  }
  fprintf(f, "size_mb,pages,round,first_touch_s,first_touch_gbs,rewrite_s,rewrite_gbs,load1\n");
  int bad = 0;
  for (int r = 1; r <= rounds && !bad; r++)
    for (size_t s = 0; s < ns && !bad; s++)
      for (int huge = 1; huge >= 0 && !bad; huge--)
        bad = one(f, sizes[s], huge, r);
  if (out)
    bad |= fclose(f) != 0;
  return bad;
}
