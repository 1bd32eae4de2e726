#include "mfs_particles.h"
#include "mfs_alloc.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_delaunay.h"
#include "mfs_neighbor.h"
#include "mfs_select.h"
#include "mfs_status.h"

void mfs_particles_free(mfs_particles *p)
{
  if (!p)
    return;
  mfs_free(p->x);
  mfs_free(p->vol);
  mfs_free(p->flags);
  mfs_free(p->ij);
  mfs_free(p->conn);
  mfs_free(p->cellx);
  mfs_free(p);
}

double mfs_cell_measure(const mfs_particles *p, size_t c)
{
  const double *v = p->cellx + c * (size_t)p->nvert * (size_t)p->dim;
  if (p->dim == 1)
    return fabs(v[1] - v[0]);
  double s = 0.0; /* shoelace */
  for (int k = 0; k < p->nvert; k++) {
    int l = (k + 1) % p->nvert;
    s += v[2 * k] * v[2 * l + 1] - v[2 * l] * v[2 * k + 1];
  }
  return 0.5 * s;
}

double mfs_particles_domain_volume(const mfs_particles *p)
{
  double s = 0.0;
  for (size_t c = 0; c < p->ncell; c++)
    s += mfs_cell_measure(p, c);
  return s;
}

/* Node index of lattice site (i, j), wrapping when periodic; -1 outside. */
static int site(const mfs_particles *p, int i, int j, int *si, int *sj)
{
  *si = *sj = 0;
  if (p->box.periodic) {
    if (i >= p->nx) {
      i -= p->nx;
      *si = 1;
    }
    if (j >= p->ny) {
      j -= p->ny;
      *sj = 1;
    }
  } else if (i >= p->nx || j >= p->ny) {
    return -1;
  }
  return j * p->nx + i;
}

/* Append cell with vertex sites (i[k], j[k]); skipped if a site is outside. */
static void add_cell(mfs_particles *p, size_t *nc, const int *i, const int *j)
{
  int nodes[4], sx[4], sy[4];
  for (int k = 0; k < p->nvert; k++) {
    nodes[k] = site(p, i[k], j[k], &sx[k], &sy[k]);
    if (nodes[k] < 0)
      return;
  }
  double Lx = p->box.hi[0] - p->box.lo[0];
  double Ly = p->dim > 1 ? p->box.hi[1] - p->box.lo[1] : 0.0;
  for (int k = 0; k < p->nvert; k++) {
    p->conn[*nc * p->nvert + k] = nodes[k];
    double *v = p->cellx + (*nc * p->nvert + k) * p->dim;
    v[0] = p->x[nodes[k] * p->dim] + sx[k] * Lx;
    if (p->dim > 1)
      v[1] = p->x[nodes[k] * p->dim + 1] + sy[k] * Ly;
  }
  (*nc)++;
}

static void build_cells(mfs_particles *p, mfs_cell_kind kind)
{
  size_t nc = 0;
  int per = p->box.periodic;
  int ni = per ? p->nx : p->nx - 1;
  int nj = per ? p->ny : p->ny - 1;
  if (p->dim == 1) {
    for (int i = 0; i < ni; i++) {
      int ii[2] = {i, i + 1}, jj[2] = {0, 0};
      add_cell(p, &nc, ii, jj);
    }
  } else if (p->lattice == MFS_LATTICE_SQUARE && kind == MFS_CELLS_QUAD) {
    for (int j = 0; j < nj; j++)
      for (int i = 0; i < ni; i++) {
        int ii[4] = {i, i + 1, i + 1, i}, jj[4] = {j, j, j + 1, j + 1};
        add_cell(p, &nc, ii, jj);
      }
  } else if (p->lattice == MFS_LATTICE_SQUARE) {
    for (int j = 0; j < nj; j++)
      for (int i = 0; i < ni; i++) {
        if (kind == MFS_CELLS_TRI || ((i + j) & 1) == 0) {
          int i1[3] = {i, i + 1, i + 1}, j1[3] = {j, j, j + 1};
          int i2[3] = {i, i + 1, i}, j2[3] = {j, j + 1, j + 1};
          add_cell(p, &nc, i1, j1);
          add_cell(p, &nc, i2, j2);
        } else {
          int i1[3] = {i, i + 1, i}, j1[3] = {j, j, j + 1};
          int i2[3] = {i + 1, i + 1, i}, j2[3] = {j, j + 1, j + 1};
          add_cell(p, &nc, i1, j1);
          add_cell(p, &nc, i2, j2);
        }
      }
  } else { /* hexagonal: triangles between rows j and j+1 */
    for (int j = 0; j < nj; j++)
      for (int i = 0; i < ni; i++) {
        if ((j & 1) == 0) {
          int i1[3] = {i, i + 1, i}, j1[3] = {j, j, j + 1};
          int i2[3] = {i + 1, i + 1, i}, j2[3] = {j, j + 1, j + 1};
          add_cell(p, &nc, i1, j1);
          add_cell(p, &nc, i2, j2);
        } else {
          int i1[3] = {i, i + 1, i}, j1[3] = {j, j + 1, j + 1};
          int i2[3] = {i, i + 1, i + 1}, j2[3] = {j, j, j + 1};
          add_cell(p, &nc, i1, j1);
          add_cell(p, &nc, i2, j2);
        }
      }
  }
  p->ncell = nc;
}

