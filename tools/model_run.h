/* The analyses of a finite model that `mfstab eigs` and `mfstab check` share
 * (tools/model_run.c): assemble, check the lumped masses, lambda_max
 * (ARPACK), the element bound, the Gershgorin bound, the Fourier estimate,
 * zero-energy modes, the certified step, the peers' step rules; and the
 * modes written for ParaView (--write-modes). */
#ifndef MFSTAB_MODEL_RUN_H
#define MFSTAB_MODEL_RUN_H

#include "eigs_figures.h"

typedef struct {
  int zero_modes;       /* count the zero-energy modes */
  double tol;           /* their threshold relative to lambda_max */
  long nev, ncv, maxiter;
  double arpack_tol;
  double lambda_tol;    /* ARPACK's tolerance of lambda_max alone (0: arpack_tol) */
  int certify;          /* dt_certified */
  int keep;             /* keep the model and the modes (write-modes, check) */
  int distributed;      /* over the MPI ranks (tools/par.h, model_prun.c): no model kept */
} run_opts;

#define RUN_MAX_RULES 8

typedef struct {
  mfs_model *m;              /* kept with run_opts.keep, else NULL */
  eigs_derived dv;
  size_t particles;
  size_t dofs;               /* free degrees of freedom */
  /* lumped masses (consistent: all reported positive) */
  size_t nonpositive;        /* free dofs with m_i <= 0 */
  double min_mass;           /* NAN with a consistent mass */
  size_t min_mass_particle;
  double min_mass_x[2];      /* its coordinates (y NAN in 1D) */
  int masses_ok;
  mfs_bound_result br;
  int bound_valid;
  double lf, kf, tf;         /* Fourier estimate */
  mfs_gershgorin_result g;   /* lambda NAN where it does not apply */
  int have_lambda;           /* lambda_max computed (masses_ok) */
  double lambda;
  int iters, matvecs;
  double resid;
  int have_zero;
  mfs_zero_modes z;          /* z.modes kept with keep */
  int zero_runs, rigid;
  int have_cert;
  mfs_certify_result cr;
  double *vmax;              /* eigenvector of lambda_max (m->n), with keep */
  double dt_rule[RUN_MAX_RULES]; /* mfs_step_rules, in order */
} run_result;

/* Build and analyse the model of c (dies with one line on a bad input or a
 * numerical failure, with its exit code). */
void model_run(const model_cmd *c, const run_opts *o, run_result *r);
void run_result_free(run_result *r);
/* r->lambda, computed with info: dies (exit 1) unless it is positive, else
 * marks it computed and keeps the ARPACK counts and residual. */
void run_take_lambda(run_result *r, const mfs_eig_info *info);

/* The same analyses over the MPI ranks (tools/model_prun.c, lib/analysis/
 * mfs_peigs.h): the element bound, the lumped masses, the Gershgorin bound
 * and lambda_max (PARPACK); no model is kept (r->m NULL), zero modes and
 * certification are not computed.  Collective: every rank calls it. */
void model_prun(const model_cmd *c, const run_opts *o, run_result *r);

/* The bounds of `mfstab bound` over the MPI ranks: the element bound (on a
 * lattice the streaming bound, as one process computes it), the Gershgorin
 * bound streamed from each rank's rows (lumped mass; gr->lambda NAN
 * otherwise), the coordinates gx of its row's particle, the particle *mI of
 * the smallest mass, the numbers of particles and quadrature points. */
void bound_prun(const model_cmd *c, mfs_bound_result *br, mfs_gershgorin_result *gr, double *gx,
                size_t *mI, size_t *np, size_t *npts);

/* The peers' step rules for the model of c (the convention's peer with the
 * user's h and --rule-factor; every other peer with its default kernel's h =
 * a / support_per_h): dt[k] for mfs_step_rules[k]. */
void model_rules(const model_cmd *c, double *dt);

/* The CSV column names of the rules: ",dt_rule_<name>,dt_rule_<name>_unsafe" each. */
void rules_header(FILE *f);
/* Their values; unsafe = 1 when the rule's step is above unsafe_above, 0
 * when it is at most safe_below, empty otherwise (eigs: both dt_crit; bound:
 * dt_certified and the Lanczos value's 2/sqrt(lambda) >= dt_crit; NAN: not
 * known).  Each value followed by ',' (the last by '\n' if last). */
void rules_row(FILE *f, const double *dt, double safe_below, double unsafe_above, int last);

/* Mode diagnostics: participation ratio (sum |u_I|^2)^2 / (N sum |u_I|^4) over
 * the N free particles, the share of sum V_I |u_I|^2 in the boundary layer
 * (particles within the support radius of a boundary particle) and the
 * layer's share of the volume; location "boundary" when the mode's share
 * exceeds one half and the layer's volume share, else "interior". */
typedef struct {
  double participation, boundary_share, layer_share;
  const char *location;
  size_t peak_particle;      /* the particle of the largest |u_I| */
} mode_info;

/* The boundary layer of a model (p->n flags), malloc'ed. */
unsigned char *model_boundary_layer(const mfs_model *m);
void mode_describe(const mfs_model *m, const unsigned char *layer, const double *u, mode_info *mi);

/* The spurious zero modes: the zero modes M-orthogonalized against the
 * rigid fields that are null vectors and orthonormalized again; *count of
 * them, malloc'ed count x n (NULL if none). */
double *model_spurious_modes(const mfs_model *m, const run_result *r, int *count);

/* --write-modes PREFIX: PREFIX_modes.csv and PREFIX_modes.vtk with the spurious
 * zero modes and the highest mode. */
void write_modes(const model_cmd *c, const run_result *r, const char *prefix);

#endif
