#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *cli_command = "";

static cli_out *current_out = NULL;
static void remove_pending(void);

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
  exit(code);
}

double cli_double(const char *opt, const char *val)
{
  char *end;
  errno = 0;
  double v = strtod(val, &end);
  if (end == val || *end != '\0' || errno == ERANGE || !isfinite(v))
    cli_die(2, "%s '%s': not a number; expected a finite decimal number", opt, val);
  return v;
}

long cli_long(const char *opt, const char *val, long lo, long hi)
{
  char *end;
  errno = 0;
  long v = strtol(val, &end, 10);
  if (end == val || *end != '\0' || errno == ERANGE)
    cli_die(2, "%s '%s': not an integer", opt, val);
  if (v < lo || v > hi)
    cli_die(2, "%s %ld: out of range; allowed %ld to %ld", opt, v, lo, hi);
  return v;
}

size_t cli_double_list(const char *opt, const char *val, double **out)
{
  size_t n = 1;
  for (const char *c = val; *c; c++)
    n += *c == ',';
  double *v = malloc(n * sizeof *v);
  char *copy = strdup(val);
  if (!v || !copy)
    cli_die(1, "out of memory");
  size_t k = 0;
  char *s = copy;
  for (;;) {
    char *comma = strchr(s, ',');
    if (comma)
      *comma = '\0';
    if (*s == '\0')
      cli_die(2, "%s '%s': empty list element; expected comma-separated numbers", opt, val);
    char *end;
    errno = 0;
    v[k] = strtod(s, &end);
    if (*end != '\0' || errno == ERANGE || !isfinite(v[k]))
      cli_die(2, "%s '%s': '%s' is not a number; expected comma-separated numbers", opt, val, s);
    k++;
    if (!comma)
      break;
    s = comma + 1;
  }
  free(copy);
  *out = v;
  return k;
}

void cli_disc_defaults(cli_disc *d)
{
  *d = (cli_disc){.dim = 1,
                  .lattice = NULL,
                  .kernel = &mfs_kernel_cubic,
                  .dilation = 2.0,
                  .shape = &mfs_shape_mls,
                  .quadrature = "nodal",
                  .consistent_mass = 0,
                  .modulus = 1.0,
                  .density = 1.0,
                  .spacing = 1.0,
                  .gamma = 1.0};
}

static void list_names(char *buf, size_t len, const char *const *names, size_t n)
{
  buf[0] = '\0';
  for (size_t i = 0; i < n; i++) {
    strncat(buf, names[i], len - strlen(buf) - 1);
    if (i + 1 < n)
      strncat(buf, ", ", len - strlen(buf) - 1);
  }
}

int cli_disc_option(cli_disc *d, const char *opt, const char *val)
{
  char names[256];
  if (strcmp(opt, "--dim") == 0) {
    d->dim = (int)cli_long(opt, val, 1, 2);
  } else if (strcmp(opt, "--lattice") == 0) {
    if (strcmp(val, "line") && strcmp(val, "square") && strcmp(val, "hex"))
      cli_die(2, "--lattice '%s': unknown lattice; allowed: line, square, hex", val);
    d->lattice = val;
  } else if (strcmp(opt, "--kernel") == 0) {
    d->kernel = mfs_kernel_find(val);
    if (!d->kernel) {
      const char *n[8];
      size_t k = 0;
      for (; mfs_kernel_types[k]; k++)
        n[k] = mfs_kernel_types[k]->name;
      list_names(names, sizeof names, n, k);
      cli_die(2, "--kernel '%s': unknown kernel; allowed: %s", val, names);
    }
  } else if (strcmp(opt, "--dilation") == 0) {
    d->dilation = cli_double(opt, val);
    if (!(d->dilation > 0.0))
      cli_die(2, "--dilation %s: must be > 0", val);
  } else if (strcmp(opt, "--shape") == 0) {
    d->shape = mfs_shape_find(val);
    if (!d->shape) {
      const char *n[8];
      size_t k = 0;
      for (; mfs_shape_types[k]; k++)
        n[k] = mfs_shape_types[k]->name;
      list_names(names, sizeof names, n, k);
      cli_die(2, "--shape '%s': unknown shape function; allowed: %s", val, names);
    }
  } else if (strcmp(opt, "--quadrature") == 0) {
    mfs_quad_rule r;
    if (mfs_quad_rule_parse(val, &r) != MFS_OK)
      cli_die(2,
              "--quadrature '%s': unknown rule; allowed: nodal, stress, stress-quad, stress-tri, "
              "stress-star, stress-hex, gauss1 .. gauss10",
              val);
    d->quadrature = val;
  } else if (strcmp(opt, "--mass") == 0) {
    if (strcmp(val, "lumped") == 0)
      d->consistent_mass = 0;
    else if (strcmp(val, "consistent") == 0)
      d->consistent_mass = 1;
    else
      cli_die(2, "--mass '%s': allowed: lumped, consistent", val);
  } else if (strcmp(opt, "--modulus") == 0) {
    d->modulus = cli_double(opt, val);
    if (!(d->modulus > 0.0))
      cli_die(2, "--modulus %s: must be > 0", val);
  } else if (strcmp(opt, "--density") == 0) {
    d->density = cli_double(opt, val);
    if (!(d->density > 0.0))
      cli_die(2, "--density %s: must be > 0", val);
  } else if (strcmp(opt, "--spacing") == 0) {
    d->spacing = cli_double(opt, val);
    if (!(d->spacing > 0.0))
      cli_die(2, "--spacing %s: must be > 0", val);
  } else if (strcmp(opt, "--gamma") == 0) {
    d->gamma = cli_double(opt, val);
    if (!(d->gamma > 0.0))
      cli_die(2, "--gamma %s: must be > 0", val);
  } else {
    return 0;
  }
  return 1;
}

