/* Conformance suite of the shape functions: every shape type, at order 1 and
 * 2, with every kernel and several dilations, on 30%-perturbed particle sets
 * (1D line, 2D square and hexagonal, finite boxes), at every particle (with
 * `self`), at random points in the box, and at points on the boundary of
 * the domain:
 *   - partition of unity and linear reproduction (values, gradients, second
 *     derivatives) where the method has them;
 *   - corrected gradients (kb, rl) reproduce linear fields exactly;
 *   - the derivative slots agree with central finite differences of the slots
 *     they differentiate (re-gathering the offsets at X +- h e_n);
 *   - sph is V_J W_J;
 *   - a singular moment matrix is an error status, never a NaN. */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

#define MAXNN 512

static mfs_particles *make_set(int dim, mfs_lattice_kind lat, int nx, int ny, double dx,
                               unsigned long seed)
{
  mfs_lattice_spec s = {dim, lat, nx, ny, dx, 1.0, 0, MFS_CELLS_QUAD, 0.3, seed};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&s, &st);
  CHECK(p && st == MFS_OK, "mfs_lattice_alloc status %d", st);
  return p;
}

/* Evaluation points: every particle (self), random points in the box, random
 * points on the boundary of the domain (the union of the cells: the box for
 * the line and the square lattice, a zigzag for the hexagonal one). */
typedef struct {
  size_t n;
  double *x;  /* n*dim */
  int *node;  /* particle index or -1 */
} points;

static int cmp_edge(const void *a, const void *b)
{
  const int *x = a, *y = b;
  return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}

static points make_points(const mfs_particles *p, gsl_rng *rng, int nrand, int nbnd)
{
  int dim = p->dim;
  size_t cap = p->n + (size_t)nrand + (size_t)nbnd + 2;
  points P = {0, malloc(cap * dim * sizeof(double)), malloc(cap * sizeof(int))};
  const double *lo = p->box.lo, *hi = p->box.hi;
  for (size_t I = 0; I < p->n; I++) {
    memcpy(P.x + P.n * dim, p->x + I * dim, dim * sizeof(double));
    P.node[P.n++] = (int)I;
  }
  for (int i = 0; i < nrand; i++) {
    for (int k = 0; k < dim; k++)
      P.x[P.n * dim + k] = lo[k] + gsl_rng_uniform(rng) * (hi[k] - lo[k]);
    P.node[P.n++] = -1;
  }
  if (dim == 1) { /* the ends (particles too, here evaluated without self) */
    P.x[P.n] = lo[0];
    P.node[P.n++] = -1;
    P.x[P.n] = hi[0];
    P.node[P.n++] = -1;
    return P;
  }
  /* boundary edges: the cell edges that belong to one cell only */
  size_t ne = p->ncell * p->nvert, nb = 0;
  int *e = malloc(ne * 4 * sizeof *e); /* (lo node, hi node, cell, vertex) */
  for (size_t c = 0; c < p->ncell; c++)
    for (int k = 0; k < p->nvert; k++) {
      int a = p->conn[c * p->nvert + k], b = p->conn[c * p->nvert + (k + 1) % p->nvert];
      int *t = e + 4 * (c * p->nvert + k);
      t[0] = a < b ? a : b;
      t[1] = a < b ? b : a;
      t[2] = (int)c;
      t[3] = k;
    }
  qsort(e, ne, 4 * sizeof *e, cmp_edge);
  for (size_t i = 0; i < ne; i++) {
    int dup = (i > 0 && cmp_edge(e + 4 * i, e + 4 * (i - 1)) == 0) ||
              (i + 1 < ne && cmp_edge(e + 4 * i, e + 4 * (i + 1)) == 0);
    if (!dup)
      memcpy(e + 4 * nb++, e + 4 * i, 4 * sizeof *e);
  }
  CHECK(nb >= 4, "%zu boundary edges", nb);
  for (int i = 0; i < nbnd && nb > 0; i++) {
    const int *t = e + 4 * gsl_rng_uniform_int(rng, nb);
    const double *v = p->cellx + (size_t)t[2] * p->nvert * 2;
    const double *va = v + 2 * t[3], *vb = v + 2 * ((t[3] + 1) % p->nvert);
    double u = gsl_rng_uniform(rng);
    for (int k = 0; k < 2; k++)
      P.x[P.n * 2 + k] = va[k] + u * (vb[k] - va[k]);
    P.node[P.n++] = -1;
  }
  free(e);
  return P;
}

