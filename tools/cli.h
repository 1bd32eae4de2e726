/* Command-line helpers of the mfstab program: declarative option tables
 * (one per command, the discretization options defined once) from which
 * parsing, one-line errors (exit 2) and --help come; strict numbers; the
 * discretization descriptor built from the options; CSV output written to a
 * temporary file and renamed on success. */
#ifndef MFSTAB_CLI_H
#define MFSTAB_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "mfstab.h"

/* The command being run, for messages ("stencil"). */
extern const char *cli_command;

/* Print "mfstab CMD: MESSAGE" on stderr and exit with code, after the
 * clean-ups registered with cli_on_die (most recent first) and the removal
 * of a pending temporary output file. */
_Noreturn void cli_die(int code, const char *fmt, ...);

/* A clean-up for cli_die (at most 8 pending), and its removal once the
 * step it guards is done. */
void cli_on_die(void (*fn)(void *), void *arg);
void cli_on_die_pop(void);

/* Called by cli_die with the exit code instead of exit() when set; it must
 * not return (the fuzz targets of tests/fuzz/ longjmp back to the fuzzer). */
extern void (*cli_die_hook)(int code);


/* Strict conversions: the whole string a finite decimal number (no hex, no
 * leading or trailing space, no inf/nan), an integer in [lo, hi]; 1 on
 * success.  The cli_* forms die with a message naming opt. */
int cli_parse_double(const char *s, double *v);
/* Why s is not a strict finite decimal number (NULL when it is one). */
const char *cli_number_problem(const char *s);
int cli_parse_long(const char *s, long *v);
double cli_double(const char *opt, const char *val);
long cli_long(const char *opt, const char *val, long lo, long hi);

/* ---- option tables -------------------------------------------------- */

typedef enum {
  CLI_FLAG,   /* int: 1 when given; takes no value */
  CLI_INT,    /* long */
  CLI_REAL,   /* double */
  CLI_REALS,  /* cli_list: comma-separated numbers */
  CLI_CHOICE, /* int: the index of the value in .choices */
  CLI_TABLE,  /* const void *: the variant table called so (.find) */
  CLI_TEXT,   /* const char * */
  CLI_TEXTS,  /* cli_texts: a repeatable option */
  CLI_END
} cli_type;

/* Bounds of numbers: lo < v (CLI_GT) or lo <= v (CLI_GE), v < hi or v <= hi. */
enum { CLI_GT = 1, CLI_GE = 2, CLI_LT = 4, CLI_LE = 8 };

typedef struct {
  size_t n;
  double *v; /* malloc'ed */
} cli_list;

#define CLI_MAX_TEXTS 256
typedef struct {
  int n;
  const char *v[CLI_MAX_TEXTS];
} cli_texts;

typedef struct {
  const char *name;     /* "--dilation"; NULL: the positional argument */
  cli_type type;
  const char *arg;      /* the value's name in --help ("D") */
  const char *help;     /* lines after the first are indented */
  size_t offset;        /* of the value in the group's struct */
  unsigned bounds;      /* CLI_GT | CLI_LE ... (numbers) */
  double lo, hi;
  const char *const *choices;            /* CLI_CHOICE: NULL-terminated */
  const void *(*find)(const char *name); /* CLI_TABLE: the table, or NULL */
  const void *const *list;               /* CLI_TABLE: every table (NULL-terminated; each
                                            starts with its const char *name): the names
                                            listed in --help and in messages */
} cli_opt;

/* A table of options (ended by an entry of type CLI_END) filling the struct
 * at base; seen (one byte per entry) counts how often each was given. */
typedef struct {
  const cli_opt *opt;
  void *base;
  unsigned char *seen;
} cli_group;

/* Parse argv[1..argc) against the groups.  --help / -h prints the usage
 * line, the description and every option's help on stdout and exits 0;
 * every error is one line, exit 2. */
void cli_parse(int argc, char **argv, const char *usage, const char *about, cli_group *groups,
               size_t ngroups);

/* The help text of a command (for `mfstab help CMD`). */
void cli_print_help(FILE *f, const char *usage, const char *about, const cli_group *groups,
                    size_t ngroups);

/* The names of a NULL-terminated list of variant tables (each starting
 * with its const char *name), comma-separated, runs gauss1, gauss2, ...
 * folded to "gauss1 .. gaussN"; into buf. */
const char *cli_table_names(const void *const *list, char *buf, size_t len);

