/* Quadrature sets, Voronoi volumes and neighbour search.
 *   - every rule on uniform and 30%-perturbed, finite and periodic particle
 *     sets: positive weights summing to the domain volume (and to the exact
 *     area of the domain), the prescribed shares on uniform lattices, and the
 *     polynomial degree of the Gauss rules against exact integrals (Green's
 *     theorem on the cell edges, an independent path);
 *   - rule names and rule/lattice compatibility;
 *   - Voronoi areas;
 *   - mfs_nlist_build equals a brute-force search, mfs_nlist_transpose is the
 *     transpose. */
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static const double DX = 0.7313;

typedef struct {
  const char *name;
  int dim;
  mfs_lattice_kind lat;
  mfs_cell_kind cells;
  int nx, ny;
  double gamma;
  const char *rules[8];
} config;

static const config configs[] = {
  {"line", 1, MFS_LATTICE_LINE, MFS_CELLS_QUAD, 23, 0, 1.0,
   {"nodal", "stress", "gauss1", "gauss2", "gauss3", NULL}},
  {"square-quad", 2, MFS_LATTICE_SQUARE, MFS_CELLS_QUAD, 10, 8, 1.2731,
   {"nodal", "stress-quad", "gauss1", "gauss2", "gauss3", NULL}},
  {"square-tri", 2, MFS_LATTICE_SQUARE, MFS_CELLS_TRI, 9, 10, 1.0,
   {"nodal", "stress-tri", "gauss1", "gauss2", "gauss3", NULL}},
  {"square-star", 2, MFS_LATTICE_SQUARE, MFS_CELLS_STAR, 10, 8, 0.8839,
   {"nodal", "stress-star", "gauss1", "gauss2", "gauss3", NULL}},
  {"hex", 2, MFS_LATTICE_HEX, MFS_CELLS_TRI, 9, 8, 1.0,
   {"nodal", "stress-hex", "gauss1", "gauss2", "gauss3", NULL}},
};

/* The point-generation kinds of a rule (mfs_quad.h). */
#define IS_GAUSS(t) ((t)->gauss_n > 0)
#define IS_NODAL(t) ((t)->node_share == 1.0 && !(t)->centres && !IS_GAUSS(t))

static mfs_particles *make(const config *c, int periodic, double perturb, unsigned long seed)
{
  mfs_lattice_spec s = {c->dim, c->lat, c->nx, c->ny, DX, c->gamma, periodic, c->cells, perturb,
                        seed};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&s, &st);
  CHECK(p && st == MFS_OK, "%s: mfs_lattice_alloc status %d", c->name, st);
  return p;
}

/* The exact area (length) of the domain, from the lattice alone: the box of
 * a periodic set; the hull of the nodes of a finite one (boundary particles
 * are perturbed only along the boundary, corners and hexagonal boundaries not
 * at all, so perturbation keeps it). */
static double exact_volume(const config *c, int periodic)
{
  double dy = c->lat == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 * DX : c->gamma * DX;
  if (c->dim == 1)
    return (periodic ? c->nx : c->nx - 1) * DX;
  if (periodic)
    return c->nx * DX * c->ny * dy;
  return (c->nx - 1) * DX * (c->ny - 1) * dy; /* hex: parallelogram strips of height dy */
}

/* Exact integral of f = ((x - x0)/s)^a ((y - y0)/s)^b over cell c by Green's
 * theorem, int x^a y^b dA = closed int x^(a+1) y^b / (a+1) dy, each edge by
 * a 16-point Gauss-Legendre rule (exact to degree 31); in 1D directly. */
static double cell_integral(const mfs_particles *p, size_t c, int a, int b, const double *x0,
                            double s, const gsl_integration_glfixed_table *t)
{
  const double *v = p->cellx + c * p->nvert * p->dim;
  if (p->dim == 1) {
    double u0 = (v[0] - x0[0]) / s, u1 = (v[1] - x0[0]) / s;
    return s * (pow(u1, a + 1) - pow(u0, a + 1)) / (a + 1);
  }
  double sum = 0.0;
  for (int k = 0; k < p->nvert; k++) {
    const double *P = v + 2 * k, *Q = v + 2 * ((k + 1) % p->nvert);
    double px = (P[0] - x0[0]) / s, py = (P[1] - x0[1]) / s;
    double qx = (Q[0] - x0[0]) / s, qy = (Q[1] - x0[1]) / s;
    for (size_t i = 0; i < t->n; i++) {
      double tt, w;
      gsl_integration_glfixed_point(0.0, 1.0, i, &tt, &w, t);
      double x = px + tt * (qx - px), y = py + tt * (qy - py);
      sum += w * pow(x, a + 1) * pow(y, b) / (a + 1) * (qy - py);
    }
  }
  return sum * s * s;
}