/* Offsets d_J = X_J - X and volumes of the particles idx[0..nn). */
static void gather(const mfs_particles *p, const double *X, const int *idx, int nn, double *d,
                   double *v)
{
  for (int J = 0; J < nn; J++) {
    mfs_box_delta(&p->box, X, p->x + (size_t)idx[J] * p->dim, d + J * p->dim);
    v[J] = p->vol[idx[J]];
  }
}

/* sum_J f_J g_J / a - want, with g the offsets (or 1 if NULL).  The error is
 * measured against the natural size of the sum: sum_J |f_J| (|g_J| / a <= 1)
 * plus `floor`, the size of a derivative of that order of a unit field over
 * the length a (1/a^k), so that sums of terms that all vanish (e.g. second
 * derivatives in 1D at a node) are judged on the scale of the field. */
static double sum_err(int nn, const double *f, int fs, const double *g, int gs, double a,
                      double want, double floor, double *scale)
{
  double s = 0.0, m = floor + fabs(want);
  for (int J = 0; J < nn; J++) {
    s += f[J * fs] * (g ? g[J * gs] / a : 1.0);
    m += fabs(f[J * fs]);
  }
  *scale = m;
  return s - want;
}

#define CHECK_SUM(err, scale, tol, ...) CHECK(fabs(err) <= (tol) * (scale), __VA_ARGS__)

/* The identities of one evaluation. */
static void check_identities(const mfs_shape_type *sh, const mfs_shape_ctx *c, int nn,
                             const double *d, const double *v, int order, const double *out,
                             const char *ctx)
{
  const double tol = 1e-12;
  int dim = c->dim, nc = mfs_shape_ncomp(dim, order);
  double e, sc, A = c->a;
  int pu = sh->partition_of_unity;
  /* the identities each table claims through its capability fields */
  int linval = sh->linear_complete;  /* mls, cd2: values reproduce linear fields */
  int lingrad = sh->gradient_linear; /* mls, kb, rl, cd2: gradients do */
  int hess_sym = sh->linear_complete && sh->gradient_is_derivative; /* mls */
  int finite = 1;
  for (int i = 0; i < nn * nc; i++)
    finite &= isfinite(out[i]) != 0;
  CHECK(finite, "%s: non-finite output", ctx);
  if (!finite)
    return;

  if (!pu) { /* sph: V_J W_J, V_J grad W_J, V_J Hess W_J exactly as the kernel */
    for (int J = 0; J < nn; J++) {
      double r = 0.0;
      for (int k = 0; k < dim; k++)
        r += d[J * dim + k] * d[J * dim + k];
      r = sqrt(r);
      mfs_kernel_value kv = mfs_kernel_radial(c->kernel, dim, c->a, r);
      const double *o = out + J * nc;
      CHECK(o[0] == v[J] * kv.W, "%s J=%d: sph phi = %.17g, V W = %.17g", ctx, J, o[0],
            v[J] * kv.W);
      double gs = fabs(v[J] * kv.dW) + 1e-300;
      for (int k = 0; k < dim; k++) /* grad_X W(|X_J - X|) = -W'(r) d_J / r */
        CHECK_NEAR(o[1 + k], -v[J] * kv.dW_r * d[J * dim + k], 1e-14 * gs,
                   "%s J=%d: sph grad_%d", ctx, J, k);
      if (order >= 2)
        for (int k = 0; k < dim; k++)
          for (int n = 0; n < dim; n++) {
            double t = r > 0.0 ? (kv.d2W - kv.dW_r) / (r * r) : 0.0;
            double want = v[J] * ((k == n ? kv.dW_r : 0.0) + t * d[J * dim + k] * d[J * dim + n]);
            CHECK_NEAR(o[1 + dim + k * dim + n], want,
                       1e-13 * v[J] * (fabs(kv.d2W) + fabs(kv.dW_r)), "%s J=%d: sph hess %d%d",
                       ctx, J, k, n);
          }
    }
    return;
  }

  /* partition of unity (all but sph: kb values are Shepard, rl and sphs V-weighted Shepard,
   * cd2 MLS) */
  e = sum_err(nn, out, nc, NULL, 0, A, 1.0, 1.0, &sc);
  CHECK_SUM(e, sc, tol, "%s: sum phi - 1 = %.3g (scale %.3g)", ctx, e, sc);
  /* gradients of a constant */
  for (int k = 0; k < dim; k++) {
    e = sum_err(nn, out + 1 + k, nc, NULL, 0, A, 0.0, 1.0 / A, &sc);
    CHECK_SUM(e, sc, tol, "%s: sum d_%d phi = %.3g (scale %.3g)", ctx, k, e, sc);
  }
  if (linval) /* values reproduce linear fields: sum phi_J (X_J - X) = 0 */
    for (int m = 0; m < dim; m++) {
      e = sum_err(nn, out, nc, d + m, dim, A, 0.0, 1.0, &sc);
      CHECK_SUM(e, sc, tol, "%s: sum phi (X_J - X)_%d / a = %.3g (scale %.3g)", ctx, m, e, sc);
    }
  if (lingrad) /* gradients reproduce linear fields: sum G_J (X_J - X)^T = I */
    for (int k = 0; k < dim; k++)
      for (int m = 0; m < dim; m++) {
        e = sum_err(nn, out + 1 + k, nc, d + m, dim, A, k == m ? 1.0 / A : 0.0, 1.0 / A, &sc);
        CHECK_SUM(e, sc, tol, "%s: sum G_%d (X_J - X)_%d / a - delta / a = %.3g (scale %.3g)", ctx, k,
                  m, e, sc);
      }
  if (order >= 2) {
    /* second derivatives of constants vanish (all: sum G_J = 0 identically), of
     * linear fields too where the gradients reproduce them (mls; for kb, rl and
     * cd2 the derivative of sum G (X_J - X)^T = I gives sum dG (X_J - X)^T =
     * delta sum G = 0) */
    for (int q = 0; q < dim * dim; q++) {
      e = sum_err(nn, out + 1 + dim + q, nc, NULL, 0, A, 0.0, 1.0 / (A * A), &sc);
      CHECK_SUM(e, sc, tol, "%s: sum d2 phi [%d] = %.3g (scale %.3g)", ctx, q, e, sc);
      if (lingrad)
        for (int m = 0; m < dim; m++) {
          e = sum_err(nn, out + 1 + dim + q, nc, d + m, dim, A, 0.0, 1.0 / (A * A), &sc);
          CHECK_SUM(e, sc, tol, "%s: sum d2 phi [%d] (X_J - X)_%d / a = %.3g (scale %.3g)", ctx, q,
                    m, e, sc);
        }
    }
  }
  if (hess_sym && order >= 2) /* symmetric Hessians */
    for (int J = 0; J < nn; J++)
      for (int k = 0; k < dim; k++)
        for (int n = 0; n < k; n++) {
          const double *G = out + J * nc + 1 + dim;
          CHECK_NEAR(G[k * dim + n], G[n * dim + k], 1e-12 * (fabs(G[k * dim + n]) + 1.0 / c->a),
                     "%s J=%d: Hessian symmetric", ctx, J);
        }
}

