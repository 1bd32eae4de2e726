/* mfstab static: static linear elasticity in 2D with the seven particle
 * methods of paper 004 (Belytschko, Krongauz, Dolbow, Gerlach 1998) section
 * 6.2 on the cantilever beam and the plate with a hole (lib/analysis/
 * mfs_static.h): the nodal solution of one model, a refinement study with
 * the errors of eqs 114-119 and their fitted rates (Table III), or the patch
 * test and the integration constraint per method (section 2.3). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"

static const char usage[] = "mfstab static [options] [-o FILE]";
static const char about[] =
  "Static linear elasticity (plane stress, or --plane-strain) with the particle methods of\n"
  "paper 004 section 6.2, solved with a sparse direct solver (CHOLMOD for the symmetric\n"
  "systems, UMFPACK for the Petrov-Galerkin ones), essential conditions by Lagrange multipliers:\n"
  "  K_IJ = sum_Q w_Q B_test_I(x_Q)^T D B_trial_J(x_Q),  f_I = sum_b w_b psi_I(x_b) t(x_b)\n"
  "Problems: beam (eqs 120-126; [0, L] x [-D/2, D/2], tip load P) and plate-hole (eqs\n"
  "127-130; quarter of [0, b]^2 minus the disc of radius a, remote stress --load).\n"
  "Three outputs:\n"
  "  (default)      the nodal solution of one model: method,x_m,y_m,ux_m,uy_m,ux_exact_m,\n"
  "                 uy_exact_m (u^h(x_I), the approximation at the node, and the exact u)\n"
  "  --refine N     a study of N levels from --nodes, halving the spacing: one row per method\n"
  "                 and level with dx_m, the relative errors l2 (eqs 114-115), L2 (116-117),\n"
  "                 energy (118-119), energy at the nodes, and the rates fitted over all levels\n"
  "  --patch        per method: the reproduction of a linear field by the trial strains, the\n"
  "                 solved patch test, the integration constraint residual and the test\n"
  "                 gradients' reproduction of linear derivatives (section 2.3)\n"
  "Column lists: docs/commands.md.  --method takes a comma-separated list or 'all'.\n";

typedef struct {
  const mfs_static_problem *problem;
  const char *methods, *nodes, *out;
  long refine;
  int patch;
  const mfs_kernel_type *kernel;
  double dilation;
  const char *quadrature;
  double young, poisson, load, length, depth, hole, plate;
  int plane_strain;
  double perturb;
  long seed;
  const mfs_spsolve_type *solver;
  double solve_rcond_min;
  int ebc;
  double max_entries;
} static_opts;

static const char *const ebc_names[] = {"lm", "ghost", NULL};

static const void *find_problem(const char *n)
{
  return mfs_static_problem_find(n);
}
static const void *find_kernel(const char *n)
{
  return mfs_kernel_find(n);
}
static const void *find_solver(const char *n)
{
  return mfs_spsolve_find(n);
}

#define OFF(f) offsetof(static_opts, f)
static const cli_opt opts[] = {
  {.name = "--problem", .type = CLI_TABLE, .arg = "NAME", .help = "the problem (default beam)",
   .offset = OFF(problem), .find = find_problem, .list = (const void *const *)mfs_static_problems},
  {.name = "--method", .type = CLI_TEXT, .arg = "LIST",
   .help = "comma-separated methods, or all (default efg): sph, jb, rl, cd1, cd2, mls, efg",
   .offset = OFF(methods)},
  {.name = "--nodes", .type = CLI_TEXT, .arg = "NX,NY",
   .help = "beam: nodes along x and y (default 17,3: dx = 1/2); plate-hole: N nodes on an "
           "outer edge, h = b/(N-1) (default 6)",
   .offset = OFF(nodes)},
  {.name = "--refine", .type = CLI_INT, .arg = "LEVELS",
   .help = "a refinement study of LEVELS levels from --nodes, halving the spacing",
   .offset = OFF(refine), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 12},
  {.name = "--patch", .type = CLI_FLAG,
   .help = "patch test, reproduction and integration constraint per method",
   .offset = OFF(patch)},
  {.name = "--kernel", .type = CLI_TABLE, .arg = "NAME", .help = "the kernel (default cubic)",
   .offset = OFF(kernel), .find = find_kernel, .list = (const void *const *)mfs_kernel_types},
  {.name = "--dilation", .type = CLI_REAL, .arg = "D",
   .help = "support radius a = D h (default 2 sqrt(2) = 2.8284271247461903: eq. 126, the "
           "radius 2s with s the diagonal distance between nodes)",
   .offset = OFF(dilation), .bounds = CLI_GT | CLI_LE, .lo = 0, .hi = 100},
  {.name = "--quadrature", .type = CLI_TEXT, .arg = "RULE",
   .help = "override the method's rule: nodal, gauss1 .. gauss10 (default: nodal; gauss5 for "
           "efg)",
   .offset = OFF(quadrature)},
  {.name = "--young", .type = CLI_REAL, .arg = "E",
   .help = "Young's modulus in Pa (default 1000, the paper's)", .offset = OFF(young),
   .bounds = CLI_GT, .lo = 0},
  {.name = "--poisson", .type = CLI_REAL, .arg = "NU",
   .help = "Poisson's ratio (default 0.3; the paper's value is lost in the extraction)",
   .offset = OFF(poisson), .bounds = CLI_GT | CLI_LT, .lo = -1, .hi = 0.5},
  {.name = "--plane-strain", .type = CLI_FLAG, .help = "plane strain (default plane stress)",
   .offset = OFF(plane_strain)},
  {.name = "--load", .type = CLI_REAL, .arg = "P",
   .help = "beam: tip load P in N per unit thickness; plate-hole: remote stress in Pa (default 1)",
   .offset = OFF(load)},
  {.name = "--length", .type = CLI_REAL, .arg = "L", .help = "beam length in m (default 8)",
   .offset = OFF(length), .bounds = CLI_GT, .lo = 0},
  {.name = "--depth", .type = CLI_REAL, .arg = "D", .help = "beam depth in m (default 1)",
   .offset = OFF(depth), .bounds = CLI_GT, .lo = 0},
  {.name = "--hole-radius", .type = CLI_REAL, .arg = "A",
   .help = "plate-hole: radius a of the hole in m (default 1)", .offset = OFF(hole),
   .bounds = CLI_GT, .lo = 0},
  {.name = "--plate-size", .type = CLI_REAL, .arg = "B",
   .help = "plate-hole: side b of the quarter plate in m (default 5)", .offset = OFF(plate),
   .bounds = CLI_GT, .lo = 0},
  {.name = "--perturb", .type = CLI_REAL, .arg = "F",
   .help = "beam: random shift of the nodes, a fraction of dx in [0, 0.5) (boundary nodes "
           "along their edge, corners fixed; default 0)",
   .offset = OFF(perturb), .bounds = CLI_GE | CLI_LT, .lo = 0, .hi = 0.5},
  {.name = "--seed", .type = CLI_INT, .arg = "N", .help = "seed of --perturb (default 1)",
   .offset = OFF(seed), .bounds = CLI_GE | CLI_LE, .lo = 0, .hi = 4294967295.0},
  {.name = "--ebc", .type = CLI_CHOICE, .arg = "lm|ghost",
   .help = "essential conditions: lm, Lagrange multipliers on Gamma_u (default); ghost (beam, "
           "a diagnostic): 6 columns of nodes added at x < 0 and the exact displacements "
           "prescribed at every node with x <= 0, errors over [0, L]",
   .offset = OFF(ebc), .choices = ebc_names},
  {.name = "--solver", .type = CLI_TABLE, .arg = "NAME",
   .help = "force the sparse solver (default: cholmod for the symmetric systems, umfpack for "
           "the Petrov-Galerkin ones)",
   .offset = OFF(solver), .find = find_solver, .list = (const void *const *)mfs_spsolve_types},
  {.name = "--solve-rcond-min", .type = CLI_REAL, .arg = "R",
   .help = "a system whose solver rcond estimate is below R is singular (default 1e-15)",
   .offset = OFF(solve_rcond_min), .bounds = CLI_GE | CLI_LT, .lo = 0, .hi = 1},
  {.name = "--max-entries", .type = CLI_REAL, .arg = "N",
   .help = "refuse a model of more than about N neighbour entries, integration points times "
           "nodes in a support (default 5e8)",
   .offset = OFF(max_entries), .bounds = CLI_GE | CLI_LE, .lo = 1, .hi = 1e15},
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE",
   .help = "output file (default: standard output)", .offset = OFF(out)},
  {.type = CLI_END}};
#undef OFF
#define NOPTS (sizeof opts / sizeof opts[0])

enum { MAXM = 7 };

/* --method: a comma-separated list of names, or all. */
static size_t parse_methods(const char *arg, const mfs_static_method **out)
{
  char names[256];
  if (strcmp(arg, "all") == 0) {
    size_t n = 0;
    while (mfs_static_methods[n])
      out[n] = mfs_static_methods[n], n++;
    return n;
  }
  size_t n = 0;
  char *copy = mfs_strdup(arg);
  if (!copy)
    cli_die(1, "out of memory");
  cli_on_die(mfs_free, copy); /* after the message, which quotes it */
  for (char *s = copy;;) {
    char *comma = strchr(s, ',');
    if (comma)
      *comma = '\0';
    const mfs_static_method *m = mfs_static_method_find(s);
    if (!m)
      cli_die(2, "--method '%s': unknown method '%s'; allowed: %s, all", arg, s,
              cli_table_names((const void *const *)mfs_static_methods, names, sizeof names));
    for (size_t k = 0; k < n; k++)
      if (out[k] == m)
        cli_die(2, "--method '%s': '%s' given twice", arg, s);
    out[n++] = m;
    if (!comma)
      break;
    s = comma + 1;
  }
  cli_on_die_pop();
  mfs_free(copy);
  return n;
}