/* Degree up to which gaussN is exact on these cells:
 *   intervals, and parallelograms (affine map, constant Jacobian): 2N - 1;
 *   bilinear quadrilaterals (perturbed): the Jacobian is linear in each
 *   reference variable, so a monomial of degree m becomes degree m + 1 per
 *   variable: 2N - 2;
 *   triangles, collapsed N x N Gauss-Legendre rule: the collapse adds the
 *   factor u of the Jacobian, again m + 1 in u: 2N - 2 (2N - 1 would need
 *   Gauss-Jacobi points in u); N = 1 is the centroid rule: degree 1. */
static int gauss_degree(const mfs_particles *p, int N, int perturbed)
{
  if (p->dim == 1)
    return 2 * N - 1;
  if (p->nvert == 4)
    return perturbed ? 2 * N - 2 : 2 * N - 1;
  return N == 1 ? 1 : 2 * N - 2;
}

static void check_gauss_exactness(const char *ctx, const mfs_particles *p, const mfs_quad *q,
                                  int N, int perturbed)
{
  gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(16);
  int deg = gauss_degree(p, N, perturbed);
  double x0[2], s = 0.0;
  for (int k = 0; k < p->dim; k++) {
    x0[k] = 0.5 * (p->box.lo[k] + p->box.hi[k]);
    s = fmax(s, 0.5 * (p->box.hi[k] - p->box.lo[k]));
  }
  double V = mfs_particles_domain_volume(p);
  for (int a = 0; a <= deg; a++)
    for (int b = 0; b <= (p->dim == 1 ? 0 : deg - a); b++) {
      double exact = 0.0, got = 0.0;
      for (size_t c = 0; c < p->ncell; c++)
        exact += cell_integral(p, c, a, b, x0, s, t);
      for (size_t i = 0; i < q->n; i++) {
        const double *x = q->x + i * p->dim;
        double f = pow((x[0] - x0[0]) / s, a);
        if (p->dim == 2)
          f *= pow((x[1] - x0[1]) / s, b);
        got += q->w[i] * f;
      }
      /* |f| <= ~1 on the domain: relative to its volume */
      CHECK_NEAR(got, exact, 1e-12 * V, "%s gauss%d: integral of x^%d y^%d (degree %d <= %d)", ctx,
                 N, a, b, a + b, deg);
    }
  gsl_integration_glfixed_table_free(t);
}

