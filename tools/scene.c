/* Scene files of `mfstab run` (see scene.h).  One table lists every key: its
 * section, name, type and constraint; the parser, the --set overrides and the
 * error messages all come from it. */
#include "scene.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <ini.h>

#include "cli.h"

const char *const scene_probe_names[PROBE_COUNT] = {
  "v_center", "u_center", "kinetic_energy", "potential_energy", "total_energy",
  "sigma_end", "sigma_center", "mode_amp", "max_v", "v_mid", "v_err", "modified_energy"};

typedef enum { K_INT, K_POS, K_NONNEG, K_REAL, K_BOOL, K_WORD } key_type;

typedef enum {
  /* [model] */ NODES, LENGTH, PERIODIC, FORMULATION, DIM, NODES_Y, LENGTH_Y, PHYSICS, MAX_ENTRIES,
  /* [material] */ DENSITY, MODULUS, INITIAL_STRESS, YIELD_STRESS, FLUIDITY, EXPONENT, HARDENING,
  POISSON, INITIAL_STRESS_YY, INITIAL_STRESS_XY,
  /* [discretization] */ INTERPOLATION, VISCOSITY, KERNEL, DILATION, SHAPE, FRAME, QUADRATURE, EQUILIBRATE, SKIN,
  /* [initial] */ CENTER_VELOCITY, PERTURBATION, SEED, PULSE_AMPLITUDE, PULSE_ALPHA, PULSE_CENTER,
  PULSE_CENTER_Y, MODE_X, MODE_Y, MODE_AMPLITUDE, COMPONENT,
  /* [boundary] */ LEFT, RIGHT, LEFT_VELOCITY, RIGHT_VELOCITY, LEFT_UNTIL, RIGHT_UNTIL, EDGES,
  /* [time] */ END, DT, SAFETY, SCHEME, FORCE, MAX_STEPS, STEP_RULE,
  /* [output] */ PROBES, EVERY, MODE,
  NKEYS
} key_id;

_Static_assert(NKEYS <= SCENE_MAX_KEYS, "scene.line[] too small for the key table");

typedef struct {
  const char *section, *name;
  key_type type;
  int required;
} key_def;

static const key_def keys[NKEYS] = {
  [NODES] = {"model", "nodes", K_INT, 1},
  [LENGTH] = {"model", "length", K_POS, 1},
  [PERIODIC] = {"model", "periodic", K_BOOL, 0},
  [FORMULATION] = {"model", "formulation", K_WORD, 0},
  [DIM] = {"model", "dim", K_INT, 0},
  [NODES_Y] = {"model", "nodes_y", K_INT, 0},   /* required when dim = 2 */
  [LENGTH_Y] = {"model", "length_y", K_POS, 0}, /* required when dim = 2 */
  [PHYSICS] = {"model", "physics", K_WORD, 0},
  [MAX_ENTRIES] = {"model", "max_entries", K_POS, 0},
  [DENSITY] = {"material", "density", K_POS, 1},
  [MODULUS] = {"material", "modulus", K_POS, 1},
  [INITIAL_STRESS] = {"material", "initial_stress", K_REAL, 0},
  [YIELD_STRESS] = {"material", "yield_stress", K_POS, 0},
  [FLUIDITY] = {"material", "fluidity", K_NONNEG, 0},
  [EXPONENT] = {"material", "perzyna_exponent", K_NONNEG, 0},
  [HARDENING] = {"material", "hardening", K_REAL, 0},
  [POISSON] = {"material", "poisson", K_REAL, 0},
  [INITIAL_STRESS_YY] = {"material", "initial_stress_yy", K_REAL, 0},
  [INITIAL_STRESS_XY] = {"material", "initial_stress_xy", K_REAL, 0},
  [INTERPOLATION] = {"discretization", "interpolation", K_WORD, 0},
  [VISCOSITY] = {"discretization", "artificial_viscosity", K_NONNEG, 0},
  [KERNEL] = {"discretization", "kernel", K_WORD, 0},
  [DILATION] = {"discretization", "dilation", K_POS, 0},
  [SHAPE] = {"discretization", "shape", K_WORD, 0},
  [FRAME] = {"discretization", "frame", K_WORD, 0},
  [QUADRATURE] = {"discretization", "quadrature", K_WORD, 0},
  [EQUILIBRATE] = {"discretization", "equilibrate", K_BOOL, 0},
  [SKIN] = {"discretization", "skin", K_POS, 0},
  [CENTER_VELOCITY] = {"initial", "center_velocity", K_REAL, 0},
  [PERTURBATION] = {"initial", "perturbation", K_NONNEG, 0},
  [SEED] = {"initial", "seed", K_INT, 0},
  [PULSE_AMPLITUDE] = {"initial", "pulse_amplitude", K_REAL, 0},
  [PULSE_ALPHA] = {"initial", "pulse_alpha", K_POS, 0},
  [PULSE_CENTER] = {"initial", "pulse_center", K_REAL, 0},
  [PULSE_CENTER_Y] = {"initial", "pulse_center_y", K_REAL, 0},
  [MODE_X] = {"initial", "mode_x", K_INT, 0},
  [MODE_Y] = {"initial", "mode_y", K_INT, 0},
  [MODE_AMPLITUDE] = {"initial", "mode_amplitude", K_REAL, 0},
  [COMPONENT] = {"initial", "component", K_WORD, 0},
  [LEFT] = {"boundary", "left", K_WORD, 0},
  [RIGHT] = {"boundary", "right", K_WORD, 0},
  [LEFT_VELOCITY] = {"boundary", "left_velocity", K_REAL, 0},
  [RIGHT_VELOCITY] = {"boundary", "right_velocity", K_REAL, 0},
  [LEFT_UNTIL] = {"boundary", "left_until", K_NONNEG, 0},
  [RIGHT_UNTIL] = {"boundary", "right_until", K_NONNEG, 0},
  [EDGES] = {"boundary", "edges", K_WORD, 0},
  [END] = {"time", "end", K_POS, 1},
  [DT] = {"time", "dt", K_POS, 0},
  [SAFETY] = {"time", "safety", K_POS, 0},
  [SCHEME] = {"time", "scheme", K_WORD, 0},
  [FORCE] = {"time", "force", K_BOOL, 0},
  [MAX_STEPS] = {"time", "max_steps", K_INT, 0},
  [STEP_RULE] = {"time", "step_rule", K_WORD, 0},
  [PROBES] = {"output", "probes", K_WORD, 1},
  [EVERY] = {"output", "every", K_INT, 0},
  [MODE] = {"output", "mode", K_POS, 0},
};

