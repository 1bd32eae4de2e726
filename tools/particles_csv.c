#include "particles_csv.h"
#include "mfs_alloc.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_select.h"

enum { COL_X, COL_Y, COL_VOLUME, COL_GROUP, NCOLS };
static const char *const col_names[NCOLS] = {"x", "y", "volume", "group"};

/* Trim spaces and tabs at both ends, in place. */
static char *trim(char *s)
{
  while (*s == ' ' || *s == '\t')
    s++;
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
    s[--n] = '\0';
  return s;
}

/* Split line at commas into at most max fields (pointers into line); the
 * count of fields (which may exceed max: those are not stored). */
static int split(char *line, char **f, int max)
{
  int k = 0;
  for (char *s = line;;) {
    char *c = strchr(s, ',');
    if (c)
      *c = '\0';
    if (k < max)
      f[k] = trim(s);
    k++;
    if (!c)
      break;
    s = c + 1;
  }
  return k;
}

/* ---- group labels: a small open-addressing hash ---------------------- */

static uint64_t hash_str(const char *s)
{
  uint64_t h = 1469598103934665603ULL;
  for (; *s; s++) {
    h ^= (unsigned char)*s;
    h *= 1099511628211ULL;
  }
  return h;
}

/* The id of label s, a new one when it is new (the hash in pf->label_slot). */
static int label_id(particle_file *pf, const char *s)
{
  if ((size_t)(pf->ngroups + 1) * 2 > pf->label_cap) { /* grow and rehash */
    size_t cap = pf->label_cap ? 2 * pf->label_cap : 64;
    int *slot = mfs_calloc(cap, sizeof *slot);
    if (!slot)
      cli_die(1, "out of memory");
    for (int g = 0; g < pf->ngroups; g++) {
      size_t i = hash_str(pf->names[g]) & (cap - 1);
      while (slot[i])
        i = (i + 1) & (cap - 1);
      slot[i] = g + 1;
    }
    mfs_free(pf->label_slot);
    pf->label_slot = slot;
    pf->label_cap = cap;
  }
  int *slot = pf->label_slot;
  size_t i = hash_str(s) & (pf->label_cap - 1);
  while (slot[i]) {
    if (strcmp(pf->names[slot[i] - 1], s) == 0)
      return slot[i] - 1;
    i = (i + 1) & (pf->label_cap - 1);
  }
  char **nn = mfs_realloc(pf->names, (size_t)(pf->ngroups + 1) * sizeof *nn);
  if (!nn)
    cli_die(1, "out of memory");
  pf->names = nn;
  if (!(pf->names[pf->ngroups] = mfs_strdup(s)))
    cli_die(1, "out of memory");
  slot[i] = ++pf->ngroups;
  return pf->ngroups - 1;
}

/* ---- reading --------------------------------------------------------- */

static void grow(particle_file *pf, size_t *cap, int has_vol, int has_group)
{
  size_t c = *cap ? 2 * *cap : 4096;
  double *x = mfs_realloc(pf->x, c * (size_t)pf->dim * sizeof *x);
  if (x)
    pf->x = x;
  size_t *ln = x ? mfs_realloc(pf->line, c * sizeof *ln) : NULL;
  if (ln)
    pf->line = ln;
  int ok = x && ln;
  if (ok && has_vol) {
    double *v = mfs_realloc(pf->vol, c * sizeof *v);
    ok = v != NULL;
    if (v)
      pf->vol = v;
  }
  if (ok && has_group) {
    int *g = mfs_realloc(pf->group, c * sizeof *g);
    ok = g != NULL;
    if (g)
      pf->group = g;
  }
  if (!ok)
    cli_die(1, "%s: out of memory at %zu particles", pf->path, pf->n);
  *cap = c;
}

/* The range of coordinates and typical spacings (m), that of --spacing:
 * the shape functions and the triangulation hold their results under a
 * change of scale from about 1e-50 to 1e50 m and fail beyond (a set at
 * 1e200 m made every squared distance infinite, and the duplicate test
 * failed as "out of memory"; at 1e70 m the MLS moment matrices were refused
 * as singular, at 1e90 m Qhull found no triangulation). */
#define COORD_MAX 1e30
#define SPACING_MIN 1e-30

