#include "cli.h"
#include "mfs_alloc.h"
#include "cli_decimal.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

const char *cli_command = "";

static cli_out *current_out = NULL;
static void remove_pending(void);

void (*cli_die_hook)(int code) = NULL;

/* what cli_die undoes before it leaves, most recent first */
#define CLI_MAX_ON_DIE 8
static struct {
  void (*fn)(void *);
  void *arg;
} on_die[CLI_MAX_ON_DIE];
static int n_on_die = 0;

void cli_on_die(void (*fn)(void *), void *arg)
{
  if (n_on_die == CLI_MAX_ON_DIE)
    cli_die(1, "internal error: more than %d pending clean-ups", CLI_MAX_ON_DIE);
  on_die[n_on_die].fn = fn;
  on_die[n_on_die].arg = arg;
  n_on_die++;
}

void cli_on_die_pop(void)
{
  if (n_on_die > 0)
    n_on_die--;
}

_Noreturn void cli_die(int code, const char *fmt, ...)
{
  if (current_out)
    cli_out_abort(current_out);
  remove_pending();
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "mfstab %s: ", cli_command);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  /* after the message, which may quote what they free */
  while (n_on_die > 0) {
    n_on_die--;
    on_die[n_on_die].fn(on_die[n_on_die].arg);
  }
  if (cli_die_hook)
    cli_die_hook(code);
  exit(code);
}

/* ---- numbers ---- */

/* An optional sign and at least one digit at *c (advanced past them);
 * the count of digits.  The grammar of strict numbers. */
static int sign_digits(const char **c)
{
  int n = 0;
  if (**c == '+' || **c == '-')
    (*c)++;
  while (**c >= '0' && **c <= '9')
    (*c)++, n++;
  return n;
}

int cli_parse_double(const char *s, double *v)
{
  /* decimal only: [+-]digits[.digits][(e|E)[+-]digits] */
  const char *c = s;
  int digits = sign_digits(&c);
  if (*c == '.') {
    c++;
    while (*c >= '0' && *c <= '9')
      c++, digits++;
  }
  if (!digits)
    return 0;
  if ((*c == 'e' || *c == 'E') && (c++, sign_digits(&c) == 0))
    return 0;
  if (*c != '\0')
    return 0;
  if (cli_decimal(s, v)) /* exact, bit-identical to strtod, without its multiple precision */
    return 1;
  char *end;
  double x = strtod(s, &end);
  if (*end != '\0' || !isfinite(x)) /* overflow; an underflow to a subnormal is fine */
    return 0;
  *v = x;
  return 1;
}

const char *cli_number_problem(const char *s)
{
  double v;
  char *end;
  if (cli_parse_double(s, &v))
    return NULL;
  if (s[0] != '\0' && (strtod(s, &end), *end == '\0') && strpbrk(s, "nNiIxX") == NULL)
    return "out of range; larger in magnitude than a double holds (1.8e308)";
  return "not a number; expected a finite decimal number";
}

int cli_parse_long(const char *s, long *v)
{
  const char *c = s;
  if (sign_digits(&c) == 0 || *c != '\0')
    return 0;
  errno = 0;
  long x = strtol(s, NULL, 10);
  if (errno == ERANGE)
    return 0;
  *v = x;
  return 1;
}

double cli_double(const char *opt, const char *val)
{
  double v;
  if (!cli_parse_double(val, &v))
    cli_die(2, "%s '%s': %s", opt, val, cli_number_problem(val));
  return v;
}

long cli_long(const char *opt, const char *val, long lo, long hi)
{
  long v;
  if (!cli_parse_long(val, &v))
    cli_die(2, "%s '%s': not an integer; allowed %ld to %ld", opt, val, lo, hi);
  if (v < lo || v > hi)
    cli_die(2, "%s %ld: out of range; allowed %ld to %ld", opt, v, lo, hi);
  return v;
}

/* ---- option tables ---- */

static size_t group_len(const cli_group *g)
{
  size_t n = 0;
  while (g->opt[n].type != CLI_END)
    n++;
  return n;
}

/* "> 0", ">= 0 and < 1": the bounds of an option, for messages. */
static void bounds_text(const cli_opt *o, char *buf, size_t len)
{
  char a[64] = "", b[64] = "";
  if (o->bounds & (CLI_GT | CLI_GE))
    snprintf(a, sizeof a, "%s %g", (o->bounds & CLI_GT) ? ">" : ">=", o->lo);
  if (o->bounds & (CLI_LT | CLI_LE))
    snprintf(b, sizeof b, "%s %g", (o->bounds & CLI_LT) ? "<" : "<=", o->hi);
  snprintf(buf, len, "must be %s%s%s", a, a[0] && b[0] ? " and " : "", b);
}

