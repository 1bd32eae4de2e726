/* The finite-model commands `mfstab eigs`, `mfstab bound` and `mfstab check`
 * (tools/cmd_eigs.c, cmd_bound.c, cmd_check.c): their shared options (the
 * model: a lattice box, a perturbed lattice or a particle file; the support
 * in the user's terms; the material in SI), the analyses they share
 * (tools/model_run.c), and the data of the paper's Figs 17 and 18 for
 * `mfstab reproduce`. */
#ifndef MFSTAB_EIGS_FIGURES_H
#define MFSTAB_EIGS_FIGURES_H

#include "cli.h"
#include "particles_csv.h"

/* Write, into directory dir (which must exist), the tidy CSV data of
 *   fig17_cubic.csv, fig17_quartic.csv   lambda_max dx^2 of the 1D EFG bar
 *       (E = rho = 1, 41 and 101 nodes on [0, 1], free, gauss2, MLS, lumped)
 *       against D = 1 .. 4: ARPACK lambda_max, element bound (eq. 124),
 *       closed form alpha/D^2 (eq. 137)
 *   fig18_cubic.csv, fig18_quartic.csv   the 2D counterpart (anti-plane,
 *       21 x 21 nodes on the unit square, 2 x 2 Gauss points per cell)
 *       against D = 1.5 .. 5: lambda_max, element bound, alpha_1/D^2 of the
 *       kernel (eq. 146) and the printed 13.30/D^2 (eq. 146) and 15.00/D^2
 *       (eq. 148)
 * Returns 0, or 1 if a model fails (nothing printed: eigs_figure17_error()
 * says which model and why, for the caller's one line). */
int eigs_figure17(const char *dir);
const char *eigs_figure17_error(void);

/* The options of a finite model, shared by eigs, bound and check. */
typedef struct {
  const char *nodes, *length;
  int fixed;                  /* none, ends, boundary */
  int periodic;
  long fourier_points, fourier_angles;
  const char *out;
  const char *particles;      /* --particles FILE */
  const char *fix;            /* --fix GROUP[,GROUP...] */
  double support;             /* --support A (m) */
  double smoothing_length;    /* --smoothing-length H (m) */
  const mfs_convention *convention;
  double perturb;             /* --perturb F: fraction of dx */
  long seed;
  double young, shear_modulus;
  double rule_factor;         /* --rule-factor F: the convention's step rule with this factor */
  int certify;
} model_opts;

extern const cli_opt model_opts_table[];
#define MODEL_NOPTS 19

/* The parsed options of eigs, bound or check, and what they resolve to. */
typedef struct {
  cli_disc d;
  model_opts m;
  mfs_model_spec s;           /* the model */
  particle_file pf;           /* --particles */
  int have_file;
  unsigned char *fix_mask;    /* --fix: one flag per particle */
  double young, shear, poisson; /* E (Pa), the shear modulus (2D; Pa), nu */
  const char *support_option; /* the option that set the support radius, for messages */
} model_cmd;

/* Check the options of a finite model and build its spec (exit 2 with one
 * line naming the option): reads the particle file, maps the convention,
 * resolves the material.  physics_group: the group of --physics and
 * --poisson (to know whether --poisson was given). */
void model_finish(model_cmd *c, const cli_group *disc_group, const cli_group *physics_group,
                  const cli_group *model_group);
void model_cmd_free(model_cmd *c);

/* Column values that the commands write. */
typedef struct {
  double c;        /* wave speed sqrt(modulus/density) of the model */
  double c_p;      /* P-wave speed: bar sqrt(E/rho) in 1D, sqrt((lambda+2mu)/rho) in 2D */
  double c_bulk;   /* sqrt(K/rho), K = E/(3(1-2nu)) */
  double h_sph;    /* SPH smoothing length a/2 */
  double dt_rule_p, dt_rule_bulk; /* 0.3 h_sph / c */
  double alpha, bound_alpha;      /* eq. 136/146 constant and alpha c^2/h^2 */
} eigs_derived;

void eigs_derive(const mfs_model_spec *s, eigs_derived *dv);

/* The configuration columns (header and values, no trailing comma). */
void eigs_config_header(FILE *f);
void eigs_config_row(FILE *f, const model_cmd *c, const mfs_model_spec *s, const eigs_derived *dv);

/* The columns bound_alpha, alpha, lambda_fourier, kappa_fourier, theta_fourier
 * (degrees), each followed by a comma. */
void eigs_put_estimates(FILE *f, const eigs_derived *dv, double lf, double kf, double tf);

/* One number into a CSV row, followed by ',' (or '\n' when last); dies
 * (exit 1) rather than write an infinity; a NAN (undefined) is an empty cell. */
void eigs_put(FILE *f, double v, int last);

/* Die with the right message for a library status met while building the
 * model (a particle file: the file, the line and the particle). */
_Noreturn void model_die_status(const model_cmd *c, mfs_status st, size_t bad_point,
                                const char *what);

#endif
