#include "mfs_quad.h"
#include "mfs_alloc.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"
#include "mfs_voronoi.h"

#define D1 (1u << 1)
#define D2 (1u << 2)
#define LINE (1u << MFS_LATTICE_LINE)
#define SQUARE (1u << MFS_LATTICE_SQUARE)
#define HEX (1u << MFS_LATTICE_HEX)
#define POINTS (1u << MFS_LATTICE_POINTS)

const mfs_quad_type mfs_quad_nodal = {
  .name = "nodal", .dims = D1 | D2, .lattices = LINE | SQUARE | HEX | POINTS, .cells = MFS_CELLS_QUAD,
  .node_share = 1.0};
const mfs_quad_type mfs_quad_stress = {
  .name = "stress", .dims = D1, .lattices = LINE | POINTS, .cells = MFS_CELLS_QUAD, .node_share = 0.5,
  .centres = 1};
const mfs_quad_type mfs_quad_stress_quad = {
  .name = "stress-quad", .dims = D2, .lattices = SQUARE, .cells = MFS_CELLS_QUAD,
  .node_share = 0.5, .centres = 1};
const mfs_quad_type mfs_quad_stress_tri = {
  .name = "stress-tri", .dims = D2, .lattices = SQUARE | POINTS, .cells = MFS_CELLS_TRI,
  .node_share = 1.0 / 3.0, .centres = 1};
const mfs_quad_type mfs_quad_stress_star = {
  .name = "stress-star", .dims = D2, .lattices = SQUARE, .cells = MFS_CELLS_STAR,
  .node_share = 1.0, .centres = 1, .voronoi = 1};
const mfs_quad_type mfs_quad_stress_hex = {
  .name = "stress-hex", .dims = D2, .lattices = HEX, .cells = MFS_CELLS_TRI,
  .node_share = 1.0 / 3.0, .centres = 1};

#define GAUSS(n)                                                                             \
  {.name = "gauss" #n, .dims = D1 | D2, .lattices = LINE | SQUARE | HEX | POINTS,           \
   .cells = MFS_CELLS_QUAD, .gauss_n = n}
const mfs_quad_type mfs_quad_gauss[10] = {GAUSS(1), GAUSS(2), GAUSS(3), GAUSS(4), GAUSS(5),
                                          GAUSS(6), GAUSS(7), GAUSS(8), GAUSS(9), GAUSS(10)};
#undef GAUSS

const mfs_quad_type *const mfs_quad_types[] = {
  &mfs_quad_nodal,     &mfs_quad_stress,    &mfs_quad_stress_quad, &mfs_quad_stress_tri,
  &mfs_quad_stress_star, &mfs_quad_stress_hex, &mfs_quad_gauss[0],   &mfs_quad_gauss[1],
  &mfs_quad_gauss[2],  &mfs_quad_gauss[3],  &mfs_quad_gauss[4],    &mfs_quad_gauss[5],
  &mfs_quad_gauss[6],  &mfs_quad_gauss[7],  &mfs_quad_gauss[8],    &mfs_quad_gauss[9],
  NULL};

const mfs_quad_type *mfs_quad_find(const char *name)
{
  for (int i = 0; name && mfs_quad_types[i]; i++)
    if (strcmp(name, mfs_quad_types[i]->name) == 0)
      return mfs_quad_types[i];
  return NULL;
}

int mfs_quad_applies(const mfs_quad_type *t, int dim, mfs_lattice_kind lattice)
{
  if (!t || dim < 1 || dim > 3 || (unsigned)lattice > MFS_LATTICE_POINTS)
    return 0;
  return (t->dims >> dim & 1u) && (t->lattices >> lattice & 1u);
}

void mfs_quad_free(mfs_quad *q)
{
  if (!q)
    return;
  mfs_free(q->x);
  mfs_free(q->w);
  mfs_free(q->node);
  mfs_free(q);
}

mfs_quad *mfs_quad_empty(int dim, size_t cap)
{
  mfs_quad *q = mfs_calloc(1, sizeof *q);
  if (!q)
    return NULL;
  cap = cap ? cap : 1;
  q->dim = dim;
  q->x = mfs_malloc(cap * (size_t)dim * sizeof *q->x);
  q->w = mfs_malloc(cap * sizeof *q->w);
  q->node = mfs_malloc(cap * sizeof *q->node);
  if (!q->x || !q->w || !q->node) {
    mfs_quad_free(q);
    return NULL;
  }
  return q;
}

/* Appends one point. */
static void put(mfs_quad *q, const double *x, double w, int node)
{
  for (int k = 0; k < q->dim; k++) /* dim <= 3: inline, not a call of memcpy per point */
    q->x[q->n * q->dim + k] = x[k];
  q->w[q->n] = w;
  q->node[q->n] = node;
  q->n++;
}

static void centroid(const mfs_particles *p, size_t c, double *x)
{
  const double *v = p->cellx + c * p->nvert * p->dim;
  for (int k = 0; k < p->dim; k++) {
    x[k] = 0.0;
    for (int i = 0; i < p->nvert; i++)
      x[k] += v[i * p->dim + k] / p->nvert;
  }
}