static int in_bounds(const cli_opt *o, double v)
{
  if ((o->bounds & CLI_GT) && !(v > o->lo))
    return 0;
  if ((o->bounds & CLI_GE) && !(v >= o->lo))
    return 0;
  if ((o->bounds & CLI_LT) && !(v < o->hi))
    return 0;
  if ((o->bounds & CLI_LE) && !(v <= o->hi))
    return 0;
  return 1;
}

static void check_bounds(const cli_opt *o, const char *val, double v)
{
  if (!in_bounds(o, v)) {
    char b[160];
    bounds_text(o, b, sizeof b);
    cli_die(2, "%s %s: out of range; %s", o->name, val, b);
  }
}

static void set_value(const cli_opt *o, void *base, const char *val)
{
  char *at = (char *)base + o->offset;
  switch (o->type) {
  case CLI_FLAG:
    *(int *)at = 1;
    break;
  case CLI_INT: {
    long v;
    if (!cli_parse_long(val, &v))
      cli_die(2, "%s '%s': not an integer", o->name, val);
    check_bounds(o, val, (double)v);
    *(long *)at = v;
    break;
  }
  case CLI_REAL: {
    double v;
    if (!cli_parse_double(val, &v))
      cli_die(2, "%s '%s': %s", o->name, val, cli_number_problem(val));
    check_bounds(o, val, v);
    *(double *)at = v;
    break;
  }
  case CLI_REALS: {
    cli_list *l = (cli_list *)at;
    size_t n = 1;
    for (const char *c = val; *c; c++)
      n += *c == ',';
    double *v = mfs_malloc(n * sizeof *v);
    char *copy = mfs_strdup(val);
    cli_on_die(mfs_free, v);
    cli_on_die(mfs_free, copy);
    if (!v || !copy)
      cli_die(1, "out of memory");
    size_t k = 0;
    for (char *s = copy;;) {
      char *comma = strchr(s, ',');
      if (comma)
        *comma = '\0';
      if (*s == '\0')
        cli_die(2, "%s '%s': empty list element; expected comma-separated numbers", o->name, val);
      if (!cli_parse_double(s, &v[k]))
        cli_die(2, "%s '%s': '%s': %s", o->name, val, s, cli_number_problem(s));
      if (!in_bounds(o, v[k])) {
        char b[160];
        bounds_text(o, b, sizeof b);
        cli_die(2, "%s %s: %s out of range; every value %s", o->name, val, s, b);
      }
      k++;
      if (!comma)
        break;
      s = comma + 1;
    }
    cli_on_die_pop();
    cli_on_die_pop();
    mfs_free(copy);
    mfs_free(l->v);
    l->v = v;
    l->n = k;
    break;
  }
  case CLI_CHOICE:
    for (int k = 0; o->choices[k]; k++)
      if (strcmp(val, o->choices[k]) == 0) {
        *(int *)at = k;
        return;
      }
    {
      char names[512] = "";
      for (int k = 0; o->choices[k]; k++) {
        if (k)
          strncat(names, ", ", sizeof names - strlen(names) - 1);
        strncat(names, o->choices[k], sizeof names - strlen(names) - 1);
      }
      cli_die(2, "%s '%s': not allowed; allowed: %s", o->name, val, names);
    }
  case CLI_TABLE: {
    const void *t = o->find(val);
    char names[2048];
    if (!t)
      cli_die(2, "%s '%s': unknown; allowed: %s", o->name, val,
              cli_table_names(o->list, names, sizeof names));
    *(const void **)at = t;
    break;
  }
  case CLI_TEXT:
    *(const char **)at = val;
    break;
  case CLI_TEXTS: {
    cli_texts *t = (cli_texts *)at;
    if (t->n == CLI_MAX_TEXTS)
      cli_die(2, "%s: given more than %d times", o->name, CLI_MAX_TEXTS);
    t->v[t->n++] = val;
    break;
  }
  case CLI_END:
    break;
  }
}

