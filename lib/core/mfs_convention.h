/* The conventions of the peer codes users bring their models from: how a
 * peer's smoothing length h and kernel map to mfstab's support radius a and
 * kernel (mfs_kernel.h), and the peer's own explicit step rule.
 *
 * A preset (mfs_convention) is one peer kernel: mfstab's kernel with the
 * same W(r) and a = support_per_h * h (each preset's W(r, h) is the peer's,
 * checked point by point in tests/test_convention.c against the peer's
 * formula; the definitions, with the files they are in, are cited in
 * docs/conventions.md).  A step rule (mfs_step_rule) is the peer's formula
 * for the step of a linear elastic solid at rest, with the peer's default
 * safety factor: every rule is dt = factor * h / c with the peer's h and
 * the peer's sound speed c from Young's modulus E, Poisson's ratio nu and
 * the density (3D Lame constants, as the peers write them; their 2D is
 * plane strain with the same constants):
 *   c_P = sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu)))   P-wave speed
 *   c_K = sqrt(E / (3 (1 - 2 nu) rho))                   bulk sound speed
 * Rules carry no guarantee: mfstab compares them with dt_crit. */
#ifndef MFS_CONVENTION_H
#define MFS_CONVENTION_H

#include "mfs_kernel.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a step rule is evaluated with. */
typedef struct {
  int dim;        /* 1 or 2 (TrixiParticles' rule uses the dimension) */
  double h;       /* the peer's smoothing length (m) */
  double young;   /* E (Pa) */
  double poisson; /* nu, in (-1, 0.5) */
  double density; /* rho (kg/m^3) */
} mfs_rule_args;

typedef struct {
  const char *name;           /* CSV column suffix: dt_rule_<name> */
  const char *peer;           /* the code and solver, for messages and docs */
  const char *formula;        /* the rule at rest, in the peer's symbols */
  double factor;              /* the peer's default safety (CFL) factor */
  const char *factor_source;  /* where the default comes from */
  double support_per_h;       /* a / h of the peer's default kernel: the h of a model
                                 that did not say which preset it follows */
  double (*speed)(const mfs_rule_args *r); /* the peer's sound speed (m/s) */
} mfs_step_rule;

extern const mfs_step_rule mfs_rule_lammps_smd;       /* LAMMPS MACHDYN fix smd/adjust_dt */
extern const mfs_step_rule mfs_rule_sphinxsys;        /* SPHinXsys AcousticTimeStep, c0 = c_K */
extern const mfs_step_rule mfs_rule_sphinxsys_pwave;  /* the same with c0 = c_P (PR #688) */
extern const mfs_step_rule mfs_rule_trixiparticles;   /* TrixiParticles TLSPH calculate_dt */
extern const mfs_step_rule mfs_rule_dualsphysics;     /* DualSPHysics FlexStruc DtVariable */

/* NULL-terminated list of the rules, in column order. */
extern const mfs_step_rule *const mfs_step_rules[];

/* dt = factor * h / speed (factor <= 0: the rule's default).  NAN for bad
 * arguments (h, E, rho <= 0, nu outside (-1, 0.5)). */
double mfs_rule_dt(const mfs_step_rule *rule, const mfs_rule_args *args, double factor);

/* The sound speeds of the rules. */
double mfs_speed_p(const mfs_rule_args *r);    /* c_P */
double mfs_speed_bulk(const mfs_rule_args *r); /* c_K */

/* One peer kernel. */
typedef struct {
  const char *name;              /* "peer" (its default kernel) or "peer:PeerKernelName" */
  const char *peer;              /* the code */
  const char *peer_kernel;       /* the peer's name of the kernel */
  const mfs_kernel_type *kernel; /* mfstab's kernel with the same W(r) */
  double support_per_h;          /* a = support_per_h * h */
  unsigned dims;                 /* bit d (1 << d): the peer defines W in dimension d */
  const mfs_step_rule *rule;     /* the peer's step rule, NULL if it has none for solids */
  double rule_support_per_h;     /* a / (the length the peer's step rules take) with this
                                    kernel: LAMMPS 1 (2 radius = a), the others the
                                    smoothing length (support_per_h) */
  const char *h_is;              /* what the peer calls h */
} mfs_convention;

/* NULL-terminated list of every preset. */
extern const mfs_convention *const mfs_conventions[];

/* The preset called name, or NULL. */
const mfs_convention *mfs_convention_find(const char *name);

/* The support radius of a preset for the peer's h: support_per_h * h. */
double mfs_convention_support(const mfs_convention *c, double h);

/* The length a step rule takes for a model of support radius a: under
 * convention c (NULL: none) the peer's own rules (every rule of the same
 * peer) take a / c->rule_support_per_h; any other rule takes its default
 * kernel's a / rule->support_per_h. */
double mfs_rule_h(const mfs_step_rule *rule, const mfs_convention *c, double a);

/* 1 if rule is one of the step rules of the peer of convention c. */
int mfs_rule_of(const mfs_step_rule *rule, const mfs_convention *c);

/* 1 if the preset's peer defines its kernel in dimension dim. */
int mfs_convention_applies(const mfs_convention *c, int dim);

#ifdef __cplusplus
}
#endif

#endif