/* Finite differences at X with neighbours idx[0..nn) (all within a + 2h). */
static void check_fd(const mfs_shape_type *sh, const mfs_shape_ctx *c, const mfs_particles *p,
                     const double *X, const int *idx, int nn, int order, const char *ctx)
{
  int dim = c->dim, nc = mfs_shape_ncomp(dim, order);
  double *d = malloc(nn * dim * sizeof *d), *v = malloc(nn * sizeof *v);
  double *o0 = malloc(nn * nc * sizeof *o0), *op = malloc(nn * nc * sizeof *op),
         *om = malloc(nn * nc * sizeof *om);
  double *work = malloc(mfs_shape_work_len(dim, nn) * sizeof *work);
  double rc;
  gather(p, X, idx, nn, d, v);
  /* W(|X - X_J|) has a |X - X_J|^3 term where w'''(0) != 0 (cubic, quartic,
   * wendland2): the second derivatives are continuous but not differentiable
   * at X_J, and the central difference of the gradient at a particle is only
   * first-order accurate, error ~ (w'''(0) / 2|w''(0)|) h / a relative.
   * There the step is 1e-7 a (truncation ~1e-7 and rounding ~1e-16 cond / (h/a)
   * both below the tolerance; measured optimum at corner particles); elsewhere 1e-5 a. */
  double rmin = INFINITY;
  for (int J = 0; J < nn; J++) {
    double r2 = 0.0;
    for (int k = 0; k < dim; k++)
      r2 += d[J * dim + k] * d[J * dim + k];
    rmin = fmin(rmin, sqrt(r2));
  }
  double h = (rmin < 1e-3 * c->a ? 1e-7 : 1e-5) * c->a;
  mfs_status st = sh->eval(c, nn, d, v, -1, order, o0, work, &rc);
  CHECK(st == MFS_OK, "%s: fd centre status %d", ctx, st);
  int is_grad = sh->gradient_is_derivative;
  /* scales: the largest entry, at least that of a unit field over length a */
  double gs = 1.0 / c->a, Gs = 1.0 / (c->a * c->a);
  for (int J = 0; J < nn; J++)
    for (int k = 0; k < dim; k++) {
      gs = fmax(gs, fabs(o0[J * nc + 1 + k]));
      for (int n = 0; n < dim && order >= 2; n++)
        Gs = fmax(Gs, fabs(o0[J * nc + 1 + dim + k * dim + n]));
    }
  for (int n = 0; n < dim && st == MFS_OK; n++) {
    double Xp[3], Xm[3];
    for (int k = 0; k < dim; k++)
      Xp[k] = Xm[k] = X[k];
    Xp[n] += h;
    Xm[n] -= h;
    gather(p, Xp, idx, nn, d, v);
    int s1 = sh->eval(c, nn, d, v, -1, order, op, work, &rc);
    gather(p, Xm, idx, nn, d, v);
    int s2 = sh->eval(c, nn, d, v, -1, order, om, work, &rc);
    CHECK(s1 == MFS_OK && s2 == MFS_OK, "%s: fd status %d %d", ctx, s1, s2);
    if (s1 != MFS_OK || s2 != MFS_OK)
      break;
    double em1 = 0.0, em2 = 0.0;
    for (int J = 0; J < nn; J++) {
      const double *P = op + J * nc, *M = om + J * nc, *O = o0 + J * nc;
      /* the gradient slot is d_n phi for sph, shepard, mls; for kb, rl, sphs and
       * cd2 it is a corrected gradient, which is not the derivative of the values */
      if (is_grad)
        em1 = fmax(em1, fabs((P[0] - M[0]) / (2 * h) - O[1 + n]));
      if (order >= 2) /* layout [k][n] = d_n (gradient slot k) */
        for (int k = 0; k < dim; k++)
          em2 = fmax(em2, fabs((P[1 + k] - M[1 + k]) / (2 * h) - O[1 + dim + k * dim + n]));
    }
    if (is_grad)
      CHECK(em1 <= 1e-6 * gs, "%s: d_%d phi vs central difference: max error %.3g, scale %.3g",
            ctx, n, em1, gs);
    /* a cusp kernel (spiky) has no second derivative at its particle (the
     * difference across the cone is not a derivative), and near it the second
     * derivatives vary like 1/r: the truncation error ~ (h/r)^2 exceeds the
     * tolerance within 0.05 a of a particle */
    int cone = c->kernel->cusp && rmin < 0.05 * c->a;
    if (order >= 2 && !cone)
      CHECK(em2 <= 1e-6 * Gs, "%s: d_%d (gradient) vs central difference: error %.3g, scale %.3g",
            ctx, n, em2, Gs);
  }
  free(d);
  free(v);
  free(o0);
  free(op);
  free(om);
  free(work);
}

