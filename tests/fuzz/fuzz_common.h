/* What the libFuzzer targets share (tests/fuzz/): a refusal of the tools
 * (cli_die: one line, exit 2 or 1) returns to the target through
 * cli_die_hook and a longjmp to fuzz_back, where the target releases what it
 * holds; the targets that read a file get the input through an anonymous
 * in-memory file, opened by its /proc/self/fd path as the tools open
 * theirs. */
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

#endif
