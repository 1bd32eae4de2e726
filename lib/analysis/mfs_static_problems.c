/* The problems of mfs_static (paper 004 section 6.2): the cantilever beam
 * (eqs 120-126) and the quarter plate with a hole (eqs 127-130): checks of
 * their members of the spec, closed forms, geometry (particles, background
 * Gauss cells, boundary segments), distance to the boundary, patch fields. */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_static_impl.h"
#include "mfs_alloc.h"

/* Timoshenko-Goodier cantilever (eqs 120-125); plane strain: E -> E/(1-nu^2),
 * nu -> nu/(1-nu) in the displacements (the stresses are the same). */
static void beam_exact(const mfs_static_spec *s, const double *x, double *u, double *sig)
{
  double P = s->load, L = s->length, D = s->depth, I = D * D * D / 12.0;
  double E = s->young, nu = s->poisson;
  if (s->plane_strain) {
    E = E / (1.0 - nu * nu);
    nu = nu / (1.0 - nu);
  }
  double X = x[0], Y = x[1];
  if (u) {
    u[0] = -P * Y / (6.0 * E * I) * ((6.0 * L - 3.0 * X) * X + (2.0 + nu) * (Y * Y - D * D / 4.0));
    u[1] = P / (6.0 * E * I) *
           (3.0 * nu * Y * Y * (L - X) + (4.0 + 5.0 * nu) * D * D * X / 4.0 + (3.0 * L - X) * X * X);
  }
  if (sig) {
    sig[0] = -P * (L - X) * Y / I;
    sig[1] = 0.0;
    sig[2] = P / (2.0 * I) * (D * D / 4.0 - Y * Y);
  }
}

static const char *beam_check(const mfs_static_spec *s)
{
  if (s->nx < 2)
    return "nx";
  if (s->ny < 2)
    return "ny";
  if (!(s->length > 0.0 && isfinite(s->length)))
    return "length";
  if (!(s->depth > 0.0 && isfinite(s->depth)))
    return "depth";
  if (!(s->perturb >= 0.0 && s->perturb < 0.5))
    return "perturb";
  if (s->ghost < 0 || s->ghost > 64)
    return "ghost";
  return NULL;
}

static double beam_distance(const mfs_static_spec *s, const double *x)
{
  double d = fmin(x[0], s->length - x[0]);
  return fmin(d, fmin(x[1] + s->depth / 2.0, s->depth / 2.0 - x[1]));
}

static void beam_patch(double c[2], double G[4])
{
  c[0] = 0.01;
  c[1] = -0.02;
  G[0] = 0.003;
  G[1] = 0.002;
  G[2] = -0.001;
  G[3] = 0.004;
}

/* Kirsch: remote stress S along x, hole radius a (eqs 127-129 for the
 * stresses; the displacements are not printed in the paper). */
static void plate_exact(const mfs_static_spec *s, const double *x, double *u, double *sig)
{
  double a = s->hole_radius, S = s->load, nu = s->poisson;
  double r = hypot(x[0], x[1]), t = atan2(x[1], x[0]);
  if (u) {
    double mu = s->young / (2.0 * (1.0 + nu));
    double k = s->plane_strain ? 3.0 - 4.0 * nu : (3.0 - nu) / (1.0 + nu);
    double c = S * a / (8.0 * mu);
    u[0] = c * (r / a * (k + 1.0) * cos(t) + 2.0 * a / r * ((1.0 + k) * cos(t) + cos(3.0 * t)) -
                2.0 * a * a * a / (r * r * r) * cos(3.0 * t));
    u[1] = c * (r / a * (k - 3.0) * sin(t) + 2.0 * a / r * ((1.0 - k) * sin(t) + sin(3.0 * t)) -
                2.0 * a * a * a / (r * r * r) * sin(3.0 * t));
  }
  if (sig) {
    double a2 = a * a / (r * r), a4 = 1.5 * a2 * a2;
    sig[0] = S * (1.0 - a2 * (1.5 * cos(2.0 * t) + cos(4.0 * t)) + a4 * cos(4.0 * t));
    sig[1] = S * (-a2 * (0.5 * cos(2.0 * t) - cos(4.0 * t)) - a4 * cos(4.0 * t));
    sig[2] = S * (-a2 * (0.5 * sin(2.0 * t) + sin(4.0 * t)) + a4 * sin(4.0 * t));
  }
}