static void run_set(const char *name, mfs_particles *p, const double *dils, int ndil,
                    gsl_rng *rng)
{
  int dim = p->dim;
  points P = make_points(p, rng, 40, 30);
  double *d = malloc(MAXNN * dim * sizeof *d), *v = malloc(MAXNN * sizeof *v);
  double *out = malloc(MAXNN * mfs_shape_ncomp(dim, 2) * sizeof *out);
  double *out2 = malloc(MAXNN * mfs_shape_ncomp(dim, 2) * sizeof *out2);
  double *work = malloc(mfs_shape_work_len(dim, MAXNN) * sizeof *work);
  for (int id = 0; id < ndil; id++) {
    double a = dils[id] * p->dx;
    mfs_status st;
    /* exact support radius for the identities; a little more for the
     * finite differences, so that X +- h keeps every particle it sees */
    double afd = a * (1.0 + 1e-3);
    mfs_grid *g = mfs_grid_alloc(dim, p->n, p->x, &p->box, afd, &st);
    mfs_nlist *nl = g ? mfs_nlist_build(g, P.n, P.x, a, &st) : NULL;
    mfs_nlist *nlfd = g ? mfs_nlist_build(g, P.n, P.x, afd, &st) : NULL;
    CHECK(nl && nlfd, "%s: neighbour lists status %d", name, st);
    if (!nl || !nlfd)
      goto next;
    for (int ik = 0; mfs_kernel_types[ik]; ik++) {
      mfs_shape_ctx c = {mfs_kernel_types[ik], dim, a, 1e-12};
      for (int is = 0; mfs_shape_types[is]; is++) {
        const mfs_shape_type *sh = mfs_shape_types[is];
        for (int order = 1; order <= 2; order++) {
          int nc = mfs_shape_ncomp(dim, order);
          for (size_t q = 0; q < P.n; q++) {
            const double *X = P.x + q * dim;
            const int *idx = nl->idx + nl->ptr[q];
            int nn = (int)(nl->ptr[q + 1] - nl->ptr[q]), self = -1;
            CHECK(nn <= MAXNN, "%s: %d neighbours, room for %d", name, nn, MAXNN);
            if (nn > MAXNN)
              continue;
            gather(p, X, idx, nn, d, v);
            for (int J = 0; J < nn; J++)
              if (idx[J] == P.node[q])
                self = J;
            CHECK(P.node[q] < 0 || self >= 0, "%s: particle %d not in its own list", name,
                  P.node[q]);
            char ctx[200];
            snprintf(ctx, sizeof ctx, "%s %s %s D=%g order %d point %zu (%s)", name, sh->name,
                     c.kernel->name, dils[id], order, q,
                     P.node[q] >= 0 ? "particle" : (q < p->n + 40 ? "random" : "boundary"));
            double rc = -1.0;
            st = sh->eval(&c, nn, d, sh->uses_volumes ? v : NULL, self, order, out, work, &rc);
            CHECK(st == MFS_OK, "%s: status %d (%s), rcond %.3g", ctx, st, mfs_strerror(st), rc);
            CHECK(rc > 0.0 && rc <= 1.0 + 1e-12, "%s: rcond %.3g out of (0, 1]", ctx, rc);
            if (st != MFS_OK)
              continue;
            check_identities(sh, &c, nn, d, v, order, out, ctx);
            /* order 1 is the leading part of order 2 */
            if (order == 2) {
              int n1 = mfs_shape_ncomp(dim, 1);
              sh->eval(&c, nn, d, v, self, 1, out2, work, &rc);
              double e = 0.0, m = 0.0;
              for (int J = 0; J < nn; J++)
                for (int t = 0; t < n1; t++) {
                  e = fmax(e, fabs(out2[J * n1 + t] - out[J * nc + t]));
                  m = fmax(m, fabs(out[J * nc + t]));
                }
              CHECK(e <= 1e-13 * m, "%s: order 1 and order 2 values/gradients differ by %.3g",
                    ctx, e);
            }
            /* only rl and sphs read self: everywhere else self = -1 changes nothing */
            if (self >= 0 && !sh->uses_self) {
              sh->eval(&c, nn, d, v, -1, order, out2, work, &rc);
              CHECK(memcmp(out, out2, nn * nc * sizeof *out) == 0, "%s: depends on self", ctx);
            }
            /* finite differences on a sample of the points */
            if (q % 7 == 3 || q >= p->n + 40) {
              const int *fi = nlfd->idx + nlfd->ptr[q];
              int nf = (int)(nlfd->ptr[q + 1] - nlfd->ptr[q]);
              check_fd(sh, &c, p, X, fi, nf, order, ctx);
            }
          }
        }
      }
    }
  next:
    mfs_nlist_free(nl);
    mfs_nlist_free(nlfd);
    mfs_grid_free(g);
  }
  free(P.x);
  free(P.node);
  free(d);
  free(v);
  free(out);
  free(out2);
  free(work);
}