/* The work of the largest model (the finest level of --refine, the ghost
 * columns included): about (integration points) x (nodes in a support, pi D^2
 * in 2D) neighbour entries, an integration point per node (nodal) or N^2 per
 * cell (gaussN), for the method of the most points; or the entries of the
 * stiffness matrix, 2 x 2 for each pair of nodes within two supports (16 pi
 * D^2 a node), where that is more (the nodal methods).  Refused beyond
 * --max-entries (default CLI_MAX_ENTRIES, as the plans of the other
 * commands): a model of 3e8 nodes would otherwise run for hours. */
static void check_work(const mfs_static_spec *s, const mfs_static_method **ms, size_t nm,
                       const static_opts *o, const char *nodes_arg)
{
  double scale = o->refine > 1 ? (double)(1L << (o->refine - 1)) : 1.0;
  double nx = (double)(s->nx - 1) * scale + 1.0 + (double)s->ghost;
  double ny = (double)(s->ny - 1) * scale + 1.0;
  double nodes = nx * ny;
  double per_point = M_PI * s->dilation * s->dilation;
  if (per_point < 1.0)
    per_point = 1.0;
  double worst = 16.0 * nodes * per_point; /* the stiffness */
  const char *wm = ms[0]->name;
  for (size_t k = 0; k < nm; k++) {
    const mfs_quad_type *q = s->quadrature ? s->quadrature : ms[k]->quadrature;
    double g = q && q->gauss_n > 0 ? (double)q->gauss_n : 1.0;
    double e = nodes * g * g * per_point;
    if (e > worst)
      worst = e, wm = ms[k]->name;
  }
  double lim = o->max_entries > 0.0 ? o->max_entries : CLI_MAX_ENTRIES;
  if (!(worst <= lim))
    cli_die(2,
            "--nodes %s: about %.3g neighbour entries (%.3g nodes%s, method %s, --dilation %g), "
            "more than --max-entries %.3g%s; fewer nodes, levels or a smaller dilation, or raise "
            "--max-entries",
            nodes_arg ? nodes_arg : "(default)", worst, nodes,
            o->refine > 1 ? " on the finest level" : "", wm, s->dilation, lim,
            o->max_entries > 0.0 ? "" : " (the default)");
}