static void check_rule(const config *c, const char *rname, int periodic, double perturb)
{
  char ctx[160];
  snprintf(ctx, sizeof ctx, "%s %s %s perturb %.1f", c->name, rname,
           periodic ? "periodic" : "finite", perturb);
  const mfs_quad_type *rule = mfs_quad_find(rname);
  mfs_status st;
  CHECK(rule != NULL, "%s: no rule of that name", ctx);
  if (!rule)
    return;
  CHECK(mfs_quad_applies(rule, c->dim, c->lat), "%s: rule check", ctx);
  mfs_particles *p = make(c, periodic, perturb, 1000003 + (unsigned long)c->nx * 7 + periodic);
  if (!p)
    return;
  mfs_quad *q = mfs_quad_alloc(rule, p, &st);
  CHECK(q && st == MFS_OK, "%s: mfs_quad_alloc status %d", ctx, st);
  if (!q) {
    mfs_particles_free(p);
    return;
  }
  double V = mfs_particles_domain_volume(p), Vx = exact_volume(c, periodic);
  double sum = 0.0, wmin = INFINITY;
  for (size_t i = 0; i < q->n; i++) {
    sum += q->w[i];
    wmin = fmin(wmin, q->w[i]);
  }
  CHECK_NEAR(V, Vx, 1e-12 * Vx, "%s: domain volume vs the exact area", ctx);
  CHECK_NEAR(sum, V, 1e-12 * V, "%s: sum of weights vs domain volume", ctx);
  CHECK_NEAR(sum, Vx, 1e-12 * Vx, "%s: sum of weights vs exact area", ctx);
  CHECK(wmin > 0.0, "%s: smallest weight %.3g not positive", ctx, wmin);
  for (size_t c2 = 0; c2 < p->ncell; c2++)
    if (!(mfs_cell_measure(p, c2) > 0.0)) {
      CHECK(0, "%s: cell %zu measure %.3g not positive (orientation)", ctx, c2,
            mfs_cell_measure(p, c2));
      break;
    }

  /* number of points and the particle points */
  size_t want_n = IS_NODAL(rule) ? p->n
                  : IS_GAUSS(rule)
                    ? p->ncell * (size_t)(c->dim == 1 ? rule->gauss_n : rule->gauss_n * rule->gauss_n)
                    : p->n + p->ncell;
  CHECK(q->n == want_n, "%s: %zu points, want %zu", ctx, q->n, want_n);
  size_t nnode = 0;
  for (size_t i = 0; i < q->n; i++) {
    int I = q->node[i];
    if (I < 0)
      continue;
    nnode++;
    int same = 1;
    for (int k = 0; k < c->dim; k++)
      same &= q->x[i * c->dim + k] == p->x[(size_t)I * c->dim + k];
    CHECK(same, "%s: point %zu of node %d not at the particle", ctx, i, I);
  }
  CHECK(nnode == (IS_GAUSS(rule) ? 0 : p->n), "%s: %zu node points", ctx, nnode);

  /* prescribed shares on a uniform lattice: a node of volume dx dy (interior
   * or periodic) and a cell pair of area dx dy */
  /* (not the star pattern: its cell-dual node volumes alternate between 4/3
   * and 2/3 dx dy, as the nodes touch 8 or 4 triangles) */
  if (perturb == 0.0 && !IS_GAUSS(rule) && !rule->voronoi &&
      !(c->cells == MFS_CELLS_STAR && c->dim == 2)) {
    double cell = c->dim == 1 ? DX : DX * p->dy; /* the area of one lattice cell */
    double share = IS_NODAL(rule) ? 1.0 : rule->node_share == 0.5 ? 0.5 : 1.0 / 3.0;
    double emax = 0.0;
    for (size_t i = 0; i < q->n; i++) {
      int I = q->node[i];
      if (I >= 0 && p->flags[I])
        continue; /* boundary nodes carry their part of the boundary cells */
      emax = fmax(emax, fabs(q->w[i] - share * cell));
    }
    CHECK(emax <= 1e-14 * cell, "%s: weights differ from %.4g of the cell area by %.3g", ctx,
          share, emax);
  }
  if (perturb == 0.0 && rule->voronoi && periodic) {
    /* the star pattern on a uniform lattice: by symmetry all centroids have
     * the same Voronoi area, and the nodes two (star centres, i + j even,
     * where 8 triangles meet; and the others, where 4 meet) */
    double w[2] = {q->w[0], q->w[1]}, wc = q->w[p->n], emax = 0.0;
    for (size_t i = 0; i < q->n; i++) {
      int I = q->node[i];
      emax = fmax(emax, fabs(q->w[i] - (I >= 0 ? w[(p->ij[2 * I] + p->ij[2 * I + 1]) & 1] : wc)));
    }
    CHECK(emax <= 1e-12 * wc, "%s: Voronoi weights not equal by symmetry (%.3g)", ctx, emax);
    CHECK(w[0] != w[1], "%s: both node classes have the same Voronoi area", ctx);
  }
  if (IS_GAUSS(rule)) {
    /* weights of each cell's points add to its measure (points come per cell) */
    size_t per = q->n / p->ncell;
    double emax = 0.0;
    for (size_t c2 = 0; c2 < p->ncell; c2++) {
      double s = 0.0;
      for (size_t i = 0; i < per; i++)
        s += q->w[c2 * per + i];
      emax = fmax(emax, fabs(s - mfs_cell_measure(p, c2)));
    }
    CHECK(emax <= 1e-14 * V / p->ncell * 10, "%s: cell weight sums off by %.3g", ctx, emax);
    check_gauss_exactness(ctx, p, q, rule->gauss_n, perturb > 0.0);
  }
  mfs_quad_free(q);
  mfs_particles_free(p);
}

