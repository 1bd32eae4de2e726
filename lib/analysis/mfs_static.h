/* Static linear elasticity in 2D (plane stress or plane strain) with the
 * seven particle methods of Belytschko, Krongauz, Dolbow, Gerlach (1998),
 * "On the completeness of meshfree particle methods" ("paper 004"),
 * section 6.2, on its two problems with closed-form solutions.
 *
 * Every method is a (Petrov-)Galerkin discretization of the static weak
 * form (paper 004 eq. 89 without inertia, eqs 94-95):
 *
 *   K_IJ = sum_Q w_Q B^test_I(x_Q)^T D B^trial_J(x_Q),   f_I = sum_b w_b psi_I(x_b) t(x_b)
 *
 * with the strain-displacement block of a neighbour J at a point,
 *
 *   B_J = [ bx g_Jx   0     ]   g_J the (corrected) gradient of the trial or
 *         [ 0       by g_Jy ]   test shape functions at the point, bx = by = 1
 *         [ g_Jy    g_Jx    ]   except for Johnson-Beissel (eqs 49-52).
 *
 *   method  trial (values; gradient)          test     quadrature   paper
 *   sph     sphs: V-Shepard; symmetrized SPH  = trial  nodal        eq. 47
 *   jb      sphs, normal strains x beta       = trial  nodal        eqs 49-52
 *   rl      rl: V-Shepard; RL normalized      = trial  nodal        eqs 68-69
 *   cd1     kb: Shepard; corrected (eq. 56)   shepard  nodal        eqs 55-62
 *   cd2     cd2: MLS; diffuse derivative      shepard  nodal        eqs 63-64
 *   mls     mls                               = trial  nodal        eqs 44-46
 *   efg     mls                               = trial  gauss5 cells eqs 44-46
 *
 * The SPH family (sph, jb, rl) carries particle values: at a quadrature
 * point located at a particle, the value there is the particle's own
 * (phi_J = delta_J,self); elsewhere (error norms) the V-weighted Shepard
 * interpolant of the particle values.  Nodal quadrature uses the particle
 * volumes (eq. 95: the dual of the cells, summing to the area) and, on the
 * boundary, the trapezoid rule at the nodes; Gauss quadrature uses
 * gauss_n x gauss_n points per background cell and gauss_n points per
 * boundary segment.
 *
 * Essential boundary conditions: Lagrange multipliers, piecewise linear on
 * the nodes of Gamma_u, integrated with the method's boundary rule (for
 * nodal rules: point collocation at the nodes; for the SPH family, whose
 * values at the nodes are the particle values, that is the elimination of
 * the prescribed particle values, solved by CHOLMOD for the symmetric
 * methods).  The paper's layer of finite elements (eqs 100-105) is not
 * used: with nodal quadrature it is not consistent (docs/errata.md).
 * Otherwise the system [[K, C_test^T], [C_trial, 0]] is solved by UMFPACK.
 *
 * Problems:
 *   beam        cantilever [0, L] x [-D/2, D/2] (eqs 120-126): exact
 *               displacements on x = 0, the exact shear traction at x = L,
 *               free edges; P the tip load.  nx x ny regular nodes.
 *   plate-hole  quarter of an infinite plate with a hole of radius a under
 *               remote tension (eqs 127-129; displacements: Kirsch), on
 *               [0, b]^2 minus the disc: exact tractions on x = b and y = b,
 *               a free hole, u_y = 0 on y = 0 and u_x = 0 on x = 0.  Nodes:
 *               the square lattice of spacing h = b/(nx - 1) outside r <= a +
 *               h/2, plus nodes on the arc at spacing <= h (the paper's Fig. 7
 *               is lost); volumes: the 5 x 5 Gauss points of the background
 *               mesh given to the nearest node (a discrete Voronoi partition);
 *               background cells: a mapped mesh of the exact geometry.
 *
 * Errors (eqs 114-119): the nodal l2 error of u^h(x_I) with weights V_I,
 * the L2 and energy errors with the 5 x 5 Gauss points of the background
 * cells, all relative to the norm of the exact solution; and, as a
 * diagnostic, the energy error with the method's own nodal quadrature. */
#ifndef MFS_STATIC_H
#define MFS_STATIC_H

#include <stddef.h>

#include "mfs_csr.h"
#include "mfs_kernel.h"
#include "mfs_particles.h"
#include "mfs_quad.h"
#include "mfs_shape.h"
#include "mfs_spsolve.h"
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A method of section 6.2: a const table. */
typedef struct {
  const char *name;
  const char *what;                /* one line for --help */
  const mfs_shape_type *trial;     /* values and gradients of the trial functions */
  const mfs_shape_type *test;      /* NULL: Bubnov-Galerkin (test = trial); else Petrov-Galerkin */
  const mfs_quad_type *quadrature; /* nodal or gaussN */
  int jb_normal;                   /* normal strains normalized by beta (eq. 52), shear not */
  int particle_values;             /* the value at a particle is its own (SPH family) */
} mfs_static_method;