static const cli_opt *find_opt(cli_group *groups, size_t ngroups, const char *name, cli_group **g,
                               size_t *k)
{
  for (size_t i = 0; i < ngroups; i++)
    for (size_t j = 0; groups[i].opt[j].type != CLI_END; j++) {
      const char *n = groups[i].opt[j].name;
      if (name ? (n && strcmp(n, name) == 0) : n == NULL) {
        *g = &groups[i];
        *k = j;
        return &groups[i].opt[j];
      }
    }
  return NULL;
}

static void print_opt(FILE *f, const cli_opt *o)
{
  char left[96];
  if (o->type == CLI_FLAG)
    snprintf(left, sizeof left, "  %s", o->name);
  else
    snprintf(left, sizeof left, "  %s %s", o->name, o->arg ? o->arg : "VALUE");
  char hbuf[2560];
  const char *h = o->help ? o->help : "";
  if (o->type == CLI_TABLE) { /* the names come from the tables */
    char names[2048];
    snprintf(hbuf, sizeof hbuf, "%s: %s", h, cli_table_names(o->list, names, sizeof names));
    h = hbuf;
  }
  if (strlen(left) >= 26)
    fprintf(f, "%s\n%26s", left, "");
  else
    fprintf(f, "%-26s", left);
  int col = 26;
  for (const char *c = h; *c; c++) { /* wrap at a space past column 92 */
    if (*c == '\n' || (*c == ' ' && col > 92)) {
      fprintf(f, "\n%26s", "");
      col = 26;
      continue;
    }
    fputc(*c, f);
    col++;
  }
  fputc('\n', f);
}

void cli_print_help(FILE *f, const char *usage, const char *about, const cli_group *groups,
                    size_t ngroups)
{
  fprintf(f, "usage: %s\n%s", usage, about);
  fputs("options:\n", f);
  for (size_t i = 0; i < ngroups; i++)
    for (size_t j = 0; groups[i].opt[j].type != CLI_END; j++)
      if (groups[i].opt[j].name)
        print_opt(f, &groups[i].opt[j]);
  fputs("  -h, --help              this text\n", f);
}

void cli_parse(int argc, char **argv, const char *usage, const char *about, cli_group *groups,
               size_t ngroups)
{
  for (size_t i = 0; i < ngroups; i++)
    memset(groups[i].seen, 0, group_len(&groups[i]));
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *val = NULL;
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      cli_print_help(stdout, usage, about, groups, ngroups);
      if (cli_die_hook)
        cli_die_hook(0);
      exit(0);
    }
    cli_group *g;
    size_t k;
    const cli_opt *o;
    if (a[0] != '-' || a[1] == '\0' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') {
      o = find_opt(groups, ngroups, NULL, &g, &k); /* a positional argument */
      if (!o)
        cli_die(2, "'%s': unexpected argument; see 'mfstab %s --help'", a, cli_command);
      if (g->seen[k])
        cli_die(2, "'%s': only one %s is allowed", a, o->arg ? o->arg : "argument");
      set_value(o, g->base, a);
      g->seen[k]++;
      continue;
    }
    char name[128];
    const char *eq = a[1] == '-' ? strchr(a, '=') : NULL;
    if (eq) {
      size_t n = (size_t)(eq - a);
      if (n >= sizeof name)
        cli_die(2, "%.40s...: unknown option; see 'mfstab %s --help'", a, cli_command);
      memcpy(name, a, n);
      name[n] = '\0';
      val = eq + 1;
    } else {
      snprintf(name, sizeof name, "%s", a);
    }
    o = find_opt(groups, ngroups, name, &g, &k);
    if (!o)
      cli_die(2, "%s: unknown option; see 'mfstab %s --help'", name, cli_command);
    if (o->type == CLI_FLAG) {
      if (val)
        cli_die(2, "%s: a flag takes no value (got '%s'); give %s alone", name, val, name);
    } else if (!val) {
      const char *next = i + 1 < argc ? argv[i + 1] : NULL;
      /* the next word is an option, not a value ("-1" and "-.5" are values) */
      if (!next || (next[0] == '-' && next[1] != '\0' && next[1] != '.' &&
                    !(next[1] >= '0' && next[1] <= '9')))
        cli_die(2, "%s: missing value (%s)%s%s", name, o->arg ? o->arg : "VALUE",
                next ? " before " : "", next ? next : "");
      val = argv[++i];
    }
    if (g->seen[k] && o->type != CLI_TEXTS && o->type != CLI_REALS)
      cli_die(2, "%s: given twice", name);
    set_value(o, g->base, val);
    if (g->seen[k] < 255)
      g->seen[k]++;
  }
}