static void check_rule_names(void)
{
  const char *good[] = {"nodal", "stress", "stress-quad", "stress-tri", "stress-star",
                        "stress-hex", "gauss1", "gauss2", "gauss3", "gauss10"};
  const mfs_quad_type *r;
  for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
    CHECK(mfs_quad_find(good[i]) != NULL, "parse \"%s\"", good[i]);
  r = mfs_quad_find("gauss3");
  CHECK(r && IS_GAUSS(r) && r->gauss_n == 3, "gauss3 is 3 points per direction");
  r = mfs_quad_find("gauss10");
  CHECK(r && r->gauss_n == 10, "gauss10");
  for (int i = 0; mfs_quad_types[i]; i++)
    CHECK(mfs_quad_find(mfs_quad_types[i]->name) == mfs_quad_types[i], "find %s",
          mfs_quad_types[i]->name);
  const char *bad[] = {"gauss0", "gaussx", "foo", "gauss", "gauss11", "gauss01", "gauss2x",
                       "gauss-1", "gauss 2", "Nodal", "stress-", ""};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
    CHECK(mfs_quad_find(bad[i]) == NULL, "parse \"%s\" not rejected", bad[i]);

  struct {
    const char *name;
    int dim;
    mfs_lattice_kind lat;
    int ok;
  } cases[] = {
    {"stress-quad", 1, MFS_LATTICE_LINE, 0},   {"stress-hex", 2, MFS_LATTICE_SQUARE, 0},
    {"stress", 2, MFS_LATTICE_SQUARE, 0},      {"stress", 2, MFS_LATTICE_HEX, 0},
    {"stress-tri", 2, MFS_LATTICE_HEX, 0},     {"stress-star", 2, MFS_LATTICE_HEX, 0},
    {"stress-quad", 2, MFS_LATTICE_HEX, 0},    {"stress-hex", 1, MFS_LATTICE_LINE, 0},
    {"stress", 1, MFS_LATTICE_LINE, 1},        {"stress-quad", 2, MFS_LATTICE_SQUARE, 1},
    {"stress-tri", 2, MFS_LATTICE_SQUARE, 1},  {"stress-star", 2, MFS_LATTICE_SQUARE, 1},
    {"stress-hex", 2, MFS_LATTICE_HEX, 1},     {"nodal", 1, MFS_LATTICE_LINE, 1},
    {"nodal", 2, MFS_LATTICE_HEX, 1},          {"gauss2", 1, MFS_LATTICE_LINE, 1},
    {"gauss2", 2, MFS_LATTICE_HEX, 1},         {"gauss3", 2, MFS_LATTICE_SQUARE, 1},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    int ok = mfs_quad_applies(mfs_quad_find(cases[i].name), cases[i].dim, cases[i].lat);
    CHECK(ok == cases[i].ok, "rule check %s dim %d lattice %d: %d", cases[i].name, cases[i].dim,
          (int)cases[i].lat, ok);
  }
}