/* --nodes NX,NY (beam) or N (plate-hole). */
static void parse_nodes(const char *arg, int beam, int *nx, int *ny)
{
  char *copy = mfs_strdup(arg);
  if (!copy)
    cli_die(1, "out of memory");
  cli_on_die(mfs_free, copy);
  char *comma = strchr(copy, ',');
  if (comma)
    *comma = '\0';
  long lo = beam ? 2 : 3, hi = 100000;
  long a, b = 0;
  if (!cli_parse_long(copy, &a) || (comma && !cli_parse_long(comma + 1, &b)))
    cli_die(2, "--nodes '%s': expected %s", arg, beam ? "two integers NX,NY" : "an integer N");
  if (beam && !comma)
    cli_die(2, "--nodes '%s': the beam needs NX,NY (nodes along x and y)", arg);
  if (!beam && comma && b != a)
    cli_die(2, "--nodes '%s': plate-hole takes one count N (nodes on an outer edge)", arg);
  if (a < lo || a > hi)
    cli_die(2, "--nodes '%s': %s = %ld out of range; allowed %ld to %ld", arg, beam ? "NX" : "N",
            a, lo, hi);
  if (beam && (b < lo || b > hi))
    cli_die(2, "--nodes '%s': NY = %ld out of range; allowed %ld to %ld", arg, b, lo, hi);
  *nx = (int)a;
  *ny = beam ? (int)b : (int)a;
  cli_on_die_pop();
  mfs_free(copy);
}