/* Where the value being parsed came from, for messages. */
typedef struct {
  scene *sc;
  int line;      /* current line of the file, 0 for --set */
  FILE *f;
} parse_ctx;

static char set_origin[512];

static void vkey_error(const scene *sc, int line, const char *section, const char *key,
                       const char *value, const char *fmt, va_list ap)
{
  char msg[512];
  vsnprintf(msg, sizeof msg, fmt, ap);
  if (line > 0)
    cli_die(2, "%s:%d: [%s] %s = %s: %s", sc->path, line, section, key, value, msg);
  if (value)
    cli_die(2, "--set %s.%s=%s: %s", section, key, value, msg);
  cli_die(2, "%s: [%s] %s: %s", sc->path, section, key, msg);
}

static _Noreturn void key_error(const scene *sc, int line, const char *section, const char *key,
                                const char *value, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vkey_error(sc, line, section, key, value, fmt, ap);
  va_end(ap);
  exit(2);
}

/* Values as given, to repeat them in later (cross-key) errors. */
static char values[NKEYS][128];

_Noreturn void scene_key_error(const scene *sc, const char *section, const char *key,
                               const char *fmt, ...)
{
  int id = 0;
  for (; id < NKEYS; id++)
    if (strcmp(keys[id].section, section) == 0 && strcmp(keys[id].name, key) == 0)
      break;
  va_list ap;
  va_start(ap, fmt);
  if (id < NKEYS && values[id][0])
    vkey_error(sc, sc->line[id], section, key, values[id], fmt, ap);
  else
    vkey_error(sc, 0, section, key, NULL, fmt, ap);
  va_end(ap);
  exit(2);
}

static mfs_bc parse_bc(const scene *sc, int line, key_id id, const char *v)
{
  if (strcmp(v, "fixed") == 0)
    return MFS_BC_FIXED;
  if (strcmp(v, "free") == 0)
    return MFS_BC_FREE;
  if (strcmp(v, "velocity") == 0)
    return MFS_BC_VELOCITY;
  key_error(sc, line, keys[id].section, keys[id].name, v, "allowed: fixed, free, velocity");
}

/* Whether quadrature rule `name` applies to the lattice of dimension dim
 * (1: line, 2: square). */
static int quad_applies(const mfs_quad_type *t, int dim)
{
  return mfs_quad_applies(t, dim, dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE);
}

static const char *quad_allowed(int dim)
{
  static char buf[512];
  char names[400];
  cli_quad_names(dim, dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE, names, sizeof names);
  snprintf(buf, sizeof buf, "allowed%s: %s", dim == 2 ? " with [model] dim = 2" : "", names);
  return buf;
}