int cli_seen(const cli_group *g, const char *name)
{
  for (size_t j = 0; g->opt[j].type != CLI_END; j++)
    if (g->opt[j].name && strcmp(g->opt[j].name, name) == 0)
      return g->seen[j];
  return 0;
}

static int gauss_index(const char *name)
{
  int n, len = 0;
  if (sscanf(name, "gauss%d%n", &n, &len) == 1 && name[len] == '\0')
    return n;
  return 0;
}

/* Append the names of the tables t[0..n) to buf, folding runs of gaussN. */
static const char *join_names(const char *const *names, size_t n, char *buf, size_t len)
{
  buf[0] = '\0';
  for (size_t i = 0; i < n; i++) {
    size_t j = i;
    while (j + 1 < n && gauss_index(names[j]) && gauss_index(names[j + 1]) == gauss_index(names[j]) + 1)
      j++;
    char item[96];
    if (j > i + 1)
      snprintf(item, sizeof item, "%s .. %s", names[i], names[j]);
    else
      snprintf(item, sizeof item, "%s", names[i]);
    if (buf[0])
      strncat(buf, ", ", len - strlen(buf) - 1);
    strncat(buf, item, len - strlen(buf) - 1);
    if (j > i + 1)
      i = j;
  }
  return buf;
}

const char *cli_table_names(const void *const *list, char *buf, size_t len)
{
  const char *names[64];
  size_t n = 0;
  for (; list && list[n] && n < 64; n++)
    names[n] = *(const char *const *)list[n];
  return join_names(names, n, buf, len);
}

const char *cli_quad_names(int dim, mfs_lattice_kind lat, char *buf, size_t len)
{
  const char *names[64];
  size_t n = 0;
  for (size_t i = 0; mfs_quad_types[i] && n < 64; i++)
    if (mfs_quad_applies(mfs_quad_types[i], dim, lat))
      names[n++] = mfs_quad_types[i]->name;
  return join_names(names, n, buf, len);
}

/* ---- discretization options ---- */

static const char *const lattice_names[] = {"line", "square", "hex", NULL};
static const char *const mass_names[] = {"lumped", "consistent", "volume", NULL};
static const char *const physics_names[] = {"antiplane", "plane-strain", NULL};

static const void *find_kernel(const char *n)
{
  return mfs_kernel_find(n);
}
static const void *find_shape(const char *n)
{
  return mfs_shape_find(n);
}
static const void *find_quad(const char *n)
{
  return mfs_quad_find(n);
}

#define DOFF(f) offsetof(cli_disc, f)
const cli_opt cli_disc_opts[] = {
  {.name = "--dim", .type = CLI_INT, .arg = "1|2", .help = "dimension (default 1)",
   .offset = DOFF(dim), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 2},
  {.name = "--lattice", .type = CLI_CHOICE, .arg = "line|square|hex",
   .help = "particle lattice (default line in 1D, square in 2D)", .offset = DOFF(lattice),
   .choices = lattice_names},
  {.name = "--kernel", .type = CLI_TABLE, .arg = "NAME",
   .help = "the kernel (default cubic)", .offset = DOFF(kernel), .find = find_kernel,
   .list = (const void *const *)mfs_kernel_types},
  {.name = "--dilation", .type = CLI_REALS, .arg = "D",
   .help = "support radius a = D*dx (default 2)", .offset = DOFF(dilation),
   .bounds = CLI_GT | CLI_LE, .lo = 0, .hi = 1e4},
  {.name = "--shape", .type = CLI_TABLE, .arg = "NAME",
   .help = "shape functions (default mls)", .offset = DOFF(shape), .find = find_shape,
   .list = (const void *const *)mfs_shape_types},
  {.name = "--quadrature", .type = CLI_TABLE, .arg = "RULE",
   .help = "the quadrature rule (default nodal; docs/commands.md says which lattice "
           "each needs)",
   .offset = DOFF(quadrature), .find = find_quad, .list = (const void *const *)mfs_quad_types},
  {.name = "--mass", .type = CLI_CHOICE, .arg = "lumped|consistent|volume",
   .help = "mass matrix (default lumped, row sum, eq. 131); volume: lumped as density times the "
           "node volume, eq. 119 (dispersion and stencil only)",
   .offset = DOFF(mass), .choices = mass_names},
  {.name = "--modulus", .type = CLI_REAL, .arg = "C",
   .help = "tangent modulus (E in 1D, shear modulus in 2D; default 1)", .offset = DOFF(modulus),
   .bounds = CLI_GE | CLI_LE, .lo = 1e-30, .hi = 1e30},
  {.name = "--density", .type = CLI_REAL, .arg = "RHO", .help = "density (default 1)",
   .offset = DOFF(density),
   .bounds = CLI_GE | CLI_LE, .lo = 1e-30, .hi = 1e30},
  {.name = "--spacing", .type = CLI_REAL, .arg = "DX", .help = "particle spacing (default 1)",
   .offset = DOFF(spacing),
   .bounds = CLI_GE | CLI_LE, .lo = 1e-30, .hi = 1e30},
  {.name = "--gamma", .type = CLI_REAL, .arg = "G", .help = "dy/dx of the square lattice (default 1)",
   .offset = DOFF(gamma), .bounds = CLI_GE | CLI_LE, .lo = 1e-6, .hi = 1e6},
  {.name = "--max-entries", .type = CLI_REAL, .arg = "N",
   .help = "refuse a plan of more neighbour entries (default 5e8, and a model whose\n"
           "estimated memory exceeds what is available; a value given here skips the\n"
           "memory check)",
   .offset = DOFF(max_entries), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 1e15},
  {.type = CLI_END}};