static int check_spec(const mfs_lattice_spec *s)
{
  if (s->dim == 1 && s->lattice != MFS_LATTICE_LINE)
    return MFS_EINVAL;
  if (s->dim == 2 && s->lattice == MFS_LATTICE_LINE)
    return MFS_EINVAL;
  if (s->dim != 1 && s->dim != 2)
    return MFS_EINVAL;
  if (s->nx < 2 || (s->dim == 2 && s->ny < 2))
    return MFS_EINVAL;
  if (!(s->dx > 0.0) || s->gamma < 0.0 || !(s->perturb >= 0.0 && s->perturb < 0.5))
    return MFS_EINVAL;
  if (s->periodic && s->dim == 2 && s->lattice == MFS_LATTICE_HEX && (s->ny & 1))
    return MFS_EINVAL;
  if (s->periodic && s->dim == 2 && s->lattice == MFS_LATTICE_SQUARE &&
      s->cells == MFS_CELLS_STAR && ((s->nx & 1) || (s->ny & 1)))
    return MFS_EINVAL;
  return MFS_OK;
}

static int perturb(mfs_particles *p, double frac, unsigned long seed)
{
  gsl_error_handler_t *handler = gsl_set_error_handler_off(); /* GSL's aborts */
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_set_error_handler(handler);
  if (!rng)
    return MFS_ENOMEM;
  gsl_rng_set(rng, seed);
  double h[2] = {p->dx, p->dy};
  for (size_t I = 0; I < p->n; I++) {
    for (int k = 0; k < p->dim; k++) {
      double u = frac * h[k] * (2.0 * gsl_rng_uniform(rng) - 1.0);
      unsigned f = p->flags[I];
      /* boundary particles move only along their boundary; hexagonal
       * boundaries (ragged) and corners not at all */
      int fixed = (k == 0 && (f & (MFS_BND_XLO | MFS_BND_XHI))) ||
                  (k == 1 && (f & (MFS_BND_YLO | MFS_BND_YHI))) ||
                  (f && p->lattice == MFS_LATTICE_HEX);
      if (!fixed)
        p->x[I * p->dim + k] += u;
    }
  }
  gsl_rng_free(rng);
  return MFS_OK;
}