static void set_key(scene *sc, int line, key_id id, const char *value)
{
  const key_def *k = &keys[id];
  double x = 0.0;
  long l = 0;
  switch (k->type) {
  case K_INT:
    if (!cli_parse_long(value, &l))
      key_error(sc, line, k->section, k->name, value, "not an integer");
    break;
  case K_POS:
  case K_NONNEG:
  case K_REAL:
    if (!cli_parse_double(value, &x))
      key_error(sc, line, k->section, k->name, value, "%s", cli_number_problem(value));
    if (k->type == K_POS && !(x > 0.0))
      key_error(sc, line, k->section, k->name, value, "must be > 0");
    if (k->type == K_NONNEG && !(x >= 0.0))
      key_error(sc, line, k->section, k->name, value, "must be >= 0");
    /* magnitudes whose products stay finite (moduli, lengths, times, amplitudes) */
    if (!(fabs(x) <= SCENE_MAX_MAGNITUDE) || (k->type == K_POS && !(x >= SCENE_MIN_POSITIVE)))
      key_error(sc, line, k->section, k->name, value, "out of range; allowed %s%g to %g",
                k->type == K_REAL ? "magnitudes " : "", k->type == K_POS ? SCENE_MIN_POSITIVE : 0.0,
                SCENE_MAX_MAGNITUDE);
    break;
  case K_BOOL:
    if (!strcmp(value, "1") || !strcmp(value, "true") || !strcmp(value, "yes"))
      l = 1;
    else if (!strcmp(value, "0") || !strcmp(value, "false") || !strcmp(value, "no"))
      l = 0;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: 0, 1, true, false, yes, no");
    break;
  case K_WORD:
    break;
  }
  mfs_solver_spec *sp = &sc->spec;
  switch (id) {
  case NODES:
    if (l < 3 || l > 100000000)
      key_error(sc, line, k->section, k->name, value, "allowed 3 to 100000000");
    sp->disc.source.nx = (int)l;
    break;
  case LENGTH: sp->disc.source.lx = x; break;
  case PERIODIC: sp->disc.source.periodic = (int)l; break;
  case DIM:
    if (l != 1 && l != 2)
      key_error(sc, line, k->section, k->name, value, "allowed: 1, 2");
    sc->dim = (int)l;
    break;
  case NODES_Y:
    if (l < 3 || l > 100000000)
      key_error(sc, line, k->section, k->name, value, "allowed 3 to 100000000");
    sc->ny = (int)l;
    break;
  case LENGTH_Y: sc->ly = x; break;
  case MAX_ENTRIES: sc->max_entries = x; break;
  case PHYSICS:
    if (!strcmp(value, "antiplane"))
      sc->physics = MFS_PHYS_SCALAR;
    else if (!strcmp(value, "plane_strain"))
      sc->physics = MFS_PHYS_PLANE_STRAIN;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: antiplane, plane_strain");
    break;
  case POISSON:
    if (!(x > -1.0 && x < 0.5))
      key_error(sc, line, k->section, k->name, value, "must be in (-1, 0.5)");
    sc->poisson = x;
    break;
  case PULSE_CENTER_Y: sc->pulse_center_y = x; break;
  case MODE_X:
  case MODE_Y:
    if (l < -100000000 || l > 100000000)
      key_error(sc, line, k->section, k->name, value, "allowed -100000000 to 100000000");
    *(id == MODE_X ? &sc->mode_x : &sc->mode_y) = (int)l;
    sc->have_mode = 1;
    break;
  case MODE_AMPLITUDE: sc->mode_amplitude = x; break;
  case COMPONENT:
    if (strcmp(value, "x") && strcmp(value, "y"))
      key_error(sc, line, k->section, k->name, value, "allowed: x, y");
    sc->component = value[0] == 'y';
    break;
  case EDGES:
    if (!strcmp(value, "fixed"))
      sc->fixed_edges = 1;
    else if (!strcmp(value, "free"))
      sc->fixed_edges = 0;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: fixed, free");
    break;
  case FORMULATION:
    if (!strcmp(value, "displacement"))
      sc->stress_velocity = 0;
    else if (!strcmp(value, "stress_velocity"))
      sc->stress_velocity = 1;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: displacement, stress_velocity");
    break;
  case YIELD_STRESS: sc->yield_stress = x; break;
  case FLUIDITY: sc->fluidity = x; break;
  case EXPONENT: sc->exponent = x; break;
  case HARDENING: sc->hardening = x; break;
  case DENSITY: sp->disc.material.density = x; break;
  case MODULUS: sp->disc.material.modulus = x; break;
  case INITIAL_STRESS: sp->disc.material.initial_stress = x; break;
  case INITIAL_STRESS_YY: sc->stress_yy = x; break;
  case INITIAL_STRESS_XY: sc->stress_xy = x; break;
  case KERNEL:
    if (!(sp->disc.kernel = mfs_kernel_find(value))) {
      char names[256];
      key_error(sc, line, k->section, k->name, value, "unknown kernel; allowed: %s",
                cli_table_names((const void *const *)mfs_kernel_types, names, sizeof names));
    }
    break;
  case DILATION: sp->disc.dilation = x; break;
  case VISCOSITY: sc->viscosity = x; break;
  case INTERPOLATION:
    if (!strcmp(value, "shepard"))
      sc->linear_interpolation = 0;
    else if (!strcmp(value, "linear"))
      sc->linear_interpolation = 1;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: shepard, linear");
    break;
  case SHAPE:
    if (!(sp->disc.shape = mfs_shape_find(value))) {
      char names[256];
      key_error(sc, line, k->section, k->name, value, "unknown shape function; allowed: %s",
                cli_table_names((const void *const *)mfs_shape_types, names, sizeof names));
    }
    break;
  case FRAME:
    if (!strcmp(value, "eulerian"))
      sp->disc.frame = MFS_FRAME_EULERIAN;
    else if (!strcmp(value, "lagrangian"))
      sp->disc.frame = MFS_FRAME_LAGRANGIAN;
    else
      key_error(sc, line, k->section, k->name, value, "allowed: eulerian, lagrangian");
    break;
  case QUADRATURE:
    /* a rule of the square lattice only is checked against [model] dim by
     * scene_finish (dim may come later); any other bad rule fails here */
    sp->disc.quadrature = mfs_quad_find(value);
    if (!quad_applies(sp->disc.quadrature, 1) && !quad_applies(sp->disc.quadrature, 2))
      key_error(sc, line, k->section, k->name, value, "%s", quad_allowed(sc->dim));
    break;
  case EQUILIBRATE: sp->equilibrate = (int)l; break;
  case SKIN: sp->skin = x; break;
  case CENTER_VELOCITY: sc->center_velocity = x; break;
  case PERTURBATION: sc->perturbation = x; break;
  case SEED:
    if (l < 0 || l > 4294967295L)
      key_error(sc, line, k->section, k->name, value, "allowed 0 to 4294967295");
    sc->seed = (unsigned long)l;
    break;
  case PULSE_AMPLITUDE: sc->pulse_amplitude = x; break;
  case PULSE_ALPHA: sc->pulse_alpha = x; break;
  case PULSE_CENTER: sc->pulse_center = x; break;
  case LEFT: sp->bc[0] = parse_bc(sc, line, id, value); break;
  case RIGHT: sp->bc[1] = parse_bc(sc, line, id, value); break;
  case LEFT_VELOCITY: sp->bc_velocity[0] = x; break;
  case RIGHT_VELOCITY: sp->bc_velocity[1] = x; break;
  case LEFT_UNTIL: sp->bc_until[0] = x; break;
  case RIGHT_UNTIL: sp->bc_until[1] = x; break;
  case END: sc->end = x; break;
  case DT: sc->dt = x; sc->have_dt = 1; break;
  case SAFETY:
    if (x > 1.0)
      key_error(sc, line, k->section, k->name, value, "must be in (0, 1]");
    sc->safety = x;
    break;
  case SCHEME:
    sc->tsph = !strcmp(value, "tsph");
    if (!sc->tsph && mfs_scheme_parse(value, &sc->scheme) != MFS_OK)
      key_error(sc, line, k->section, k->name, value, "allowed: leapfrog, euler, rk2, rk4, tsph");
    break;
  case FORCE: sc->force = (int)l; break;
  case STEP_RULE:
    if (mfs_dt_rule_parse(value, &sc->step_rule) != MFS_OK)
      key_error(sc, line, k->section, k->name, value, "allowed: gershgorin, certified, power");
    sc->have_step_rule = 1;
    break;
  case MAX_STEPS:
    if (l < 1 || l > 1000000000000L)
      key_error(sc, line, k->section, k->name, value, "allowed 1 to 1000000000000");
    sc->max_steps = l;
    break;
  case PROBES: {
    char buf[512];
    if (strlen(value) >= sizeof buf)
      key_error(sc, line, k->section, k->name, value, "too long");
    strcpy(buf, value);
    sc->nprobes = 0;
    for (char *tok = strtok(buf, ", \t"); tok; tok = strtok(NULL, ", \t")) {
      int p = 0;
      while (p < PROBE_COUNT && strcmp(tok, scene_probe_names[p]))
        p++;
      if (p == PROBE_COUNT)
        key_error(sc, line, k->section, k->name, value,
                  "unknown probe '%s'; allowed: v_center, u_center, kinetic_energy, "
                  "potential_energy, total_energy, sigma_end, sigma_center, mode_amp, max_v, "
                  "v_mid, v_err, modified_energy",
                  tok);
      if (sc->nprobes == SCENE_MAX_PROBES)
        key_error(sc, line, k->section, k->name, value, "at most %d probes", SCENE_MAX_PROBES);
      sc->probe[sc->nprobes++] = p;
    }
    if (sc->nprobes == 0)
      key_error(sc, line, k->section, k->name, value, "empty list");
    break;
  }
  case EVERY:
    if (l < 1 || l > 2147483647L)
      key_error(sc, line, k->section, k->name, value, "allowed 1 to 2147483647");
    sc->every = l;
    break;
  case MODE:
    if (x > 1.0)
      key_error(sc, line, k->section, k->name, value, "must be in (0, 1] (kappa dX / pi)");
    sc->mode = x;
    break;
  case NKEYS: break;
  }
  sc->line[id] = line;
  snprintf(values[id], sizeof values[id], "%s", value);
}

