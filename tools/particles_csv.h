/* Particle files: a user's particle set as CSV (reading is I/O, so it lives
 * in the tools; the library gets the set as arrays, mfs_point_set).
 *
 *   x[,y][,volume][,group]      header, columns in any order, names exact
 *   0.0,0.0,2.5e-5,clamp        one particle per line
 *
 * x alone is a 1D set, x and y a 2D set; volume (length in 1D, area in 2D,
 * > 0) is optional (without it the volumes come from the set: the dual of
 * its intervals or Delaunay triangles); group is any label without commas
 * (options such as --fix name them).  Fields are trimmed of spaces and tabs,
 * a CR before the newline is dropped, blank lines are skipped.  Numbers are
 * strict decimal (no nan, inf, hex).  Every error is one line
 * "FILE:LINE: what is wrong" and exit 2. */
#ifndef MFSTAB_PARTICLES_CSV_H
#define MFSTAB_PARTICLES_CSV_H

#include <stddef.h>
#include <stdio.h>

#include "mfstab.h"

typedef struct {
  const char *path;
  int dim;             /* 1 or 2, from the header */
  size_t n;
  double *x;           /* n*dim */
  double *vol;         /* n, or NULL without a volume column */
  int *group;          /* n group ids, or NULL without a group column */
  char **names;        /* ngroups labels, in order of first appearance */
  int ngroups;
  size_t *line;        /* n: the file line of each particle (the header is line 1) */
  int dual_volumes;    /* the file had no volume column: vol holds the set's dual volumes */
  mfs_point_set set;   /* the arrays above, for the library */
  /* the reader's own while it reads (NULL after it): particle_file_free
   * releases them too, so that a caller who catches cli_die (the fuzzer,
   * tests/fuzz/fuzz_particles.c) leaks nothing */
  FILE *file;
  char *buf;           /* getline's line buffer (the C library's memory) */
  int *label_slot;     /* the group labels' hash: label_cap entries, group id + 1 or 0 */
  size_t label_cap;
} particle_file;

/* Read path (dies with exit 2 and one line on any error).  min_dist: two
 * particles closer than min_dist times the mean spacing are duplicates
 * (an error naming both lines). */
void particle_file_read(particle_file *pf, const char *path, double min_dist);

/* Complete the set: without a volume column, the dual volumes of its
 * intervals (1D) or Delaunay triangles (2D; dies naming the file when the
 * particles have no triangulation), computed once; and its typical spacing
 * (mfs_point_set_spacing) into pf->set.spacing. */
void particle_file_volumes(particle_file *pf);
/* Everything pf holds, also after particle_file_read died part way. */
void particle_file_free(particle_file *pf);

/* The fix mask of "--fix A[,B...]": 1 for the particles of those groups
 * (dies naming the file when a group is unknown or the file has no group
 * column).  malloc'ed, n flags. */
unsigned char *particle_file_fix_mask(const particle_file *pf, const char *groups);

/* The file line of particle I, and the nearest particle to a point (for
 * messages about quadrature points). */
size_t particle_file_line(const particle_file *pf, size_t I);
size_t particle_file_nearest(const particle_file *pf, const double *x);

#endif