const cli_opt cli_physics_opts[] = {
  {.name = "--physics", .type = CLI_CHOICE, .arg = "antiplane|plane-strain",
   .help = "2D problem (default antiplane)", .offset = DOFF(physics), .choices = physics_names},
  {.name = "--poisson", .type = CLI_REAL, .arg = "NU",
   .help = "Poisson ratio of plane strain (default 0.25)", .offset = DOFF(poisson),
   .bounds = CLI_GT | CLI_LT, .lo = -1, .hi = 0.5},
  {.type = CLI_END}};
#undef DOFF

_Static_assert(sizeof cli_disc_opts / sizeof cli_disc_opts[0] == CLI_DISC_NOPTS,
               "CLI_DISC_NOPTS");
_Static_assert(sizeof cli_physics_opts / sizeof cli_physics_opts[0] == CLI_PHYSICS_NOPTS,
               "CLI_PHYSICS_NOPTS");

void cli_disc_defaults(cli_disc *d)
{
  *d = (cli_disc){.dim = 1,
                  .lattice = -1,
                  .kernel = &mfs_kernel_cubic,
                  .dilation = {0, NULL},
                  .shape = &mfs_shape_mls,
                  .quadrature = &mfs_quad_nodal,
                  .mass = 0,
                  .modulus = 1.0,
                  .density = 1.0,
                  .spacing = 1.0,
                  .gamma = 1.0,
                  .physics = 0,
                  .poisson = 0.25,
                  .max_entries = 0.0};
}

mfs_disc cli_disc_build(const cli_disc *o, const unsigned char *seen)
{
  (void)seen;
  int dim = (int)o->dim;
  int lat = o->lattice >= 0 ? o->lattice : (dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE);
  if (dim == 1 && lat != MFS_LATTICE_LINE)
    cli_die(2, "--lattice %s: not a 1D lattice; with --dim 1 allowed: line", lattice_names[lat]);
  if (dim == 2 && lat == MFS_LATTICE_LINE)
    cli_die(2, "--lattice line: not a 2D lattice; with --dim 2 allowed: square, hex");
  if (!mfs_quad_applies(o->quadrature, dim, (mfs_lattice_kind)lat)) {
    char names[512];
    cli_die(2, "--quadrature %s: not defined for --dim %d --lattice %s; allowed: %s",
            o->quadrature->name, dim, lattice_names[lat],
            cli_quad_names(dim, (mfs_lattice_kind)lat, names, sizeof names));
  }
  if (o->physics == 1 && dim != 2)
    cli_die(2, "--physics plane-strain needs --dim 2");
  mfs_disc d = mfs_disc_default();
  d.dim = dim;
  d.source = (mfs_source){.lattice = (mfs_lattice_kind)lat, .spacing = o->spacing, .gamma = o->gamma};
  d.kernel = o->kernel;
  d.dilation = o->dilation.n ? o->dilation.v[0] : 2.0;
  d.shape = o->shape;
  d.quadrature = o->quadrature;
  d.consistent_mass = o->mass == 1;
  d.node_volume_mass = o->mass == 2;
  /* the element bound, the Gershgorin rows of the checks and the solvers are
   * written for the row sum: the node-volume mass is for the lattice analyses */
  if (d.node_volume_mass && strcmp(cli_command, "dispersion") != 0 &&
      strcmp(cli_command, "stencil") != 0)
    cli_die(2, "--mass volume: only dispersion and stencil take it; allowed here: lumped, "
               "consistent");
  d.material = (mfs_material){.physics = o->physics == 1 ? MFS_PHYS_PLANE_STRAIN : MFS_PHYS_SCALAR,
                              .modulus = o->modulus,
                              .poisson = o->poisson,
                              .density = o->density};
  return d;
}

