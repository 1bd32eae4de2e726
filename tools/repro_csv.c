/* The rows of `mfstab reproduce` and the CSV files behind them, read back
 * (tools/repro.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "repro.h"

const char *repro_outdir = "notebooks-data";

const char *repro_path(const char *file)
{
  static char buf[8][1024];
  static int slot = 0;
  char *p = buf[slot];
  slot = (slot + 1) % 8;
  snprintf(p, sizeof buf[0], "%s/%s", repro_outdir, file);
  return p;
}

const char *repro_errata(int cond, const char *entry)
{
  static char buf[8][24];
  static int slot = 0;
  if (!cond)
    return "differs";
  char *b = buf[slot];
  slot = (slot + 1) % 8;
  snprintf(b, sizeof buf[0], "errata %s", entry);
  return b;
}

void repro_csv_free(repro_csv *t)
{
  mfs_free(t->name);
  mfs_free(t->cell);
  mfs_free(t->buf);
  *t = (repro_csv){0};
}

/* Split the text in place into fields (RFC 4180: quoted fields with doubled
 * quotes); returns the number of fields, or -1 if more than cap. */
static long split_fields(char **p, char **field, size_t cap, int *eol)
{
  size_t n = 0;
  char *s = *p;
  for (;;) {
    char *start = s, *w = s;
    if (*s == '"') {
      s++;
      for (; *s; s++) {
        if (*s == '"' && s[1] == '"') {
          *w++ = '"';
          s++;
        } else if (*s == '"') {
          s++;
          break;
        } else {
          *w++ = *s;
        }
      }
    } else {
      while (*s && *s != ',' && *s != '\n' && *s != '\r')
        *w++ = *s++;
    }
    char end = *s;
    if (n == cap)
      return -1;
    field[n++] = start;
    if (end == ',') {
      *w = '\0';
      s++;
      continue;
    }
    if (end == '\r' && s[1] == '\n')
      s++;
    if (*s)
      s++;
    *w = '\0';
    *eol = 1;
    *p = s;
    return (long)n;
  }
}

void repro_csv_read(repro_csv *t, const char *file)
{
  *t = (repro_csv){0};
  const char *path = repro_path(file);
  FILE *f = fopen(path, "rb");
  if (!f)
    cli_die(1, "cannot read %s", path);
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fseek(f, 0, SEEK_SET);
  t->buf = mfs_malloc((size_t)(len > 0 ? len : 0) + 1);
  if (!t->buf)
    cli_die(1, "out of memory");
  size_t got = fread(t->buf, 1, (size_t)len, f);
  fclose(f);
  t->buf[got] = '\0';
  size_t lines = 0;
  for (size_t i = 0; i < got; i++)
    lines += t->buf[i] == '\n';
  char *p = t->buf;
  char *hdr[256];
  int eol = 0;
  long nc = split_fields(&p, hdr, 256, &eol);
  if (nc < 1)
    cli_die(1, "reproduce: %s: no header", path);
  t->ncols = (size_t)nc;
  t->name = mfs_malloc(t->ncols * sizeof *t->name);
  t->cell = mfs_malloc((lines + 1) * t->ncols * sizeof *t->cell);
  if (!t->name || !t->cell)
    cli_die(1, "out of memory");
  memcpy(t->name, hdr, t->ncols * sizeof *hdr);
  while (*p) {
    char **row = t->cell + t->nrows * t->ncols;
    long n = split_fields(&p, row, t->ncols, &eol);
    if (n != (long)t->ncols)
      cli_die(1, "reproduce: %s: row %zu has not the header's %zu fields", path, t->nrows + 1,
              t->ncols);
    t->nrows++;
  }
}

size_t repro_col(const repro_csv *t, const char *file, const char *name)
{
  for (size_t c = 0; c < t->ncols; c++)
    if (strcmp(t->name[c], name) == 0)
      return c;
  cli_die(1, "reproduce: %s has no column %s", repro_path(file), name);
}

double repro_num(const repro_csv *t, size_t r, size_t c)
{
  const char *s = t->cell[r * t->ncols + c];
  return *s ? strtod(s, NULL) : NAN;
}

const char *repro_text(const repro_csv *t, size_t r, size_t c) { return t->cell[r * t->ncols + c]; }