/* Gauss-Legendre points and weights on [0, 1]. */
static int gauss01(int n, double *t, double *w)
{
  gsl_error_handler_t *handler = gsl_set_error_handler_off(); /* GSL's aborts */
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)n);
  gsl_set_error_handler(handler);
  if (!tab)
    return MFS_ENOMEM;
  for (int i = 0; i < n; i++) {
    double xi, wi;
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)i, &xi, &wi, tab);
    t[i] = xi;
    w[i] = wi;
  }
  gsl_integration_glfixed_table_free(tab);
  return MFS_OK;
}

static void gauss_cell(mfs_quad *q, const mfs_particles *p, size_t c, int n, const double *t,
                       const double *tw)
{
  const double *v = p->cellx + c * p->nvert * p->dim;
  double x[2];
  if (p->dim == 1) {
    for (int i = 0; i < n; i++) {
      x[0] = v[0] + t[i] * (v[1] - v[0]);
      put(q, x, tw[i] * (v[1] - v[0]), -1);
    }
  } else if (p->nvert == 4) { /* bilinear map of the unit square */
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double u = t[i], s = t[j];
        double N[4] = {(1 - u) * (1 - s), u * (1 - s), u * s, (1 - u) * s};
        double dNu[4] = {-(1 - s), 1 - s, s, -s}, dNs[4] = {-(1 - u), -u, u, 1 - u};
        double J[4] = {0, 0, 0, 0};
        x[0] = x[1] = 0.0;
        for (int k = 0; k < 4; k++) {
          x[0] += N[k] * v[2 * k];
          x[1] += N[k] * v[2 * k + 1];
          J[0] += dNu[k] * v[2 * k];
          J[1] += dNs[k] * v[2 * k];
          J[2] += dNu[k] * v[2 * k + 1];
          J[3] += dNs[k] * v[2 * k + 1];
        }
        put(q, x, tw[i] * tw[j] * (J[0] * J[3] - J[1] * J[2]), -1);
      }
  } else if (n == 1) {
    centroid(p, c, x);
    put(q, x, mfs_cell_measure(p, c), -1);
  } else { /* collapsed tensor rule: (u, s) -> v0 + u (v1 - v0) + u s (v2 - v1) */
    double A2 = 2.0 * mfs_cell_measure(p, c);
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double u = t[i], s = t[j];
        for (int k = 0; k < 2; k++)
          x[k] = v[k] + u * (v[2 + k] - v[k]) + u * s * (v[4 + k] - v[2 + k]);
        put(q, x, tw[i] * tw[j] * u * A2, -1);
      }
  }
}

mfs_quad *mfs_quad_alloc(const mfs_quad_type *t, const mfs_particles *p, mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_quad *q = NULL;
  if (!mfs_quad_applies(t, p->dim, p->lattice))
    goto fail;
  /* the particles' cells must be the ones the rule is defined on */
  int cells_ok = p->dim == 1 || p->lattice == MFS_LATTICE_HEX || p->cells == t->cells;
  if (t->centres && !cells_ok)
    goto fail;
  if ((t->centres || t->gauss_n > 0) && p->ncell == 0) /* a set built without cells */
    goto fail;
  st = MFS_ENOMEM;
  int g = t->gauss_n;
  size_t per = g > 0 ? (size_t)g * (p->dim == 1 ? 1 : (size_t)g) : 1;
  q = mfs_quad_empty(p->dim, p->n + p->ncell * per);
  if (!q)
    goto fail;

  if (t->node_share > 0.0)
    for (size_t I = 0; I < p->n; I++)
      put(q, p->x + I * p->dim, t->node_share * p->vol[I], (int)I);
  if (t->centres) {
    double cshare = 1.0 - t->node_share;
    for (size_t c = 0; c < p->ncell; c++) {
      double x[3];
      centroid(p, c, x);
      put(q, x, cshare * mfs_cell_measure(p, c), -1);
    }
  }
  if (t->voronoi) {
    if (p->box.periodic) /* wrap centroids into the box */
      for (size_t i = p->n; i < q->n; i++)
        for (int k = 0; k < 2; k++) {
          double L = p->box.hi[k] - p->box.lo[k], *xk = q->x + 2 * i + k;
          while (*xk >= p->box.hi[k])
            *xk -= L;
          while (*xk < p->box.lo[k])
            *xk += L;
        }
    st = mfs_voronoi_areas(q->n, q->x, &p->box, q->w);
    if (st != MFS_OK)
      goto fail;
  }
  if (g > 0) {
    double tt[10], tw[10];
    if (g > 10 || gauss01(g, tt, tw) != MFS_OK)
      goto fail;
    for (size_t c = 0; c < p->ncell; c++)
      gauss_cell(q, p, c, g, tt, tw);
  }
  if (status)
    *status = MFS_OK;
  return q;
fail:
  mfs_quad_free(q);
  if (status)
    *status = st;
  return NULL;
}
