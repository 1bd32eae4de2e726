/* Command-line helpers of the mfstab program: strict parsing with one-line
 * errors (exit 2), the discretization options shared by the commands, and
 * CSV output written to a temporary file and renamed on success. */
#ifndef MFSTAB_CLI_H
#define MFSTAB_CLI_H

#include <stdio.h>

#include "mfstab.h"

/* The command being run, for messages ("stencil"). */
extern const char *cli_command;

/* Print "mfstab CMD: MESSAGE" on stderr and exit with code. */
_Noreturn void cli_die(int code, const char *fmt, ...);

/* Strict conversions: the whole string must be a finite number / an integer. */
double cli_double(const char *opt, const char *val);
long cli_long(const char *opt, const char *val, long lo, long hi);
/* Comma-separated list of numbers; returns the count, *out malloc'ed. */
size_t cli_double_list(const char *opt, const char *val, double **out);

/* Options that describe a discretization. */
typedef struct {
  int dim;
  const char *lattice;
  const mfs_kernel_type *kernel;
  double dilation;
  const mfs_shape_type *shape;
  const char *quadrature;
  int consistent_mass;
  double modulus, density, spacing, gamma;
  int seen_lattice;
} cli_disc;

void cli_disc_defaults(cli_disc *d);
/* Consume option opt with value val if it is a discretization option: 1 if
 * consumed, 0 if not ours.  Exits with code 2 on a bad value. */
int cli_disc_option(cli_disc *d, const char *opt, const char *val);
/* Cross-option checks after parsing (lattice vs dim, quadrature vs lattice). */
void cli_disc_finish(cli_disc *d, mfs_lattice_kind *lattice, mfs_quad_rule *rule);
/* Help text for the discretization options. */
extern const char cli_disc_help[];

/* Die with the right message and code for a library status. */
_Noreturn void cli_die_status(int status, const cli_disc *d, const char *what);

/* CSV output: path NULL or "-" is stdout. */
typedef struct {
  FILE *f;
  char *path, *tmp;
} cli_out;
void cli_out_open(cli_out *o, const char *path);
void cli_out_commit(cli_out *o);  /* close and rename; exits 1 on I/O failure */
void cli_out_abort(cli_out *o);   /* close and remove the temporary file */

/* Format a double with 16 significant digits, "0" for zero. */
void cli_fmt(char *buf, size_t len, double v);

#endif