mfs_particles *mfs_lattice_alloc(const mfs_lattice_spec *s, mfs_status *status)
{
  int st = check_spec(s);
  mfs_particles *p = NULL;
  if (st != MFS_OK)
    goto fail;
  st = MFS_ENOMEM;
  p = mfs_calloc(1, sizeof *p);
  if (!p)
    goto fail;
  int dim = s->dim;
  p->dim = dim;
  p->lattice = s->lattice;
  p->nx = s->nx;
  p->ny = dim == 1 ? 1 : s->ny;
  p->n = (size_t)p->nx * (size_t)p->ny;
  p->dx = s->dx;
  double gamma = s->gamma > 0.0 ? s->gamma : 1.0;
  p->dy = dim == 1 ? 0.0 : (s->lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 * s->dx : gamma * s->dx);
  p->a1[0] = s->dx;
  p->a2[0] = s->lattice == MFS_LATTICE_HEX ? 0.5 * s->dx : 0.0;
  p->a2[1] = p->dy;
  p->box.dim = dim;
  p->box.periodic = s->periodic;
  p->x = mfs_malloc(p->n * dim * sizeof *p->x);
  p->vol = mfs_calloc(p->n, sizeof *p->vol);
  p->flags = mfs_calloc(p->n, 1);
  p->ij = mfs_malloc(p->n * 2 * sizeof *p->ij);
  if (!p->x || !p->vol || !p->flags || !p->ij)
    goto fail;

  for (int j = 0; j < p->ny; j++)
    for (int i = 0; i < p->nx; i++) {
      size_t I = (size_t)j * p->nx + i;
      int odd = s->lattice == MFS_LATTICE_HEX && (j & 1);
      p->x[I * dim] = i * s->dx + (odd ? 0.5 * s->dx : 0.0);
      if (dim > 1)
        p->x[I * dim + 1] = j * p->dy;
      p->ij[2 * I] = s->lattice == MFS_LATTICE_HEX ? i - j / 2 : i;
      p->ij[2 * I + 1] = j;
      if (!s->periodic) {
        unsigned f = 0;
        if (i == 0)
          f |= MFS_BND_XLO;
        if (i == p->nx - 1)
          f |= MFS_BND_XHI;
        if (dim > 1 && j == 0)
          f |= MFS_BND_YLO;
        if (dim > 1 && j == p->ny - 1)
          f |= MFS_BND_YHI;
        p->flags[I] = (unsigned char)f;
      }
    }
  p->box.lo[0] = p->box.lo[1] = 0.0;
  if (s->periodic) {
    p->box.hi[0] = p->nx * s->dx;
    p->box.hi[1] = p->ny * p->dy;
  } else {
    p->box.hi[0] = (p->nx - 1) * s->dx + (s->lattice == MFS_LATTICE_HEX ? 0.5 * s->dx : 0.0);
    p->box.hi[1] = (p->ny - 1) * p->dy;
  }
  if (s->perturb > 0.0 && perturb(p, s->perturb, s->seed) != MFS_OK)
    goto fail;

  mfs_cell_kind kind = s->lattice == MFS_LATTICE_SQUARE ? s->cells : MFS_CELLS_TRI;
  if (dim == 1)
    kind = MFS_CELLS_QUAD;
  p->cells = kind;
  p->nvert = dim == 1 ? 2 : (kind == MFS_CELLS_QUAD ? 4 : 3);
  size_t maxcell = (size_t)p->nx * p->ny * (p->nvert == 3 ? 2 : 1);
  p->conn = mfs_malloc(maxcell * p->nvert * sizeof *p->conn);
  p->cellx = mfs_malloc(maxcell * p->nvert * dim * sizeof *p->cellx);
  if (!p->conn || !p->cellx)
    goto fail;
  build_cells(p, kind);

  /* cell-dual volumes: each cell's measure shared equally by its vertices */
  for (size_t c = 0; c < p->ncell; c++) {
    double m = mfs_cell_measure(p, c) / p->nvert;
    for (int k = 0; k < p->nvert; k++)
      p->vol[p->conn[c * p->nvert + k]] += m;
  }
  if (status)
    *status = MFS_OK;
  return p;
fail:
  mfs_particles_free(p);
  if (status)
    *status = st;
  return NULL;
}

/* ------------------------------------------------------------------ */
/* particle sets given as arrays                                        */

static int set_ok(const mfs_point_set *s)
{
  if (!s || (s->dim != 1 && s->dim != 2) || !s->x || s->n < (size_t)s->dim + 1 ||
      s->n > (size_t)INT32_MAX / 4)
    return 0;
  for (size_t i = 0; i < s->n * (size_t)s->dim; i++)
    if (!isfinite(s->x[i]))
      return 0;
  if (s->vol)
    for (size_t i = 0; i < s->n; i++)
      if (!(s->vol[i] > 0.0) || !isfinite(s->vol[i]))
        return 0;
  return 1;
}