static const char *plate_check(const mfs_static_spec *s)
{
  if (s->nx < 3)
    return "nx";
  if (!(s->hole_radius > 0.0 && isfinite(s->hole_radius)))
    return "hole_radius";
  if (!(s->plate_size > 2.0 * s->hole_radius && isfinite(s->plate_size)))
    return "plate_size";
  if (s->perturb != 0.0)
    return "perturb";
  if (s->ghost != 0)
    return "ghost";
  return NULL;
}

static double plate_distance(const mfs_static_spec *s, const double *x)
{
  double b = s->plate_size, d = fmin(fmin(x[0], x[1]), fmin(b - x[0], b - x[1]));
  return fmin(d, hypot(x[0], x[1]) - s->hole_radius);
}

static void plate_patch(double c[2], double G[4])
{
  c[0] = c[1] = 0.0;
  G[0] = 0.003;
  G[1] = G[2] = 0.0;
  G[3] = -0.001;
}

/* ------------------------------------------------------------------ */
/* geometry                                                            */

int mfs_static_impl_add_segment(mfs_static *m, int a, int b, int kind, unsigned fixed)
{
  if (m->nseg == m->seg_cap) {
    size_t cap = m->seg_cap ? 2 * m->seg_cap : 64;
    segment *t = mfs_realloc(m->seg, cap * sizeof *t);
    if (!t)
      return MFS_ENOMEM;
    m->seg = t;
    m->seg_cap = cap;
  }
  const double *xa = m->p->x + 2 * (size_t)a, *xb = m->p->x + 2 * (size_t)b;
  double tx = xb[0] - xa[0], ty = xb[1] - xa[1], len = hypot(tx, ty);
  m->seg[m->nseg++] = (segment){
    .a = a, .b = b, .kind = kind, .fixed = fixed, .n = {ty / len, -tx / len}, .len = len};
  return MFS_OK;
}