static void static_free_cb(void *m)
{
  mfs_static_free(m);
}

/* Done with a model of run_model: its clean-up for cli_die removed, freed. */
static void model_done(mfs_static *m)
{
  cli_on_die_pop();
  mfs_static_free(m);
}

/* One model, assembled and solved; dies with the right message and code.
 * The model is freed by cli_die until model_done (a die leaves nothing
 * behind, for the sanitizer's leak check of tests/test_alloc.sh). */
static mfs_static *run_model(const mfs_static_spec *s, const static_opts *o, int solve)
{
  mfs_status st;
  const char *field = NULL;
  mfs_static *m = mfs_static_alloc(s, &st, &field);
  if (!m) {
    if (st == MFS_EINVAL)
      cli_die(2, "invalid model (%s): check the options of the problem %s", field ? field : "?",
              s->problem->name);
    cli_die(1, "building the model: %s", mfs_strerror(st));
  }
  cli_on_die(static_free_cb, m);
  mfs_static_where w = {{0, 0}, 0, 0};
  st = mfs_static_assemble(m, &w);
  mfs_static_info in;
  mfs_static_get_info(m, &in);
  if (st == MFS_ESINGULAR)
    cli_die(2,
            "--dilation %g: too few nodes in the support for method %s (kernel %s, a = %g m): "
            "singular %s at (%g, %g) m with %d node%s; use a larger dilation or more nodes",
            s->dilation, s->method->name, s->kernel->name, in.support,
            s->method->jb_normal ? "JB normalization (eq. 52) or moment matrix" : "moment matrix",
            w.x[0], w.x[1], w.nn, w.nn == 1 ? "" : "s");
  if (st != MFS_OK)
    cli_die(1, "assembling method %s: %s", s->method->name, mfs_strerror(st));
  if (!solve)
    return m;
  st = mfs_static_solve(m);
  mfs_static_get_info(m, &in);
  if (st == MFS_EINVAL && o->solver)
    cli_die(2,
            "--solver %s: needs a symmetric positive definite system; method %s gives %s; "
            "use umfpack",
            o->solver->name, s->method->name,
            in.eliminated ? "a non-symmetric one" : "an indefinite one (Lagrange multipliers)");
  if (st == MFS_ESYSTEM && !(in.rcond > 0.0))
    cli_die(1, "the linear system of method %s (%zu nodes, %s) is singular: a zero or negative pivot",
            s->method->name, in.nodes, in.solver);
  if (st == MFS_ESYSTEM)
    cli_die(1,
            "the linear system of method %s (%zu nodes, %s) is singular: rcond estimate %g "
            "below --solve-rcond-min %g",
            s->method->name, in.nodes, in.solver, in.rcond,
            s->solve_rcond_min > 0.0 ? s->solve_rcond_min : 1e-15);
  if (st != MFS_OK)
    cli_die(1, "solving method %s: %s", s->method->name, mfs_strerror(st));
  return m;
}