typedef struct {
  double x;
  size_t i;
} key1;

static int cmp_key1(const void *a, const void *b)
{
  double x = ((const key1 *)a)->x, y = ((const key1 *)b)->x;
  return (x > y) - (x < y);
}

/* 1D: intervals between neighbours in x. */
static int cells_1d(mfs_particles *p)
{
  size_t n = p->n;
  key1 *k = mfs_malloc(n * sizeof *k);
  p->conn = mfs_malloc((n - 1) * 2 * sizeof *p->conn);
  p->cellx = mfs_malloc((n - 1) * 2 * sizeof *p->cellx);
  if (!k || !p->conn || !p->cellx) {
    mfs_free(k);
    return MFS_ENOMEM;
  }
  for (size_t i = 0; i < n; i++)
    k[i] = (key1){p->x[i], i};
  qsort(k, n, sizeof *k, cmp_key1);
  for (size_t c = 0; c + 1 < n; c++) {
    if (!(k[c + 1].x > k[c].x)) { /* two particles at one place */
      mfs_free(k);
      return MFS_EINVAL;
    }
    p->conn[2 * c] = (int)k[c].i;
    p->conn[2 * c + 1] = (int)k[c + 1].i;
    p->cellx[2 * c] = k[c].x;
    p->cellx[2 * c + 1] = k[c + 1].x;
  }
  p->ncell = n - 1;
  p->flags[k[0].i] |= MFS_BND_XLO;
  p->flags[k[n - 1].i] |= MFS_BND_XHI;
  mfs_free(k);
  return MFS_OK;
}

static int cells_2d(mfs_particles *p)
{
  size_t nt = 0;
  int *tri = NULL;
  int st = mfs_delaunay_2d(p->n, p->x, &nt, &tri);
  if (st != MFS_OK)
    return st;
  p->conn = tri;
  p->ncell = nt;
  p->cellx = mfs_malloc(nt * 6 * sizeof *p->cellx);
  if (!p->cellx)
    return MFS_ENOMEM;
  for (size_t c = 0; c < nt; c++)
    for (int k = 0; k < 3; k++) {
      p->cellx[6 * c + 2 * k] = p->x[2 * (size_t)tri[3 * c + k]];
      p->cellx[6 * c + 2 * k + 1] = p->x[2 * (size_t)tri[3 * c + k] + 1];
    }
  return MFS_OK;
}

mfs_particles *mfs_particles_from_set(const mfs_point_set *s, int cells, mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_particles *p = NULL;
  if (!set_ok(s))
    goto fail;
  st = MFS_ENOMEM;
  p = mfs_calloc(1, sizeof *p);
  if (!p)
    goto fail;
  int dim = s->dim;
  size_t n = s->n;
  p->dim = dim;
  p->n = n;
  p->lattice = MFS_LATTICE_POINTS;
  p->nx = (int)n;
  p->ny = 1;
  p->box.dim = dim;
  p->x = mfs_malloc(n * dim * sizeof *p->x);
  p->vol = mfs_malloc(n * sizeof *p->vol);
  p->flags = mfs_calloc(n, 1);
  p->ij = mfs_calloc(n * 2, sizeof *p->ij);
  if (!p->x || !p->vol || !p->flags || !p->ij)
    goto fail;
  memcpy(p->x, s->x, n * dim * sizeof *p->x);
  for (int k = 0; k < dim; k++) {
    p->box.lo[k] = p->box.hi[k] = s->x[k];
    for (size_t i = 1; i < n; i++) {
      double v = s->x[i * dim + k];
      p->box.lo[k] = v < p->box.lo[k] ? v : p->box.lo[k];
      p->box.hi[k] = v > p->box.hi[k] ? v : p->box.hi[k];
    }
  }
  p->cells = dim == 1 ? MFS_CELLS_QUAD : MFS_CELLS_TRI;
  p->nvert = dim == 1 ? 2 : 3;
  if (dim == 1) {
    st = cells_1d(p);
  } else {
    st = mfs_convex_hull_2d(n, p->x, p->flags);
    if (st == MFS_OK)
      for (size_t i = 0; i < n; i++)
        p->flags[i] = p->flags[i] ? MFS_BND_HULL : 0;
    if (st == MFS_OK && (cells || !s->vol))
      st = cells_2d(p);
  }
  if (st != MFS_OK)
    goto fail;
  if (s->vol) {
    memcpy(p->vol, s->vol, n * sizeof *p->vol);
  } else if (dim == 1) {
    memset(p->vol, 0, n * sizeof *p->vol);
    for (size_t c = 0; c < p->ncell; c++) {
      double m = 0.5 * mfs_cell_measure(p, c);
      p->vol[p->conn[2 * c]] += m;
      p->vol[p->conn[2 * c + 1]] += m;
    }
  } else {
    mfs_dual_areas(n, p->x, p->ncell, p->conn, p->vol);
    st = MFS_EDOMAIN; /* a particle in no triangle (Qhull merged it away) */
    for (size_t i = 0; i < n; i++)
      if (!(p->vol[i] > 0.0))
        goto fail;
  }
  if (s->spacing > 0.0) {
    p->dx = s->spacing;
  } else {
    mfs_point_set t = *s;
    t.vol = p->vol;
    p->dx = mfs_point_set_spacing(&t);
  }
  p->dy = dim == 1 ? 0.0 : p->dx;
  if (status)
    *status = MFS_OK;
  return p;
fail:
  mfs_particles_free(p);
  if (status)
    *status = st;
  return NULL;
}

