/* The parts of `mfstab reproduce` (tools/cmd_reproduce.c): one row per
 * artifact of the four papers, and the CSV files behind the rows, read back
 * from the output directory (the rows are computed from what the commands
 * wrote, so a row and its CSV cannot disagree). */
#ifndef MFSTAB_REPRO_H
#define MFSTAB_REPRO_H

#include <stddef.h>

/* One row of the table: the artifact ("003 Fig 4 ..."; the paper's number
 * first), the paper's value as printed, ours (NAN: none, an empty cell), the
 * status (match, errata En, data, differs, not built) and the CSV file of the
 * output directory behind it ("" when none). */
void repro_row(const char *artifact, const char *paper, double ours, const char *status,
               const char *csv);

/* The status of a row whose claim the print makes and mfstab does not
 * reproduce: "errata En" when ours is what entry En of docs/errata.md
 * records (cond), else "differs".  (A static buffer per call slot.) */
const char *repro_errata(int cond, const char *entry);

/* The output directory, and a path in it (a static buffer per call slot:
 * valid until the 8th next call). */
extern const char *repro_outdir;
const char *repro_path(const char *file);

/* A CSV file read into memory: the header's names and the cells as text. */
typedef struct {
  size_t nrows, ncols;
  char **name;  /* ncols column names */
  char **cell;  /* nrows x ncols, row-major; "" for an empty cell */
  char *buf;
} repro_csv;

/* Read outdir/file (exit 1 with one line if it cannot be read). */
void repro_csv_read(repro_csv *t, const char *file);
void repro_csv_free(repro_csv *t);
/* The column named name (exit 1 naming the file when it has none). */
size_t repro_col(const repro_csv *t, const char *file, const char *name);
/* Cell (r, c) as a number (NAN when empty). */
double repro_num(const repro_csv *t, size_t r, size_t c);
const char *repro_text(const repro_csv *t, size_t r, size_t c);

/* The rows of the parts in their own files. */
void repro_static_rows(void);  /* paper 004 Table III (tools/repro_static.c) */
void repro_scene_rows(void);   /* scenes: paper 003 Figs 6-7, paper 001 Figs 4-9, paper 000
                                  Table 3 (tools/repro_scenes.c) */

#endif