static void put(FILE *f, double v, int last)
{
  cli_put_num(f, v, "a static result");
  fputc(last ? '\n' : ',', f);
}

static void config_header(FILE *f)
{
  fputs("problem,method,quadrature,ebc,kernel,dilation,young_pa,poisson,plane_strain,", f);
}

static void config_row(FILE *f, const mfs_static_spec *s)
{
  const mfs_quad_type *q = s->quadrature ? s->quadrature : s->method->quadrature;
  fprintf(f, "%s,%s,%s,%s,%s,", s->problem->name, s->method->name, q->name,
          s->ghost ? "ghost" : "lm", s->kernel->name);
  put(f, s->dilation, 0);
  put(f, s->young, 0);
  put(f, s->poisson, 0);
  fprintf(f, "%d,", s->plane_strain);
}

static void nodal_csv(FILE *f, const mfs_static_spec *base, const mfs_static_method **ms, size_t nm,
                      const static_opts *o)
{
  fputs("method,x_m,y_m,ux_m,uy_m,ux_exact_m,uy_exact_m\n", f);
  for (size_t k = 0; k < nm; k++) {
    mfs_static_spec s = *base;
    s.method = ms[k];
    mfs_static *m = run_model(&s, o, 1);
    size_t n = mfs_static_nnodes(m);
    double *uh = mfs_malloc(4 * n * sizeof *uh), *ue = uh + 2 * n; /* one block */
    if (!uh)
      cli_die(1, "out of memory");
    cli_on_die(mfs_free, uh);
    mfs_status st = mfs_static_nodal_solution(m, uh, ue);
    if (st != MFS_OK)
      cli_die(1, "the nodal solution of method %s: %s", s.method->name, mfs_strerror(st));
    for (size_t I = 0; I < n; I++) {
      double x[2];
      if (!mfs_static_node_in_domain(m, I))
        continue; /* a ghost column */
      mfs_static_node(m, I, x);
      fprintf(f, "%s,", s.method->name);
      put(f, x[0], 0);
      put(f, x[1], 0);
      put(f, uh[2 * I], 0);
      put(f, uh[2 * I + 1], 0);
      put(f, ue[2 * I], 0);
      put(f, ue[2 * I + 1], 1);
    }
    cli_on_die_pop();
    mfs_free(uh);
    model_done(m);
  }
}

typedef struct {
  int nx, ny;
  size_t nodes, unknowns, multipliers;
  double dx, support, rcond, backward;
  const char *solver;
  mfs_static_errors e;
} level_row;