/* The memory this process may still take, in bytes (0 if unknown): the
 * least of MemAvailable (/proc/meminfo), a cgroup v2 limit less its use, and
 * RLIMIT_AS. */
static double available_memory(void)
{
  double best = 0.0;
  FILE *f = fopen("/proc/meminfo", "r");
  if (f) {
    char line[128];
    double kb;
    while (fgets(line, sizeof line, f))
      if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1)
        best = kb * 1024.0;
    fclose(f);
  }
  double lim = 0.0, cur = 0.0;
  f = fopen("/sys/fs/cgroup/memory.max", "r");
  if (f) {
    if (fscanf(f, "%lf", &lim) != 1)
      lim = 0.0; /* "max": no limit */
    fclose(f);
  }
  f = lim > 0.0 ? fopen("/sys/fs/cgroup/memory.current", "r") : NULL;
  if (f) {
    if (fscanf(f, "%lf", &cur) != 1)
      cur = 0.0;
    fclose(f);
  }
  if (lim > 0.0 && (best == 0.0 || lim - cur < best))
    best = lim - cur > 0.0 ? lim - cur : 1.0;
  struct rlimit rl;
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
      (best == 0.0 || (double)rl.rlim_cur < best))
    best = (double)rl.rlim_cur;
  return best;
}

double cli_available_memory(void)
{
  return available_memory();
}

void cli_check_work(const cli_disc *o, const mfs_disc *d, double n, const char *what)
{
  cli_check_entries(o, d, n, mfs_disc_plan_entries(d, n, NULL), what,
                    "the dilation or the nodes");
}

void cli_check_entries(const cli_disc *o, const mfs_disc *d, double n, double entries,
                       const char *what, const char *lower)
{
  double lim = o->max_entries > 0.0 ? o->max_entries : CLI_MAX_ENTRIES;
  if (!(entries <= lim))
    cli_die(2, "%s: about %.3g neighbour entries in the plan, more than --max-entries %.3g%s; "
               "lower %s, or raise --max-entries",
            what, entries, lim, o->max_entries > 0.0 ? "" : " (the default)", lower);
  if (o->max_entries > 0.0)
    return; /* the user's own limit: no memory check */
  double est = mfs_disc_plan_entries(d, n, NULL), bytes = mfs_disc_model_bytes(d, n);
  if (est > 0.0 && entries > est)
    bytes *= entries / est; /* a clustered set: its counted entries */
  double mem = available_memory();
  if (mem > 0.0 && bytes > mem)
    cli_die(2, "%s: needs about %.3g GB, and %.3g GB of memory are available; lower %s, or "
               "give --max-entries to try anyway",
            what, bytes / 1e9, mem / 1e9, lower);
}

_Noreturn void cli_die_status(mfs_status status, const cli_disc *d, double dilation,
                              const char *what)
{
  if (status == MFS_ESINGULAR)
    cli_die(2,
            "--dilation %g: too small for the %s moment matrix with kernel %s (singular %s); "
            "use a larger dilation",
            dilation, d->shape->name, d->kernel->name, what);
  if (status == MFS_ETOOSMALL)
    cli_die(2, "model too small for --dilation %g: %s", dilation, what);
  if (status == MFS_EINVAL)
    cli_die(2, "invalid combination of options: %s", what);
  cli_die(1, "%s: %s", what, mfs_strerror(status));
}

/* ---- Output files ----------------------------------------------------
 * A regular file or a new path is written through a temporary file in the
 * same directory and renamed on success, so a failed run never leaves a half
 * file.  A symlink is followed to its target (the link stays a link).  A
 * character device or a FIFO is written directly (renaming over it would
 * replace the device node); a directory, a block device or a socket is
 * refused.  New files get 0666 & ~umask, a replaced file keeps its mode.
 * SIGINT, SIGTERM, SIGHUP and SIGPIPE remove the temporary files. */

