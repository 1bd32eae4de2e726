/* Finite models, ARPACK eigenvalues, zero-energy modes, element bounds and
 * the Fourier estimate (lib/mfs_model, mfs_eigen, mfs_bound; paper 003
 * section 5).  Independent paths are compared: ARPACK against LAPACK dense,
 * the spectrum of periodic models against the Bloch symbol of
 * lib/mfs_dispersion, the streaming bound against the table bound, and the
 * linear finite element limit (D = 1) against its exact eigenvalues. */
#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stdio.h>

#include "check.h"
#include "mfstab.h"

static mfs_model_spec spec1(int n, double D, const char *quad)
{
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.source.nx = n;
  s.disc.dilation = D;
  s.disc.quadrature = mfs_quad_find(quad);
  return s;
}

static mfs_model_spec spec2(int nx, int ny, double D, const char *quad)
{
  mfs_model_spec s = spec1(nx, D, quad);
  s.disc.dim = 2;
  s.disc.source.lattice = MFS_LATTICE_SQUARE;
  s.disc.source.ny = ny;
  s.disc.source.lx = 1.137;
  s.disc.source.ly = 0.8725;
  return s;
}

static mfs_model *build(const mfs_model_spec *s, const char *what)
{
  mfs_status st;
  size_t bad = 0;
  mfs_model *m = mfs_model_alloc(s, &st, &bad);
  CHECK(m != NULL, "%s: model: %s (point %zu)", what, mfs_strerror(st), bad);
  return m;
}

