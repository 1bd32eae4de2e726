/* Plans and assembly: exact properties of the discrete operators.
 *   - K annihilates constants wherever the gradients sum to zero;
 *   - K and the consistent M are symmetric; the lumped mass is the row sum
 *     of the consistent one and adds up to density times the volume;
 *   - the energy of a linear field is exact (modulus times volume) for shapes
 *     whose gradients reproduce linear fields, whatever the quadrature;
 *   - plane strain: symmetric, the rigid modes in the null space, uniform
 *     strains with the exact energy;
 *   - mfs_stencil equals the row of the centre particle of a large finite
 *     model. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static const double DX = 0.7313;

typedef struct {
  mfs_particles *p;
  mfs_quad *q;
  mfs_plan *pl;
} model;

static void model_free(model *m)
{
  mfs_plan_free(m->pl);
  mfs_quad_free(m->q);
  mfs_particles_free(m->p);
  m->pl = NULL;
  m->q = NULL;
  m->p = NULL;
}

/* The discretization of a plan: kernel, shape, dilation. */
static mfs_disc plan_disc(const mfs_kernel_type *k, const mfs_shape_type *sh, double D)
{
  mfs_disc d = mfs_disc_default();
  d.kernel = k;
  d.shape = sh;
  d.dilation = D;
  return d;
}

static int model_build(model *m, const mfs_lattice_spec *ls, const char *rule_name,
                       const mfs_disc *ps, const char *ctx)
{
  mfs_status st;
  size_t bad = 0;
  memset(m, 0, sizeof *m);
  const mfs_quad_type *rule = mfs_quad_find(rule_name);
  CHECK(rule != NULL, "%s: rule %s", ctx, rule_name);
  if (!rule)
    return MFS_EINVAL;
  m->p = mfs_lattice_alloc(ls, &st);
  m->q = m->p ? mfs_quad_alloc(rule, m->p, &st) : NULL;
  m->pl = m->q ? mfs_plan_alloc(ps, m->p, m->q, &st) : NULL;
  if (m->pl)
    st = mfs_plan_tabulate(m->pl, 1, &bad);
  CHECK(m->pl && st == MFS_OK, "%s: building the model: status %d (%s), point %zu", ctx, st,
        mfs_strerror(st), bad);
  if (m->pl)
    CHECK(mfs_plan_rcond(m->pl) > 0.0 && mfs_plan_rcond(m->pl) <= 1.0, "%s: plan rcond %g", ctx,
          mfs_plan_rcond(m->pl));
  if (st != MFS_OK)
    model_free(m);
  return st;
}

static double vmaxabs(size_t n, const double *x)
{
  double m = 0.0;
  for (size_t i = 0; i < n; i++)
    m = fmax(m, fabs(x[i]));
  return m;
}

static double dot(size_t n, const double *x, const double *y)
{
  double s = 0.0;
  for (size_t i = 0; i < n; i++)
    s += x[i] * y[i];
  return s;
}

/* u^T A v */
static double energy(const mfs_csr *A, const double *u, const double *v, double *work)
{
  mfs_csr_matvec(A, v, work);
  return dot(A->nrow, u, work);
}

/* The plan's table against a direct evaluation with brute-force neighbours. */
static void check_plan_table(const model *m, const char *ctx)
{
  const mfs_plan *pl = m->pl;
  const mfs_particles *p = m->p;
  int dim = p->dim, nc = mfs_plan_ncomp(pl);
  const mfs_disc *pd = mfs_plan_disc(pl);
  const mfs_shape_ctx sc = {.kernel = pd->kernel, .dim = dim, .a = mfs_plan_support(pl),
                             .rcond_min = 1e-12};
  int *idx = malloc(p->n * sizeof *idx);
  double *d = malloc(p->n * dim * sizeof *d), *v = malloc(p->n * sizeof *v);
  double *out = malloc(p->n * nc * sizeof *out);
  double *work = malloc(mfs_shape_work_len(dim, (int)p->n) * sizeof *work);
  size_t step = m->q->n / 7 + 1, bad = 0;
  for (size_t Q = 3; Q < m->q->n; Q += step) {
    const double *xq = m->q->x + Q * dim;
    int nn = 0, self = -1;
    for (size_t I = 0; I < p->n; I++) {
      double t[3], r2 = 0.0;
      mfs_box_delta(&p->box, xq, p->x + I * dim, t);
      for (int k = 0; k < dim; k++)
        r2 += t[k] * t[k];
      if (r2 < sc.a * sc.a) {
        if ((int)I == m->q->node[Q])
          self = nn;
        memcpy(d + nn * dim, t, dim * sizeof *t);
        v[nn] = p->vol[I];
        idx[nn++] = (int)I;
      }
    }
    double rc;
    mfs_status st = pd->shape->eval(&sc, nn, d, v, self, mfs_plan_order(pl), out, work, &rc);
    mfs_point pt;
    mfs_plan_point(pl, Q, &pt);
    if (st != MFS_OK || (size_t)nn != pt.nn) {
      bad++;
      continue;
    }
    for (int J = 0; J < nn; J++) {
      bad += pt.idx[J] != idx[J];
      for (int c = 0; c < nc; c++) {
        double t = out[J * nc + c], u = pt.phi[J * nc + c];
        bad += fabs(t - u) > 1e-14 * (fabs(t) + 1.0 / pow(sc.a, c == 0 ? 0 : 1 + (c > dim)));
      }
    }
  }
  CHECK(bad == 0, "%s: %zu mismatches between the plan's table and direct evaluation", ctx, bad);
  free(idx);
  free(d);
  free(v);
  free(out);
  free(work);
}