static void number(const particle_file *pf, size_t ln, const char *col, const char *s, double *v)
{
  if (*s == '\0')
    cli_die(2, "%s:%zu: %s: empty field; expected a number", pf->path, ln, col);
  if (!cli_parse_double(s, v)) {
    const char *c = s + (*s == '+' || *s == '-');
    int word = strncmp(c, "nan", 3) == 0 || strncmp(c, "NaN", 3) == 0 || strncmp(c, "inf", 3) == 0 ||
               strncmp(c, "Inf", 3) == 0 || strncmp(c, "NAN", 3) == 0 || strncmp(c, "INF", 3) == 0;
    cli_die(2, "%s:%zu: %s '%s': %s", pf->path, ln, col, s,
            word ? "not a finite number" : "not a number (decimal, e.g. 0.25 or 2.5e-3)");
  }
}

static void coordinate(const particle_file *pf, size_t ln, const char *col, const char *s,
                       double *v)
{
  number(pf, ln, col, s, v);
  if (!(fabs(*v) <= COORD_MAX))
    cli_die(2, "%s:%zu: %s %s: beyond 1e30 m in magnitude; allowed |%s| <= 1e30 (as --spacing)",
            pf->path, ln, col, s, col);
}

void particle_file_read(particle_file *pf, const char *path, double min_dist)
{
  memset(pf, 0, sizeof *pf);
  pf->path = path;
  FILE *f = pf->file = fopen(path, "r");
  if (!f)
    cli_die(2, "--particles %s: cannot open the file (%s)", path, strerror(errno));
  size_t len = 0, ln = 0, cap = 0;
  ssize_t got;
  int col[NCOLS], ncol = 0, header = 0;
  int where[NCOLS] = {-1, -1, -1, -1}; /* field index of each column */
  char *fields[8], *buf;
  while ((got = getline(&pf->buf, &len, f)) >= 0) {
    buf = pf->buf;
    ln++;
    if (got > 0 && buf[got - 1] == '\n')
      buf[--got] = '\0';
    if (got > 0 && buf[got - 1] == '\r')
      buf[--got] = '\0';
    if (strlen(buf) != (size_t)got)
      cli_die(2, "%s:%zu: a NUL byte: not a text file", path, ln);
    char *t = trim(buf);
    if (*t == '\0')
      continue; /* blank lines */
    if (!header) {
      int k = split(t, fields, 8);
      if (k > NCOLS)
        cli_die(2, "%s:%zu: %d columns in the header; allowed: x, y, volume, group", path, ln, k);
      for (int i = 0; i < k; i++) {
        int c = -1;
        for (int j = 0; j < NCOLS; j++)
          if (strcmp(fields[i], col_names[j]) == 0)
            c = j;
        if (c < 0)
          cli_die(2, "%s:%zu: column '%s': unknown; allowed: x, y, volume, group (header first)",
                  path, ln, fields[i]);
        if (where[c] >= 0)
          cli_die(2, "%s:%zu: column '%s' twice", path, ln, fields[i]);
        where[c] = i;
        col[i] = c;
      }
      ncol = k;
      if (where[COL_X] < 0)
        cli_die(2, "%s:%zu: no column x; the header names x (1D) or x,y (2D), then optional "
                   "volume and group",
                path, ln);
      pf->dim = where[COL_Y] >= 0 ? 2 : 1;
      header = 1;
      continue;
    }
    int k = split(t, fields, 8);
    if (k != ncol)
      cli_die(2, "%s:%zu: %d fields; the header has %d", path, ln, k, ncol);
    if (pf->n == cap)
      grow(pf, &cap, where[COL_VOLUME] >= 0, where[COL_GROUP] >= 0);
    size_t I = pf->n;
    for (int i = 0; i < k; i++) {
      switch (col[i]) {
      case COL_X:
        coordinate(pf, ln, "x", fields[i], &pf->x[I * pf->dim]);
        break;
      case COL_Y:
        coordinate(pf, ln, "y", fields[i], &pf->x[I * pf->dim + 1]);
        break;
      case COL_VOLUME: {
        double v;
        number(pf, ln, "volume", fields[i], &v);
        if (!(v > 0.0))
          cli_die(2, "%s:%zu: volume %s: must be > 0", path, ln, fields[i]);
        pf->vol[I] = v;
        break;
      }
      case COL_GROUP:
        if (fields[i][0] == '\0')
          cli_die(2, "%s:%zu: group: empty label", path, ln);
        pf->group[I] = label_id(pf, fields[i]);
        break;
      }
    }
    pf->line[I] = ln;
    pf->n++;
  }
  int rerr = ferror(f), eof = feof(f);
  mfs_free_libc(pf->buf); /* getline's: the C library's */
  mfs_free(pf->label_slot);
  fclose(f);
  pf->buf = NULL;
  pf->label_slot = NULL;
  pf->label_cap = 0;
  pf->file = NULL;
  if (rerr)
    cli_die(2, "--particles %s: read error", path);
  if (!eof) /* getline stopped before the end: its memory */
    cli_die(1, "%s:%zu: out of memory", path, ln + 1);
  if (!header)
    cli_die(2, "%s:1: empty file; expected a header x[,y][,volume][,group] and one particle a line",
            path);
  if (pf->n == 0)
    cli_die(2, "%s:%zu: a header and no particles", path, ln);
  if (pf->n < (size_t)pf->dim + 1)
    cli_die(2, "%s:%zu: %zu particle%s; a %dD model needs at least %d", path,
            pf->line[pf->n - 1], pf->n, pf->n == 1 ? "" : "s", pf->dim, pf->dim + 1);
  if (pf->n > 100000000)
    cli_die(2, "%s: %zu particles: more than 10^8", path, pf->n);
  pf->set = (mfs_point_set){.dim = pf->dim, .n = pf->n, .x = pf->x, .vol = pf->vol};
  /* duplicates: two particles closer than min_dist of the typical spacing
   * (cell lists).  The spacing of the bulk: from the bounding box, one far
   * particle made it so large that every pair counted as a duplicate; the
   * box's where the bulk has none (a flat set, fewer than 4 particles) */
  double dx = mfs_point_set_bulk_spacing(&pf->set);
  if (!(dx > 0.0)) {
    mfs_disc d = mfs_disc_default();
    d.dim = pf->dim;
    d.source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &pf->set};
    dx = mfs_disc_dx(&d);
  }
  int found = 0;
  size_t i = 0, j = 0;
  double r = min_dist * (dx > 0.0 ? dx : 1.0);
  mfs_status st = r > 0.0 && isfinite(r) ? mfs_point_set_close_pair(&pf->set, r, &found, &i, &j)
                                          : MFS_OK;
  if (st != MFS_OK)
    cli_die(st == MFS_ENOMEM ? 1 : 2, "%s: the duplicate test: %s", path, mfs_strerror(st));
  if (found) {
    size_t a = pf->line[i] > pf->line[j] ? i : j, b = a == i ? j : i;
    if (pf->dim == 1)
      cli_die(2, "%s:%zu: the particle at x = %.17g is also on line %zu: duplicate points", path,
              pf->line[a], pf->x[a], pf->line[b]);
    cli_die(2, "%s:%zu: the particle at (%.17g, %.17g) is %s line %zu: duplicate points", path,
            pf->line[a], pf->x[2 * a], pf->x[2 * a + 1],
            pf->x[2 * a] == pf->x[2 * b] && pf->x[2 * a + 1] == pf->x[2 * b + 1]
              ? "also on"
              : "within 1e-10 mean spacings of the particle of",
            pf->line[b]);
  }
}