static int cmp_dbl(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The proven steps of a model with largest eigenvalue lam: the Gershgorin
 * bound (lumped, positive masses) is above it, the certification succeeds at
 * 1.001 lam and fails at 0.999 lam. */
static void check_steps(const mfs_model *m, double lam, const char *what)
{
  mfs_pencil P = {m->K, m->M, m->m};
  if (m->m) {
    mfs_gershgorin_result g;
    mfs_gershgorin_csr(m->K, m->m, m->dof, &g);
    if (g.nonpositive == 0)
      CHECK(g.lambda >= lam * (1.0 - 1e-12), "%s: gershgorin %.10g below lambda_max %.10g", what,
            g.lambda, lam);
  }
  mfs_certificate c1, c2;
  mfs_status s1 = mfs_eig_certify(&P, 1.001 * lam, &c1), s2 = mfs_eig_certify(&P, 0.999 * lam, &c2);
  CHECK(s1 == MFS_OK && c1.ok, "%s: certification fails at 1.001 lambda_max", what);
  CHECK(s2 == MFS_OK && !c2.ok, "%s: certification succeeds at 0.999 lambda_max", what);
}

/* Largest eigenvalue by ARPACK and by dense LAPACK; the element bound
 * (table and streaming) against it. */
static void check_max(const mfs_model_spec *s, const char *what)
{
  mfs_model *m = build(s, what);
  if (!m)
    return;
  mfs_pencil P = {m->K, m->M, m->m};
  double lam = 0.0, *w = malloc(m->n * sizeof *w);
  mfs_eig_info info;
  mfs_status st = mfs_eig_max(&P, NULL, &lam, NULL, &info);
  CHECK(st == MFS_OK, "%s: mfs_eig_max: %s (info %d)", what, mfs_strerror(st), info.info);
  st = mfs_eig_dense(&P, w);
  CHECK(st == MFS_OK, "%s: mfs_eig_dense: %s", what, mfs_strerror(st));
  double ref = w[m->n - 1];
  CHECK_NEAR(lam / ref, 1.0, 1e-10, "%s: ARPACK lambda_max vs dense (n = %zu)", what, m->n);
  CHECK(info.residual < 1e-10, "%s: residual %.3g", what, info.residual);
  CHECK(w[0] > -1e-10 * ref, "%s: K not positive semidefinite: lambda_min %.3g", what, w[0]);

  mfs_bound_result b, bs;
  st = mfs_bound_of_model(m, &b);
  CHECK(st == MFS_OK, "%s: bound: %s", what, mfs_strerror(st));
  st = mfs_bound_model(s, &bs, NULL);
  CHECK(st == MFS_OK, "%s: streaming bound: %s", what, mfs_strerror(st));
  CHECK_NEAR(bs.lambda / b.lambda, 1.0, 1e-12, "%s: streaming vs table bound", what);
  CHECK(bs.negative_phi == b.negative_phi && bs.points == b.points,
        "%s: streaming vs table: negative phi %zu/%zu points %zu/%zu", what, bs.negative_phi,
        b.negative_phi, bs.points, b.points);
  CHECK(bs.evaluated <= b.evaluated, "%s: streaming evaluated %zu > %zu", what, bs.evaluated,
        b.evaluated);
  if (!s->disc.consistent_mass && b.negative_phi == 0)
    CHECK(b.lambda >= ref * (1.0 - 1e-12), "%s: bound %.10g below lambda_max %.10g", what,
          b.lambda, ref);

  /* Gershgorin with the lumped mass: above lambda_max; the streamed rows equal the CSR */
  if (!s->disc.consistent_mass) {
    mfs_gershgorin_result g, gs;
    st = mfs_gershgorin_csr(m->K, m->m, m->dof, &g);
    CHECK(st == MFS_OK && g.nonpositive == 0, "%s: gershgorin %s, %zu masses <= 0", what,
          mfs_strerror(st), g.nonpositive);
    CHECK(g.lambda >= ref * (1.0 - 1e-12), "%s: gershgorin %.10g below lambda_max %.10g", what,
          g.lambda, ref);
    CHECK(g.lambda <= 2.0 * ref, "%s: gershgorin / lambda_max = %.4f > 2", what, g.lambda / ref);
    printf("gershgorin/lambda_max %.4f  element bound/lambda_max %.4f%s  %s\n", g.lambda / ref,
           b.lambda / ref, b.negative_phi ? " (not valid: phi < 0)" : "", what);
    st = mfs_gershgorin_plan(m->pl, &m->mat, s->fixed != MFS_FIX_NONE ? m->fixed : NULL, &gs);
    CHECK(st == MFS_OK && gs.argmax == g.argmax, "%s: streamed gershgorin %s, row %zu vs %zu",
          what, mfs_strerror(st), gs.argmax, g.argmax);
    CHECK_NEAR(gs.lambda / g.lambda, 1.0, 1e-13, "%s: streamed vs CSR gershgorin", what);
  }
  /* certification: sigma M - K factors at 1.001 lambda_max, not at 0.999 */
  mfs_certificate c;
  st = mfs_eig_certify(&P, 1.001 * ref, &c);
  CHECK(st == MFS_OK && c.ok, "%s: certification fails at 1.001 lambda_max (%s)", what,
        mfs_strerror(st));
  CHECK(c.margin > 0.0 && c.margin < 1e-10, "%s: rounding margin %.3g (row %d)", what, c.margin,
        c.max_row);
  st = mfs_eig_certify(&P, 0.999 * ref, &c);
  CHECK(st == MFS_OK && !c.ok, "%s: certification succeeds at 0.999 lambda_max", what);
  mfs_certify_opts co = {.lambda_est = lam};
  mfs_certify_result cr;
  st = mfs_eig_certify_search(&P, &co, &cr);
  CHECK(st == MFS_OK && cr.ok && cr.lambda_upper >= ref * (1.0 - 1e-13) &&
          cr.lambda_upper <= ref * (1.0 + 1e-5),
        "%s: search from the Lanczos value: ok %d sigma/lambda_max %.9f after %d", what, cr.ok,
        cr.sigma / ref, cr.factorizations);
  /* the factorization in the geometric order (the particles' coordinates, as mfstab bound
   * --certify passes them): the same search, the same sigma; 1.001 and 0.999 lambda_max */
  double *x = mfs_model_coords(m);
  CHECK(x != NULL, "%s: mfs_model_coords", what);
  if (x) {
    mfs_certify_opts cg = {.lambda_est = lam, .coord = x, .coord_dim = m->p->dim};
    mfs_certify_result rg;
    st = mfs_eig_certify_search(&P, &cg, &rg);
    CHECK(st == MFS_OK && rg.ok && rg.sigma == cr.sigma && rg.factorizations == cr.factorizations,
          "%s: geometric order: ok %d sigma %.17g vs %.17g after %d vs %d", what, rg.ok, rg.sigma,
          cr.sigma, rg.factorizations, cr.factorizations);
    CHECK(rg.margin > 0.0 && rg.margin < 1e-10, "%s: geometric order: margin %.3g", what,
          rg.margin);
    double at[2] = {1.001, 0.999};
    for (int k = 0; k < 2; k++) {
      mfs_certify_opts c1 = {.lambda_est = at[k] * ref, .gap = 1e-300, .max_factorizations = 1,
                             .coord = x, .coord_dim = m->p->dim};
      st = mfs_eig_certify_search(&P, &c1, &rg);
      CHECK(st == MFS_OK && rg.ok == (k == 0), "%s: geometric order at %.3f lambda_max: ok %d",
            what, at[k], rg.ok);
    }
    /* a search through failures: the factor reused after a failed factorization (its
     * analysis and permuted matrix built once); the bracket holds lambda_max */
    mfs_certify_opts cf = {.lambda_est = 0.99 * ref, .gap = 2e-3, .growth = 2.0, .coord = x,
                           .coord_dim = m->p->dim, .refine = 3};
    st = mfs_eig_certify_search(&P, &cf, &rg);
    CHECK(st == MFS_OK && rg.ok && rg.factorizations > 2 && rg.sigma_failed < ref &&
            rg.sigma_failed > 0.99 * ref && rg.lambda_upper >= ref * (1.0 - 1e-13) &&
            rg.lambda_upper <= 1.02 * ref,
          "%s: search through failures: ok %d after %d, failed at %.6f, upper %.6f lambda_max",
          what, rg.ok, rg.factorizations, rg.sigma_failed / ref, rg.lambda_upper / ref);
    CHECK(rg.supernodes > 0 && rg.order_s >= 0.0 && rg.analyze_s >= 0.0 && rg.numeric_s >= 0.0,
          "%s: search statistics: %d supernodes, %g %g %g s", what, rg.supernodes, rg.order_s,
          rg.analyze_s, rg.numeric_s);
    /* CHOLMOD's orders, asked for: 1.001 and 0.999 lambda_max as with the default */
    const int orders[3] = {MFS_CERT_ORDER_AMD, MFS_CERT_ORDER_METIS, MFS_CERT_ORDER_NESDIS};
    for (int o = 0; o < 3; o++)
      for (int k = 0; k < 2; k++) {
        mfs_certify_opts c1 = {.lambda_est = at[k] * ref, .gap = 1e-300, .max_factorizations = 1,
                               .coord = x, .coord_dim = m->p->dim, .order = orders[o]};
        st = mfs_eig_certify_search(&P, &c1, &rg);
        CHECK(st == MFS_OK && rg.ok == (k == 0) && (k == 1 || rg.margin < 1e-10),
              "%s: order %d at %.3f lambda_max: ok %d margin %.3g", what, orders[o], at[k], rg.ok,
              rg.margin);
      }
    for (size_t i = 0; i < m->n; i++) /* the coordinates are the particles' */
      for (int d = 0; d < m->p->dim; d++)
        if (x[i * (size_t)m->p->dim + (size_t)d] !=
            m->p->x[(m->dof[i] / (size_t)m->ndof) * (size_t)m->p->dim + (size_t)d]) {
          CHECK(0, "%s: coordinate %zu,%d", what, i, d);
          i = m->n;
          break;
        }
  }
  mfs_free(x);
  free(w);
  mfs_model_free(m);
}

static void test_arpack_vs_dense(void)
{
  mfs_model_spec s = spec1(41, 2.0, "gauss2");
  check_max(&s, "1D free gauss2 cubic mls lumped");
  s.disc.consistent_mass = 1;
  s.disc.dilation = 2.5;
  check_max(&s, "1D free gauss2 consistent D2.5");
  s = spec1(100, 1.7, "gauss3");
  s.disc.kernel = &mfs_kernel_quartic;
  s.fixed = MFS_FIX_ENDS;
  s.disc.material.modulus = 2.385;
  s.disc.material.density = 0.731;
  s.disc.source.lx = 3.21;
  check_max(&s, "1D fixed quartic gauss3");
  s = spec1(60, 2.3, "nodal");
  s.disc.source.periodic = 1;
  check_max(&s, "1D periodic nodal");
  s = spec1(50, 1.6, "stress");
  s.disc.shape = &mfs_shape_shepard;
  s.disc.consistent_mass = 1;
  check_max(&s, "1D free stress shepard consistent");
  s = spec1(80, 2.0, "nodal");
  s.disc.shape = &mfs_shape_sph;
  s.disc.source.periodic = 1;
  check_max(&s, "1D periodic sph nodal");

  s = spec2(14, 11, 2.0, "gauss2");
  check_max(&s, "2D free gauss2 lumped");
  s = spec2(12, 12, 1.8, "gauss2");
  s.fixed = MFS_FIX_BOUNDARY;
  s.disc.consistent_mass = 1;
  check_max(&s, "2D fixed consistent");
  s = spec2(12, 10, 2.1, "stress-quad");
  s.disc.source.periodic = 1;
  check_max(&s, "2D periodic stress-quad");
  s = spec2(11, 9, 2.2, "stress-tri");
  s.disc.kernel = &mfs_kernel_quartic;
  s.fixed = MFS_FIX_BOUNDARY;
  check_max(&s, "2D fixed stress-tri quartic");
  s = spec2(9, 8, 2.0, "gauss2");
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.disc.material.poisson = 0.3;
  check_max(&s, "2D plane strain free");
  s = spec2(10, 9, 2.4, "stress-quad");
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.fixed = MFS_FIX_BOUNDARY;
  s.disc.consistent_mass = 1;
  check_max(&s, "2D plane strain fixed consistent");
  /* shape functions that read particle volumes (boundary volumes differ) */
  s = spec2(12, 12, 2.2, "stress-star");
  s.disc.shape = &mfs_shape_rl;
  s.fixed = MFS_FIX_BOUNDARY;
  check_max(&s, "2D fixed stress-star rl");
  s = spec2(12, 10, 2.0, "nodal");
  s.disc.shape = &mfs_shape_sph;
  check_max(&s, "2D free nodal sph");
  s = spec1(45, 2.0, "nodal");
  s.disc.shape = &mfs_shape_rl;
  check_max(&s, "1D free nodal rl");
  s = spec1(45, 2.5, "gauss2");
  s.disc.shape = &mfs_shape_kb;
  s.disc.kernel = &mfs_kernel_wendland2;
  check_max(&s, "1D free gauss2 kb wendland2");
}

/* Spectrum of a periodic model = Bloch symbol at kappa = 2 pi m / (N dx). */
static void check_bloch(const mfs_model_spec *s, const char *what)
{
  mfs_model *m = build(s, what);
  if (!m)
    return;
  mfs_pencil P = {m->K, m->M, m->m};
  size_t n = m->n;
  double *w = malloc(n * sizeof *w), *b = malloc(n * sizeof *b);
  mfs_status st = mfs_eig_dense(&P, w);
  CHECK(st == MFS_OK, "%s: dense: %s", what, mfs_strerror(st));
  mfs_disp_spec ds = {.disc = s->disc, .stretch = 1.0};
  ds.disc.source = (mfs_source){.lattice = s->disc.source.lattice,
                                .spacing = 1.0,
                                .gamma = s->disc.dim == 1 ? 1.0 : m->dy / m->dx};
  ds.disc.frame = MFS_FRAME_LAGRANGIAN;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&ds, &st);
  CHECK(pl != NULL, "%s: dispersion plan: %s", what, mfs_strerror(st));
  if (!pl) {
    free(w);
    free(b);
    mfs_model_free(m);
    return;
  }
  int nb = mfs_disp_branches(pl);
  double c2 = s->disc.material.modulus / s->disc.material.density, dx = m->dx;
  size_t cnt = 0;
  int ny = s->disc.dim == 1 ? 1 : s->disc.source.ny;
  for (int my = 0; my < ny; my++)
    for (int mx = 0; mx < s->disc.source.nx; mx++) {
      /* wave vector in 1/dx: 2 pi m / N per direction (dy = gamma dx) */
      double k[2] = {2.0 * M_PI * mx / s->disc.source.nx, s->disc.dim == 1 ? 0.0 : 2.0 * M_PI * my / (ny * m->dy / dx)};
      double complex K[16], M[16], o[4];
      mfs_disp_symbols(pl, 0.0, k, K, M);
      if (nb == 1) {
        o[0] = K[0] / M[0];
      } else {
        double kap = hypot(k[0], k[1]) / M_PI, th = atan2(k[1], k[0]);
        mfs_disp_omega2(pl, 0.0, kap, th, o);
      }
      for (int q = 0; q < nb && cnt < n; q++)
        b[cnt++] = creal(o[q]) * c2 / (dx * dx);
    }
  CHECK(cnt == n, "%s: %zu Bloch values for %zu eigenvalues", what, cnt, n);
  qsort(b, cnt, sizeof *b, cmp_dbl);
  double worst = 0.0, scale = w[n - 1];
  for (size_t i = 0; i < n && i < cnt; i++) {
    double e = fabs(w[i] - b[i]) / scale;
    worst = e > worst ? e : worst;
  }
  CHECK(worst < 1e-10, "%s: periodic spectrum vs Bloch symbol: worst relative %.3g", what, worst);
  check_steps(m, w[n - 1], what);
  mfs_disp_plan_free(pl);
  free(w);
  free(b);
  mfs_model_free(m);
}