static void check_voronoi(void)
{
  /* uniform periodic lattices: every cell is dx dy (square) or sqrt(3)/2 dx^2 (hex) */
  for (int hex = 0; hex <= 1; hex++) {
    mfs_lattice_spec s = {2, hex ? MFS_LATTICE_HEX : MFS_LATTICE_SQUARE, 12, 10, DX, 1.3717, 1,
                          MFS_CELLS_QUAD, 0.0, 0};
    mfs_status st;
    mfs_particles *p = mfs_lattice_alloc(&s, &st);
    double *A = malloc(p->n * sizeof *A);
    st = mfs_voronoi_areas(p->n, p->x, &p->box, A);
    CHECK(st == MFS_OK, "voronoi status %d", st);
    double want = hex ? sqrt(3.0) / 2.0 * DX * DX : DX * 1.3717 * DX, emax = 0.0;
    for (size_t i = 0; i < p->n; i++)
      emax = fmax(emax, fabs(A[i] - want));
    CHECK(emax <= 1e-12 * want, "voronoi %s uniform periodic: areas differ from %.6g by %.3g",
          hex ? "hex" : "square", want, emax);
    free(A);
    mfs_particles_free(p);
  }
  /* perturbed sets: the areas tile the box */
  for (int periodic = 0; periodic <= 1; periodic++)
    for (int hex = 0; hex <= 1; hex++) {
      mfs_lattice_spec s = {2, hex ? MFS_LATTICE_HEX : MFS_LATTICE_SQUARE, 11, 10, DX, 1.0,
                            periodic, MFS_CELLS_QUAD, 0.3, 77 + periodic + 2 * hex};
      mfs_status st;
      mfs_particles *p = mfs_lattice_alloc(&s, &st);
      double *A = malloc(p->n * sizeof *A);
      st = mfs_voronoi_areas(p->n, p->x, &p->box, A);
      CHECK(st == MFS_OK, "voronoi status %d", st);
      double sum = 0.0, amin = INFINITY;
      for (size_t i = 0; i < p->n; i++) {
        sum += A[i];
        amin = fmin(amin, A[i]);
      }
      double box = (p->box.hi[0] - p->box.lo[0]) * (p->box.hi[1] - p->box.lo[1]);
      CHECK_NEAR(sum, box, 1e-12 * box, "voronoi %s %s perturbed: sum of areas vs box area",
                 hex ? "hex" : "square", periodic ? "periodic" : "finite");
      CHECK(amin > 0.0, "voronoi: smallest area %.3g", amin);
      free(A);
      mfs_particles_free(p);
    }
}

/* Brute force: indices within distance < r of y, over the images of a periodic box. */
static size_t brute(int dim, size_t n, const double *x, const mfs_box *box, const double *y,
                    double r, int *out)
{
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    double best = INFINITY;
    int sh = box->periodic ? 2 : 0;
    for (int s0 = -sh; s0 <= sh; s0++)
      for (int s1 = (dim > 1 ? -sh : 0); s1 <= (dim > 1 ? sh : 0); s1++) {
        double d2 = 0.0;
        int s[2] = {s0, s1};
        for (int k = 0; k < dim; k++) {
          double t = x[i * dim + k] + s[k] * (box->hi[k] - box->lo[k]) - y[k];
          d2 += t * t;
        }
        best = fmin(best, d2);
      }
    if (best < r * r)
      out[m++] = (int)i;
  }
  return m;
}

static void check_search_case(const char *ctx, int dim, size_t n, const double *x,
                              const mfs_box *box, double R, double r, gsl_rng *rng)
{
  size_t nq = 150;
  double *y = malloc(nq * dim * sizeof *y);
  /* queries in the box enlarged by 1.5 R on each side: outside the cloud too */
  for (size_t q = 0; q < nq; q++)
    for (int k = 0; k < dim; k++) {
      double L = box->hi[k] - box->lo[k];
      y[q * dim + k] = box->lo[k] - 1.5 * R + gsl_rng_uniform(rng) * (L + 3.0 * R);
    }
  /* and the points themselves */
  for (size_t q = 0; q < 20 && q < n; q++)
    memcpy(y + q * dim, x + q * 3 * dim, dim * sizeof *y);
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(dim, n, x, box, R, &st);
  CHECK(g && st == MFS_OK, "%s: grid status %d", ctx, st);
  mfs_nlist *nl = g ? mfs_nlist_build(g, nq, y, r, &st) : NULL;
  CHECK(nl && st == MFS_OK, "%s: nlist status %d", ctx, st);
  if (nl) {
    int *want = malloc(n * sizeof *want);
    size_t bad = 0, total = 0;
    for (size_t q = 0; q < nq; q++) {
      size_t m = brute(dim, n, x, box, y + q * dim, r, want);
      size_t len = nl->ptr[q + 1] - nl->ptr[q];
      total += m;
      if (len != m || memcmp(nl->idx + nl->ptr[q], want, m * sizeof *want) != 0)
        bad++;
    }
    CHECK(bad == 0, "%s: %zu of %zu neighbour lists differ from brute force", ctx, bad, nq);
    CHECK(total > nq, "%s: only %zu neighbours in all (test too weak)", ctx, total);
    /* the transpose */
    mfs_nlist *t = mfs_nlist_transpose(nl, n, &st);
    CHECK(t && st == MFS_OK && t->nq == n && t->ptr[n] == nl->ptr[nq],
          "%s: transpose status %d", ctx, st);
    if (t) {
      size_t mism = 0;
      for (size_t i = 0; i < n; i++)
        for (size_t e = t->ptr[i]; e < t->ptr[i + 1]; e++) {
          size_t q = (size_t)t->idx[e];
          int found = 0;
          for (size_t f = nl->ptr[q]; f < nl->ptr[q + 1]; f++)
            found |= nl->idx[f] == (int)i;
          mism += !found || (e > t->ptr[i] && t->idx[e - 1] >= t->idx[e]);
        }
      CHECK(mism == 0, "%s: %zu transpose entries not in the list (or unsorted)", ctx, mism);
    }
    mfs_nlist_free(t);
    free(want);
  }
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  free(y);
}