/* Scalar physics on a perturbed finite model. */
static void check_scalar(const mfs_lattice_spec *ls, const char *rule, const mfs_shape_type *sh,
                         const mfs_kernel_type *k, double D)
{
  char ctx[200];
  snprintf(ctx, sizeof ctx, "%dD %s %s %s %s D=%g%s", ls->dim,
           ls->lattice == MFS_LATTICE_HEX ? "hex" : ls->dim == 1 ? "line" : "square", rule,
           sh->name, k->name, D, ls->periodic ? " periodic" : "");
  mfs_disc ps = plan_disc(k, sh, D);
  model m;
  if (model_build(&m, ls, rule, &ps, ctx) != MFS_OK)
    return;
  const mfs_particles *p = m.p;
  size_t n = p->n;
  int dim = p->dim;
  mfs_material mat = {.physics = MFS_PHYS_SCALAR, .modulus = 2.3719, .density = 7.813};
  mfs_csr *K = NULL, *M = NULL;
  double *u = malloc(n * sizeof *u), *y = malloc(n * sizeof *y), *w = malloc(n * sizeof *w);
  double *ml = malloc(n * sizeof *ml);
  mfs_status st = mfs_assemble_stiffness(m.pl, &mat, &K);
  CHECK(st == MFS_OK && K && K->nrow == n, "%s: stiffness status %d", ctx, st);
  mfs_status st2 = mfs_assemble_mass_consistent(m.pl, &mat, &M);
  CHECK(st2 == MFS_OK && M && M->nrow == n, "%s: consistent mass status %d", ctx, st2);
  int st3 = mfs_assemble_mass_lumped(m.pl, &mat, ml);
  CHECK(st3 == MFS_OK, "%s: lumped mass status %d", ctx, st3);
  if (st != MFS_OK || st2 != MFS_OK || st3 != MFS_OK)
    goto done;
  double V = mfs_particles_domain_volume(p);
  int pu = sh->partition_of_unity;
  CHECK(pu == (sh != &mfs_shape_sph), "%s: partition_of_unity flag %d", ctx, pu);
  /* gradients exact for linear fields; a linear field is not periodic */
  int lin = sh != &mfs_shape_sph && sh != &mfs_shape_shepard && !ls->periodic;

  /* symmetric: K_IJ = C sum_Q w_Q G_I . G_J uses the same gradients on both
   * sides, so it is symmetric for every shape type (kb and rl included) */
  double kmax, mmax;
  double asym = mfs_csr_asymmetry(K, &kmax);
  CHECK(kmax > 0.0 && asym <= 1e-13 * kmax, "%s: K asymmetry %.3g (max |K| %.3g)", ctx, asym,
        kmax);
  asym = mfs_csr_asymmetry(M, &mmax);
  CHECK(mmax > 0.0 && asym <= 1e-13 * mmax, "%s: M asymmetry %.3g", ctx, asym);

  /* constants: sum_J G_J = 0 at every quadrature point (all but sph) */
  if (pu) {
    for (size_t i = 0; i < n; i++)
      u[i] = 1.0;
    mfs_csr_matvec(K, u, y);
    double r = vmaxabs(n, y);
    CHECK(r <= 1e-12 * kmax, "%s: max |K 1| = %.3g (max |K| %.3g)", ctx, r, kmax);
  }
  /* lumped mass: for a partition of unity the row sums of the consistent
   * mass (eq. 131), adding up to rho V; for sph the particle masses rho V_I
   * (eq. 51) */
  for (size_t i = 0; i < n; i++)
    u[i] = 1.0;
  mfs_csr_matvec(M, u, y);
  double e = 0.0, tot = 0.0;
  for (size_t i = 0; i < n; i++) {
    e = fmax(e, fabs(ml[i] - (pu ? y[i] : mat.density * p->vol[i])));
    tot += ml[i];
  }
  CHECK(e <= 1e-13 * vmaxabs(n, ml), "%s: lumped mass vs %s: %.3g", ctx,
        pu ? "row sums of the consistent mass" : "rho V_I", e);
  CHECK_NEAR(tot, mat.density * V, 1e-12 * mat.density * V, "%s: total lumped mass", ctx);
  /* energy of linear fields: the discrete gradient of u_J = X_J is exactly
   * e_k at every quadrature point when sum_J G_J (X_J - X)^T = I (mls, kb,
   * rl), so u^T K u = C sum_Q w_Q = C V for any quadrature whose weights
   * add up to the volume (not only for gauss3 on a uniform lattice); the
   * fields of different directions are K-orthogonal. */
  if (lin) {
    double *ux = malloc(n * sizeof *ux);
    for (int a = 0; a < dim; a++) {
      /* coordinates relative to a point of the box: K annihilates constants */
      for (size_t i = 0; i < n; i++)
        u[i] = p->x[i * dim + a] - 0.5 * (p->box.lo[a] + p->box.hi[a]);
      if (a == 0)
        memcpy(ux, u, n * sizeof *u);
      double E = energy(K, u, u, w);
      CHECK_NEAR(E, mat.modulus * V, 1e-12 * mat.modulus * V, "%s: energy of u = x_%d", ctx, a);
      if (a == 1)
        CHECK_NEAR(energy(K, ux, u, w), 0.0, 1e-12 * mat.modulus * V,
                   "%s: x and y fields K-orthogonal", ctx);
    }
    free(ux);
  }
  check_plan_table(&m, ctx);
done:
  mfs_csr_free(K);
  mfs_csr_free(M);
  free(u);
  free(y);
  free(w);
  free(ml);
  model_free(&m);
}