static int beam_build(mfs_static *m)
{
  const mfs_static_spec *s = &m->s;
  double dx = s->length / (s->nx - 1), dy = s->depth / (s->ny - 1);
  int G = s->ghost, nx = s->nx + G, ny = s->ny;
  mfs_lattice_spec ls = {.dim = 2,
                         .lattice = MFS_LATTICE_SQUARE,
                         .nx = nx,
                         .ny = ny,
                         .dx = dx,
                         .gamma = dy / dx,
                         .cells = MFS_CELLS_QUAD,
                         .perturb = s->perturb,
                         .seed = s->seed};
  mfs_status st;
  m->p = mfs_lattice_alloc(&ls, &st);
  if (!m->p)
    return st;
  mfs_particles *p = m->p;
  /* the paper's coordinates: x in [0, L] (ghost columns at x < 0), y in [-D/2, D/2] */
  double sx = -G * dx, sy = -s->depth / 2.0;
  for (size_t I = 0; I < p->n; I++) {
    p->x[2 * I] += sx;
    p->x[2 * I + 1] += sy;
  }
  for (size_t k = 0; k < p->ncell * 4; k++) {
    p->cellx[2 * k] += sx;
    p->cellx[2 * k + 1] += sy;
  }
  p->box.lo[0] += sx;
  p->box.hi[0] += sx;
  p->box.lo[1] += sy;
  p->box.hi[1] += sy;
  m->h = fmax(dx, dy);
  for (int i = 0; i + 1 < nx && st == MFS_OK; i++) /* bottom */
    st = mfs_static_impl_add_segment(m, i, i + 1, SEG_FREE, 0);
  for (int j = 0; j + 1 < ny && st == MFS_OK; j++) /* x = L */
    st = mfs_static_impl_add_segment(m, j * nx + nx - 1, (j + 1) * nx + nx - 1, SEG_TRACTION, 0);
  for (int i = nx - 1; i > 0 && st == MFS_OK; i--) /* top */
    st = mfs_static_impl_add_segment(m, (ny - 1) * nx + i, (ny - 1) * nx + i - 1, SEG_FREE, 0);
  for (int j = ny - 1; j > 0 && st == MFS_OK; j--) /* x = 0: u prescribed; or the ghosts' edge */
    st = mfs_static_impl_add_segment(m, j * nx, (j - 1) * nx, G ? SEG_FREE : SEG_TRACTION, G ? 0u : 3u);
  if (st != MFS_OK)
    return st;
  m->gq = mfs_quad_alloc(&mfs_quad_gauss[4], p, &st);
  if (!m->gq)
    return st;
  m->gq_block = 25;
  if (m->qt->gauss_n > 0 && m->qt->gauss_n != 5) { /* another Gauss rule for the assembly */
    m->q = mfs_quad_alloc(m->qt, p, &st);
    if (!m->q)
      return st;
  }
  if (!G)
    return MFS_OK;
  /* the ghosts: parameters prescribed at x <= 0; errors over the cells and
   * volumes in [0, L] (cells are in rows of nx - 1, the first G columns ghost) */
  m->pinned = mfs_calloc(p->n, 1);
  m->evol = mfs_calloc(p->n, sizeof *m->evol);
  m->eq = mfs_quad_empty(2, (size_t)(ny - 1) * (size_t)(s->nx - 1) * 25);
  if (!m->pinned || !m->evol || !m->eq)
    return MFS_ENOMEM;
  for (size_t c = 0; c < p->ncell; c++) {
    if ((int)(c % (size_t)(nx - 1)) < G)
      continue;
    double a4 = mfs_cell_measure(p, c) / 4.0;
    for (int k = 0; k < 4; k++)
      m->evol[p->conn[4 * c + k]] += a4;
    for (size_t g = 25 * c; g < 25 * c + 25; g++) {
      memcpy(m->eq->x + 2 * m->eq->n, m->gq->x + 2 * g, 2 * sizeof(double));
      m->eq->w[m->eq->n] = m->gq->w[g];
      m->eq->node[m->eq->n++] = -1;
    }
  }
  for (size_t I = 0; I < p->n; I++)
    m->pinned[I] = (int)(I % (size_t)nx) <= G;
  return MFS_OK;
}

/* The plate's background mesh: two mapped blocks of nr x m cells, radial
 * rays from the arc to the edge x = b (theta < pi/4) or y = b; exact
 * geometry.  Point at parameters (s, t) of a block, and the Jacobian. */
static void plate_map(double a, double b, double s, double t, int upper, double *X, double *det)
{
  double q = sqrt(1.0 + t * t);
  double pin[2] = {a / q, a * t / q}, pout[2] = {b, b * t};
  double dpin[2] = {-a * t / (q * q * q), a / (q * q * q)}, dpout[2] = {0.0, b};
  double xs[2], xt[2];
  for (int k = 0; k < 2; k++) {
    X[k] = pin[k] + s * (pout[k] - pin[k]);
    xs[k] = pout[k] - pin[k];
    xt[k] = (1.0 - s) * dpin[k] + s * dpout[k];
  }
  if (upper) { /* mirror about the diagonal */
    double t0 = X[0];
    X[0] = X[1];
    X[1] = t0;
  }
  *det = fabs(xs[0] * xt[1] - xs[1] * xt[0]);
}

int mfs_static_impl_gauss01(int n, double *t, double *w)
{
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)n);
  if (!tab)
    return MFS_ENOMEM;
  for (int i = 0; i < n; i++)
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)i, &t[i], &w[i], tab);
  gsl_integration_glfixed_table_free(tab);
  return MFS_OK;
}