extern const mfs_static_method mfs_static_sph, mfs_static_jb, mfs_static_rl, mfs_static_cd1,
  mfs_static_cd2, mfs_static_mls, mfs_static_efg;
extern const mfs_static_method *const mfs_static_methods[]; /* NULL-terminated, the paper's order */
const mfs_static_method *mfs_static_method_find(const char *name);

typedef struct mfs_static mfs_static;
typedef struct mfs_static_spec mfs_static_spec;

/* A problem: a const table. */
typedef struct {
  const char *name;
  const char *what; /* one line for --help */
  int counts;       /* node counts it takes: 2 (nx, ny: the beam) or 1 (nx: the plate) */
  /* the problem's members of the spec: NULL, or the first bad one */
  const char *(*check)(const mfs_static_spec *s);
  /* the particles, background cells, boundary and Gauss points of m (internal) */
  int (*build)(mfs_static *m);
  /* the exact displacement (m) and stress (Pa, (s_xx, s_yy, s_xy)) at x */
  void (*exact)(const mfs_static_spec *s, const double *x, double *u, double *sig);
  /* the distance from x to the boundary of the domain (m) */
  double (*distance)(const mfs_static_spec *s, const double *x);
  /* the linear field of the patch test, u = c + G x (G row-major) */
  void (*patch_field)(double c[2], double G[4]);
} mfs_static_problem;

extern const mfs_static_problem mfs_static_beam, mfs_static_plate_hole;
extern const mfs_static_problem *const mfs_static_problems[];
const mfs_static_problem *mfs_static_problem_find(const char *name);

struct mfs_static_spec {
  const mfs_static_problem *problem;
  const mfs_static_method *method;
  const mfs_quad_type *quadrature; /* NULL: the method's; else nodal or gaussN */
  const mfs_kernel_type *kernel;
  double dilation;      /* support radius a = dilation * h; eq. 126: 2 sqrt(2) */
  int nx, ny;           /* beam: nodes along x and y; plate: nodes on an outer edge (ny unused) */
  double young;         /* E (Pa) */
  double poisson;       /* nu */
  int plane_strain;     /* 0: plane stress (the paper's) */
  double load;          /* beam: tip load P (N per unit thickness); plate: remote stress (Pa) */
  double length, depth; /* beam: L, D (m) */
  double hole_radius, plate_size; /* plate: a, b (m) */
  double perturb;       /* beam: random shift of the nodes, a fraction of dx (< 0.5) */
  unsigned long seed;   /* of the perturbation */
  double rcond_min;     /* moment matrices (0: 1e-12) */
  double solve_rcond_min; /* the linear system: the solver's rcond estimate (0: 1e-15) */
  const mfs_spsolve_type *solver; /* NULL: by capability (cholmod where eliminated and symmetric) */
  int ghost;            /* beam: 0: Lagrange multipliers on x = 0 (the consistent method);
                           G > 0: G columns of nodes added at x < 0 and the exact displacements
                           prescribed as the parameters of every node at x <= 0 (a diagnostic
                           with no approximation of the essential condition; errors over
                           [0, L] only) */
  int patch;            /* solve the linear patch field u = c + G x (problem->patch_field) with
                           its tractions on every boundary instead of the problem */
};

/* The paper's setting: beam, efg, cubic, dilation 2 sqrt(2), 17 x 3 nodes
 * (dx = 1/2), E = 1000, nu = 0.3 (lost in the extraction), plane stress,
 * P = 1, L = 8, D = 1, a = 1, b = 5. */
mfs_static_spec mfs_static_spec_default(void);

/* MFS_OK or MFS_EINVAL with *field the first bad member ("problem", "method",
 * "quadrature", "kernel", "dilation", "nx", "ny", "young", "poisson", "load",
 * "length", "depth", "hole_radius", "plate_size", "perturb", "rcond_min",
 * "solve_rcond_min", "solver", "ghost"). */
mfs_status mfs_static_check(const mfs_static_spec *s, const char **field);

/* What failed, for messages: the point and its neighbour count. */
typedef struct {
  double x[2];
  int nn;
  double rcond;
} mfs_static_where;

/* The geometry: particles, quadrature points, boundary.  NULL with *status:
 * MFS_EINVAL (bad spec: *field as mfs_static_check), MFS_ENOMEM. */
mfs_static *mfs_static_alloc(const mfs_static_spec *s, mfs_status *status, const char **field);
void mfs_static_free(mfs_static *m);

/* Assemble K, f and the constraints.  MFS_OK; MFS_ESINGULAR (a moment
 * matrix, or a JB normalization, singular at the point *where: too few
 * nodes in the support); MFS_ENOMEM. */