/* SPH on an unperturbed periodic lattice.  The SPH gradients do not sum to
 * zero in general; at a quadrature point that is a centre of symmetry of the
 * lattice (a node, a midpoint, a square's centre) or a centre of 3-fold
 * rotational symmetry (a centroid of the hexagonal lattice's triangles),
 * sum_J V_J grad W_J = 0 by symmetry, and then K 1 = 0.  (Gauss points of a
 * cell other than its centre are no such centres, and there K 1 != 0.) */
static void check_sph_periodic(int dim, mfs_lattice_kind lat, const char *rule)
{
  char ctx[120];
  snprintf(ctx, sizeof ctx, "sph periodic %dD %s %s", dim,
           lat == MFS_LATTICE_HEX ? "hex" : "square/line", rule);
  mfs_lattice_spec ls = {dim, lat, 12, 10, DX, 1.0, 1, MFS_CELLS_QUAD, 0.0, 0};
  mfs_disc ps = plan_disc(&mfs_kernel_cubic, &mfs_shape_sph, 2.385);
  model m;
  if (model_build(&m, &ls, rule, &ps, ctx) != MFS_OK)
    return;
  mfs_material mat = {.physics = MFS_PHYS_SCALAR, .modulus = 1.913, .density = 1.0};
  mfs_csr *K = NULL;
  mfs_status st = mfs_assemble_stiffness(m.pl, &mat, &K);
  CHECK(st == MFS_OK, "%s: status %d", ctx, st);
  if (st == MFS_OK) {
    size_t n = m.p->n;
    double *u = malloc(n * sizeof *u), *y = malloc(n * sizeof *y), kmax;
    for (size_t i = 0; i < n; i++)
      u[i] = 1.0;
    mfs_csr_matvec(K, u, y);
    double asym = mfs_csr_asymmetry(K, &kmax), r = vmaxabs(n, y);
    CHECK(r <= 1e-12 * kmax, "%s: max |K 1| = %.3g (max |K| %.3g)", ctx, r, kmax);
    CHECK(asym <= 1e-13 * kmax, "%s: asymmetry %.3g", ctx, asym);
    free(u);
    free(y);
  }
  mfs_csr_free(K);
  model_free(&m);
}