static int find_key(const char *section, const char *name, int *section_known)
{
  *section_known = 0;
  for (int id = 0; id < NKEYS; id++) {
    if (strcmp(keys[id].section, section))
      continue;
    *section_known = 1;
    if (strcmp(keys[id].name, name) == 0)
      return id;
  }
  return -1;
}

static const char all_sections[] = "model, material, discretization, initial, boundary, time, output";

static void unknown_key(const scene *sc, int line, const char *section, const char *name,
                        const char *value, int section_known)
{
  if (!section_known)
    key_error(sc, line, section, name, value, "unknown section [%s]; allowed: %s", section,
              all_sections);
  char allowed[512] = "";
  for (int id = 0; id < NKEYS; id++)
    if (strcmp(keys[id].section, section) == 0) {
      if (allowed[0])
        strncat(allowed, ", ", sizeof allowed - strlen(allowed) - 1);
      strncat(allowed, keys[id].name, sizeof allowed - strlen(allowed) - 1);
    }
  key_error(sc, line, section, name, value, "unknown key; allowed in [%s]: %s", section, allowed);
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
  parse_ctx *c = user;
  if (!name) /* a section header alone (INI_CALL_HANDLER_ON_NEW_SECTION) */
    return 1;
  int known;
  int id = find_key(section, name, &known);
  if (id < 0)
    unknown_key(c->sc, c->line, section, name, value, known);
  if (c->sc->line[id] > 0)
    key_error(c->sc, c->line, section, name, value, "key already set on line %d",
              c->sc->line[id]);
  set_key(c->sc, c->line, (key_id)id, value);
  return 1;
}