enum { MAX_OUT = 8, MAX_LINKS = 40 };
static char *volatile pending_tmp[MAX_OUT]; /* read by the signal handler */
static mode_t process_umask;
static int signals_installed = 0;

static void remove_pending(void)
{
  for (int i = 0; i < MAX_OUT; i++)
    if (pending_tmp[i])
      unlink(pending_tmp[i]);
}

static void on_signal(int sig)
{
  remove_pending(); /* unlink is async-signal-safe */
  signal(sig, SIG_DFL);
  raise(sig);
}

static void install_signals(void)
{
  if (signals_installed)
    return;
  signals_installed = 1;
  process_umask = umask(0);
  umask(process_umask);
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
  for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t j = 0; j < sizeof sigs / sizeof sigs[0]; j++)
      sigaddset(&sa.sa_mask, sigs[j]);
    sigaction(sigs[i], &sa, NULL);
  }
}

static void track_tmp(char *tmp, int on)
{
  sigset_t all, old;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &old);
  for (int i = 0; i < MAX_OUT; i++)
    if (on ? pending_tmp[i] == NULL : pending_tmp[i] == tmp) {
      pending_tmp[i] = on ? tmp : NULL;
      break;
    }
  sigprocmask(SIG_SETMASK, &old, NULL);
}

/* Follow symlinks from path to the file they name (which may not exist yet).
 * Returns a malloc'ed path, or NULL with errno set. */
static char *resolve_links(const char *path)
{
  char *p = mfs_strdup(path);
  for (int hops = 0; p; hops++) {
    struct stat st;
    if (lstat(p, &st) != 0 || !S_ISLNK(st.st_mode))
      return p; /* missing or not a link: this is the target */
    if (hops == MAX_LINKS) {
      mfs_free(p);
      errno = ELOOP;
      return NULL;
    }
    char link[4096];
    ssize_t n = readlink(p, link, sizeof link - 1);
    if (n < 0) {
      mfs_free(p);
      return NULL;
    }
    link[n] = '\0';
    char *next;
    const char *slash = strrchr(p, '/');
    if (link[0] == '/' || !slash) {
      next = mfs_strdup(link);
    } else {
      size_t dlen = (size_t)(slash - p) + 1;
      next = mfs_malloc(dlen + (size_t)n + 1);
      if (next) {
        memcpy(next, p, dlen);
        memcpy(next + dlen, link, (size_t)n + 1);
      }
    }
    mfs_free(p);
    p = next;
  }
  errno = ENOMEM;
  return NULL;
}

void cli_out_open(cli_out *o, const char *path)
{
  o->f = NULL;
  o->path = o->tmp = NULL;
  if (!path || strcmp(path, "-") == 0) {
    o->f = stdout;
    return;
  }
  install_signals();
  char *target = resolve_links(path);
  if (!target && errno == ENOMEM)
    cli_die(1, "out of memory");
  if (!target)
    cli_die(2, "-o %s: cannot resolve the path (%s)", path, strerror(errno));
  struct stat st;
  int exists = stat(target, &st) == 0;
  if (exists && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
    /* a device or a pipe: write it in place, never rename over it */
    int fd = open(target, O_WRONLY | O_NOCTTY);
    if (fd < 0) {
      int e = errno;
      mfs_free(target);
      cli_die(2, "-o %s: cannot open the device or FIFO for writing (%s)", path, strerror(e));
    }
    o->f = fdopen(fd, "w");
    o->path = target;
    if (!o->f)
      cli_die(1, "-o %s: %s", path, strerror(errno));
    return;
  }
  if (exists && !S_ISREG(st.st_mode)) {
    mfs_free(target);
    cli_die(2, "-o %s: %s; allowed: a regular file, a new path, a character device or a FIFO",
            path, S_ISDIR(st.st_mode) ? "is a directory" : "is a block device or socket");
  }
  size_t len = strlen(target) + 16;
  o->path = target;
  o->tmp = mfs_malloc(len);
  if (!o->tmp)
    cli_die(1, "out of memory");
  snprintf(o->tmp, len, "%s.tmpXXXXXX", target);
  int fd = mkstemp(o->tmp);
  if (fd < 0) {
    int e = errno;
    mfs_free(o->tmp);
    o->tmp = NULL;
    cli_die(2, "-o %s: cannot create the output file (%s)", path, strerror(e));
  }
  track_tmp(o->tmp, 1);
  mode_t mode = exists ? (st.st_mode & 07777) : (0666 & ~process_umask);
  if (fchmod(fd, mode) != 0) {
    close(fd);
    cli_die(1, "-o %s: cannot set the file mode (%s)", path, strerror(errno));
  }
  o->f = fdopen(fd, "w");
  if (!o->f)
    cli_die(1, "-o %s: %s", path, strerror(errno));
  current_out = o;
}