static void test_bloch(void)
{
  mfs_model_spec s = spec1(24, 2.0, "nodal");
  s.disc.source.periodic = 1;
  s.disc.source.lx = 2.37;
  check_bloch(&s, "1D periodic nodal");
  s = spec1(30, 1.5, "stress");
  s.disc.source.periodic = 1;
  check_bloch(&s, "1D periodic stress");
  s = spec1(32, 2.6, "gauss2");
  s.disc.source.periodic = 1;
  s.disc.consistent_mass = 1;
  s.disc.kernel = &mfs_kernel_quartic;
  s.disc.material.modulus = 3.3;
  check_bloch(&s, "1D periodic gauss2 consistent quartic");
  s = spec2(10, 12, 2.0, "nodal");
  s.disc.source.periodic = 1;
  s.disc.source.lx = 1.0;
  s.disc.source.ly = 1.2;
  check_bloch(&s, "2D periodic nodal");
  s = spec2(10, 10, 1.8, "gauss2");
  s.disc.source.periodic = 1;
  s.disc.source.lx = s.disc.source.ly = 1.0;
  s.disc.consistent_mass = 1;
  check_bloch(&s, "2D periodic gauss2 consistent");
}

/* Zero-energy modes by shift-invert ARPACK against the dense count. */
static void check_zero(const mfs_model_spec *s, int want, int want_rigid, const char *what)
{
  mfs_model *m = build(s, what);
  if (!m)
    return;
  mfs_pencil P = {m->K, m->M, m->m};
  double lam, tol = 1e-8;
  mfs_eig_info info;
  mfs_status st = mfs_eig_max(&P, NULL, &lam, NULL, &info);
  CHECK(st == MFS_OK, "%s: max: %s", what, mfs_strerror(st));
  mfs_zero_opts zo = {tol, 0, 0, 1};
  mfs_zero_modes z;
  st = mfs_eig_zero_modes(&P, lam, &zo, NULL, &z, &info);
  CHECK(st == MFS_OK, "%s: zero modes: %s (info %d %s)", what, mfs_strerror(st), info.info,
        info.routine);
  double *w = malloc(m->n * sizeof *w);
  mfs_eig_dense(&P, w);
  int dense = 0;
  for (size_t i = 0; i < m->n; i++)
    dense += w[i] <= tol * lam;
  CHECK(z.count == dense, "%s: %d zero modes, dense %d", what, z.count, dense);
  check_steps(m, w[m->n - 1], what);
  if (want >= 0)
    CHECK(z.count == want, "%s: %d zero modes, want %d", what, z.count, want);
  if ((size_t)dense < m->n)
    CHECK_NEAR(z.lambda_min_nonzero / w[dense], 1.0, 1e-9, "%s: lambda_min_nonzero", what);
  CHECK(info.residual < 1e-8, "%s: residual %.3g", what, info.residual);
  /* the modes are null vectors */
  for (int k = 0; k < z.count; k++) {
    int null = 0;
    CHECK(mfs_eig_is_null(&P, z.modes + (size_t)k * m->n, lam, 10 * tol, &null) == MFS_OK && null,
          "%s: mode %d not null", what, k);
  }
  int nr = mfs_model_rigid_fields(m, NULL), rigid = 0;
  double *r = nr ? malloc((size_t)nr * m->n * sizeof *r) : NULL;
  mfs_model_rigid_fields(m, r);
  for (int k = 0; k < nr; k++) {
    int null = 0;
    mfs_eig_is_null(&P, r + (size_t)k * m->n, lam, tol, &null);
    rigid += null;
  }
  CHECK(rigid == want_rigid, "%s: %d rigid modes, want %d", what, rigid, want_rigid);
  free(r);
  free(w);
  free(z.modes);
  mfs_model_free(m);
}