void cli_disc_finish(cli_disc *d, mfs_lattice_kind *lattice, mfs_quad_rule *rule)
{
  const char *lat = d->lattice ? d->lattice : (d->dim == 1 ? "line" : "square");
  if (d->dim == 1 && strcmp(lat, "line"))
    cli_die(2, "--lattice %s: not a 1D lattice; with --dim 1 allowed: line", lat);
  if (d->dim == 2 && strcmp(lat, "line") == 0)
    cli_die(2, "--lattice line: not a 2D lattice; with --dim 2 allowed: square, hex");
  *lattice = strcmp(lat, "line") == 0 ? MFS_LATTICE_LINE
             : strcmp(lat, "hex") == 0 ? MFS_LATTICE_HEX
                                       : MFS_LATTICE_SQUARE;
  mfs_quad_rule_parse(d->quadrature, rule);
  if (mfs_quad_rule_check(rule, d->dim, *lattice) != MFS_OK) {
    const char *allowed = d->dim == 1 ? "nodal, stress, gaussN"
                          : *lattice == MFS_LATTICE_HEX
                            ? "nodal, stress-hex, gaussN"
                            : "nodal, stress-quad, stress-tri, stress-star, gaussN";
    cli_die(2, "--quadrature %s: not defined for --dim %d --lattice %s; allowed: %s",
            d->quadrature, d->dim, lat, allowed);
  }
}

const char cli_disc_help[] =
  "  --dim 1|2               dimension (default 1)\n"
  "  --lattice line|square|hex   particle lattice (default line in 1D, square in 2D)\n"
  "  --kernel NAME           cubic (default), quartic, wendland2, quintic\n"
  "  --dilation D            support radius a = D*dx (default 2)\n"
  "  --shape NAME            mls (default), sph, shepard, kb, rl\n"
  "  --quadrature RULE       nodal (default), stress (1D), stress-quad, stress-tri,\n"
  "                          stress-star, stress-hex, gauss1, gauss2, gaussN\n"
  "  --mass lumped|consistent    mass matrix (default lumped, row sum)\n"
  "  --modulus C             tangent modulus (E in 1D, shear modulus in 2D; default 1)\n"
  "  --density RHO           density (default 1)\n"
  "  --spacing DX            particle spacing (default 1)\n"
  "  --gamma G               dy/dx of the square lattice (default 1)\n";

_Noreturn void cli_die_status(int status, const cli_disc *d, const char *what)
{
  if (status == MFS_ESINGULAR)
    cli_die(2,
            "--dilation %g: too small for the %s moment matrix with kernel %s (singular %s); "
            "use a larger dilation",
            d->dilation, d->shape->name, d->kernel->name, what);
  if (status == MFS_ETOOSMALL)
    cli_die(2, "model too small for --dilation %g: %s", d->dilation, what);
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
  char *p = strdup(path);
  for (int hops = 0; p; hops++) {
    struct stat st;
    if (lstat(p, &st) != 0 || !S_ISLNK(st.st_mode))
      return p; /* missing or not a link: this is the target */
    if (hops == MAX_LINKS) {
      free(p);
      errno = ELOOP;
      return NULL;
    }
    char link[4096];
    ssize_t n = readlink(p, link, sizeof link - 1);
    if (n < 0) {
      free(p);
      return NULL;
    }
    link[n] = '\0';
    char *next;
    const char *slash = strrchr(p, '/');
    if (link[0] == '/' || !slash) {
      next = strdup(link);
    } else {
      size_t dlen = (size_t)(slash - p) + 1;
      next = malloc(dlen + (size_t)n + 1);
      if (next) {
        memcpy(next, p, dlen);
        memcpy(next + dlen, link, (size_t)n + 1);
      }
    }
    free(p);
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
  if (!target)
    cli_die(2, "-o %s: cannot resolve the path (%s)", path, strerror(errno));
  struct stat st;
  int exists = stat(target, &st) == 0;
  if (exists && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
    /* a device or a pipe: write it in place, never rename over it */
    int fd = open(target, O_WRONLY | O_NOCTTY);
    if (fd < 0) {
      int e = errno;
      free(target);
      cli_die(2, "-o %s: cannot open the device or FIFO for writing (%s)", path, strerror(e));
    }
    o->f = fdopen(fd, "w");
    o->path = target;
    if (!o->f)
      cli_die(1, "-o %s: %s", path, strerror(errno));
    return;
  }
  if (exists && !S_ISREG(st.st_mode)) {
    free(target);
    cli_die(2, "-o %s: %s; allowed: a regular file, a new path, a character device or a FIFO",
            path, S_ISDIR(st.st_mode) ? "is a directory" : "is a block device or socket");
  }
  size_t len = strlen(target) + 16;
  o->path = target;
  o->tmp = malloc(len);
  if (!o->tmp)
    cli_die(1, "out of memory");
  snprintf(o->tmp, len, "%s.tmpXXXXXX", target);
  int fd = mkstemp(o->tmp);
  if (fd < 0) {
    int e = errno;
    free(o->tmp);
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
  free(o->tmp);
  free(o->path);
  o->tmp = o->path = NULL;
  o->f = NULL;
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
    free(o->tmp);
    o->tmp = NULL;
    cli_die(1, "-o %s: cannot write the output file", p);
  }
  free(o->tmp);
  free(o->path);
  o->tmp = o->path = NULL;
}

void cli_fmt(char *buf, size_t len, double v)
{
  if (v == 0.0)
    snprintf(buf, len, "0");
  else
    snprintf(buf, len, "%.16g", v);
}