/* The particle farthest from the set's median point and its distance in
 * typical spacings of the bulk (0 if it cannot be told), for the message
 * when the set has no triangulation: a particle 10^9 spacings away (a
 * coordinate with the wrong unit or exponent) leaves Qhull no room for the
 * others. */
static double far_particle(const particle_file *pf, size_t *far)
{
  double h = mfs_point_set_bulk_spacing(&pf->set), med[2] = {0.0, 0.0}, best = 0.0;
  *far = 0;
  if (!(h > 0.0))
    return 0.0;
  for (int k = 0; k < pf->dim; k++)
    med[k] = mfs_kth_smallest(pf->x + k, pf->n, (size_t)pf->dim, pf->n / 2);
  for (size_t I = 0; I < pf->n; I++) {
    double d = 0.0;
    for (int k = 0; k < pf->dim; k++)
      d = fmax(d, fabs(pf->x[I * (size_t)pf->dim + (size_t)k] - med[k]));
    if (d > best) {
      best = d;
      *far = I;
    }
  }
  return best / h;
}

void particle_file_volumes(particle_file *pf)
{
  if (!pf->vol) {
    mfs_status st;
    mfs_particles *p = mfs_particles_from_set(&pf->set, 0, &st);
    size_t far = 0;
    double away = !p && st == MFS_EDOMAIN && pf->dim == 2 ? far_particle(pf, &far) : 0.0;
    if (away > 1e6)
      cli_die(2, "%s:%zu: the particle at (%.17g, %.17g) is %.3g typical spacings from the "
                 "middle of the set: no Delaunay triangulation; check its coordinates, or give a "
                 "volume column",
              pf->path, pf->line[far], pf->x[2 * far], pf->x[2 * far + 1], away);
    if (!p && st == MFS_EDOMAIN)
      cli_die(2, "%s: the particles have no Delaunay triangulation (all on a line?); give a volume "
                 "column",
              pf->path);
    if (!p)
      cli_die(1, "%s: %s", pf->path, mfs_strerror(st));
    pf->vol = mfs_malloc(pf->n * sizeof *pf->vol);
    if (!pf->vol)
      cli_die(1, "out of memory");
    memcpy(pf->vol, p->vol, pf->n * sizeof *pf->vol);
    mfs_particles_free(p);
    pf->dual_volumes = 1;
    pf->set.vol = pf->vol;
  }
  pf->set.spacing = mfs_point_set_spacing(&pf->set);
  if (!(pf->set.spacing >= SPACING_MIN && pf->set.spacing <= COORD_MAX))
    cli_die(2, "%s: typical spacing %g m (%s): allowed 1e-30 to 1e30 m, as --spacing", pf->path,
            pf->set.spacing,
            pf->dual_volumes ? "the median of the volumes of the set's cells"
                             : "the median of the volume column");
}