static void test_zero_modes(void)
{
  mfs_model_spec s = spec1(40, 2.0, "nodal");
  s.disc.source.periodic = 1;
  check_zero(&s, 2, 1, "1D periodic nodal N even: rigid + sawtooth");
  s.disc.source.nx = 41;
  check_zero(&s, 1, 1, "1D periodic nodal N odd");
  s = spec1(40, 2.0, "stress");
  s.disc.source.periodic = 1;
  check_zero(&s, 1, 1, "1D periodic stress points");
  s = spec1(41, 2.0, "gauss2");
  check_zero(&s, 1, 1, "1D free gauss2");
  s.fixed = MFS_FIX_ENDS;
  check_zero(&s, 0, 0, "1D fixed gauss2");
  s = spec1(30, 2.0, "nodal");
  s.disc.source.periodic = 1;
  s.disc.consistent_mass = 1;
  check_zero(&s, 2, 1, "1D periodic nodal consistent");
  s = spec2(10, 10, 2.0, "nodal");
  s.disc.source.periodic = 1;
  check_zero(&s, 4, 1, "2D periodic nodal: rigid + 3 spurious");
  s = spec2(10, 9, 2.0, "gauss2");
  check_zero(&s, 1, 1, "2D free gauss2");
  s = spec2(8, 8, 2.0, "gauss2");
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  check_zero(&s, 3, 3, "2D plane strain free gauss2: 2 translations + rotation");

  /* the sawtooth (-1)^I is in the null space of periodic nodal integration */
  s = spec1(40, 2.0, "nodal");
  s.disc.source.periodic = 1;
  mfs_model *m = build(&s, "sawtooth");
  if (m) {
    double *x = malloc(m->n * sizeof *x), *y = malloc(m->n * sizeof *y), ky = 0.0, kmax = 0.0;
    for (size_t i = 0; i < m->n; i++)
      x[i] = (i & 1) ? -1.0 : 1.0;
    mfs_csr_matvec(m->K, x, y);
    for (size_t i = 0; i < m->n; i++)
      ky = fabs(y[i]) > ky ? fabs(y[i]) : ky;
    mfs_csr_asymmetry(m->K, &kmax);
    CHECK(ky < 1e-13 * kmax, "K times the sawtooth: %.3g (K max %.3g)", ky, kmax);
    free(x);
    free(y);
    mfs_model_free(m);
  }
}

