#include "mfs_quad.h"

#include <gsl/gsl_integration.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"
#include "mfs_voronoi.h"

static const mfs_quad_rule rules[] = {
  {"nodal", MFS_QK_NODAL, 0, -1, MFS_CELLS_QUAD, 0},
  {"stress", MFS_QK_HALF, 1, -1, MFS_CELLS_QUAD, 0},
  {"stress-quad", MFS_QK_HALF, 2, MFS_LATTICE_SQUARE, MFS_CELLS_QUAD, 0},
  {"stress-tri", MFS_QK_THIRD, 2, MFS_LATTICE_SQUARE, MFS_CELLS_TRI, 0},
  {"stress-star", MFS_QK_VORONOI, 2, MFS_LATTICE_SQUARE, MFS_CELLS_STAR, 0},
  {"stress-hex", MFS_QK_THIRD, 2, MFS_LATTICE_HEX, MFS_CELLS_TRI, 0},
};

int mfs_quad_rule_parse(const char *name, mfs_quad_rule *rule)
{
  for (size_t i = 0; i < sizeof rules / sizeof rules[0]; i++)
    if (strcmp(name, rules[i].name) == 0) {
      *rule = rules[i];
      return MFS_OK;
    }
  int n, len = 0;
  if (sscanf(name, "gauss%d%n", &n, &len) == 1 && name[len] == '\0' && n >= 1 && n <= 10 &&
      name[5] >= '1' && name[5] <= '9') {
    *rule = (mfs_quad_rule){"gauss", MFS_QK_GAUSS, 0, -1, MFS_CELLS_QUAD, n};
    return MFS_OK;
  }
  return MFS_EINVAL;
}

int mfs_quad_rule_check(const mfs_quad_rule *rule, int dim, mfs_lattice_kind lattice)
{
  if (rule->dim && rule->dim != dim)
    return MFS_EINVAL;
  if (rule->lattice >= 0 && (int)lattice != rule->lattice)
    return MFS_EINVAL;
  return MFS_OK;
}

void mfs_quad_free(mfs_quad *q)
{
  if (!q)
    return;
  free(q->x);
  free(q->w);
  free(q->node);
  free(q);
}

/* Appends one point. */
static void put(mfs_quad *q, const double *x, double w, int node)
{
  memcpy(q->x + q->n * q->dim, x, q->dim * sizeof *x);
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
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)n);
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

mfs_quad *mfs_quad_alloc(const mfs_quad_rule *rule, const mfs_particles *p, int *status)
{
  int st = mfs_quad_rule_check(rule, p->dim, p->lattice);
  mfs_quad *q = NULL;
  if (st != MFS_OK)
    goto fail;
  /* the particles' cells must be the ones the rule is defined on */
  int cells_ok = p->dim == 1 || p->lattice == MFS_LATTICE_HEX || p->cells == rule->cells;
  if (rule->kind != MFS_QK_NODAL && rule->kind != MFS_QK_GAUSS && !cells_ok) {
    st = MFS_EINVAL;
    goto fail;
  }
  st = MFS_ENOMEM;
  q = calloc(1, sizeof *q);
  if (!q)
    goto fail;
  q->dim = p->dim;
  int g = rule->kind == MFS_QK_GAUSS ? rule->gauss_n : 1;
  size_t per = rule->kind == MFS_QK_GAUSS ? (size_t)g * (p->dim == 1 ? 1 : (size_t)g) : 1;
  size_t cap = p->n + p->ncell * per;
  q->x = malloc(cap * p->dim * sizeof *q->x);
  q->w = malloc(cap * sizeof *q->w);
  q->node = malloc(cap * sizeof *q->node);
  if (!q->x || !q->w || !q->node)
    goto fail;

  double share = rule->kind == MFS_QK_HALF ? 0.5 : (rule->kind == MFS_QK_THIRD ? 1.0 / 3.0 : 1.0);
  if (rule->kind != MFS_QK_GAUSS)
    for (size_t I = 0; I < p->n; I++)
      put(q, p->x + I * p->dim, share * p->vol[I], (int)I);
  if (rule->kind == MFS_QK_HALF || rule->kind == MFS_QK_THIRD || rule->kind == MFS_QK_VORONOI) {
    double cshare = 1.0 - share;
    for (size_t c = 0; c < p->ncell; c++) {
      double x[3];
      centroid(p, c, x);
      put(q, x, cshare * mfs_cell_measure(p, c), -1);
    }
  }
  if (rule->kind == MFS_QK_VORONOI) {
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
  if (rule->kind == MFS_QK_GAUSS) {
    double t[10], tw[10];
    if (gauss01(g, t, tw) != MFS_OK)
      goto fail;
    for (size_t c = 0; c < p->ncell; c++)
      gauss_cell(q, p, c, g, t, tw);
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