/* Line reader that counts lines for the messages, and refuses what inih
 * would misread: a line longer than its buffer (inih would read the tail as
 * a line of its own) and a NUL byte (which would cut the value short). */
static char *reader(char *str, int num, void *stream)
{
  parse_ctx *c = stream;
  int k = 0, ch = EOF;
  while (k < num - 1 && (ch = getc(c->f)) != EOF) {
    if (ch == '\0')
      cli_die(2, "%s:%d: a NUL byte; a scene file is text", c->sc->path, c->line + 1);
    str[k++] = (char)ch;
    if (ch == '\n')
      break;
  }
  if (k == 0)
    return NULL;
  str[k] = '\0';
  c->line++;
  if (str[k - 1] != '\n' && k == num - 1 && (ch = getc(c->f)) != EOF) {
    if (ch != '\n')
      cli_die(2, "%s:%d: line longer than %d characters", c->sc->path, c->line, num - 2);
  }
  return str;
}

static void defaults(scene *sc, const char *path)
{
  memset(sc, 0, sizeof *sc);
  memset(values, 0, sizeof values);
  sc->path = path;
  mfs_solver_spec *sp = &sc->spec;
  sp->disc = mfs_disc_default();
  sp->disc.source = (mfs_source){.lattice = MFS_LATTICE_LINE};
  sp->disc.kernel = &mfs_kernel_quartic;
  sp->disc.shape = &mfs_shape_mls;
  sp->disc.dilation = 2.0;
  sp->disc.frame = MFS_FRAME_LAGRANGIAN;
  sp->disc.quadrature = &mfs_quad_nodal;
  sp->equilibrate = 1;
  sp->bc[0] = sp->bc[1] = MFS_BC_FIXED;
  sp->bc_until[0] = sp->bc_until[1] = INFINITY;
  sc->seed = 1;
  sc->safety = 0.9;
  sc->scheme = MFS_SCHEME_LEAPFROG;
  sc->every = 1;
  sc->max_steps = 100000000; /* 10^8: a limit on the work, raised by [time] max_steps */
  sc->max_entries = 0.0; /* the default limit (cli_entries_limit), or [model] max_entries */
  sc->mode = 1.0;
  sc->pulse_alpha = 1.0;
  sc->yield_stress = INFINITY;
  sc->dim = 1;
  sc->physics = MFS_PHYS_SCALAR;
  sc->poisson = 0.25; /* as mfstab dispersion --poisson */
  sc->fixed_edges = 1;
}

static void close_file(void *f) { fclose(f); }

/* Parse the open stream c->f into c->sc (closes it). */
static void parse_stream(parse_ctx *c, const char *path)
{
  cli_on_die(close_file, c->f);
  int r = ini_parse_stream(reader, c, handler, c);
  cli_on_die_pop();
  fclose(c->f);
  if (r > 0)
    cli_die(2, "%s:%d: syntax error; expected [section] or key = value", path, r);
  if (r < 0)
    cli_die(2, "%s: cannot read the scene file", path);
}

void scene_load_text(scene *sc, const char *name, const char *text)
{
  defaults(sc, name);
  parse_ctx c = {sc, 0, fmemopen((void *)text, strlen(text), "r")};
  if (!c.f)
    cli_die(1, "%s: cannot read the built-in scene (%s)", name, strerror(errno));
  parse_stream(&c, name);
}