/* The 1D EFG bar of Fig. 17 (41 nodes on [0, 1], E = rho = 1, free-free,
 * cubic MLS, gauss2).  At D = 1 the MLS functions are the linear finite
 * element hats: lambda_max dx^2 = 4 (lumped) and 12 (consistent), the
 * sawtooth mode; eq. 138. */
static void test_fig17(void)
{
  for (int cons = 0; cons < 2; cons++) {
    mfs_model_spec s = spec1(41, 1.0, "gauss2");
    s.disc.consistent_mass = cons;
    mfs_model *m = build(&s, "fig17 D = 1");
    if (!m)
      continue;
    mfs_pencil P = {m->K, m->M, m->m};
    double lam;
    mfs_status st = mfs_eig_max(&P, NULL, &lam, NULL, NULL);
    CHECK(st == MFS_OK, "fig17 D = 1: %s", mfs_strerror(st));
    CHECK_NEAR(lam * m->dx * m->dx, cons ? 12.0 : 4.0, 1e-10, "fig17 D = 1 %s",
               cons ? "consistent" : "lumped");
    mfs_model_free(m);
  }
  for (int i = 0; i <= 12; i++) {
    double D = 1.0 + 0.25 * i;
    mfs_model_spec s = spec1(41, D, "gauss2");
    mfs_model *m = build(&s, "fig17");
    if (!m)
      continue;
    mfs_pencil P = {m->K, m->M, m->m};
    double lam;
    mfs_status st = mfs_eig_max(&P, NULL, &lam, NULL, NULL);
    CHECK(st == MFS_OK, "fig17 D = %g: %s", D, mfs_strerror(st));
    mfs_bound_result b;
    mfs_bound_of_model(m, &b);
    CHECK(b.lambda >= lam, "fig17 D = %g: bound %.10g < lambda_max %.10g", D, b.lambda, lam);
    mfs_model_free(m);
  }
  /* at D = 1 the bound is the linear element's lambda^Q = 1/(dx^2 t (1 - t)) = 6/dx^2
   * at the Gauss points t = 1/2 -+ 1/(2 sqrt 3) */
  mfs_model_spec s = spec1(41, 1.0, "gauss2");
  mfs_bound_result b;
  mfs_bound_model(&s, &b, NULL);
  CHECK_NEAR(b.lambda * (1.0 / 40) * (1.0 / 40), 6.0, 1e-10, "linear element bound");
  CHECK(b.negative_phi == 0, "linear element: %zu negative phi points", b.negative_phi);
}