double mfs_point_set_spacing(const mfs_point_set *s)
{
  if (!s || !s->vol || s->n < 1)
    return NAN;
  size_t k = s->n / 2;
  double med = mfs_kth_smallest(s->vol, s->n, 1, k);
  if (s->n % 2 == 0) /* the largest of the lower half */
    med = 0.5 * (med + mfs_kth_smallest(s->vol, s->n, 1, k - 1));
  return s->dim == 1 ? med : sqrt(med);
}

/* The quartiles q1 <= q3 of each coordinate (mfs_quartiles) and, with
 * count, the number of particles in the box between them (one pass). */
static size_t quartile_box(const mfs_point_set *s, double q1[2], double q3[2], int count)
{
  int dim = s->dim;
  size_t n = s->n, in = 0;
  mfs_quartiles(dim, n, s->x, q1, q3);
  for (size_t i = 0; count && i < n; i++) {
    int inside = 1;
    for (int k = 0; k < dim; k++) {
      double v = s->x[i * (size_t)dim + (size_t)k];
      inside &= v >= q1[k] && v <= q3[k];
    }
    in += (size_t)inside;
  }
  return in;
}

static int coords_finite(const mfs_point_set *s)
{
  for (size_t i = 0; i < s->n * (size_t)s->dim; i++)
    if (!isfinite(s->x[i]))
      return 0;
  return 1;
}

double mfs_point_set_bulk_spacing(const mfs_point_set *s)
{
  if (!s || (s->dim != 1 && s->dim != 2) || !s->x || s->n < 4 || !coords_finite(s))
    return NAN;
  double q1[2], q3[2];
  size_t in = quartile_box(s, q1, q3, 1);
  if (s->dim == 1)
    return q3[0] > q1[0] && in >= 2 ? (q3[0] - q1[0]) / (double)(in - 1) : NAN;
  double area = (q3[0] - q1[0]) * (q3[1] - q1[1]);
  return area > 0.0 && isfinite(area) && in >= 2 ? sqrt(area / (double)in) : NAN;
}

/* The set's bounding box (not periodic). */
static mfs_box set_box(const mfs_point_set *s)
{
  mfs_box box = {.dim = s->dim, .periodic = 0};
  for (int k = 0; k < s->dim; k++) {
    box.lo[k] = box.hi[k] = s->x[k];
    for (size_t q = 1; q < s->n; q++) {
      double v = s->x[q * (size_t)s->dim + (size_t)k];
      box.lo[k] = fmin(box.lo[k], v);
      box.hi[k] = fmax(box.hi[k], v);
    }
  }
  return box;
}