void scene_load(scene *sc, const char *path)
{
  defaults(sc, path);
  parse_ctx c = {sc, 0, fopen(path, "r")};
  if (!c.f)
    cli_die(2, "%s: cannot open the scene file (%s)", path, strerror(errno));
  struct stat st;
  if (fstat(fileno(c.f), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode) &&
      !S_ISCHR(st.st_mode)) {
    fclose(c.f);
    cli_die(2, "%s: %s; expected a scene file", path,
            S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file");
  }
  parse_stream(&c, path);
}

void scene_set(scene *sc, const char *assignment)
{
  snprintf(set_origin, sizeof set_origin, "%s", assignment);
  char *eq = strchr(set_origin, '='), *dot = strchr(set_origin, '.');
  if (!eq || !dot || dot > eq)
    cli_die(2, "--set '%s': expected SECTION.KEY=VALUE", assignment);
  *eq = '\0';
  *dot = '\0';
  const char *section = set_origin, *name = dot + 1, *value = eq + 1;
  int known;
  int id = find_key(section, name, &known);
  if (id < 0)
    unknown_key(sc, 0, section, name, value, known);
  set_key(sc, 0, (key_id)id, value);
}

/* Keys of the 1D rod that a 2D run refuses, and why. */
static const struct {
  key_id id;
  const char *why;
} not_2d[] = {
  {EQUILIBRATE, "a stressed 2D plate always applies the internal force at u = 0 as a load"},
  {PERTURBATION, "1D only; seed a 2D run with mode_x, mode_y, mode_amplitude or a pulse"},
  {SEED, "1D only (the random perturbation)"},
  {LEFT, "1D only; in 2D use [boundary] edges = fixed | free"},
  {RIGHT, "1D only; in 2D use [boundary] edges = fixed | free"},
  {LEFT_VELOCITY, "1D only: 2D runs have no velocity boundaries"},
  {RIGHT_VELOCITY, "1D only: 2D runs have no velocity boundaries"},
  {LEFT_UNTIL, "1D only: 2D runs have no velocity boundaries"},
  {RIGHT_UNTIL, "1D only: 2D runs have no velocity boundaries"},
  {INTERPOLATION, "the stress-velocity (TSPH) bar is 1D only"},
  {VISCOSITY, "the stress-velocity (TSPH) bar is 1D only"},
  {YIELD_STRESS, "viscoplasticity is 1D only (the TSPH bar)"},
  {FLUIDITY, "viscoplasticity is 1D only (the TSPH bar)"},
  {EXPONENT, "viscoplasticity is 1D only (the TSPH bar)"},
  {HARDENING, "viscoplasticity is 1D only (the TSPH bar)"},
  {MODE, "1D only; in 2D mode_amp takes the wave vector of [initial] mode_x, mode_y"},
};

/* Keys of a 2D run that a 1D run refuses. */
static const key_id only_2d[] = {NODES_Y, LENGTH_Y, PHYSICS, POISSON, PULSE_CENTER_Y, MODE_X,
                                 MODE_Y, MODE_AMPLITUDE, COMPONENT, EDGES, INITIAL_STRESS_YY,
                                 INITIAL_STRESS_XY};

/* A pulse centred outside the body [0, length] starts nothing (and v_err
 * would divide by a zero exact solution). */
static void check_pulse_center(const scene *sc, const char *key, double c, double length)
{
  if (values[PULSE_AMPLITUDE][0] && !(c >= 0.0 && c <= length))
    scene_key_error(sc, "initial", key, "outside the body; allowed 0 to %g (m)", length);
}

static void finish_2d(scene *sc)
{
  mfs_solver_spec *sp = &sc->spec;
  static const int req[] = {NODES_Y, LENGTH_Y};
  for (int i = 0; i < 2; i++)
    if (!values[req[i]][0])
      cli_die(2, "%s: [model] %s: missing; this key is required when [model] dim = 2", sc->path,
              keys[req[i]].name);
  if (sc->stress_velocity)
    scene_key_error(sc, "model", "formulation",
                    "the stress-velocity (TSPH) bar is 1D only; 2D runs are displacement form");
  int stressed = sp->disc.material.initial_stress != 0.0 || sc->stress_yy != 0.0 ||
                 sc->stress_xy != 0.0 || sp->disc.frame == MFS_FRAME_EULERIAN;
  if (sc->physics != MFS_PHYS_PLANE_STRAIN) {
    static const int plane[] = {INITIAL_STRESS, INITIAL_STRESS_YY, INITIAL_STRESS_XY};
    for (int i = 0; i < 3; i++)
      if (values[plane[i]][0])
        scene_key_error(sc, "material", keys[plane[i]].name,
                        "the stressed 2D plate is plane strain ([model] physics = plane_strain)");
    if (sp->disc.frame == MFS_FRAME_EULERIAN)
      scene_key_error(sc, "discretization", "frame",
                      "the kernel frame does not enter anti-plane motion; an Eulerian 2D plate "
                      "is plane strain ([model] physics = plane_strain)");
  }
  if (values[SKIN][0] && sp->disc.frame != MFS_FRAME_EULERIAN)
    scene_key_error(sc, "discretization", "skin", "the Eulerian neighbour skin needs frame = eulerian");
  for (size_t i = 0; i < sizeof not_2d / sizeof not_2d[0]; i++)
    if (values[not_2d[i].id][0])
      scene_key_error(sc, keys[not_2d[i].id].section, keys[not_2d[i].id].name,
                      "not used with [model] dim = 2: %s", not_2d[i].why);
  if (sc->tsph)
    scene_key_error(sc, "time", "scheme", "tsph is the 1D stress-velocity bar's scheme; "
                                          "allowed with dim = 2: leapfrog, euler, rk2, rk4");
  if (!quad_applies(sp->disc.quadrature, 2))
    scene_key_error(sc, "discretization", "quadrature", "%s", quad_allowed(2));
  if (sp->disc.quadrature->cells == MFS_CELLS_STAR && sp->disc.source.periodic &&
      ((sp->disc.source.nx | sc->ny) & 1))
    scene_key_error(sc, "discretization", "quadrature",
                    "the star pattern tiles a periodic box only with even nodes and nodes_y");
  if ((double)sp->disc.source.nx * sc->ny > 1e8)
    scene_key_error(sc, "model", "nodes_y", "at most 100000000 particles (nodes * nodes_y)");
  if (sp->disc.source.periodic && values[EDGES][0])
    scene_key_error(sc, "boundary", "edges", "no edge conditions on a periodic box "
                                             "([model] periodic = 1)");
  if (sc->physics != MFS_PHYS_PLANE_STRAIN) {
    if (values[POISSON][0])
      scene_key_error(sc, "material", "poisson", "plane strain only ([model] physics = plane_strain)");
    if (values[COMPONENT][0])
      scene_key_error(sc, "initial", "component",
                      "plane strain only; anti-plane shear has the one component u_z");
  }
  if (values[MODE_AMPLITUDE][0] && !sc->have_mode)
    scene_key_error(sc, "initial", "mode_amplitude", "needs [initial] mode_x or mode_y");
  if (sc->have_mode && !sp->disc.source.periodic)
    scene_key_error(sc, "initial", values[MODE_X][0] ? "mode_x" : "mode_y",
                    "the Bloch mode needs a periodic box ([model] periodic = 1)");
  if (sc->have_dt && values[SAFETY][0])
    scene_key_error(sc, "time", "safety", "give either dt or safety, not both");
  check_pulse_center(sc, "pulse_center", sc->pulse_center, sp->disc.source.lx);
  check_pulse_center(sc, "pulse_center_y", sc->pulse_center_y, sc->ly);
  for (int p = 0; p < sc->nprobes; p++) {
    int q = sc->probe[p];
    if (q == PROBE_SIGMA_END || q == PROBE_SIGMA_CENTER || q == PROBE_V_MID || q == PROBE_V_ERR)
      scene_key_error(sc, "output", "probes",
                      "%s is 1D only; with dim = 2: u_center, v_center, kinetic_energy, "
                      "potential_energy, total_energy, modified_energy, max_v, mode_amp",
                      scene_probe_names[q]);
    if (q == PROBE_MODE_AMP && !sc->have_mode)
      scene_key_error(sc, "output", "probes",
                      "mode_amp needs the wave vector [initial] mode_x, mode_y");
    if (q == PROBE_MODIFIED && stressed)
      scene_key_error(sc, "output", "probes",
                      "modified_energy is the energy the leapfrog conserves on the linear "
                      "(unstressed, Lagrangian) plate");
    if ((q == PROBE_POTENTIAL || q == PROBE_TOTAL) && sp->disc.frame == MFS_FRAME_EULERIAN)
      scene_key_error(sc, "output", "probes",
                      "%s: an Eulerian kernel has no energy (its operator is not symmetric)",
                      scene_probe_names[q]);
  }
  sp->bc[0] = sp->bc[1] = MFS_BC_FREE; /* unused in 2D */
}

void scene_finish(scene *sc)
{
  for (int id = 0; id < NKEYS; id++)
    if (keys[id].required && !values[id][0])
      cli_die(2, "%s: [%s] %s: missing; this key is required", sc->path, keys[id].section,
              keys[id].name);
  mfs_solver_spec *sp = &sc->spec;
  if (sc->dim == 2) {
    finish_2d(sc);
    return;
  }
  for (size_t i = 0; i < sizeof only_2d / sizeof only_2d[0]; i++)
    if (values[only_2d[i]][0])
      scene_key_error(sc, keys[only_2d[i]].section, keys[only_2d[i]].name,
                      "needs [model] dim = 2");
  if (!quad_applies(sp->disc.quadrature, 1))
    scene_key_error(sc, "discretization", "quadrature", "%s", quad_allowed(1));
  for (int p = 0; p < sc->nprobes; p++)
    if (sc->probe[p] == PROBE_MODIFIED)
      scene_key_error(sc, "output", "probes",
                      "modified_energy (the energy the leapfrog conserves on a linear model) "
                      "needs [model] dim = 2");
  const int periodic = sp->disc.source.periodic;
  if (periodic && (values[LEFT][0] || values[RIGHT][0]))
    scene_key_error(sc, "boundary", values[LEFT][0] ? "left" : "right",
                    "no end conditions on a periodic rod ([model] periodic = 1)");
  if (periodic)
    sp->bc[0] = sp->bc[1] = MFS_BC_FREE;
  if (sp->disc.material.initial_stress <= -sp->disc.material.modulus)
    scene_key_error(sc, "material", "initial_stress",
                    "must be > -modulus (the tangent E + S0 must stay positive)");
  for (int k = 0; k < 2; k++)
    if (values[k ? RIGHT_VELOCITY : LEFT_VELOCITY][0] && sp->bc[k] != MFS_BC_VELOCITY)
      scene_key_error(sc, "boundary", k ? "right_velocity" : "left_velocity",
                      "needs [boundary] %s = velocity", k ? "right" : "left");
  if (sc->have_dt && values[SAFETY][0])
    scene_key_error(sc, "time", "safety", "give either dt or safety, not both");
  check_pulse_center(sc, "pulse_center", sc->pulse_center, sp->disc.source.lx);
  if (!(sc->perturbation < 0.5))
    scene_key_error(sc, "initial", "perturbation",
                    "must be < 0.5 (a fraction of the spacing dX; particles keep their order)");
  int uses_v_err = 0;
  for (int p = 0; p < sc->nprobes; p++)
    uses_v_err |= sc->probe[p] == PROBE_V_ERR;
  if (uses_v_err && (periodic || sp->bc[0] != MFS_BC_FREE || sp->bc[1] != MFS_BC_FREE ||
                     sc->perturbation > 0.0 || sc->center_velocity != 0.0 ||
                     sp->disc.material.initial_stress != 0.0 || sc->pulse_amplitude == 0.0))
    scene_key_error(sc, "output", "probes",
                    "v_err compares with the d'Alembert solution of a linear rod with free ends "
                    "started by the velocity pulse alone: it needs left = right = free, "
                    "pulse_amplitude != 0, no perturbation, center_velocity or initial_stress");
  if (!sc->stress_velocity) {
    if (sc->tsph)
      scene_key_error(sc, "time", "scheme", "tsph needs [model] formulation = stress_velocity");
    if (values[INTERPOLATION][0])
      scene_key_error(sc, "discretization", "interpolation",
                      "needs [model] formulation = stress_velocity");
    if (values[VISCOSITY][0])
      scene_key_error(sc, "discretization", "artificial_viscosity",
                      "needs [model] formulation = stress_velocity");
    static const int plastic[] = {YIELD_STRESS, FLUIDITY, EXPONENT, HARDENING};
    for (int i = 0; i < 4; i++)
      if (values[plastic[i]][0])
        scene_key_error(sc, "material", keys[plastic[i]].name,
                        "viscoplasticity needs [model] formulation = stress_velocity");
    return;
  }
  /* stress-velocity bar (TSPH, lib/time/mfs_tsph.h) */
  static const int unused[] = {PERIODIC, INITIAL_STRESS, SHAPE, FRAME, QUADRATURE, EQUILIBRATE,
                               SKIN, PERTURBATION, SEED, STEP_RULE};
  for (int i = 0; i < (int)(sizeof unused / sizeof unused[0]); i++)
    if (values[unused[i]][0])
      scene_key_error(sc, keys[unused[i]].section, keys[unused[i]].name,
                      "not used by [model] formulation = stress_velocity");
  if (values[SCHEME][0] && !sc->tsph && sc->scheme == MFS_SCHEME_LEAPFROG)
    scene_key_error(sc, "time", "scheme",
                    "allowed with formulation = stress_velocity: tsph, euler, rk2, rk4");
  sc->tscheme = MFS_TSPH_TAYLOR;
  if (values[SCHEME][0] && !sc->tsph)
    sc->tscheme = sc->scheme == MFS_SCHEME_EULER ? MFS_TSPH_EULER
                  : sc->scheme == MFS_SCHEME_RK2 ? MFS_TSPH_RK2
                                                 : MFS_TSPH_RK4;
  if (!values[KERNEL][0])
    sp->disc.kernel = &mfs_kernel_cubic; /* paper 001 eq. 24 */
  if ((values[FLUIDITY][0] || values[EXPONENT][0] || values[HARDENING][0]) &&
      !values[YIELD_STRESS][0])
    scene_key_error(sc, "material", values[FLUIDITY][0] ? "fluidity"
                                    : values[EXPONENT][0] ? "perzyna_exponent" : "hardening",
                    "needs [material] yield_stress");
  for (int p = 0; p < sc->nprobes; p++)
    if (sc->probe[p] == PROBE_U_CENTER || sc->probe[p] == PROBE_MODE_AMP)
      scene_key_error(sc, "output", "probes",
                      "%s: no displacement in formulation = stress_velocity",
                      scene_probe_names[sc->probe[p]]);
}

mfs_model_spec scene_model_spec(const scene *sc)
{
  mfs_disc d = sc->spec.disc;
  d.dim = 2;
  d.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE,
                          .nx = sc->spec.disc.source.nx,
                          .ny = sc->ny,
                          .lx = sc->spec.disc.source.lx,
                          .ly = sc->ly,
                          .periodic = sc->spec.disc.source.periodic};
  d.consistent_mass = 0; /* lumped: explicit steps without a solve */
  d.material.physics = sc->physics;
  d.material.poisson = sc->poisson;
  return (mfs_model_spec){
    .disc = d, .fixed = !d.source.periodic && sc->fixed_edges ? MFS_FIX_BOUNDARY : MFS_FIX_NONE};
}

mfs_tsph_spec scene_tsph_spec(const scene *sc)
{
  const mfs_solver_spec *sp = &sc->spec;
  mfs_tsph_spec t = {.disc = sp->disc,
                     .yield_stress = sc->yield_stress,
                     .fluidity = sc->fluidity,
                     .exponent = sc->exponent,
                     .hardening = sc->hardening,
                     .scheme = sc->tscheme,
                     .viscosity = sc->viscosity,
                     .linear_interpolation = sc->linear_interpolation};
  for (int k = 0; k < 2; k++) {
    t.bc[k] = sp->bc[k];
    t.bc_velocity[k] = sp->bc_velocity[k];
    t.bc_until[k] = sp->bc_until[k];
  }
  return t;
}