/* Gauss points (ng per direction) of the plate's background mesh. */
static mfs_quad *plate_gauss(const mfs_static_spec *s, int nr, int mb, int ng, mfs_status *st)
{
  double tt[10], tw[10];
  *st = MFS_EINVAL;
  if (ng < 1 || ng > 10)
    return NULL;
  *st = MFS_ENOMEM;
  if (mfs_static_impl_gauss01(ng, tt, tw) != MFS_OK)
    return NULL;
  size_t n = (size_t)nr * 2 * mb * ng * ng;
  mfs_quad *q = mfs_quad_empty(2, n);
  if (!q)
    return NULL;
  for (int i = 0; i < nr; i++)
    for (int k = 0; k < 2 * mb; k++)
      for (int gi = 0; gi < ng; gi++)
        for (int gj = 0; gj < ng; gj++) {
          double sp = (i + tt[gi]) / nr, kk = k + tt[gj];
          int upper = k >= mb;
          double t = upper ? (2.0 * mb - kk) / mb : kk / mb, det;
          plate_map(s->hole_radius, s->plate_size, sp, t, upper, q->x + 2 * q->n, &det);
          q->w[q->n] = tw[gi] * tw[gj] * det / ((double)nr * mb);
          q->node[q->n++] = -1;
        }
  *st = MFS_OK;
  return q;
}

typedef struct {
  double key;
  int node;
} keyed;

static int cmp_keyed(const void *a, const void *b)
{
  double x = ((const keyed *)a)->key, y = ((const keyed *)b)->key;
  return (x > y) - (x < y);
}

/* Segments along the nodes of `sel` sorted by key (ascending). */
static int chain(mfs_static *m, keyed *sel, size_t n, int kind, unsigned fixed)
{
  qsort(sel, n, sizeof *sel, cmp_keyed);
  int st = MFS_OK;
  for (size_t i = 0; i + 1 < n && st == MFS_OK; i++)
    st = mfs_static_impl_add_segment(m, sel[i].node, sel[i + 1].node, kind, fixed);
  return st;
}