/* Plane strain on a perturbed finite 2D model. */
static void check_plane_strain(mfs_lattice_kind lat, const char *rule, const mfs_shape_type *sh)
{
  char ctx[120];
  snprintf(ctx, sizeof ctx, "plane strain %s %s %s", lat == MFS_LATTICE_HEX ? "hex" : "square",
           rule, sh->name);
  mfs_lattice_spec ls = {2, lat, 11, 10, DX, 1.0, 0, MFS_CELLS_QUAD, 0.3, 2718};
  mfs_disc ps = plan_disc(&mfs_kernel_quartic, sh, 2.385);
  model m;
  if (model_build(&m, &ls, rule, &ps, ctx) != MFS_OK)
    return;
  const mfs_particles *p = m.p;
  size_t n = p->n, N = 2 * n;
  /* mu = 1.3791, lambda = 2.0719: nu = lambda / (2 (lambda + mu)) */
  mfs_material mat = {.physics = MFS_PHYS_PLANE_STRAIN,
                      .modulus = 1.3791,
                      .poisson = 2.0719 / (2.0 * (2.0719 + 1.3791)),
                      .density = 3.1};
  CHECK(mfs_physics_ndof(mat.physics) == 2, "plane strain: 2 dofs per particle");
  CHECK_NEAR(mfs_material_lambda(&mat), 2.0719, 1e-14, "lambda from nu");
  mfs_csr *K = NULL, *M = NULL;
  double *u = malloc(N * sizeof *u), *y = malloc(N * sizeof *y), *w = malloc(N * sizeof *w);
  double *ml = malloc(N * sizeof *ml);
  mfs_status st = mfs_assemble_stiffness(m.pl, &mat, &K);
  CHECK(st == MFS_OK && K && K->nrow == N && K->ncol == N, "%s: status %d", ctx, st);
  mfs_status st2 = mfs_assemble_mass_consistent(m.pl, &mat, &M);
  int st3 = mfs_assemble_mass_lumped(m.pl, &mat, ml);
  CHECK(st2 == MFS_OK && st3 == MFS_OK && M->nrow == N, "%s: mass status %d %d", ctx, st2, st3);
  if (st != MFS_OK || st2 != MFS_OK || st3 != MFS_OK)
    goto done;
  double kmax, V = mfs_particles_domain_volume(p);
  double asym = mfs_csr_asymmetry(K, &kmax);
  CHECK(asym <= 1e-13 * kmax, "%s: K asymmetry %.3g (max %.3g)", ctx, asym, kmax);
  double xc = 0.5 * (p->box.lo[0] + p->box.hi[0]), yc = 0.5 * (p->box.lo[1] + p->box.hi[1]);
  /* rigid modes: two translations and the rotation u = (-y, x) */
  for (int mode = 0; mode < 3; mode++) {
    for (size_t i = 0; i < n; i++) {
      double x = p->x[2 * i] - xc, yy = p->x[2 * i + 1] - yc;
      u[2 * i] = mode == 0 ? 1.0 : mode == 1 ? 0.0 : -yy;
      u[2 * i + 1] = mode == 0 ? 0.0 : mode == 1 ? 1.0 : x;
    }
    mfs_csr_matvec(K, u, y);
    double r = vmaxabs(N, y);
    CHECK(r <= 1e-11 * kmax * vmaxabs(N, u), "%s: rigid mode %d: max |K u| = %.3g (max |K| %.3g)",
          ctx, mode, r, kmax);
  }
  /* uniform strains, exact energies: u = (x, 0): lambda + 2 mu;
   * u = (y, x) (gamma_xy = 2): 4 mu; u = (x, y): 2 (lambda + 2 mu) + 2 lambda */
  double lam = mfs_material_lambda(&mat), mu = mat.modulus;
  double want[3] = {(lam + 2 * mu) * V, 4 * mu * V, (2 * (lam + 2 * mu) + 2 * lam) * V};
  for (int s = 0; s < 3; s++) {
    for (size_t i = 0; i < n; i++) {
      double x = p->x[2 * i] - xc, yy = p->x[2 * i + 1] - yc;
      u[2 * i] = s == 0 ? x : s == 1 ? yy : x;
      u[2 * i + 1] = s == 0 ? 0.0 : s == 1 ? x : yy;
    }
    CHECK_NEAR(energy(K, u, u, w), want[s], 1e-12 * want[s], "%s: energy of uniform strain %d",
               ctx, s);
  }
  /* mass: symmetric, per dof, lumped = row sums, total 2 rho V */
  double mmax;
  asym = mfs_csr_asymmetry(M, &mmax);
  CHECK(asym <= 1e-13 * mmax, "%s: M asymmetry %.3g", ctx, asym);
  CHECK(mfs_csr_get(M, 0, 1) == 0.0 && mfs_csr_get(M, 1, 0) == 0.0,
        "%s: consistent mass couples the two components", ctx);
  for (size_t i = 0; i < N; i++)
    u[i] = 1.0;
  mfs_csr_matvec(M, u, y);
  double e = 0.0, tot = 0.0;
  for (size_t i = 0; i < N; i++) {
    e = fmax(e, fabs(y[i] - ml[i]));
    tot += ml[i];
  }
  CHECK(e <= 1e-13 * vmaxabs(N, ml), "%s: lumped vs row sums %.3g", ctx, e);
  CHECK_NEAR(tot, 2.0 * mat.density * V, 1e-12 * mat.density * V, "%s: total lumped mass", ctx);
done:
  mfs_csr_free(K);
  mfs_csr_free(M);
  free(u);
  free(y);
  free(w);
  free(ml);
  model_free(&m);
}