/* The quadrature rules defined in dimension dim on lattice lat, as above. */
const char *cli_quad_names(int dim, mfs_lattice_kind lat, char *buf, size_t len);

/* The entry of group g for option name (must exist), and whether it was given. */
int cli_seen(const cli_group *g, const char *name);

/* ---- the discretization options, shared by the commands ---------------- */

typedef struct {
  long dim;
  int lattice;                     /* CLI_CHOICE: line, square, hex */
  const mfs_kernel_type *kernel;
  cli_list dilation;               /* one value, or a list where a command takes one */
  const mfs_shape_type *shape;
  const mfs_quad_type *quadrature;
  int mass;                        /* lumped, consistent */
  double modulus, density, spacing, gamma;
  int physics;                     /* antiplane (scalar), plane-strain */
  double poisson;
  double max_entries;              /* the limit on a plan's neighbour entries (0: the default) */
} cli_disc;

extern const cli_opt cli_disc_opts[];     /* --dim .. --gamma */
extern const cli_opt cli_physics_opts[];  /* --physics, --poisson */
#define CLI_DISC_NOPTS 13                 /* entries of cli_disc_opts, CLI_END included */
#define CLI_MAX_ENTRIES 5e8               /* the default limit on a plan's neighbour entries */
#define CLI_PHYSICS_NOPTS 3

/* The defaults (1D, cubic, D = 2, mls, nodal, lumped, unit modulus,
 * density and spacing, gamma 1, anti-plane, nu = 0.25). */
void cli_disc_defaults(cli_disc *d);

/* The descriptor of the options, once parsed (an infinite lattice source of
 * the given spacing and gamma; commands with finite models set their own
 * source), dilation: its first value.  Cross-option checks (lattice and
 * dimension, quadrature and lattice, plane strain in 2D) die with one line. */
mfs_disc cli_disc_build(const cli_disc *o, const unsigned char *seen_disc);

/* The memory this process may still take, in bytes (0 if unknown): the
 * least of MemAvailable, a cgroup v2 limit less its use, and RLIMIT_AS. */
double cli_available_memory(void);

/* A limit on the work: die (exit 2) when a plan of d on n particles would
 * hold more than o->max_entries neighbour entries (mfs_disc_plan_entries),
 * naming what makes it large (`what`: "--dilation 40 on 10^6 nodes") and the
 * override --max-entries; without that override, also when its model would
 * need more than the memory available (mfs_disc_model_bytes). */
void cli_check_work(const cli_disc *o, const mfs_disc *d, double n, const char *what);

/* The same for a plan of `entries` neighbour entries counted (not
 * estimated): a particle file, whose particles may cluster (the memory
 * estimate scaled by entries over the lattice estimate); `lower` says what
 * to lower ("the dilation or the nodes"). */
void cli_check_entries(const cli_disc *o, const mfs_disc *d, double n, double entries,
                       const char *what, const char *lower);

/* Die with the right message and code for a library status met while
 * building the discretization of o (what: where it happened). */
_Noreturn void cli_die_status(mfs_status status, const cli_disc *o, double dilation,
                              const char *what);

/* ---- output -------------------------------------------------------- */

/* CSV output: path NULL or "-" is stdout.  A regular file or a new path is
 * written through a temporary file renamed on success; a symlink is
 * followed; a device or FIFO is written in place. */
typedef struct {
  FILE *f;
  char *path, *tmp;
} cli_out;
void cli_out_open(cli_out *o, const char *path);
/* The same for the path printf(fmt, ...) makes; returns the path (valid until commit or abort). */
const char *cli_out_open_fmt(cli_out *o, const char *fmt, ...);
void cli_out_commit(cli_out *o);  /* close and rename; exits 1 on I/O failure */
void cli_out_abort(cli_out *o);   /* close and remove the temporary file */
/* All or nothing for a command that writes several files: after
 * cli_out_hold, cli_out_commit closes and checks a file but leaves it under
 * its temporary name (removed if the command fails) until cli_out_release
 * renames every one of them. */
void cli_out_hold(void);
void cli_out_release(void);

/* Format a double with 16 significant digits, "0" for zero. */
void cli_fmt(char *buf, size_t len, double v);

/* One CSV text field: as is, or quoted per RFC 4180 when it holds a comma,
 * a quote or a line break (quotes doubled). */
void cli_put_text(FILE *f, const char *s);

/* One CSV number field: the value, or an empty field for NAN (undefined);
 * dies (exit 1, one line naming `what`) rather than write an infinity. */
void cli_put_num(FILE *f, double v, const char *what);

#endif
