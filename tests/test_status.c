/* Status codes: mfs_strerror names every status of MFS_STATUS_LIST, and
 * every error return of the core library is provoked at least once (except
 * MFS_ENOMEM, which needs a failing allocator). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static const double DX = 0.7313;

static void check_strerror(void)
{
  static const struct {
    int code;
    const char *name;
  } all[] = {
#define X(name, value, msg) {name, #name},
    MFS_STATUS_LIST(X)
#undef X
  };
  size_t n = sizeof all / sizeof all[0];
  CHECK(n >= 2 && all[0].code == MFS_OK && mfs_strerror(MFS_OK)[0] != '\0', "MFS_OK first");
  for (size_t i = 0; i < n; i++) {
    const char *s = mfs_strerror(all[i].code);
    CHECK(s && s[0] != '\0', "%s: empty message", all[i].name);
    CHECK(s && strcmp(s, "unknown status") != 0, "%s: not named", all[i].name);
    for (size_t j = 0; j < i; j++) {
      CHECK(all[i].code != all[j].code, "%s and %s share a value", all[i].name, all[j].name);
      CHECK(strcmp(s, mfs_strerror(all[j].code)) != 0, "%s and %s share a message", all[i].name,
            all[j].name);
    }
  }
  CHECK(strcmp(mfs_strerror(-1), "unknown status") == 0, "strerror(-1)");
  CHECK(strcmp(mfs_strerror(9973), "unknown status") == 0, "strerror(9973)");
}

static void check_lattice(void)
{
  const mfs_lattice_spec good = {2, MFS_LATTICE_SQUARE, 6, 5, DX, 1.0, 0, MFS_CELLS_QUAD, 0.1, 7};
  struct {
    const char *what;
    mfs_lattice_spec s;
  } bad[] = {
    {"dim 3", good},          {"dim 0", good},          {"nx < 2", good},
    {"ny < 2", good},         {"dx = 0", good},         {"dx < 0", good},
    {"dx NaN", good},         {"perturb 0.5", good},    {"perturb < 0", good},
    {"gamma < 0", good},      {"periodic hex odd ny", good}, {"periodic star odd nx", good},
    {"line lattice in 2D", good}, {"square lattice in 1D", good},
  };
  bad[0].s.dim = 3;
  bad[1].s.dim = 0;
  bad[2].s.nx = 1;
  bad[3].s.ny = 1;
  bad[4].s.dx = 0.0;
  bad[5].s.dx = -DX;
  bad[6].s.dx = NAN;
  bad[7].s.perturb = 0.5;
  bad[8].s.perturb = -0.1;
  bad[9].s.gamma = -1.0;
  bad[10].s.lattice = MFS_LATTICE_HEX;
  bad[10].s.periodic = 1;
  bad[10].s.ny = 7;
  bad[11].s.cells = MFS_CELLS_STAR;
  bad[11].s.periodic = 1;
  bad[11].s.nx = 7;
  bad[11].s.ny = 6;
  bad[12].s.lattice = MFS_LATTICE_LINE;
  bad[13].s.dim = 1;
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    mfs_status st = MFS_OK;
    mfs_particles *p = mfs_lattice_alloc(&bad[i].s, &st);
    CHECK(p == NULL && st == MFS_EINVAL, "mfs_lattice_alloc %s: status %d, %s", bad[i].what, st,
          p ? "not NULL" : "NULL");
    mfs_particles_free(p);
  }
  mfs_status st = -1;
  mfs_particles *p = mfs_lattice_alloc(&good, &st);
  CHECK(p && st == MFS_OK, "good spec: status %d", st);
  mfs_particles_free(p);
  /* the valid periodic variants of the rejected ones */
  mfs_lattice_spec h = good;
  h.lattice = MFS_LATTICE_HEX;
  h.periodic = 1;
  h.ny = 6;
  p = mfs_lattice_alloc(&h, &st);
  CHECK(p && st == MFS_OK, "periodic hex, even ny: status %d", st);
  mfs_particles_free(p);
  mfs_particles_free(NULL); /* free accepts NULL */
}

