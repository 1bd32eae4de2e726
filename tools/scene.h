/* Scene files of `mfstab run`: an INI file (read with inih) describing a
 * rod ([model] dim = 1) or a rectangle (dim = 2: anti-plane shear or plane
 * strain, the linear Lagrangian models of lib/time/mfs_solver2d.h), its
 * discretization, initial and boundary conditions, the time integration and
 * the probes to record.  Validated once; every error names the file, the
 * line, the section and the key, and exits with code 2. */
#ifndef MFSTAB_SCENE_H
#define MFSTAB_SCENE_H

#include "mfstab.h"
#include "mfs_integrator.h"
#include "mfs_solver.h"
#include "mfs_tsph.h"

#define SCENE_MAX_PROBES 16
/* The range of real keys: magnitudes up to 1e30, positive keys from 1e-30,
 * so that products (moduli over lengths squared, energies) stay finite. */
#define SCENE_MAX_MAGNITUDE 1e30
#define SCENE_MIN_POSITIVE 1e-30
#define SCENE_MAX_KEYS 64

typedef struct {
  const char *path;        /* the scene file */
  mfs_solver_spec spec;    /* model, material, discretization, boundary */
  /* [model] formulation = stress_velocity: the TSPH bar (lib/time/mfs_tsph.h) */
  int stress_velocity;
  int linear_interpolation; /* [discretization] interpolation = linear */
  double viscosity;        /* [discretization] artificial_viscosity (alpha) */
  double yield_stress, fluidity, exponent, hardening; /* [material] Perzyna */
  /* [initial] */
  double center_velocity;  /* velocity of the particle nearest L/2 */
  double perturbation;     /* random displacement in [-p, p] dX */
  unsigned long seed;
  double pulse_amplitude, pulse_alpha, pulse_center; /* v = A exp(-alpha (X - c)^2) */
  /* [model] dim = 2 (lib/time/mfs_solver2d.h): nodes x nodes_y particles on
   * length x length_y; [material] modulus is the shear modulus mu */
  int dim;
  int ny;                  /* [model] nodes_y */
  double ly;               /* [model] length_y */
  mfs_physics_kind physics; /* [model] physics: antiplane | plane_strain */
  double poisson;          /* [material] poisson (plane strain; 0.25) */
  double stress_yy, stress_xy; /* [material] initial_stress_yy, _xy (Pa; 2D plane strain; sigma_xx
                                  is initial_stress) */
  int fixed_edges;         /* [boundary] edges: fixed (1, default) | free (0) */
  double pulse_center_y;   /* 2D pulse: v = A exp(-alpha |X - c|^2) */
  int component;           /* [initial] component: 0 x (anti-plane: u_z), 1 y */
  int have_mode;           /* mode_x or mode_y given */
  int mode_x, mode_y;      /* Bloch mode k = 2 pi (mode_x / lx, mode_y / ly) */
  double mode_amplitude;   /* seed u = A cos(k.X) on `component` (0: none) */
  /* [time] */
  double end, dt, safety;
  int have_dt, force;
  long max_steps;          /* refuse a run of more steps (default 10^8) */
  double max_entries;      /* refuse a plan of more neighbour entries ([model] max_entries) */
  mfs_scheme scheme;
  mfs_dt_rule step_rule;   /* [time] step_rule (gershgorin | certified | power) */
  int have_step_rule;
  int print_step;          /* mfstab run: the step line on stderr */
  int tsph;                /* scheme = tsph given */
  mfs_tsph_scheme tscheme; /* stress_velocity: tsph | euler | rk2 | rk4 */
  /* [output] */
  int nprobes;
  int probe[SCENE_MAX_PROBES];
  long every;
  double mode;             /* kappa dX / pi of the mode_amp probe */
  /* where each key was set (line, or 0 for --set / default) */
  int line[SCENE_MAX_KEYS];
} scene;

/* Probe identifiers and names. */
enum {
  PROBE_V_CENTER,
  PROBE_U_CENTER,
  PROBE_KINETIC,
  PROBE_POTENTIAL,
  PROBE_TOTAL,
  PROBE_SIGMA_END,
  PROBE_SIGMA_CENTER,
  PROBE_MODE_AMP,
  PROBE_MAX_V,
  PROBE_V_MID,
  PROBE_V_ERR,
  PROBE_MODIFIED, /* 2D: the leapfrog's conserved energy (lib/time/mfs_solver2d.h) */
  PROBE_COUNT
};
extern const char *const scene_probe_names[PROBE_COUNT];

/* The stress-velocity spec of a scene with [model] formulation = stress_velocity. */
mfs_tsph_spec scene_tsph_spec(const scene *sc);

/* The model of a scene with [model] dim = 2 (lumped mass). */
mfs_model_spec scene_model_spec(const scene *sc);

/* Read the file (exit 2 on any error). */
/* The solver of a finished scene, through the integrator interface; dies
 * (one line, exit 2 or 1) when it cannot be built or the plan would exceed
 * [model] max_entries.  Defined in cmd_run.c. */
mfs_integrator scene_build(scene *sc);

void scene_load(scene *sc, const char *path);
/* Read a scene from the text of a file (NUL-terminated, not empty); name
 * stands for the file in messages (exit 2 on any error). */
void scene_load_text(scene *sc, const char *name, const char *text);
/* The scene files of analysis/scenes/, built into the program
 * (tools/embed_scenes.py writes scenes_embedded.c at build time): name
 * ("rod-tensile.ini") and text.  NULL when there is no such scene. */
const char *scene_builtin(const char *name);

/* An observer of scene_run: called at every output row with the state and
 * the values of the probes of [output] probes (in their order); a nonzero
 * return stops the run there. */
typedef int (*scene_row_fn)(void *ctx, const mfs_state *s, const double *probe_values);

/* The outcome of scene_run. */
typedef struct {
  long steps;       /* steps taken */
  double t;         /* time reached (s) */
  int failed;       /* 1: a step or a probe turned non-finite at time t (only with keep_failure) */
} scene_result;

/* Run a finished scene: build the solver, choose the step, set the initial
 * state, step to [time] end; each output row ([output] every) goes to the
 * CSV file csv_path (standard output when NULL; only if write_csv: the
 * header first) and to row (when not NULL).  A numerical
 * failure dies with one line (exit 1) unless keep_failure, which ends the
 * run and reports it in the result.  Defined in cmd_run.c. */
scene_result scene_run(scene *sc, int write_csv, const char *csv_path, scene_row_fn row, void *ctx,
                        int keep_failure);

/* Apply "section.key=value" from the command line (exit 2 on error). */
void scene_set(scene *sc, const char *assignment);
/* Check required keys and cross-key constraints (exit 2). */
void scene_finish(scene *sc);
/* Die (code 2) with "FILE:LINE: [section] key = value: message" for a key
 * of the table by section and name. */
_Noreturn void scene_key_error(const scene *sc, const char *section, const char *key,
                               const char *fmt, ...);

#endif