/* Where some MLS phi_I < 0 the output says so. */
static void test_negative_phi(void)
{
  mfs_model_spec s = spec1(41, 1.25, "gauss2");
  mfs_bound_result b;
  mfs_status st = mfs_bound_model(&s, &b, NULL);
  CHECK(st == MFS_OK && b.negative_phi > 0, "D = 1.25: negative phi points %zu", b.negative_phi);
  /* on a periodic lattice the interior MLS functions at D = 2 are positive */
  s = spec1(40, 2.0, "gauss2");
  s.disc.source.periodic = 1;
  st = mfs_bound_model(&s, &b, NULL);
  CHECK(st == MFS_OK && b.negative_phi == 0, "periodic D = 2: negative phi %zu", b.negative_phi);
  CHECK(b.evaluated == 2, "periodic gauss2: %zu distinct points evaluated, want 2", b.evaluated);
}

/* The constants of eqs 136 and 145 and the Fourier estimate. */
static void test_closed_forms(void)
{
  double al = mfs_bound_alpha(&mfs_kernel_cubic, 1);
  CHECK_NEAR(al, 12.42, 0.005, "alpha of eq. 136");
  CHECK_NEAR(al / 48.0, 0.2587, 0.00005, "0.2587 of eq. 136");
  CHECK_NEAR(mfs_bound_alpha(&mfs_kernel_cubic, 2), 13.30, 0.1, "alpha_1 of eq. 145");
  CHECK_NEAR(mfs_bound_alpha_continuum(&mfs_kernel_cubic, 1), 12.4629, 0.001,
             "continuum limit of the interior lambda^Q (1D cubic)");
  /* the interior lambda^Q of a fine periodic lattice tends to the continuum value */
  mfs_model_spec s = spec1(400, 12.0, "gauss1");
  s.disc.source.periodic = 1;
  s.disc.shape = &mfs_shape_sph;
  mfs_bound_result b;
  mfs_bound_model(&s, &b, NULL);
  double h = 12.0 / 400;
  CHECK_NEAR(b.lambda * h * h, mfs_bound_alpha_continuum(&mfs_kernel_cubic, 1), 0.05,
             "interior lambda^Q h^2 at D = 12");
  CHECK_NEAR(mfs_dt_crit(4.0), 1.0, 1e-15, "dt = 2/omega");

  /* Fourier: D = 1 gauss2 lumped is the linear element, omega^2 dx^2/c^2 = 4 sin^2(k dx/2) */
  s = spec1(41, 1.0, "gauss2");
  s.disc.material.modulus = 2.385;
  s.disc.material.density = 0.7;
  double lf, kf;
  mfs_status st = mfs_bound_fourier(&s, 101, 1, &lf, &kf, NULL);
  CHECK(st == MFS_OK, "fourier: %s", mfs_strerror(st));
  CHECK_NEAR(lf * (1.0 / 40) * (1.0 / 40) * 0.7 / 2.385, 4.0, 1e-10, "Fourier max, linear element");
  CHECK_NEAR(kf, 1.0, 1e-6, "Fourier max at kappa = 1");
  /* Table II: nodal integration 1.0 at D = 1.5 */
  s = spec1(41, 1.5, "nodal");
  st = mfs_bound_fourier(&s, 201, 1, &lf, NULL, NULL);
  CHECK_NEAR(lf / 1600.0, 1.0, 1e-6, "Table II nodal integration");
  /* the periodic model with N even samples kappa = 1: its lambda_max is the Fourier max */
  s = spec1(40, 2.0, "stress");
  s.disc.source.periodic = 1;
  mfs_model *m = build(&s, "periodic stress");
  if (m) {
    mfs_pencil P = {m->K, m->M, m->m};
    double lam;
    mfs_eig_max(&P, NULL, &lam, NULL, NULL);
    st = mfs_bound_fourier(&s, 201, 1, &lf, &kf, NULL);
    CHECK(lf >= lam * (1.0 - 1e-12), "Fourier %.12g below periodic lambda_max %.12g", lf, lam);
    CHECK_NEAR(lf / lam, 1.0, 1e-2, "Fourier vs periodic lambda_max (max at kappa %g)", kf);
    mfs_model_free(m);
  }
  s = spec2(10, 10, 2.0, "gauss2");
  st = mfs_bound_fourier(&s, 51, 7, &lf, NULL, NULL);
  CHECK(st == MFS_OK && lf > 0.0, "2D Fourier: %s", mfs_strerror(st));
}

