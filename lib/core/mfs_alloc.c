/* madvise (Linux): the C library declares it for _DEFAULT_SOURCE */
#define _DEFAULT_SOURCE 1
#include "mfs_alloc.h"
#include "mfs_huge.h"

#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#ifdef __linux__
#include <sys/mman.h>
#endif

#include <suitesparse/SuiteSparse_config.h>

static void *c_malloc(size_t size) { return malloc(size); }
static void *c_calloc(size_t count, size_t size) { return calloc(count, size); }
static void *c_realloc(void *p, size_t size) { return realloc(p, size); }
static void c_free(void *p) { free(p); }

static const mfs_allocator libc_allocator = {c_malloc, c_calloc, c_realloc, c_free};
static mfs_allocator current = {c_malloc, c_calloc, c_realloc, c_free};

/* CHOLMOD allocates through SuiteSparse's process-wide configuration: it is
 * pointed at the library's allocator while a client's allocator is set, and
 * given back its own functions when the C library's is restored. */
static struct {
  int saved;
  void *(*malloc_func)(size_t);
  void *(*calloc_func)(size_t, size_t);
  void *(*realloc_func)(void *, size_t);
  void (*free_func)(void *);
} suitesparse;

mfs_status mfs_set_allocator(const mfs_allocator *a)
{
  if (a && (!a->malloc || !a->calloc || !a->realloc || !a->free))
    return MFS_EINVAL;
  if (!suitesparse.saved) {
    suitesparse.malloc_func = SuiteSparse_config.malloc_func;
    suitesparse.calloc_func = SuiteSparse_config.calloc_func;
    suitesparse.realloc_func = SuiteSparse_config.realloc_func;
    suitesparse.free_func = SuiteSparse_config.free_func;
    suitesparse.saved = 1;
  }
  if (!a) {
    current = libc_allocator;
    SuiteSparse_config.malloc_func = suitesparse.malloc_func;
    SuiteSparse_config.calloc_func = suitesparse.calloc_func;
    SuiteSparse_config.realloc_func = suitesparse.realloc_func;
    SuiteSparse_config.free_func = suitesparse.free_func;
    return MFS_OK;
  }
  current = *a;
  SuiteSparse_config.malloc_func = mfs_malloc;
  SuiteSparse_config.calloc_func = mfs_calloc;
  SuiteSparse_config.realloc_func = mfs_realloc;
  SuiteSparse_config.free_func = mfs_free;
  return MFS_OK;
}

const mfs_allocator *mfs_get_allocator(void)
{
  return &current;
}

void *mfs_malloc(size_t size)
{
  return current.malloc(size);
}

void *mfs_calloc(size_t count, size_t size)
{
  return current.calloc(count, size);
}

void *mfs_realloc(void *p, size_t size)
{
  return current.realloc(p, size);
}

void mfs_free(void *p)
{
  current.free(p);
}

char *mfs_strdup(const char *s)
{
  size_t n = strlen(s) + 1;
  char *d = mfs_malloc(n);
  if (d)
    memcpy(d, s, n);
  return d;
}

void mfs_free_libc(void *p)
{
  free(p);
}

void mfs_advise_huge(void *p, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const uintptr_t page = 4096, huge = (uintptr_t)1 << 21;
  if (!p || bytes < 4 * huge)
    return;
  uintptr_t a = ((uintptr_t)p + page - 1) & ~(page - 1), e = ((uintptr_t)p + bytes) & ~(page - 1);
  if (e > a)
    (void)madvise((void *)a, e - a, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}