/* Singular moment matrices: an error status, a finite rcond, never NaN. */
static void check_singular(void)
{
  double dx = 0.7313;
  mfs_lattice_spec s = {2, MFS_LATTICE_SQUARE, 6, 5, dx, 1.0, 0, MFS_CELLS_QUAD, 0.0, 0};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&s, &st);
  if (!p)
    return;
  double a = 0.9 * dx, d[2 * MAXNN], v[MAXNN], out[MAXNN * 7], work[256];
  int idx[MAXNN];
  mfs_grid *g = mfs_grid_alloc(2, p->n, p->x, &p->box, a, &st);
  /* at an interior particle: only itself within 0.9 dx; on the bottom edge
   * half way between two particles: two collinear neighbours */
  double X[2][2] = {{p->x[2 * 8], p->x[2 * 8 + 1]}, {2.5 * dx, 0.0}};
  for (int t = 0; t < 2; t++) {
    mfs_nlist *nl = mfs_nlist_build(g, 1, X[t], a, &st);
    int nn = (int)nl->ptr[1];
    CHECK(nn == (t == 0 ? 1 : 2), "singular case %d: %d neighbours", t, nn);
    memcpy(idx, nl->idx, nn * sizeof *idx);
    gather(p, X[t], idx, nn, d, v);
    for (int ik = 0; mfs_kernel_types[ik]; ik++) {
      mfs_shape_ctx c = {mfs_kernel_types[ik], 2, a, 1e-12};
      for (int order = 1; order <= 2; order++) {
        double rc = -1.0;
        st = mfs_shape_mls.eval(&c, nn, d, v, t == 0 ? 0 : -1, order, out, work, &rc);
        CHECK(st == MFS_ESINGULAR, "mls singular case %d %s order %d: status %d", t,
              c.kernel->name, order, st);
        CHECK(isfinite(rc) && rc < 1e-12, "mls singular case %d: rcond %g", t, rc);
        /* the corrected gradients need dim independent directions too */
        st = mfs_shape_kb.eval(&c, nn, d, v, t == 0 ? 0 : -1, order, out, work, &rc);
        CHECK(st == MFS_ESINGULAR, "kb singular case %d %s: status %d", t, c.kernel->name, st);
        CHECK(isfinite(rc), "kb singular case %d: rcond %g", t, rc);
        st = mfs_shape_rl.eval(&c, nn, d, v, t == 0 ? 0 : -1, order, out, work, &rc);
        CHECK(st == MFS_ESINGULAR, "rl singular case %d %s: status %d", t, c.kernel->name, st);
        CHECK(isfinite(rc), "rl singular case %d: rcond %g", t, rc);
        st = mfs_shape_cd2.eval(&c, nn, d, v, t == 0 ? 0 : -1, order, out, work, &rc);
        CHECK(st == MFS_ESINGULAR, "cd2 singular case %d %s: status %d", t, c.kernel->name, st);
        CHECK(isfinite(rc) && rc < 1e-12, "cd2 singular case %d: rcond %g", t, rc);
        /* Shepard needs only one neighbour */
        st = mfs_shape_shepard.eval(&c, nn, d, v, -1, order, out, work, &rc);
        CHECK(st == MFS_OK, "shepard case %d: status %d", t, st);
      }
    }
    mfs_nlist_free(nl);
  }
  /* no neighbour at all: Shepard's moment is zero */
  mfs_shape_ctx c = {&mfs_kernel_cubic, 2, a, 1e-12};
  double rc = -1.0;
  st = mfs_shape_shepard.eval(&c, 0, d, v, -1, 1, out, work, &rc);
  CHECK(st == MFS_ESINGULAR && isfinite(rc), "shepard with no neighbour: status %d", st);
  /* neighbours all at the edge of the support (W = 0) */
  double dz[4] = {a, 0.0, 0.0, -a};
  st = mfs_shape_mls.eval(&c, 2, dz, v, -1, 2, out, work, &rc);
  CHECK(st == MFS_ESINGULAR && isfinite(rc), "mls with zero weights: status %d", st);
  /* 1D, D = 0.9 at a particle */
  mfs_shape_ctx c1 = {&mfs_kernel_quartic, 1, 0.9 * dx, 1e-12};
  double d1[1] = {0.0};
  st = mfs_shape_mls.eval(&c1, 1, d1, v, 0, 2, out, work, &rc);
  CHECK(st == MFS_ESINGULAR && isfinite(rc), "1D mls with one neighbour: status %d", st);
  /* rcond_min is honoured: a regular but ill-conditioned 1D matrix (two
   * neighbours close together) passes with 0 and fails with 0.5 */
  double d2[2] = {0.2 * c1.a, 0.2013 * c1.a};
  c1.rcond_min = 0.0;
  st = mfs_shape_mls.eval(&c1, 2, d2, v, -1, 1, out, work, &rc);
  CHECK(st == MFS_OK && rc > 0.0 && rc < 0.5, "ill-conditioned but regular: status %d rc %g", st,
        rc);
  c1.rcond_min = 0.5;
  st = mfs_shape_mls.eval(&c1, 2, d2, v, -1, 1, out, work, &rc);
  CHECK(st == MFS_ESINGULAR, "rcond %g below rcond_min 0.5: status %d", rc, st);
  mfs_grid_free(g);
  mfs_particles_free(p);
}