static void study_csv(FILE *f, const mfs_static_spec *base, const mfs_static_method **ms,
                      size_t nm, const static_opts *o)
{
  int beam = base->problem->counts == 2;
  size_t L = (size_t)o->refine;
  config_header(f);
  fputs("level,nodes_x,nodes_y,nodes,dx_m,support_m,unknowns,multipliers,solver,rcond,"
        "backward_error,l2_error_norm,L2_error_norm,energy_error_norm,energy_nodal_error_norm,"
        "rate_l2,rate_L2,rate_energy,rate_energy_nodal,local_rate_L2,local_rate_energy\n",
        f);
  level_row *rows = mfs_malloc(L * sizeof *rows);
  double *h = mfs_malloc(5 * L * sizeof *h), *e[4]; /* h and the four errors: one block */
  if (!rows || !h) {
    mfs_free(rows);
    mfs_free(h);
    cli_die(1, "out of memory");
  }
  for (int k = 0; k < 4; k++)
    e[k] = h + (size_t)(k + 1) * L;
  cli_on_die(mfs_free, rows);
  cli_on_die(mfs_free, h);
  for (size_t k = 0; k < nm; k++) {
    mfs_static_spec s = *base;
    s.method = ms[k];
    for (size_t l = 0; l < L; l++) {
      long scale = 1L << l;
      s.nx = (int)((base->nx - 1) * scale + 1);
      s.ny = (int)((base->ny - 1) * scale + 1);
      mfs_static *m = run_model(&s, o, 1);
      mfs_static_info in;
      mfs_static_get_info(m, &in);
      level_row *r = rows + l;
      mfs_static_where w;
      mfs_status st = mfs_static_error_norms(m, &r->e, &w);
      if (st != MFS_OK)
        cli_die(1, "errors of method %s: %s", s.method->name, mfs_strerror(st));
      *r = (level_row){.nx = s.nx, .ny = s.ny, .nodes = in.nodes, .unknowns = in.unknowns,
                       .multipliers = in.multipliers, .dx = in.h, .support = in.support,
                       .rcond = in.rcond, .backward = in.backward, .solver = in.solver,
                       .e = r->e};
      h[l] = in.h;
      e[0][l] = r->e.l2;
      e[1][l] = r->e.L2;
      e[2][l] = r->e.energy;
      e[3][l] = r->e.energy_nodal;
      model_done(m);
    }
    double rate[4];
    for (int q = 0; q < 4; q++)
      rate[q] = mfs_static_rate(L, h, e[q]);
    for (size_t l = 0; l < L; l++) {
      const level_row *r = rows + l;
      config_row(f, &s);
      fprintf(f, "%zu,%d,", l + 1, r->nx);
      if (beam)
        fprintf(f, "%d", r->ny);
      fprintf(f, ",%zu,", r->nodes);
      put(f, r->dx, 0);
      put(f, r->support, 0);
      fprintf(f, "%zu,%zu,%s,", r->unknowns, r->multipliers, r->solver);
      put(f, r->rcond, 0);
      put(f, r->backward, 0);
      put(f, r->e.l2, 0);
      put(f, r->e.L2, 0);
      put(f, r->e.energy, 0);
      put(f, r->e.energy_nodal, 0);
      for (int q = 0; q < 4; q++)
        put(f, rate[q], 0);
      double lr = l ? mfs_static_rate(2, h + l - 1, e[1] + l - 1) : NAN;
      double le = l ? mfs_static_rate(2, h + l - 1, e[2] + l - 1) : NAN;
      put(f, lr, 0);
      put(f, le, 1);
    }
  }
  cli_on_die_pop();
  cli_on_die_pop();
  mfs_free(rows);
  mfs_free(h);
}

static void patch_csv(FILE *f, const mfs_static_spec *base, const mfs_static_method **ms,
                      size_t nm, const static_opts *o)
{
  config_header(f);
  fputs("nodes,dx_m,support_m,perturb,reproduction_norm,values_reproduction_norm,"
        "reproduces_1e-10,patch_error_norm,patch_L2_error_norm,patch_1e-10,"
        "int_residual_interior_norm,int_residual_all_norm,interior_nodes,test_lambda,"
        "test_lambda_dev,lambda_points\n",
        f);
  for (size_t k = 0; k < nm; k++) {
    mfs_static_spec s = *base;
    s.method = ms[k];
    s.patch = 1;
    mfs_static *m = run_model(&s, o, 1);
    mfs_static_consistency c;
    mfs_static_errors e;
    mfs_static_where w;
    mfs_status st = mfs_static_check_consistency(m, &c, &w);
    if (st == MFS_OK)
      st = mfs_static_error_norms(m, &e, &w);
    if (st != MFS_OK)
      cli_die(1, "patch test of method %s: %s", s.method->name, mfs_strerror(st));
    mfs_static_info in;
    mfs_static_get_info(m, &in);
    config_row(f, &s);
    fprintf(f, "%zu,", in.nodes);
    put(f, in.h, 0);
    put(f, in.support, 0);
    put(f, s.perturb, 0);
    put(f, c.reproduction, 0);
    put(f, c.values, 0);
    fprintf(f, "%d,", c.reproduction < 1e-10);
    put(f, e.max_nodal, 0);
    put(f, e.L2, 0);
    fprintf(f, "%d,", e.max_nodal < 1e-10);
    put(f, c.int_interior, 0);
    put(f, c.int_all, 0);
    fprintf(f, "%zu,", c.interior_nodes);
    put(f, c.test_lambda, 0);
    put(f, c.test_lambda_dev, 0);
    fprintf(f, "%zu\n", c.lambda_points);
    model_done(m);
  }
}