mfs_status mfs_static_assemble(mfs_static *m, mfs_static_where *where);

/* Solve (after assembly).  MFS_OK; MFS_ESYSTEM (singular system); MFS_EINVAL
 * (a symmetric-only solver asked for a system that is not); MFS_ENOMEM. */
mfs_status mfs_static_solve(mfs_static *m);

typedef struct {
  size_t nodes, unknowns, multipliers, quad_points, boundary_points;
  double h;             /* the node spacing the support scales with (m) */
  double support;       /* a (m) */
  size_t max_neighbours;
  double volume;        /* sum of the node volumes (m^2) */
  double cell_area;     /* sum of the weights of the background Gauss points of the domain (m^2) */
  size_t nnz_K;
  int symmetric;        /* Bubnov: K symmetric by construction */
  int eliminated;       /* the constraints were eliminations (no multipliers) */
  const char *solver;
  double rcond, backward, factor_nnz; /* of the last solve (rcond also after a failed one;
                                         NAN at a zero pivot) */
} mfs_static_info;
void mfs_static_get_info(const mfs_static *m, mfs_static_info *info);

/* max |K_IJ - K_JI| / max |K_IJ| of the assembled K (NAN before assembly). */
double mfs_static_asymmetry(const mfs_static *m);

/* The errors of the solution (eqs 114-119), relative. */
typedef struct {
  double l2;            /* nodal, eqs 114-115, u^h(x_I) */
  double L2;            /* eqs 116-117, 5 x 5 Gauss per background cell */
  double energy;        /* eqs 118-119, the same points */
  double energy_nodal;  /* the energy error at the nodes with the volumes (diagnostic) */
  double max_nodal;     /* max over nodes and components |u^h(x_I) - u(x_I)| / max |u(x_I)| */
} mfs_static_errors;
mfs_status mfs_static_error_norms(mfs_static *m, mfs_static_errors *e, mfs_static_where *where);

/* Nodes and the solution at them: u^h(x_I) (not the nodal parameter) and
 * the exact u(x_I) (m). */
size_t mfs_static_nnodes(const mfs_static *m);
/* 1 if node I lies in the problem's domain (0 for the ghost columns of spec.ghost). */
int mfs_static_node_in_domain(const mfs_static *m, size_t node);
void mfs_static_node(const mfs_static *m, size_t node, double x[2]);
/* uh: 2n values u^h(x_I); needs mfs_static_solve.  MFS_OK, MFS_EINVAL, MFS_ENOMEM. */
mfs_status mfs_static_nodal_solution(mfs_static *m, double *uh, double *uexact);

/* The assembled operators (after mfs_static_assemble): K (2n x 2n, dofs
 * interleaved (u_x, u_y) per node), f (2n). */
const mfs_csr *mfs_static_stiffness(const mfs_static *m);
const double *mfs_static_load(const mfs_static *m);

/* Why a method converges or not (section 2.3), without solving:
 *   reproduction   max over the quadrature points of the trial strains'
 *                  error for u_I = u_lin(x_I) (problem->patch_field: beam
 *                  c = (0.01, -0.02) m, G = [[0.003, 0.002], [-0.001, 0.004]]; plate
 *                  c = 0, G = diag(0.003, -0.001), u_n = 0 on the symmetry lines),
 *                  relative to max |eps|: the reproducing conditions (eq. 8)
 *   values         the same for the trial values, relative to max |u|
 *   int_interior   the integration constraint residual max_I |sum_Q w_Q
 *                  B^test_I(x_Q)^T sigma - sum_b w_b psi_I sigma n_b| / h for
 *                  the three unit stresses sigma, over the nodes farther than
 *                  2a from the boundary (no quadrature point of the test
 *                  support sees it; NAN if there is none)
 *   int_all        the same over all nodes
 *   test_lambda    the test gradients' reproduction of linear derivatives
 *                  sum_I grad psi_I(x_Q) (x) x_I, mean of its diagonal over
 *                  the points farther than a from the boundary (NAN if none),
 *                  and test_lambda_dev the largest deviation from the identity
 *                  over them (Shepard at the nodes: 1.013722 for the cubic
 *                  kernel at a = 2 sqrt(2) dx) */
typedef struct {
  double reproduction, values, int_interior, int_all, test_lambda, test_lambda_dev;
  size_t interior_nodes, lambda_points;
} mfs_static_consistency;
mfs_status mfs_static_check_consistency(mfs_static *m, mfs_static_consistency *c,
                                        mfs_static_where *where);

/* Least-squares slope of log(err) against log(h) over n levels (NAN if n <
 * 2 or an error is not positive). */
double mfs_static_rate(size_t n, const double *h, const double *err);

#ifdef __cplusplus
}
#endif

#endif