/* mfs_stencil against the row of the centre particle of a finite lattice of
 * 61 (1D) or 31 x 31 nodes: its support and quadrature points are farther
 * than 2a from the boundary, so the row is that of the infinite lattice. */
static void check_stencil(int dim, mfs_lattice_kind lat, const char *rule,
                          const mfs_kernel_type *k, const mfs_shape_type *sh, double D,
                          int consistent)
{
  char ctx[160];
  snprintf(ctx, sizeof ctx, "stencil %dD %s %s %s %s D=%g %s mass", dim,
           lat == MFS_LATTICE_HEX ? "hex" : dim == 1 ? "line" : "square", rule, k->name, sh->name,
           D, consistent ? "consistent" : "lumped");
  double gamma = 1.0;
  mfs_disc s = plan_disc(k, sh, D);
  s.dim = dim;
  s.source = (mfs_source){.lattice = lat, .spacing = DX, .gamma = gamma};
  s.quadrature = mfs_quad_find(rule);
  s.material = (mfs_material){.physics = MFS_PHYS_SCALAR, .modulus = 1.7, .density = 2.9};
  s.consistent_mass = consistent;
  mfs_stencil_entry *e = NULL;
  size_t ne = 0, bad = 0;
  mfs_status st = mfs_stencil(&s, &e, &ne, &bad);
  CHECK(st == MFS_OK && ne > 0, "%s: status %d", ctx, st);
  if (st != MFS_OK)
    return;
  int nx = dim == 1 ? 61 : 31, ny = dim == 1 ? 1 : 31;
  mfs_lattice_spec ls = {.dim = dim,
                         .lattice = lat,
                         .nx = nx,
                         .ny = ny,
                         .dx = DX,
                         .gamma = gamma,
                         .cells = s.quadrature->cells};
  model m;
  if (model_build(&m, &ls, rule, &s, ctx) != MFS_OK) {
    free(e);
    return;
  }
  size_t Ic = (size_t)(ny / 2) * nx + nx / 2, n = m.p->n;
  mfs_csr *K = NULL, *M = NULL;
  double *ml = malloc(n * sizeof *ml);
  st = mfs_assemble_stiffness(m.pl, &s.material, &K);
  mfs_status st2 = consistent ? mfs_assemble_mass_consistent(m.pl, &s.material, &M)
                              : mfs_assemble_mass_lumped(m.pl, &s.material, ml);
  CHECK(st == MFS_OK && st2 == MFS_OK, "%s: finite model status %d %d", ctx, st, st2);
  if (st == MFS_OK && st2 == MFS_OK) {
    double kmax = 0.0, mmax = 0.0;
    for (size_t i = 0; i < ne; i++) {
      kmax = fmax(kmax, fabs(e[i].K));
      mmax = fmax(mmax, fabs(e[i].M));
    }
    /* The row and the stencil are equal as vectors.  Their patterns need
     * not be: at D = 2 (an integer multiple of the spacing) particles sit
     * exactly on the edge of the support, and whether roundoff puts them in
     * or out differs between the periodic and the finite coordinates; their
     * entries are zero or of the order of w(1 - eps) (1e-45).  So: every
     * stencil entry equals the finite entry at its offset (0 if not stored),
     * and finite entries at offsets the stencil lacks are negligible. */
    double ek = 0.0, em = 0.0, extra = 0.0;
    for (size_t i = 0; i < ne; i++) {
      int J = -1;
      for (size_t I = 0; I < n && J < 0; I++)
        if (m.p->ij[2 * I] - m.p->ij[2 * Ic] == e[i].j &&
            m.p->ij[2 * I + 1] - m.p->ij[2 * Ic + 1] == e[i].k)
          J = (int)I;
      CHECK(J >= 0, "%s: offset (%d, %d) outside the finite model", ctx, e[i].j, e[i].k);
      if (J < 0)
        continue;
      ek = fmax(ek, fabs(e[i].K - mfs_csr_get(K, Ic, J)));
      double mfin = consistent ? mfs_csr_get(M, Ic, J) : ((size_t)J == Ic ? ml[Ic] : 0.0);
      em = fmax(em, fabs(e[i].M - mfin));
    }
    for (size_t t = K->ptr[Ic]; t < K->ptr[Ic + 1]; t++) {
      int J = K->idx[t], found = 0;
      int dj = m.p->ij[2 * J] - m.p->ij[2 * Ic], dk = m.p->ij[2 * J + 1] - m.p->ij[2 * Ic + 1];
      for (size_t i = 0; i < ne && !found; i++)
        found = e[i].j == dj && e[i].k == dk;
      if (!found) {
        extra = fmax(extra, fabs(K->val[t]) / kmax);
        if (consistent)
          extra = fmax(extra, fabs(mfs_csr_get(M, Ic, J)) / mmax);
      }
    }
    CHECK(ek <= 1e-12 * kmax, "%s: K entries differ by %.3g (max %.3g)", ctx, ek, kmax);
    CHECK(em <= 1e-12 * mmax, "%s: M entries differ by %.3g (max %.3g)", ctx, em, mmax);
    CHECK(extra <= 1e-12, "%s: finite-row entry %.3g (relative) missing from the stencil", ctx,
          extra);
    /* sorted by (k, j), offsets distinct; symmetric about the origin (an
     * entry without its mirror image must be negligible, as above) */
    size_t unsorted = 0, asym = 0;
    for (size_t i = 0; i < ne; i++) {
      if (i > 0 && (e[i].k < e[i - 1].k || (e[i].k == e[i - 1].k && e[i].j <= e[i - 1].j)))
        unsorted++;
      double Km = 0.0, Mm = 0.0;
      for (size_t j = 0; j < ne; j++)
        if (e[j].j == -e[i].j && e[j].k == -e[i].k) {
          Km = e[j].K;
          Mm = e[j].M;
        }
      asym += fabs(Km - e[i].K) > 1e-13 * kmax || fabs(Mm - e[i].M) > 1e-13 * mmax;
    }
    CHECK(unsorted == 0, "%s: %zu entries out of (k, j) order", ctx, unsorted);
    CHECK(asym == 0, "%s: %zu entries differ from their mirror image", ctx, asym);
  }
  free(ml);
  mfs_csr_free(K);
  mfs_csr_free(M);
  model_free(&m);
  free(e);
}