static int plate_build(mfs_static *m)
{
  const mfs_static_spec *s = &m->s;
  double a = s->hole_radius, b = s->plate_size;
  int N = s->nx - 1;
  double h = b / N;
  int na = (int)ceil(M_PI / 2.0 * a / h - 1e-9);
  size_t cap = (size_t)(N + 1) * (N + 1) + (size_t)na + 1;
  int st = MFS_ENOMEM;
  mfs_particles *p = mfs_calloc(1, sizeof *p);
  keyed *sel = NULL;
  mfs_grid *g = NULL;
  mfs_nlist *nl = NULL;
  m->p = p;
  if (!p)
    return MFS_ENOMEM;
  p->dim = 2;
  p->lattice = MFS_LATTICE_SQUARE;
  p->x = mfs_malloc(2 * cap * sizeof *p->x);
  p->vol = mfs_calloc(cap, sizeof *p->vol);
  p->flags = mfs_calloc(cap, 1);
  p->ij = mfs_calloc(2 * cap, sizeof *p->ij);
  sel = mfs_malloc(cap * sizeof *sel);
  if (!p->x || !p->vol || !p->flags || !p->ij || !sel)
    goto done;
  /* the arc: theta from 0 to pi/2 */
  for (int k = 0; k <= na; k++) {
    double t = k == na ? M_PI / 2.0 : k * (M_PI / 2.0) / na;
    p->x[2 * p->n] = k == na ? 0.0 : a * cos(t);
    p->x[2 * p->n + 1] = k == 0 ? 0.0 : a * sin(t);
    p->n++;
  }
  for (int j = 0; j <= N; j++)
    for (int i = 0; i <= N; i++) {
      double x = i * h, y = j * h;
      if (hypot(x, y) <= a + 0.5 * h)
        continue;
      p->x[2 * p->n] = i == N ? b : x;
      p->x[2 * p->n + 1] = j == N ? b : y;
      p->ij[2 * p->n] = i;
      p->ij[2 * p->n + 1] = j;
      p->n++;
    }
  p->dx = p->dy = h;
  p->nx = p->ny = N + 1;
  p->box = (mfs_box){.dim = 2, .lo = {0.0, 0.0}, .hi = {b, b}, .periodic = 0};
  p->nvert = 4;
  m->h = h;
  /* background mesh: radial divisions nr = 2 N (b - a)/b, mb = 1.25 nr angular per block */
  int nr = (int)lround(2.0 * N * (b - a) / b);
  nr = nr < 2 ? 2 : nr;
  int mb = (int)lround(1.25 * nr);
  mfs_status ms;
  m->gq = plate_gauss(s, nr, mb, 5, &ms);
  if (m->gq && m->qt->gauss_n > 0 && m->qt->gauss_n != 5)
    m->q = plate_gauss(s, nr, mb, m->qt->gauss_n, &ms);
  st = ms;
  if (!m->gq || (m->qt->gauss_n > 0 && m->qt->gauss_n != 5 && !m->q))
    goto done;
  m->gq_block = 25;
  /* volumes: each background Gauss point's weight to its nearest node */
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, 2.0 * h, &ms);
  nl = g ? mfs_nlist_build(g, m->gq->n, m->gq->x, 2.0 * h, &ms) : NULL;
  st = ms;
  if (!nl)
    goto done;
  for (size_t Q = 0; Q < m->gq->n; Q++) {
    int best = -1;
    double bd = INFINITY;
    for (size_t e = nl->ptr[Q]; e < nl->ptr[Q + 1]; e++) {
      const double *y = p->x + 2 * (size_t)nl->idx[e];
      double d = hypot(y[0] - m->gq->x[2 * Q], y[1] - m->gq->x[2 * Q + 1]);
      if (d < bd) {
        bd = d;
        best = nl->idx[e];
      }
    }
    st = MFS_EINVAL;
    if (best < 0)
      goto done;
    p->vol[best] += m->gq->w[Q];
  }
  /* boundary, counter-clockwise: y = 0 (u_y = 0), x = b, y = b, x = 0 (u_x = 0), the hole */
  const double tol = 1e-9 * b;
  size_t n;
  st = MFS_OK;
  n = 0;
  for (size_t I = 0; I < p->n; I++)
    if (fabs(p->x[2 * I + 1]) < tol)
      sel[n++] = (keyed){p->x[2 * I], (int)I};
  st = chain(m, sel, n, SEG_TRACTION, 2u);
  n = 0;
  for (size_t I = 0; I < p->n && st == MFS_OK; I++)
    if (fabs(p->x[2 * I] - b) < tol)
      sel[n++] = (keyed){p->x[2 * I + 1], (int)I};
  if (st == MFS_OK)
    st = chain(m, sel, n, SEG_TRACTION, 0u);
  n = 0;
  for (size_t I = 0; I < p->n && st == MFS_OK; I++)
    if (fabs(p->x[2 * I + 1] - b) < tol)
      sel[n++] = (keyed){-p->x[2 * I], (int)I};
  if (st == MFS_OK)
    st = chain(m, sel, n, SEG_TRACTION, 0u);
  n = 0;
  for (size_t I = 0; I < p->n && st == MFS_OK; I++)
    if (fabs(p->x[2 * I]) < tol)
      sel[n++] = (keyed){-p->x[2 * I + 1], (int)I};
  if (st == MFS_OK)
    st = chain(m, sel, n, SEG_TRACTION, 1u);
  for (int k = na; k > 0 && st == MFS_OK; k--)
    st = mfs_static_impl_add_segment(m, k, k - 1, SEG_FREE, 0u);
done:
  mfs_free(sel);
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  return st;
}

const mfs_static_problem mfs_static_beam = {
  .name = "beam",
  .what = "cantilever [0, L] x [-D/2, D/2], tip load P (eqs 120-126)",
  .counts = 2,
  .check = beam_check,
  .build = beam_build,
  .exact = beam_exact,
  .distance = beam_distance,
  .patch_field = beam_patch};
const mfs_static_problem mfs_static_plate_hole = {
  .name = "plate-hole",
  .what = "quarter plate [0, b]^2 with a hole of radius a, remote tension (eqs 127-130)",
  .counts = 1,
  .check = plate_check,
  .build = plate_build,
  .exact = plate_exact,
  .distance = plate_distance,
  .patch_field = plate_patch};
const mfs_static_problem *const mfs_static_problems[] = {&mfs_static_beam, &mfs_static_plate_hole,
                                                         NULL};

const mfs_static_problem *mfs_static_problem_find(const char *name)
{
  for (int i = 0; name && mfs_static_problems[i]; i++)
    if (strcmp(name, mfs_static_problems[i]->name) == 0)
      return mfs_static_problems[i];
  return NULL;
}

