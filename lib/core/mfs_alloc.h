/* The library's allocator, which a client can replace: every allocation of
 * libmfstab (and of CHOLMOD while it works for the library) goes through
 * these four functions, so that a program can count them, limit them, or
 * make the k-th fail (tests/test_alloc.sh fails each in turn and checks that
 * every command ends in exit 1 with one line and, under ASan, no leak).
 *
 * Out of memory is always reported as MFS_ENOMEM, and nothing the failing
 * call had allocated is left behind.  Two allocations do not go through the
 * hook: GSL's inside gsl_rng_alloc (the perturbed lattices' generator) and
 * gsl_integration_glfixed_table_alloc (Gauss-Legendre points); their
 * failure is checked and reported as MFS_ENOMEM all the same. */
#ifndef MFS_ALLOC_H
#define MFS_ALLOC_H

#include <stddef.h>

#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  void *(*malloc)(size_t size);
  void *(*calloc)(size_t count, size_t size);
  void *(*realloc)(void *p, size_t size);
  void (*free)(void *p);
} mfs_allocator;

/* Use a (all four members set) from now on, or the C library's for NULL.
 * Memory must be freed by the allocator that gave it: set the allocator
 * before any call that allocates, and not while objects of the library are
 * alive.  Not thread-safe (a process-wide setting).  MFS_OK, or MFS_EINVAL
 * for a member missing. */
mfs_status mfs_set_allocator(const mfs_allocator *a);

/* The allocator in use. */
const mfs_allocator *mfs_get_allocator(void);

/* The library's allocation calls (what lib/ calls instead of malloc ...). */
void *mfs_malloc(size_t size);
void *mfs_calloc(size_t count, size_t size);
void *mfs_realloc(void *p, size_t size);
void mfs_free(void *p);
/* strdup through the allocator (NULL on failure). */
char *mfs_strdup(const char *s);
/* Free what the C library allocated itself (open_memstream's buffer): the C
 * library's free, whatever allocator is set. */
void mfs_free_libc(void *p);

#ifdef __cplusplus
}
#endif

#endif