void particle_file_free(particle_file *pf)
{
  if (pf->file)
    fclose(pf->file);
  mfs_free_libc(pf->buf);
  mfs_free(pf->label_slot);
  mfs_free(pf->x);
  mfs_free(pf->vol);
  mfs_free(pf->group);
  for (int g = 0; g < pf->ngroups; g++)
    mfs_free(pf->names[g]);
  mfs_free(pf->names);
  mfs_free(pf->line);
  memset(pf, 0, sizeof *pf);
}

unsigned char *particle_file_fix_mask(const particle_file *pf, const char *groups)
{
  if (!pf->group)
    cli_die(2, "%s: --fix %s: the file has no group column to name the fixed particles", pf->path,
            groups);
  unsigned char *mask = mfs_calloc(pf->n, 1), *want = mfs_calloc((size_t)pf->ngroups + 1, 1);
  char *copy = mfs_strdup(groups);
  if (!mask || !want || !copy)
    cli_die(1, "out of memory");
  for (char *s = copy;;) {
    char *c = strchr(s, ',');
    if (c)
      *c = '\0';
    char *g = trim(s);
    int id = -1;
    for (int k = 0; k < pf->ngroups; k++)
      if (strcmp(pf->names[k], g) == 0)
        id = k;
    if (id < 0) {
      char names[512] = "";
      for (int k = 0; k < pf->ngroups && strlen(names) < 400; k++) {
        if (k)
          strcat(names, ", ");
        strncat(names, pf->names[k], 400 - strlen(names));
      }
      cli_die(2, "%s: --fix %s: no group '%s' in the file; groups: %s", pf->path, groups, g,
              names);
    }
    want[id] = 1;
    if (!c)
      break;
    s = c + 1;
  }
  for (size_t I = 0; I < pf->n; I++)
    mask[I] = want[pf->group[I]];
  mfs_free(copy);
  mfs_free(want);
  return mask;
}

size_t particle_file_line(const particle_file *pf, size_t I)
{
  return I < pf->n ? pf->line[I] : 0;
}

size_t particle_file_nearest(const particle_file *pf, const double *x)
{
  size_t best = 0;
  double bd = INFINITY;
  for (size_t I = 0; I < pf->n; I++) { /* one scan, for one message */
    double d = 0.0;
    for (int k = 0; k < pf->dim; k++) {
      double t = pf->x[I * pf->dim + k] - x[k];
      d += t * t;
    }
    if (d < bd) {
      bd = d;
      best = I;
    }
  }
  return best;
}