mfs_status mfs_point_set_neighbours(const mfs_point_set *s, double r, double limit, double *count)
{
  *count = 0.0;
  if (!s || (s->dim != 1 && s->dim != 2) || !s->x || !(r > 0.0) || !isfinite(r) ||
      !(limit >= 0.0) || !coords_finite(s))
    return MFS_EINVAL;
  mfs_box box = set_box(s);
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(s->dim, s->n, s->x, &box, r, &st);
  if (!g)
    return st;
  st = mfs_grid_count(g, s->n, s->x, r, limit, count);
  mfs_grid_free(g);
  return st;
}

mfs_status mfs_point_set_close_pair(const mfs_point_set *s, double r, int *found, size_t *i,
                                    size_t *j)
{
  *found = 0;
  *i = *j = 0;
  if (!s || (s->dim != 1 && s->dim != 2) || !s->x || !(r > 0.0) || !isfinite(r))
    return MFS_EINVAL;
  size_t n = s->n;
  if (n < 2)
    return MFS_OK;
  if (!coords_finite(s))
    return MFS_EINVAL;
  int dim = s->dim;
  mfs_box box = set_box(s);
  double meas = 1.0, q1[2] = {0.0, 0.0}, q3[2] = {0.0, 0.0};
  if (n >= 4)
    quartile_box(s, q1, q3, 0);
  for (int k = 0; k < dim; k++) {
    /* the grid over the bulk, the quartiles widened by their distance on
     * each side: a few far particles go to the edge cells (the cells clamp)
     * instead of stretching every cell, which put the bulk in one cell */
    double w = q3[k] - q1[k];
    if (n >= 4 && w > 0.0) {
      box.lo[k] = fmax(box.lo[k], q1[k] - w);
      box.hi[k] = fmin(box.hi[k], q3[k] + w);
    }
    double L = box.hi[k] - box.lo[k];
    meas *= L > 0.0 && isfinite(L) ? L : 1.0;
  }
  /* cells of about the mean spacing, so that their count stays O(n), and at
   * least 2r: a pair closer than r lies in one cell or two adjacent ones
   * (also through the clamping: it keeps the order of the cells) */
  double R = dim == 1 ? meas / (double)n : sqrt(meas / (double)n);
  R = R > 2.0 * r ? R : 2.0 * r;
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(dim, n, s->x, &box, R, &st);
  if (!g)
    return st;
  int ny = dim == 2 ? g->nc[1] : 1, nx = g->nc[0];
  double r2 = r * r;
  size_t bi = 0, bj = 0;
  for (int cy = 0; cy < ny; cy++)
    for (int cx = 0; cx < nx; cx++) {
      size_t c = (size_t)cy * (size_t)nx + (size_t)cx;
      /* this cell and the forward half of its neighbours: each pair of cells once */
      static const int off[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
      for (int o = 0; o < (dim == 2 ? 5 : 2); o++) {
        int ox = cx + off[o][0], oy = cy + off[o][1];
        if (ox < 0 || ox >= nx || oy >= ny)
          continue;
        size_t d = (size_t)oy * (size_t)nx + (size_t)ox;
        for (size_t a = g->start[c]; a < g->start[c + 1]; a++) {
          size_t b0 = o == 0 ? a + 1 : g->start[d];
          int hit = 0;
          for (size_t b = b0; b < g->start[d + 1]; b++) {
            const double *xa = s->x + (size_t)g->item[a] * dim, *xb = s->x + (size_t)g->item[b] * dim;
            double t = xa[0] - xb[0], d2 = t * t;
            if (dim == 2) {
              t = xa[1] - xb[1];
              d2 += t * t;
            }
            if (d2 < r2) {
              size_t p = (size_t)g->item[a], q = (size_t)g->item[b];
              size_t lo = p < q ? p : q, hi = p < q ? q : p;
              if (!*found || lo < bi || (lo == bi && hi < bj)) { /* the first pair by index */
                bi = lo;
                bj = hi;
              }
              *found = 1;
              hit = 1;
            }
          }
          /* within one cell (items ascending) every later a's pairs have a larger
           * lower index: none can come first (40 000 copies of one point, a
           * file whose exporter wrote one row again and again, took 1.8 s of
           * pair tests, 10^6 of them would take 20 minutes) */
          if (hit && o == 0)
            break;
        }
      }
    }
  mfs_grid_free(g);
  *i = bi;
  *j = bj;
  return MFS_OK;
}