static void check_neighbor(void)
{
  mfs_lattice_spec s = {2, MFS_LATTICE_SQUARE, 6, 6, DX, 1.0, 1, MFS_CELLS_QUAD, 0.0, 0};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&s, &st);
  double L = 6 * DX;
  /* periodic box not larger than twice the radius */
  mfs_grid *g = mfs_grid_alloc(2, p->n, p->x, &p->box, 0.5 * L, &st);
  CHECK(!g && st == MFS_ETOOSMALL, "grid radius L/2 in a periodic box: status %d", st);
  mfs_grid_free(g);
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, 0.6137 * L, &st);
  CHECK(!g && st == MFS_ETOOSMALL, "grid radius 0.61 L: status %d", st);
  mfs_grid_free(g);
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, 0.0, &st);
  CHECK(!g && st == MFS_EINVAL, "grid radius 0: status %d", st);
  mfs_grid_free(g);
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, -1.3, &st);
  CHECK(!g && st == MFS_EINVAL, "grid radius < 0: status %d", st);
  mfs_grid_free(g);
  g = mfs_grid_alloc(0, p->n, p->x, &p->box, 1.3, &st);
  CHECK(!g && st == MFS_EINVAL, "grid dim 0: status %d", st);
  mfs_grid_free(g);
  /* lists with a radius beyond the grid's */
  double R = 1.7 * DX;
  g = mfs_grid_alloc(2, p->n, p->x, &p->box, R, &st);
  CHECK(g && st == MFS_OK, "grid: status %d", st);
  mfs_nlist *nl = mfs_nlist_build(g, p->n, p->x, 1.0001 * R, &st);
  CHECK(!nl && st == MFS_EINVAL, "nlist r > grid radius: status %d", st);
  mfs_nlist_free(nl);
  nl = mfs_nlist_build(g, p->n, p->x, 0.0, &st);
  CHECK(!nl && st == MFS_EINVAL, "nlist r = 0: status %d", st);
  mfs_nlist_free(nl);
  nl = mfs_nlist_build(g, p->n, p->x, R, &st);
  CHECK(nl && st == MFS_OK, "nlist r = R: status %d", st);
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  mfs_grid_free(NULL);
  mfs_nlist_free(NULL);
  mfs_particles_free(p);
}