const char *cli_out_open_fmt(cli_out *o, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *path = n >= 0 ? mfs_malloc((size_t)n + 1) : NULL;
  if (!path)
    cli_die(1, "out of memory");
  va_start(ap, fmt);
  vsnprintf(path, (size_t)n + 1, fmt, ap);
  va_end(ap);
  cli_out_open(o, path);
  mfs_free(path);
  return o->path;
}

void cli_out_abort(cli_out *o)
{
  if (current_out == o)
    current_out = NULL;
  if (o->f && o->f != stdout)
    fclose(o->f);
  if (o->tmp) {
    remove(o->tmp);
    track_tmp(o->tmp, 0);
  }
  mfs_free(o->tmp);
  mfs_free(o->path);
  o->tmp = o->path = NULL;
  o->f = NULL;
}

/* Commits held back by cli_out_hold: closed and checked, still pending (a
 * failure removes them), renamed by cli_out_release. */
static struct {
  char *tmp, *path;
} held[MAX_OUT];
static int holding = 0, nheld = 0;

void cli_out_hold(void)
{
  holding = 1;
}

void cli_out_release(void)
{
  holding = 0;
  for (int i = 0; i < nheld; i++) {
    char *tmp = held[i].tmp, *path = held[i].path;
    held[i].tmp = held[i].path = NULL;
    int bad = rename(tmp, path) != 0;
    if (bad)
      remove(tmp);
    track_tmp(tmp, 0);
    mfs_free(tmp);
    if (bad) {
      for (int j = i + 1; j < nheld; j++) /* the others stay unwritten too */
        remove(held[j].tmp);
      nheld = 0;
      cli_die(1, "-o %s: cannot write the output file", path);
    }
    mfs_free(path);
  }
  nheld = 0;
}

void cli_out_commit(cli_out *o)
{
  if (current_out == o)
    current_out = NULL;
  if (o->f == stdout) {
    if (fflush(stdout) != 0 || ferror(stdout))
      cli_die(1, "cannot write the output: %s", strerror(errno));
    o->f = NULL;
    return;
  }
  int bad = ferror(o->f);
  bad |= fclose(o->f) != 0;
  o->f = NULL;
  if (o->tmp && !bad && holding && nheld < MAX_OUT) {
    held[nheld].tmp = o->tmp;
    held[nheld++].path = o->path;
    o->tmp = o->path = NULL;
    return;
  }
  if (o->tmp) {
    if (bad || rename(o->tmp, o->path) != 0)
      bad = 1;
    if (bad)
      remove(o->tmp);
    track_tmp(o->tmp, 0);
  }
  if (bad) {
    char *p = o->path;
    o->path = NULL;
    mfs_free(o->tmp);
    o->tmp = NULL;
    cli_die(1, "-o %s: cannot write the output file", p);
  }
  mfs_free(o->tmp);
  mfs_free(o->path);
  o->tmp = o->path = NULL;
}

void cli_fmt(char *buf, size_t len, double v)
{
  if (v == 0.0)
    snprintf(buf, len, "0");
  else
    snprintf(buf, len, "%.16g", v);
}

void cli_put_text(FILE *f, const char *s)
{
  if (!strpbrk(s, ",\"\r\n")) {
    fputs(s, f);
    return;
  }
  fputc('"', f); /* RFC 4180: quoted, a quote doubled */
  for (; *s; s++) {
    if (*s == '"')
      fputc('"', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

void cli_put_num(FILE *f, double v, const char *what)
{
  if (isnan(v))
    return; /* an undefined value: an empty field */
  if (!isfinite(v))
    cli_die(1, "%s is not finite (%g); no output written", what, v);
  char b[40];
  cli_fmt(b, sizeof b, v);
  fputs(b, f);
}