/* Error returns. */
static void test_errors(void)
{
  mfs_model_spec s = spec1(20, 2.0, "gauss2");
  s.disc.source.periodic = 1;
  s.fixed = MFS_FIX_ENDS;
  const char *field = NULL;
  CHECK(mfs_model_spec_check(&s, &field) == MFS_EINVAL && strcmp(field, "fixed") == 0,
        "periodic and fixed: field %s", field);
  s = spec1(4, 2.0, "gauss2");
  s.disc.source.periodic = 1;
  CHECK(mfs_model_spec_check(&s, &field) == MFS_ETOOSMALL && strcmp(field, "disc.source.nx") == 0,
        "periodic box of 4 nodes at D = 2: field %s", field);
  mfs_status st;
  CHECK(mfs_model_alloc(&s, &st, NULL) == NULL && st == MFS_ETOOSMALL, "alloc too small");
  s = spec1(20, 2.0, "gauss2");
  s.disc.material.modulus = -1.0;
  CHECK(mfs_model_spec_check(&s, &field) == MFS_EINVAL &&
          strcmp(field, "disc.material.modulus") == 0,
        "negative modulus: field %s", field);
  s = spec1(20, 2.0, "stress-quad");
  CHECK(mfs_model_spec_check(&s, &field) == MFS_EINVAL && strcmp(field, "disc.quadrature") == 0,
        "2D rule in 1D: field %s", field);
  s = spec2(10, 10, 2.0, "gauss2");
  s.fixed = MFS_FIX_ENDS;
  CHECK(mfs_model_spec_check(&s, &field) == MFS_EINVAL && strcmp(field, "fixed") == 0,
        "ends in 2D: field %s", field);
  CHECK(mfs_model_spec_check(&s, NULL) == MFS_EINVAL, "field may be NULL");
  s = spec1(20, 0.5, "gauss2");
  size_t bad = 99;
  CHECK(mfs_model_alloc(&s, &st, &bad) == NULL && st == MFS_ESINGULAR, "D = 0.5: %s",
        mfs_strerror(st));
  mfs_bound_result b;
  CHECK(mfs_bound_model(&s, &b, &bad) == MFS_ESINGULAR, "streaming bound D = 0.5");

  s = spec1(200, 2.0, "gauss2");
  mfs_model *m = build(&s, "errors");
  if (!m)
    return;
  mfs_pencil P = {m->K, m->M, m->m};
  double lam;
  mfs_eig_info info;
  mfs_pencil bad1 = {m->K, NULL, NULL};
  CHECK(mfs_eig_max(&bad1, NULL, &lam, NULL, &info) == MFS_EINVAL, "no mass");
  m->m[3] = -1.0;
  CHECK(mfs_eig_max(&P, NULL, &lam, NULL, &info) == MFS_EINVAL, "negative lumped mass");
  m->m[3] = 1.0 / 199;
  mfs_eig_opts o = {3, 1, 1e-15};
  st = mfs_eig_max(&P, &o, &lam, NULL, &info);
  CHECK(st == MFS_ENOCONV && info.info == 1 && strcmp(info.routine, "dsaupd") == 0,
        "maxiter 1: %s, info %d", mfs_strerror(st), info.info);
  /* consistent "mass" that is not positive definite: CHOLMOD reports it */
  mfs_csr *N = mfs_csr_alloc(m->n, m->n, m->n);
  for (size_t i = 0; i < m->n; i++) {
    N->idx[i] = (int)i;
    N->val[i] = i == 7 ? -1.0 : 1.0;
    N->ptr[i + 1] = i + 1;
  }
  mfs_pencil Pn = {m->K, N, NULL};
  st = mfs_eig_max(&Pn, NULL, &lam, NULL, &info);
  CHECK(st == MFS_EDOMAIN && strcmp(info.routine, "cholmod") == 0 && info.cholmod_status != 0,
        "indefinite M: %s %s %d", mfs_strerror(st), info.routine, info.cholmod_status);
  mfs_zero_opts zo = {0.0, 0, 0, 0};
  mfs_zero_modes z;
  CHECK(mfs_eig_zero_modes(&P, 1.0, &zo, NULL, &z, &info) == MFS_EINVAL, "tol 0");
  mfs_csr_free(N);
  mfs_model_free(m);
  s = spec1(2100, 2.0, "gauss2");
  m = build(&s, "dense too large");
  if (m) {
    mfs_pencil Pl = {m->K, m->M, m->m};
    double *w = malloc(m->n * sizeof *w);
    CHECK(mfs_eig_dense(&Pl, w) == MFS_EINVAL, "dense n > 2000");
    free(w);
    mfs_model_free(m);
  }
}

/* A particle set holding a lattice (its coordinates, and its volumes or
 * none: the dual areas are the lattice's volumes) is the lattice model: the
 * same lambda_max and zero-mode count to 1e-12. */