static void check_quad(void)
{
  CHECK(mfs_quad_find("gauss0") == NULL, "parse gauss0");
  CHECK(mfs_quad_find("gaussx") == NULL, "parse gaussx");
  CHECK(mfs_quad_find("foo") == NULL, "parse foo");
  CHECK(mfs_quad_find(NULL) == NULL, "parse NULL");
  mfs_lattice_spec s = {2, MFS_LATTICE_SQUARE, 6, 5, DX, 1.0, 0, MFS_CELLS_TRI, 0.2, 3};
  mfs_status st;
  mfs_particles *tri = mfs_lattice_alloc(&s, &st);
  s.cells = MFS_CELLS_STAR;
  mfs_particles *star = mfs_lattice_alloc(&s, &st);
  s.cells = MFS_CELLS_QUAD;
  mfs_particles *quad = mfs_lattice_alloc(&s, &st);
  s.lattice = MFS_LATTICE_HEX;
  mfs_particles *hex = mfs_lattice_alloc(&s, &st);
  mfs_lattice_spec s1 = {1, MFS_LATTICE_LINE, 9, 0, DX, 1.0, 0, MFS_CELLS_QUAD, 0.2, 3};
  mfs_particles *line = mfs_lattice_alloc(&s1, &st);
  struct {
    const char *rule;
    const mfs_particles *p;
    const char *why;
  } bad[] = {
    {"stress-quad", tri, "quadrilateral centres on triangle cells"},
    {"stress-tri", quad, "triangle centroids on quadrilateral cells"},
    {"stress-star", quad, "star centroids on quadrilateral cells"},
    {"stress-hex", quad, "stress-hex on the square lattice"},
    {"stress-quad", hex, "stress-quad on the hexagonal lattice"},
    {"stress-quad", line, "stress-quad in 1D"},
    {"stress", quad, "1D stress points in 2D"},
    {"stress-tri", star, "one-diagonal centroids on star cells"},
    {"stress-star", tri, "star centroids on one-diagonal cells"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    mfs_quad *q = mfs_quad_alloc(mfs_quad_find(bad[i].rule), bad[i].p, &st);
    CHECK(!q && st == MFS_EINVAL, "mfs_quad_alloc %s: status %d", bad[i].why, st);
    mfs_quad_free(q);
  }
  CHECK(!mfs_quad_applies(&mfs_quad_stress_quad, 1, MFS_LATTICE_LINE), "check stress-quad 1D");
  CHECK(!mfs_quad_applies(&mfs_quad_stress_hex, 2, MFS_LATTICE_SQUARE), "check stress-hex square");
  CHECK(!mfs_quad_applies(&mfs_quad_stress, 2, MFS_LATTICE_SQUARE), "check stress 2D");
  CHECK(!mfs_quad_applies(NULL, 1, MFS_LATTICE_LINE), "check no rule");
  CHECK(!mfs_quad_alloc(NULL, line, &st) && st == MFS_EINVAL, "mfs_quad_alloc without a rule");
  mfs_quad_free(NULL);

  /* Voronoi: not 2D; a point outside a finite box */
  double area[64];
  CHECK(mfs_voronoi_areas(line->n, line->x, &line->box, area) == MFS_EINVAL, "voronoi in 1D");
  double x[6] = {0.1, 0.1, 0.5, 0.4, 1.2, 0.3};
  mfs_box box = {2, {0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, 0};
  CHECK(mfs_voronoi_areas(3, x, &box, area) == MFS_EINVAL, "voronoi point outside the box");
  x[4] = 0.9;
  CHECK(mfs_voronoi_areas(3, x, &box, area) == MFS_OK, "voronoi points inside the box");
  mfs_particles_free(tri);
  mfs_particles_free(star);
  mfs_particles_free(quad);
  mfs_particles_free(hex);
  mfs_particles_free(line);
}

static void check_plan(void)
{
  mfs_lattice_spec s = {2, MFS_LATTICE_SQUARE, 8, 7, DX, 1.0, 0, MFS_CELLS_QUAD, 0.0, 0};
  mfs_status st;
  mfs_particles *p = mfs_lattice_alloc(&s, &st);
  mfs_quad *q = mfs_quad_alloc(&mfs_quad_nodal, p, &st);
  mfs_disc ps = mfs_disc_default();
  ps.dilation = 0.0;
  size_t bad = SIZE_MAX;
  mfs_plan *pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(!pl && st == MFS_EINVAL, "plan dilation 0: status %d", st);
  ps.dilation = -2.0;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(!pl && st == MFS_EINVAL, "plan dilation < 0: status %d", st);
  ps.dilation = 2.385;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(pl && st == MFS_OK, "plan D = 2.385: status %d", st);
  st = mfs_plan_tabulate(pl, 3, &bad);
  CHECK(st == MFS_EINVAL && mfs_plan_order(pl) == 0, "plan order 3: status %d", st);
  CHECK(mfs_plan_tabulate(NULL, 1, &bad) == MFS_EINVAL, "tabulate without a plan");
  mfs_plan_free(pl);
  ps.kernel = NULL;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(!pl && st == MFS_EINVAL, "plan without kernel: status %d", st);
  ps.kernel = &mfs_kernel_cubic;
  ps.shape = NULL;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(!pl && st == MFS_EINVAL, "plan without shape: status %d", st);
  ps.shape = &mfs_shape_mls;
  /* too small a dilation: every node sees only itself */
  ps.dilation = 0.9;
  bad = SIZE_MAX;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  CHECK(pl && st == MFS_OK, "plan D = 0.9, symbolic: status %d", st);
  st = mfs_plan_tabulate(pl, 1, &bad);
  CHECK(st == MFS_ESINGULAR, "plan D = 0.9: status %d", st);
  /* every point is singular: the first one is named */
  CHECK(bad == 0, "plan D = 0.9: bad point %zu, want 0", bad);
  mfs_plan_free(pl);
  ps.dilation = 2.385;
  pl = mfs_plan_alloc(&ps, p, q, &st);
  st = mfs_plan_tabulate(pl, 1, NULL); /* bad may be NULL */
  CHECK(pl && st == MFS_OK, "plan D = 2.385: status %d", st);
  mfs_plan_free(pl);
  mfs_plan_free(NULL);

  /* a periodic box too small for the support */
  mfs_lattice_spec sp = {2, MFS_LATTICE_SQUARE, 4, 4, DX, 1.0, 1, MFS_CELLS_QUAD, 0.0, 0};
  mfs_particles *pp = mfs_lattice_alloc(&sp, &st);
  mfs_quad *qp = mfs_quad_alloc(&mfs_quad_nodal, pp, &st);
  ps.dilation = 2.385;
  pl = mfs_plan_alloc(&ps, pp, qp, &st);
  CHECK(!pl && st == MFS_ETOOSMALL, "plan in a periodic box of 4 dx with a = 2.385 dx: status %d",
        st);
  mfs_quad_free(qp);
  mfs_particles_free(pp);

  /* a quadrature set of another dimension */
  mfs_lattice_spec s1 = {1, MFS_LATTICE_LINE, 9, 0, DX, 1.0, 0, MFS_CELLS_QUAD, 0.0, 0};
  mfs_particles *line = mfs_lattice_alloc(&s1, &st);
  mfs_quad *q1 = mfs_quad_alloc(&mfs_quad_nodal, line, &st);
  pl = mfs_plan_alloc(&ps, p, q1, &st);
  CHECK(!pl && st == MFS_EINVAL, "plan with a 1D quadrature on 2D particles: status %d", st);

  /* plane strain on a 1D plan */
  mfs_plan *pl1 = mfs_plan_alloc(&ps, line, q1, &st);
  if (pl1)
    st = mfs_plan_tabulate(pl1, 1, &bad);
  CHECK(pl1 && st == MFS_OK, "1D plan: status %d", st);
  if (pl1) {
    mfs_material mat = {.physics = MFS_PHYS_PLANE_STRAIN, .modulus = 1.0, .poisson = 0.3,
                        .density = 1.0};
    mfs_csr dummy, *K = &dummy; /* must be overwritten with NULL */
    st = mfs_assemble_stiffness(pl1, &mat, &K);
    CHECK(st == MFS_EINVAL && K == NULL, "plane strain stiffness on a 1D plan: status %d", st);
  }
  mfs_plan_free(pl1);
  mfs_quad_free(q1);
  mfs_particles_free(line);
  mfs_quad_free(q);
  mfs_particles_free(p);
}

static void check_stencil(void)
{
  mfs_disc s = mfs_disc_default();
  s.dim = 2;
  s.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .spacing = DX, .gamma = 1.0};
  s.quadrature = &mfs_quad_nodal; /* each node sees only itself within 0.9 dx */
  s.dilation = 0.9;
  mfs_stencil_entry dummy, *e = &dummy; /* must be overwritten with NULL */
  size_t n = 77, bad = SIZE_MAX;
  mfs_status st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_ESINGULAR && e == NULL && n == 0, "stencil D = 0.9: status %d", st);
  CHECK(bad != SIZE_MAX, "stencil D = 0.9: bad point not set");
  /* with 2 x 2 Gauss points each point sees three non-collinear nodes
   * within 0.9 dx, so that is regular; within 0.25 dx it sees none */
  s.quadrature = &mfs_quad_gauss[1];
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_OK, "stencil gauss2 D = 0.9: status %d", st);
  free(e);
  s.dilation = 0.25;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_ESINGULAR && e == NULL, "stencil gauss2 D = 0.25: status %d", st);
  s.dilation = 2.385;
  s.quadrature = NULL;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_EINVAL && e == NULL, "stencil unknown rule: status %d", st);
  s.quadrature = &mfs_quad_stress_hex;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_EINVAL && e == NULL, "stencil stress-hex on a square lattice: status %d", st);
  s.quadrature = &mfs_quad_gauss[1];
  s.material.physics = MFS_PHYS_PLANE_STRAIN;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_EINVAL && e == NULL, "stencil plane strain: status %d", st);
  s.material.physics = MFS_PHYS_SCALAR;
  s.dilation = 0.0;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_EINVAL && e == NULL, "stencil dilation 0: status %d", st);
  s.dilation = 2.385;
  s.source.nx = 10; /* not the infinite lattice */
  s.source.lx = 10.0;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_EINVAL && e == NULL, "stencil of a finite box: status %d", st);
  s.source.nx = 0;
  st = mfs_stencil(&s, &e, &n, &bad);
  CHECK(st == MFS_OK && e && n > 0, "stencil D = 2.385: status %d", st);
  free(e);
}