/* mfs_assemble (pattern and values in one sweep) against the separate path
 * mfs_assemble_pattern + mfs_assemble_fill: the same ptr, idx and values bit
 * for bit, and the same lumped masses, with every third particle fixed (and
 * with none), with the plan's table and without one (streamed). */
static void check_fused(const mfs_lattice_spec *ls, const char *rule_name, const mfs_shape_type *sh,
                        mfs_physics_kind phys, int consistent, int table, int fix)
{
  char ctx[160];
  snprintf(ctx, sizeof ctx, "fused %dD %s %s %s %s %s %s", ls->dim, rule_name, sh->name,
           phys == MFS_PHYS_PLANE_STRAIN ? "plane-strain" : "scalar",
           consistent ? "consistent" : "lumped", table ? "table" : "streamed",
           fix ? "fixed" : "free");
  mfs_status st;
  const mfs_quad_type *rule = mfs_quad_find(rule_name);
  CHECK(rule != NULL, "%s: rule", ctx);
  if (!rule)
    return;
  mfs_disc ps = plan_disc(&mfs_kernel_quartic, sh, 2.385);
  mfs_particles *p = mfs_lattice_alloc(ls, &st);
  mfs_quad *q = p ? mfs_quad_alloc(rule, p, &st) : NULL;
  mfs_plan *pl = q ? mfs_plan_alloc(&ps, p, q, &st) : NULL;
  if (pl && table)
    st = mfs_plan_tabulate(pl, 1, NULL);
  CHECK(pl && st == MFS_OK, "%s: plan status %d", ctx, st);
  if (!pl || st != MFS_OK)
    goto out;
  mfs_material mat = {.physics = phys, .modulus = 1.3791, .poisson = 0.31, .density = 3.1};
  size_t n = p->n, nd = (size_t)mfs_physics_ndof(phys);
  unsigned char *fixed = calloc(n, 1);
  double *m1 = calloc(n * nd, sizeof *m1), *m2 = calloc(n * nd, sizeof *m2);
  for (size_t I = 0; I < n && fix; I++)
    fixed[I] = I % 3 == 1;
  const unsigned char *fx = fix ? fixed : NULL;
  mfs_csr *K1 = NULL, *M1 = NULL, *K2 = NULL, *M2 = NULL;
  st = mfs_assemble(pl, &mat, fx, &K1, consistent ? &M1 : NULL, consistent ? NULL : m1, NULL);
  CHECK(st == MFS_OK && K1 && (!consistent || M1), "%s: mfs_assemble status %d", ctx, st);
  mfs_status s2 = mfs_assemble_pattern(pl, (int)nd, fx, &K2);
  if (s2 == MFS_OK && consistent)
    s2 = mfs_assemble_pattern(pl, (int)nd, fx, &M2);
  if (s2 == MFS_OK)
    s2 = mfs_assemble_fill(pl, &mat, fx, K2, M2, consistent ? NULL : m2, NULL);
  CHECK(s2 == MFS_OK, "%s: pattern + fill status %d", ctx, s2);
  if (st == MFS_OK && s2 == MFS_OK) {
    size_t nf = 0;
    for (size_t I = 0; I < n; I++)
      nf += !(fx && fx[I]);
    CHECK(K1->nrow == nf * nd && K1->ncol == nf * nd && K1->nrow == K2->nrow,
          "%s: order %zu, separate %zu, free dofs %zu", ctx, K1->nrow, K2->nrow, nf * nd);
    size_t dp = 0, di = 0, dk = 0, dm = 0, dl = 0, nnz = K2->ptr[K2->nrow];
    for (size_t i = 0; i <= K1->nrow && K1->nrow == K2->nrow; i++)
      dp += K1->ptr[i] != K2->ptr[i];
    CHECK(dp == 0, "%s: %zu row pointers differ", ctx, dp);
    if (dp == 0) {
      for (size_t e = 0; e < nnz; e++) {
        di += K1->idx[e] != K2->idx[e];
        dk += K1->val[e] != K2->val[e];
        if (consistent)
          dm += M1->idx[e] != M2->idx[e] || M1->val[e] != M2->val[e] || M1->ptr[0] != 0;
      }
      for (size_t i = 0; i < K1->nrow && di == 0; i++) /* sorted within rows */
        for (size_t e = K1->ptr[i] + 1; e < K1->ptr[i + 1]; e++)
          di += K1->idx[e - 1] >= K1->idx[e];
      for (size_t i = 0; i < nf * nd && !consistent; i++)
        dl += m1[i] != m2[i];
    }
    CHECK(di == 0 && dk == 0 && dm == 0 && dl == 0,
          "%s: %zu columns, %zu K values, %zu M entries, %zu lumped masses differ (of %zu)", ctx,
          di, dk, dm, dl, nnz);
    if (consistent)
      CHECK(M1->ptr != K1->ptr && M1->idx != K1->idx && M1->ptr[M1->nrow] == nnz,
            "%s: M has its own copy of the pattern", ctx);
  }
  mfs_csr_free(K1);
  mfs_csr_free(M1);
  mfs_csr_free(K2);
  mfs_csr_free(M2);
  free(fixed);
  free(m1);
  free(m2);
out:
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
}