static void check_set_is_lattice(mfs_model_spec s, int with_vol, const char *what)
{
  mfs_model *lat = build(&s, what);
  if (!lat)
    return;
  mfs_point_set ps = {.dim = s.disc.dim, .n = lat->p->n, .x = lat->p->x,
                      .vol = with_vol ? lat->p->vol : NULL};
  unsigned char *mask = malloc(lat->p->n);
  for (size_t I = 0; I < lat->p->n; I++)
    mask[I] = lat->fixed[I];
  mfs_model_spec t = s;
  t.disc.source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &ps};
  t.disc.support = lat->a;
  if (s.fixed != MFS_FIX_NONE) {
    t.fixed = MFS_FIX_MASK;
    t.fix_mask = mask;
  }
  mfs_model *set = build(&t, what);
  if (set) {
    mfs_pencil P = {lat->K, lat->M, lat->m}, Q = {set->K, set->M, set->m};
    double l1 = 0.0, l2 = 0.0;
    mfs_eig_info info;
    mfs_status st = mfs_eig_max(&P, NULL, &l1, NULL, &info);
    st |= mfs_eig_max(&Q, NULL, &l2, NULL, &info);
    CHECK(st == MFS_OK && set->n == lat->n, "%s: eig %s, dofs %zu/%zu", what, mfs_strerror(st),
          set->n, lat->n);
    CHECK_NEAR(l2 / l1, 1.0, 1e-12, "%s (%s volumes): lambda_max of the set vs the lattice",
               what, with_vol ? "the lattice's" : "dual");
    check_steps(set, l2, what);
    mfs_zero_opts zo = {1e-8, 0, 0, 0};
    mfs_zero_modes z1, z2;
    st = mfs_eig_zero_modes(&P, l1, &zo, NULL, &z1, &info);
    st |= mfs_eig_zero_modes(&Q, l2, &zo, NULL, &z2, &info);
    CHECK(st == MFS_OK && z1.count == z2.count, "%s: zero modes %d (set) vs %d (lattice)", what,
          z2.count, z1.count);
    CHECK(mfs_model_rigid_fields(set, NULL) == mfs_model_rigid_fields(lat, NULL),
          "%s: rigid fields", what);
    mfs_bound_result b1, b2;
    mfs_bound_model(&s, &b1, NULL);
    mfs_bound_model(&t, &b2, NULL);
    CHECK_NEAR(b2.lambda / b1.lambda, 1.0, 1e-12, "%s: element bound of the set vs the lattice",
               what);
    mfs_model_free(set);
  }
  free(mask);
  mfs_model_free(lat);
}

static void test_point_sets(void)
{
  mfs_model_spec s = spec1(31, 2.3, "nodal");
  check_set_is_lattice(s, 1, "1D free nodal");
  check_set_is_lattice(s, 0, "1D free nodal");
  s.fixed = MFS_FIX_ENDS;
  s.disc.kernel = &mfs_kernel_quartic;
  check_set_is_lattice(s, 1, "1D fixed nodal quartic");
  s = spec2(13, 11, 2.1, "nodal");
  check_set_is_lattice(s, 1, "2D free nodal");
  check_set_is_lattice(s, 0, "2D free nodal");
  s.fixed = MFS_FIX_BOUNDARY;
  s.disc.consistent_mass = 1;
  check_set_is_lattice(s, 1, "2D fixed nodal consistent");
  s = spec2(10, 9, 2.0, "nodal");
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.disc.material.poisson = 0.3;
  check_set_is_lattice(s, 1, "2D plane strain nodal");
  s.disc.shape = &mfs_shape_rl;
  check_set_is_lattice(s, 1, "2D plane strain nodal rl");
  /* the 1D stress points of a set are those of the lattice */
  s = spec1(31, 1.8, "stress");
  check_set_is_lattice(s, 0, "1D free stress points");

  /* a set with random positions: the bound through the plan is the table bound */
  s = spec2(12, 12, 2.2, "gauss2");
  s.disc.source.perturb = 0.3;
  s.disc.source.seed = 11;
  mfs_model *m = build(&s, "perturbed");
  if (m) {
    mfs_bound_result b1, b2;
    mfs_bound_of_model(m, &b1);
    mfs_bound_model(&s, &b2, NULL);
    CHECK(b1.lambda == b2.lambda && b1.negative_phi == b2.negative_phi,
          "perturbed lattice: bound %.17g vs streaming %.17g", b1.lambda, b2.lambda);
    mfs_pencil P = {m->K, m->M, m->m};
    double lp;
    CHECK(mfs_eig_max(&P, NULL, &lp, NULL, NULL) == MFS_OK, "perturbed: lambda_max");
    check_steps(m, lp, "perturbed lattice gauss2");
    CHECK(fabs(m->p->x[2 * 30] - 6 * m->dx) > 1e-6 * m->dx && fabs(m->p->x[2 * 30] - 6 * m->dx) < 0.3 * m->dx, "the lattice moved, by less than 0.3 dx");
    mfs_model_free(m);
  }
  s.disc.source.perturb = 0.5;
  CHECK(mfs_model_spec_check(&s, NULL) == MFS_EINVAL, "perturbation 0.5 refused");
}

int main(void)
{
  test_point_sets();
  test_arpack_vs_dense();
  test_bloch();
  test_zero_modes();
  test_fig17();
  test_negative_phi();
  test_closed_forms();
  test_errors();
  return check_summary("test_eigen");
}