static void check_search(gsl_rng *rng)
{
  for (int dim = 1; dim <= 2; dim++)
    for (int periodic = 0; periodic <= 1; periodic++) {
      /* perturbed lattices (periodic ones have points just outside the box) */
      mfs_lattice_spec s = {dim, dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_HEX, dim == 1 ? 97 : 17,
                            16, DX, 1.0, periodic, MFS_CELLS_TRI, 0.3, 5 + periodic};
      mfs_status st;
      mfs_particles *p = mfs_lattice_alloc(&s, &st);
      CHECK(p != NULL, "search: lattice status %d", st);
      if (!p)
        continue;
      double R = 2.385 * DX;
      char ctx[100];
      snprintf(ctx, sizeof ctx, "search %dD %s lattice", dim, periodic ? "periodic" : "finite");
      check_search_case(ctx, dim, p->n, p->x, &p->box, R, R, rng);
      snprintf(ctx, sizeof ctx, "search %dD %s lattice r < R", dim,
               periodic ? "periodic" : "finite");
      check_search_case(ctx, dim, p->n, p->x, &p->box, R, 0.6137 * R, rng);
      mfs_particles_free(p);

      /* random points, and a box only a little wider than 2 R (2 cells) */
      mfs_box box = {dim, {-0.3, 1.1, 0}, {0.0, 0.0, 0}, periodic};
      box.hi[0] = box.lo[0] + 1.7313;
      box.hi[1] = box.lo[1] + 0.9317;
      size_t n = dim == 1 ? 60 : 300;
      double *x = malloc(n * dim * sizeof *x);
      for (size_t i = 0; i < n; i++)
        for (int k = 0; k < dim; k++)
          x[i * dim + k] = box.lo[k] + gsl_rng_uniform(rng) * (box.hi[k] - box.lo[k]);
      snprintf(ctx, sizeof ctx, "search %dD %s random", dim, periodic ? "periodic" : "finite");
      check_search_case(ctx, dim, n, x, &box, 0.2119, 0.2119, rng);
      snprintf(ctx, sizeof ctx, "search %dD %s random, 2 cells", dim,
               periodic ? "periodic" : "finite");
      check_search_case(ctx, dim, n, x, &box, 0.41, 0.3877, rng);
      if (!periodic) { /* a radius larger than the box */
        snprintf(ctx, sizeof ctx, "search %dD finite random, r > box", dim);
        check_search_case(ctx, dim, n, x, &box, 2.5, 2.5, rng);
      }
      free(x);
    }
}

int main(void)
{
  check_rule_names();
  for (size_t c = 0; c < sizeof configs / sizeof configs[0]; c++)
    for (int periodic = 0; periodic <= 1; periodic++)
      for (int pert = 0; pert <= 1; pert++)
        for (int r = 0; configs[c].rules[r]; r++)
          check_rule(&configs[c], configs[c].rules[r], periodic, pert ? 0.3 : 0.0);
  check_voronoi();
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 8675309);
  check_search(rng);
  gsl_rng_free(rng);
  return check_summary("test_quad");
}