static void check_csr(void)
{
  mfs_csr *A = mfs_csr_alloc(2, 2, 3);
  CHECK(A != NULL, "csr alloc");
  if (!A)
    return;
  A->ptr[1] = 2;
  A->ptr[2] = 3;
  A->idx[0] = 1;
  A->idx[1] = 0;
  A->idx[2] = 0;
  A->val[0] = 2.5;
  A->val[1] = 1.25;
  A->val[2] = 2.0;
  double amax;
  CHECK_NEAR(mfs_csr_asymmetry(A, &amax), 0.5, 0.0, "asymmetry of [[1.25 2.5][2 0]]");
  CHECK(amax == 2.5, "max |A| %g", amax);
  CHECK(mfs_csr_get(A, 1, 1) == 0.0 && mfs_csr_get(A, 0, 1) == 2.5, "csr_get");
  /* a stream that cannot be written */
  FILE *f = fopen("/dev/null", "r");
  if (f) {
    CHECK(mfs_csr_write_mtx(A, f) == MFS_EIO, "write to a read-only stream: not MFS_EIO");
    fclose(f);
  }
  f = tmpfile();
  if (f) {
    CHECK(mfs_csr_write_mtx(A, f) == MFS_OK, "write to a temporary file");
    fclose(f);
  }
  mfs_csr_free(A);
  mfs_csr_free(NULL);
}

static void check_shape_errors(void)
{
  double d[4] = {0.0, 0.0, 0.3, 0.0}, v[2] = {1.0, 1.0}, out[14], work[64], rc;
  mfs_shape_ctx c = {&mfs_kernel_cubic, 2, 1.0, 1e-12};
  CHECK(mfs_shape_mls.eval(&c, 2, d, v, 0, 2, out, work, &rc) == MFS_ESINGULAR,
        "mls with two neighbours in 2D");
  CHECK(mfs_shape_kb.eval(&c, 2, d, v, 0, 1, out, work, &rc) == MFS_ESINGULAR,
        "kb with collinear neighbours in 2D");
  CHECK(mfs_shape_rl.eval(&c, 2, d, v, 0, 1, out, work, &rc) == MFS_ESINGULAR,
        "rl with collinear neighbours in 2D");
  CHECK(mfs_shape_shepard.eval(&c, 0, d, v, -1, 1, out, work, &rc) == MFS_ESINGULAR,
        "shepard with no neighbour");
}

int main(void)
{
  check_strerror();
  check_lattice();
  check_neighbor();
  check_quad();
  check_plan();
  check_stencil();
  check_csr();
  check_shape_errors();
  return check_summary("test_status");
}