int cmd_static(int argc, char **argv)
{
  mfs_static_spec d = mfs_static_spec_default();
  static_opts o = {.problem = d.problem,
                   .methods = "efg",
                   .kernel = d.kernel,
                   .dilation = d.dilation,
                   .young = d.young,
                   .poisson = d.poisson,
                   .load = d.load,
                   .length = d.length,
                   .depth = d.depth,
                   .hole = d.hole_radius,
                   .plate = d.plate_size,
                   .seed = 1};
  unsigned char seen[NOPTS];
  cli_group g = {opts, &o, seen};
  cli_parse(argc, argv, usage, about, &g, 1);
  int beam = o.problem->counts == 2;
  if (o.patch && cli_seen(&g, "--refine"))
    cli_die(2, "--patch and --refine: give one of them");
  if (o.load == 0.0)
    cli_die(2, "--load 0: the relative errors need a nonzero load");
  if (!beam && (cli_seen(&g, "--length") || cli_seen(&g, "--depth") || cli_seen(&g, "--perturb")))
    cli_die(2, "--length, --depth and --perturb are beam options; --problem is %s",
            o.problem->name);
  if (!beam && o.ebc == 1)
    cli_die(2, "--ebc ghost: a beam option (columns of nodes at x < 0); --problem is %s",
            o.problem->name);
  if (beam && (cli_seen(&g, "--hole-radius") || cli_seen(&g, "--plate-size")))
    cli_die(2, "--hole-radius and --plate-size are plate-hole options; --problem is beam");
  if (!beam && !(o.plate > 2.0 * o.hole))
    cli_die(2, "--plate-size %g: must exceed twice --hole-radius (%g)", o.plate, o.hole);
  const mfs_quad_type *rule = o.quadrature ? mfs_quad_find(o.quadrature) : NULL;
  if (o.quadrature && (!rule || !(rule->gauss_n > 0 || (rule->node_share == 1.0 && !rule->centres))))
    cli_die(2, "--quadrature '%s': not available here; allowed: nodal, gauss1 .. gauss10",
            o.quadrature);
  const mfs_static_method *ms[MAXM];
  size_t nm = parse_methods(o.methods, ms);
  mfs_static_spec s = d;
  s.problem = o.problem;
  s.kernel = o.kernel;
  s.dilation = o.dilation;
  s.quadrature = rule;
  s.young = o.young;
  s.poisson = o.poisson;
  s.plane_strain = o.plane_strain;
  s.load = o.load;
  s.length = o.length;
  s.depth = o.depth;
  s.hole_radius = o.hole;
  s.plate_size = o.plate;
  s.perturb = o.perturb;
  s.seed = (unsigned long)o.seed;
  s.solver = o.solver;
  s.solve_rcond_min = o.solve_rcond_min;
  s.ghost = o.ebc == 1 ? 6 : 0;
  s.nx = beam ? 17 : 6;
  s.ny = beam ? 3 : 6;
  if (o.nodes)
    parse_nodes(o.nodes, beam, &s.nx, &s.ny);
  if (o.refine > 1) { /* the finest level must stay buildable */
    double fine = (double)(s.nx - 1) * (double)(1L << (o.refine - 1)) + 1.0;
    double finey = beam ? (double)(s.ny - 1) * (double)(1L << (o.refine - 1)) + 1.0 : fine;
    if (fine * finey > 2e7)
      cli_die(2, "--refine %ld: the finest level would have %.3g nodes (more than 2e7); fewer levels",
              o.refine, fine * finey);
  }
  check_work(&s, ms, nm, &o, o.nodes);
  cli_out out;
  cli_out_open(&out, o.out);
  if (o.patch)
    patch_csv(out.f, &s, ms, nm, &o);
  else if (o.refine)
    study_csv(out.f, &s, ms, nm, &o);
  else
    nodal_csv(out.f, &s, ms, nm, &o);
  cli_out_commit(&out);
  return 0;
}