int main(void)
{
  const mfs_shape_type *shapes[] = {&mfs_shape_sph, &mfs_shape_shepard, &mfs_shape_mls,
                                    &mfs_shape_kb, &mfs_shape_rl};
  /* perturbed finite models */
  mfs_lattice_spec line = {1, MFS_LATTICE_LINE, 29, 0, DX, 1.0, 0, MFS_CELLS_QUAD, 0.3, 1618};
  mfs_lattice_spec sq = {2, MFS_LATTICE_SQUARE, 11, 10, DX, 1.0, 0, MFS_CELLS_QUAD, 0.3, 1414};
  mfs_lattice_spec tri = {2, MFS_LATTICE_SQUARE, 10, 11, DX, 1.0, 0, MFS_CELLS_TRI, 0.3, 1732};
  mfs_lattice_spec star = {2, MFS_LATTICE_SQUARE, 10, 10, DX, 1.0, 0, MFS_CELLS_STAR, 0.3, 2236};
  mfs_lattice_spec hex = {2, MFS_LATTICE_HEX, 11, 10, DX, 1.0, 0, MFS_CELLS_TRI, 0.3, 2646};
  mfs_lattice_spec sqp = {2, MFS_LATTICE_SQUARE, 11, 10, DX, 1.0, 1, MFS_CELLS_QUAD, 0.3, 3162};
  const char *r1[] = {"nodal", "stress", "gauss2"};
  const char *rq[] = {"nodal", "stress-quad", "gauss2"};
  for (int s = 0; s < 5; s++) {
    for (int r = 0; r < 3; r++) {
      check_scalar(&line, r1[r], shapes[s], &mfs_kernel_cubic, 2.385);
      check_scalar(&sq, rq[r], shapes[s], &mfs_kernel_quartic, 2.385);
    }
    check_scalar(&line, "gauss3", shapes[s], &mfs_kernel_wendland2, 1.7);
    check_scalar(&sq, "gauss1", shapes[s], &mfs_kernel_cubic, 1.8);
    check_scalar(&tri, "stress-tri", shapes[s], &mfs_kernel_wendland2, 2.385);
    check_scalar(&star, "stress-star", shapes[s], &mfs_kernel_quintic, 2.385);
    check_scalar(&hex, "stress-hex", shapes[s], &mfs_kernel_cubic, 2.385);
    check_scalar(&hex, "gauss2", shapes[s], &mfs_kernel_quartic, 1.8);
    check_scalar(&sqp, "stress-quad", shapes[s], &mfs_kernel_cubic, 2.385);
  }
  /* SPH: K 1 = 0 by symmetry on unperturbed periodic lattices */
  check_sph_periodic(1, MFS_LATTICE_LINE, "nodal");
  check_sph_periodic(1, MFS_LATTICE_LINE, "stress");
  check_sph_periodic(2, MFS_LATTICE_SQUARE, "nodal");
  check_sph_periodic(2, MFS_LATTICE_SQUARE, "stress-quad");
  check_sph_periodic(2, MFS_LATTICE_SQUARE, "gauss1");
  check_sph_periodic(2, MFS_LATTICE_HEX, "nodal");
  check_sph_periodic(2, MFS_LATTICE_HEX, "stress-hex");
  /* plane strain */
  const char *rs[] = {"nodal", "stress-quad", "gauss2"}, *rh[] = {"nodal", "stress-hex", "gauss2"};
  for (int r = 0; r < 3; r++) {
    check_plane_strain(MFS_LATTICE_SQUARE, rs[r], &mfs_shape_mls);
    check_plane_strain(MFS_LATTICE_HEX, rh[r], &mfs_shape_mls);
    check_plane_strain(MFS_LATTICE_SQUARE, rs[r], &mfs_shape_kb);
    check_plane_strain(MFS_LATTICE_HEX, rh[r], &mfs_shape_rl);
  }
  /* stencils */
  const mfs_kernel_type *ks[] = {&mfs_kernel_cubic, &mfs_kernel_quartic};
  const double Ds[] = {2.0, 1.5};
  const char *sl[] = {"nodal", "gauss2", "stress"}, *ss[] = {"nodal", "gauss2", "stress-quad"},
             *sh[] = {"nodal", "gauss2", "stress-hex"};
  for (int ik = 0; ik < 2; ik++)
    for (int id = 0; id < 2; id++)
      for (int r = 0; r < 3; r++) {
        int cm = (ik + id + r) & 1;
        check_stencil(1, MFS_LATTICE_LINE, sl[r], ks[ik], &mfs_shape_mls, Ds[id], cm);
        check_stencil(2, MFS_LATTICE_SQUARE, ss[r], ks[ik], &mfs_shape_mls, Ds[id], cm);
        check_stencil(2, MFS_LATTICE_HEX, sh[r], ks[ik], &mfs_shape_mls, Ds[id], !cm);
      }
  check_stencil(2, MFS_LATTICE_SQUARE, "gauss2", &mfs_kernel_cubic, &mfs_shape_sph, 2.0, 1);
  check_stencil(2, MFS_LATTICE_HEX, "stress-hex", &mfs_kernel_quartic, &mfs_shape_rl, 2.0, 0);
  check_stencil(1, MFS_LATTICE_LINE, "stress", &mfs_kernel_cubic, &mfs_shape_kb, 1.5, 1);
  /* the one sweep against the separate pattern and fill */
  for (int t = 0; t < 2; t++)
    for (int fix = 0; fix < 2; fix++) {
      check_fused(&line, "gauss2", &mfs_shape_mls, MFS_PHYS_SCALAR, fix, t, fix);
      check_fused(&sq, "stress-quad", &mfs_shape_mls, MFS_PHYS_SCALAR, 0, t, fix);
      check_fused(&sq, "gauss2", &mfs_shape_sph, MFS_PHYS_SCALAR, 1, t, fix);
      check_fused(&hex, "stress-hex", &mfs_shape_rl, MFS_PHYS_PLANE_STRAIN, !fix, t, fix);
      check_fused(&sqp, "stress-quad", &mfs_shape_kb, MFS_PHYS_PLANE_STRAIN, fix, t, fix);
    }
  /* several blocks of rows (2048 with a table, at least 1024 streamed), so
   * that with threads the blocks land in their places in turn */
  mfs_lattice_spec big = {2, MFS_LATTICE_SQUARE, 61, 59, DX, 1.0, 0, MFS_CELLS_QUAD, 0.3, 4142};
  for (int t = 0; t < 2; t++) {
    check_fused(&big, "stress-quad", &mfs_shape_mls, MFS_PHYS_SCALAR, 0, t, 1);
    check_fused(&big, "gauss2", &mfs_shape_mls, MFS_PHYS_PLANE_STRAIN, 1, t, 0);
  }
  return check_summary("test_assemble");
}
