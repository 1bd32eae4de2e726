/* The finite-model commands `mfstab eigs` and `mfstab bound` (tools/cmd_eigs.c,
 * tools/cmd_bound.c): their shared options, and the data of the paper's
 * Figs 17 and 18 for `mfstab reproduce`. */
#ifndef MFSTAB_EIGS_FIGURES_H
#define MFSTAB_EIGS_FIGURES_H

#include "cli.h"

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
 * Returns 0, or 1 after one line on stderr if a model or a file fails. */
int eigs_figure17(const char *dir);

/* Options shared by eigs and bound. */
typedef struct {
  cli_disc d;              /* kernel, dilation, shape, quadrature, mass, modulus, density */
  mfs_model_spec s;        /* the model, filled by eigs_finish */
  const char *outpath;     /* -o */
  const char *export_prefix;
  int zero_modes;          /* --zero-modes */
  double tol;              /* --tol: zero-mode threshold relative to lambda_max */
  double poisson;          /* --poisson */
  int nev, ncv, maxiter;   /* ARPACK controls */
  double arpack_tol;
  int fourier_points, fourier_angles;
  /* raw values, validated once the dimension is known */
  const char *nodes, *length, *fixed;
  int periodic, plane_strain;
} eigs_opts;

/* Parse the command line of eigs (is_eigs = 1) or bound; exits 2 on bad
 * input with one line naming the option. */
void eigs_parse(int argc, char **argv, const char *help, int is_eigs, eigs_opts *o);

/* Column values that both commands write. */
typedef struct {
  double c;        /* wave speed sqrt(modulus/density) of the model */
  double c_p;      /* P-wave speed: bar sqrt(E/rho) in 1D, sqrt((lambda+2mu)/rho) in 2D */
  double c_bulk;   /* sqrt(K/rho), K = E/(3(1-2nu)) */
  double h_sph;    /* SPH smoothing length a/2 */
  double dt_rule_p, dt_rule_bulk; /* 0.3 h_sph / c */
  double alpha, bound_alpha;      /* eq. 136/146 constant and alpha c^2/h^2 */
} eigs_derived;

void eigs_derive(const eigs_opts *o, eigs_derived *dv);

/* The configuration columns (header and values, no trailing comma). */
void eigs_config_header(FILE *f);
void eigs_config_row(FILE *f, const eigs_opts *o, const eigs_derived *dv);

/* One number into a CSV row; dies (exit 1) rather than write a NaN. */
void eigs_put(FILE *f, double v, int last);

#endif
