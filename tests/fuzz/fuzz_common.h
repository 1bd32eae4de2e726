/* What the libFuzzer targets share (tests/fuzz/): a refusal of the tools
 * (cli_die: one line, exit 2 or 1) returns to the target through
 * cli_die_hook and a longjmp to fuzz_back, where the target releases what it
 * holds; the targets that read a file get the input through an anonymous
 * in-memory file, opened by its /proc/self/fd path as the tools open
 * theirs; the targets that build a model check its invariants with
 * fuzz_check_model. */
#ifndef MFS_FUZZ_COMMON_H
#define MFS_FUZZ_COMMON_H

#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* memfd_create; this header comes before any other */
#endif
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "cli.h"
#include "mfstab.h"

#include <lapacke.h>
#undef I /* complex.h's, through lapacke.h: the tools name particle indices I */
#include <math.h>

static jmp_buf fuzz_back;

static void fuzz_die_hook(int code)
{
  longjmp(fuzz_back, code ? code : 1);
}

/* Refusals come back to fuzz_back; the tools' messages name `command`. */
static inline void fuzz_catch_refusals(const char *command)
{
  cli_command = command;
  cli_die_hook = fuzz_die_hook;
}

/* An in-memory file named name (for messages), its path into path[64]. */
static inline int fuzz_file_open(const char *name, char path[64])
{
  int fd = memfd_create(name, 0);
  if (fd < 0)
    abort();
  snprintf(path, 64, "/proc/self/fd/%d", fd);
  return fd;
}

/* The file's contents made data[0 .. size-1]. */
static inline void fuzz_file_write(int fd, const uint8_t *data, size_t size)
{
  if (ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != (ssize_t)size)
    abort();
}

/* ---- the invariants of a model that was built (fuzz_particles,
 * fuzz_options) ---- */

#define FUZZ_MAX_DENSE 240 /* unknowns for the dense spectrum */

/* Row j's entry in column i (sorted rows), 0 if absent. */
static inline double fuzz_entry(const mfs_csr *K, size_t j, size_t i)
{
  size_t lo = K->ptr[j], hi = K->ptr[j + 1];
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if ((size_t)K->idx[mid] < i)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < K->ptr[j + 1] && (size_t)K->idx[lo] == i ? K->val[lo] : 0.0;
}

/* With positive lumped masses: the spectrum of M^-1/2 K M^-1/2 (dense,
 * LAPACK) lies in [0, lambda_gershgorin]: K is positive semidefinite (the
 * quadrature weights are positive) and the Gershgorin bound is proven. */
static inline void fuzz_check_spectrum(const mfs_model *m)
{
  size_t n = m->n;
  mfs_gershgorin_result gr;
  if (mfs_gershgorin_csr(m->K, m->m, m->dof, &gr) != MFS_OK)
    __builtin_trap();
  if (gr.nonpositive > 0) {
    if (!isnan(gr.lambda))
      __builtin_trap(); /* the bound must say it does not apply */
    return;
  }
  double *a = calloc(n * n, sizeof *a), *w = malloc(n * sizeof *w);
  if (!a || !w)
    abort();
  for (size_t i = 0; i < n; i++)
    for (size_t e = m->K->ptr[i]; e < m->K->ptr[i + 1]; e++) {
      size_t j = (size_t)m->K->idx[e];
      a[i * n + j] = m->K->val[e] / sqrt(m->m[i] * m->m[j]);
    }
  if (LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', (lapack_int)n, a, (lapack_int)n, w) == 0) {
    double top = fmax(fabs(w[0]), fabs(w[n - 1]));
    if (!isfinite(gr.lambda) || w[n - 1] > gr.lambda * (1.0 + 1e-10) + 1e-300 ||
        w[0] < -1e-9 * top)
      __builtin_trap();
  }
  free(a);
  free(w);
}

/* A built model: a finite stiffness, symmetric to 1e-10 of its largest
 * entry, finite masses, and with positive lumped masses the spectrum of
 * check_spectrum.  A violation is a finding (__builtin_trap). */
static inline void fuzz_check_model(const mfs_model *m)
{
  const mfs_csr *K = m->K;
  double kmax = 0.0;
  for (size_t e = 0; e < K->ptr[m->n]; e++) {
    if (!isfinite(K->val[e]))
      __builtin_trap();
    kmax = fmax(kmax, fabs(K->val[e]));
  }
  for (size_t i = 0; i < m->n; i++) {
    for (size_t e = K->ptr[i]; e < K->ptr[i + 1]; e++)
      if (fabs(K->val[e] - fuzz_entry(K, (size_t)K->idx[e], i)) > 1e-10 * kmax)
        __builtin_trap();
    if (m->m && !isfinite(m->m[i]))
      __builtin_trap();
  }
  if (m->m && m->n <= FUZZ_MAX_DENSE)
    fuzz_check_spectrum(m);
}

#endif