/* Position derivatives in any dimension (mfs_shape_type.dpos) against
 * central differences of eval with one neighbour moved, for every shape that
 * has them, in 1D (also against dpos_1d) and 2D, at a random point of a
 * perturbed set; each kernel; and the identity sum_K d g_J / d x_K = -d g_J/dx
 * (the shape functions depend only on the offsets x_K - x). */
static void check_dpos(gsl_rng *rng)
{
  double worst = 0.0, wsum = 0.0, w1 = 0.0, wg = 0.0;
  int tested = 0;
  for (int dim = 1; dim <= 2; dim++)
    for (int ik = 0; mfs_kernel_types[ik]; ik++)
      for (int is = 0; mfs_shape_types[is]; is++) {
        const mfs_shape_type *sh = mfs_shape_types[is];
        if (!sh->dpos) {
          CHECK(mfs_shape_dpos(sh, NULL, 0, NULL, NULL, 0, 0, NULL, NULL) == MFS_ENOTSUP,
                "%s: no dpos is MFS_ENOTSUP", sh->name);
          continue;
        }
        mfs_shape_ctx c = {.kernel = mfs_kernel_types[ik], .dim = dim, .a = 1.7, .rcond_min = 1e-12};
        double d[2 * 64], v[64], out[3 * 64], outp[3 * 64], outm[3 * 64], work[4096];
        double dphi[64], dgrad[2 * 64], dphi1[64], dgrad1[64], sum[2 * 2 * 64];
        int nn = 0;
        while (nn < 64 && nn < (dim == 1 ? 6 : 14)) { /* neighbours within a */
          double x[2] = {gsl_ran_flat(rng, -1.6, 1.6), dim == 2 ? gsl_ran_flat(rng, -1.6, 1.6) : 0};
          if (hypot(x[0], x[1]) >= 1.55 || hypot(x[0], x[1]) < 0.05)
            continue;
          for (int k = 0; k < dim; k++)
            d[nn * dim + k] = x[k];
          v[nn++] = gsl_ran_flat(rng, 0.5, 1.5);
        }
        double rc;
        if (sh->eval(&c, nn, d, v, -1, 1, out, work, &rc) != MFS_OK) {
          CHECK(0, "%s %s %dD: eval", sh->name, c.kernel->name, dim);
          continue;
        }
        memset(sum, 0, sizeof sum);
        double grow[64 * 2 * 2];
        int Jg = nn / 2;
        CHECK(mfs_shape_dpos_grad(sh, &c, nn, d, v, Jg, grow, work) == MFS_OK, "dpos_grad");
        for (int K = 0; K < nn; K++)
          for (int l = 0; l < dim; l++) {
            CHECK(mfs_shape_dpos(sh, &c, nn, d, v, K, l, dphi, dgrad) == MFS_OK, "dpos");
            double h = 1e-5, dd[2 * 64];
            memcpy(dd, d, sizeof dd);
            dd[K * dim + l] = d[K * dim + l] + h;
            sh->eval(&c, nn, dd, v, -1, 1, outp, work, &rc);
            dd[K * dim + l] = d[K * dim + l] - h;
            sh->eval(&c, nn, dd, v, -1, 1, outm, work, &rc);
            int os = 1 + dim;
            for (int J = 0; J < nn; J++) {
              double fd = (outp[J * os] - outm[J * os]) / (2 * h);
              worst = fmax(worst, fabs(fd - dphi[J]));
              for (int m = 0; m < dim; m++) {
                double fg = (outp[J * os + 1 + m] - outm[J * os + 1 + m]) / (2 * h);
                worst = fmax(worst, fabs(fg - dgrad[J * dim + m]));
                sum[(J * dim + m) * dim + l] += dgrad[J * dim + m];
              }
            }
            for (int m = 0; m < dim; m++)
              wg = fmax(wg, fabs(grow[(K * dim + l) * dim + m] - dgrad[Jg * dim + m]));
            if (dim == 1 && sh->dpos_1d) {
              mfs_shape_dpos_1d(sh, &c, nn, d, v, K, dphi1, dgrad1);
              for (int J = 0; J < nn; J++)
                w1 = fmax(w1, fmax(fabs(dphi1[J] - dphi[J]), fabs(dgrad1[J] - dgrad[J])));
            }
            tested++;
          }
        /* sum_K d g_J,m / d x_K,l = -d g_J,m / d x_l: central differences of eval in x */
        for (int l = 0; l < dim; l++) {
          double h = 1e-5, dd[2 * 64];
          for (int J = 0; J < nn; J++)
            for (int k = 0; k < dim; k++)
              dd[J * dim + k] = d[J * dim + k] - (k == l ? h : 0.0); /* x + h e_l */
          sh->eval(&c, nn, dd, v, -1, 1, outp, work, &rc);
          for (int J = 0; J < nn; J++)
            for (int k = 0; k < dim; k++)
              dd[J * dim + k] = d[J * dim + k] + (k == l ? h : 0.0);
          sh->eval(&c, nn, dd, v, -1, 1, outm, work, &rc);
          int os = 1 + dim;
          for (int J = 0; J < nn; J++)
            for (int m = 0; m < dim; m++) {
              double gx = (outp[J * os + 1 + m] - outm[J * os + 1 + m]) / (2 * h);
              if (sh->partition_of_unity) /* sph: V_J W(x_J - x) depends on x_J - x too */
                wsum = fmax(wsum, fabs(sum[(J * dim + m) * dim + l] + gx));
            }
        }
      }
  CHECK(tested > 0 && worst < 1e-6, "dpos vs central differences of eval: %g", worst);
  CHECK(w1 < 1e-12, "dpos in 1D vs dpos_1d: %g", w1);
  CHECK(wg < 1e-12, "dpos_grad vs dpos: %g", wg);
  CHECK(wsum < 1e-6, "sum_K dg/dx_K = -dg/dx: %g", wsum);
  printf("dpos: %d derivatives, fd %.2g, 1D %.2g, sum %.2g, dpos_grad %.2g\n", tested, worst, w1, wsum, wg);
}

int main(void)
{
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 20240611);
  const double dx = 0.7313;

  mfs_particles *line = make_set(1, MFS_LATTICE_LINE, 17, 0, dx, 4711);
  const double dil1[] = {1.7, 2.385, 3.1};
  if (line)
    run_set("line", line, dil1, 3, rng);
  mfs_particles_free(line);

  const double dil2[] = {1.8, 2.385};
  mfs_particles *sq = make_set(2, MFS_LATTICE_SQUARE, 10, 9, dx, 90210);
  if (sq)
    run_set("square", sq, dil2, 2, rng);
  mfs_particles_free(sq);

  mfs_particles *hex = make_set(2, MFS_LATTICE_HEX, 10, 9, dx, 31337);
  if (hex)
    run_set("hex", hex, dil2, 2, rng);
  mfs_particles_free(hex);

  check_singular();
  check_dpos(rng);

  /* lookup and the volume flags */
  int ns = 0;
  for (int i = 0; mfs_shape_types[i]; i++, ns++)
    CHECK(mfs_shape_find(mfs_shape_types[i]->name) == mfs_shape_types[i], "find %s",
          mfs_shape_types[i]->name);
  CHECK(ns == 7, "%d shape types, want 7", ns);
  CHECK(mfs_shape_find("efg") == NULL, "unknown shape name gives NULL");
  CHECK(mfs_shape_sph.uses_volumes && mfs_shape_rl.uses_volumes && !mfs_shape_mls.uses_volumes &&
          !mfs_shape_shepard.uses_volumes && !mfs_shape_kb.uses_volumes &&
          mfs_shape_sphs.uses_volumes && !mfs_shape_cd2.uses_volumes,
        "uses_volumes flags");
  CHECK(mfs_shape_mls.gradient_linear && mfs_shape_kb.gradient_linear && mfs_shape_rl.gradient_linear &&
          mfs_shape_cd2.gradient_linear && !mfs_shape_sph.gradient_linear &&
          !mfs_shape_shepard.gradient_linear && !mfs_shape_sphs.gradient_linear,
        "gradient_linear flags");
  CHECK(mfs_shape_rl.uses_self && mfs_shape_sphs.uses_self && !mfs_shape_mls.uses_self &&
          !mfs_shape_kb.uses_self && !mfs_shape_cd2.uses_self && !mfs_shape_sph.uses_self &&
          !mfs_shape_shepard.uses_self,
        "uses_self flags");
  CHECK(!mfs_shape_sph.partition_of_unity && mfs_shape_rl.partition_of_unity &&
          mfs_shape_mls.partition_of_unity && mfs_shape_shepard.partition_of_unity &&
          mfs_shape_kb.partition_of_unity && mfs_shape_sphs.partition_of_unity &&
          mfs_shape_cd2.partition_of_unity,
        "partition_of_unity flags");
  CHECK(mfs_shape_ncomp(2, 1) == 3 && mfs_shape_ncomp(2, 2) == 7 && mfs_shape_ncomp(1, 2) == 3,
        "mfs_shape_ncomp");
  gsl_rng_free(rng);
  return check_summary("test_shape");
}
