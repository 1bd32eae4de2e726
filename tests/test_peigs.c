/* The distributed model (lib/analysis/mfs_peigs.h) against the whole model
 * of one process, on every rank: the products K x through the halo
 * exchange, the lumped Gershgorin bound (assembled and streamed) and the
 * element bound bit for bit; lambda_max (PARPACK) against mfs_eig_max
 * (ARPACK) to 1e-12; the sizes add up over the ranks; every status.
 * Run by tests/test_mpi.sh under `mpirun -np 1` and `-np 2`; built without
 * MPI it checks that every entry point says MFS_ENOTSUP. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

#ifndef MFS_HAVE_MPI

int main(void)
{
  mfs_model_spec s = mfs_model_spec_default();
  mfs_status st = MFS_OK;
  CHECK(!mfs_peigs_available(), "built without MPI: mfs_peigs_available() = 1");
  CHECK(mfs_pmodel_alloc(&s, 0, 1, &st, NULL) == NULL && st == MFS_ENOTSUP,
        "without MPI: mfs_pmodel_alloc gives %s, want MFS_ENOTSUP", mfs_strerror(st));
  double lam;
  CHECK(mfs_peig_max(NULL, NULL, &lam, NULL) == MFS_ENOTSUP, "without MPI: mfs_peig_max");
  return check_summary("test_peigs (no MPI)");
}

#else

#include <mpi.h>

static int rank, size;
static int fcomm;

/* A global test vector of high entropy, by global dof. */
static double xval(long g)
{
  return sin(1.7 * (double)g + 0.3) + 0.25 * cos(0.37 * (double)g * (double)g);
}

static int all_true(int ok)
{
  int r = 0;
  MPI_Allreduce(&ok, &r, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return r;
}

static unsigned long long sum_ull(unsigned long long v)
{
  unsigned long long r = 0;
  MPI_Allreduce(&v, &r, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return r;
}

static void compare(const mfs_model_spec *s, const char *what, int with_lambda)
{
  mfs_status st, pst;
  size_t bad = 0, pbad = 0;
  mfs_model *m = mfs_model_alloc(s, &st, &bad);
  mfs_pmodel *pm = mfs_pmodel_alloc(s, fcomm, 1, &pst, &pbad);
  CHECK(m != NULL, "%s: the whole model: %s", what, mfs_strerror(st));
  CHECK(pm != NULL, "%s: the distributed model: %s (point %zu)", what, mfs_strerror(pst), pbad);
  if (!m || !pm) {
    mfs_model_free(m);
    mfs_pmodel_free(pm);
    return;
  }
  mfs_pmodel_info in;
  mfs_pmodel_sizes(pm, &in);
  CHECK(in.size == size && in.rank == rank, "%s: rank %d of %d, want %d of %d", what, in.rank,
        in.size, rank, size);
  CHECK(in.particles == m->p->n && in.dofs == m->n && in.points == m->q->n,
        "%s: the whole model's sizes %zu particles %zu dofs %zu points, want %zu %zu %zu", what,
        in.particles, in.dofs, in.points, m->p->n, m->n, m->q->n);
  unsigned long long rows = sum_ull(in.rows), own = sum_ull(in.own_particles);
  unsigned long long halo = sum_ull(in.halo), sent = sum_ull(in.sent);
  CHECK(rows == m->n, "%s: rows over the ranks %llu, want the %zu dofs", what, rows, m->n);
  CHECK(own == m->p->n, "%s: owned particles over the ranks %llu, want %zu", what, own, m->p->n);
  CHECK(halo == sent, "%s: halo dofs received %llu, sent %llu", what, halo, sent);
  CHECK((size == 1) == (halo == 0), "%s: %llu halo dofs on %d ranks", what, halo, size);
  CHECK(in.local_points <= m->q->n && in.local_particles <= m->p->n,
        "%s: local part larger than the model", what);

  /* the products, bit for bit: the same rows in the same order */
  double *xg = malloc(m->n * sizeof *xg), *yg = malloc(m->n * sizeof *yg);
  double *x = malloc((in.rows + 1) * sizeof *x), *y = malloc((in.rows + 1) * sizeof *y);
  for (size_t i = 0; i < m->n; i++)
    xg[i] = xval((long)i);
  mfs_csr_matvec(m->K, xg, yg);
  long prev = -1;
  int sorted = 1;
  for (size_t i = 0; i < in.rows; i++) {
    long g = mfs_pmodel_row_dof(pm, i);
    sorted &= g > prev && g < (long)m->n;
    prev = g;
    x[i] = xval(g);
  }
  CHECK(mfs_pmodel_row_dof(pm, in.rows) == -1, "%s: row %zu out of range has a dof", what, in.rows);
  CHECK(all_true(sorted), "%s: rows not in increasing global order", what);
  st = mfs_pmodel_matvec(pm, x, y);
  CHECK(st == MFS_OK, "%s: mfs_pmodel_matvec: %s", what, mfs_strerror(st));
  size_t diff = 0;
  double worst = 0.0;
  for (size_t i = 0; i < in.rows && sorted; i++) {
    double want = yg[mfs_pmodel_row_dof(pm, i)];
    diff += y[i] != want;
    worst = fmax(worst, fabs(y[i] - want));
  }
  unsigned long long ndiff = sum_ull(diff);
  CHECK(ndiff == 0, "%s: K x differs from the whole model's in %llu rows (rank %d: by up to %.3g)",
        what, ndiff, rank, worst);

  /* Gershgorin, assembled: mfs_gershgorin_csr bit for bit */
  mfs_gershgorin_result gs, gp;
  if (m->m) {
    mfs_gershgorin_csr(m->K, m->m, m->dof, &gs);
    st = mfs_pmodel_gershgorin(pm, &gp);
    CHECK(st == MFS_OK, "%s: mfs_pmodel_gershgorin: %s", what, mfs_strerror(st));
    CHECK((gp.lambda == gs.lambda || (isnan(gp.lambda) && isnan(gs.lambda))) &&
              gp.argmax == gs.argmax,
          "%s: Gershgorin %.17g at dof %zu, the whole model's %.17g at %zu", what, gp.lambda,
          gp.argmax, gs.lambda, gs.argmax);
    CHECK(gp.min_mass == gs.min_mass && gp.argmin_mass == gs.argmin_mass &&
              gp.nonpositive == gs.nonpositive,
          "%s: smallest mass %.17g at %zu (%zu <= 0), the whole model's %.17g at %zu (%zu)", what,
          gp.min_mass, gp.argmin_mass, gp.nonpositive, gs.min_mass, gs.argmin_mass,
          gs.nonpositive);
  }
  /* the element bound: mfs_bound_plan bit for bit */
  mfs_bound_result bs, bp;
  mfs_bound_of_model(m, &bs);
  st = mfs_pmodel_bound(pm, &bp);
  CHECK(st == MFS_OK, "%s: mfs_pmodel_bound: %s", what, mfs_strerror(st));
  CHECK(bp.lambda == bs.lambda && bp.argmax == bs.argmax && bp.xmax[0] == bs.xmax[0] &&
            bp.xmax[1] == bs.xmax[1],
        "%s: element bound %.17g at point %zu, the whole model's %.17g at %zu", what, bp.lambda,
        bp.argmax, bs.lambda, bs.argmax);
  CHECK(bp.points == bs.points && bp.negative_phi == bs.negative_phi,
        "%s: %zu points (%zu with phi <= 0), the whole model %zu (%zu)", what, bp.points,
        bp.negative_phi, bs.points, bs.negative_phi);
  /* a particle's coordinates, from its owner */
  size_t I = m->p->n / 3 + 1;
  double xy[2];
  st = mfs_pmodel_particle_x(pm, I, xy);
  CHECK(st == MFS_OK && xy[0] == m->p->x[I * m->p->dim] &&
            xy[1] == (m->p->dim == 2 ? m->p->x[I * 2 + 1] : 0.0),
        "%s: particle %zu at (%g, %g), want (%g, ...)", what, I, xy[0], xy[1], m->p->x[I * m->p->dim]);
  CHECK(mfs_pmodel_particle_x(pm, m->p->n, xy) == MFS_EINVAL, "%s: particle out of range", what);

  /* lambda_max: PARPACK against ARPACK */
  if (with_lambda && m->m) {
    mfs_pencil P = {m->K, NULL, m->m};
    mfs_eig_opts eo = {0, 0, 1e-12};
    mfs_eig_info is, ip;
    double ls = 0.0, lp = 0.0;
    st = mfs_eig_max(&P, &eo, &ls, NULL, &is);
    pst = mfs_peig_max(pm, &eo, &lp, &ip);
    CHECK(st == MFS_OK && pst == MFS_OK, "%s: lambda_max: ARPACK %s, PARPACK %s (info %d %s)",
          what, mfs_strerror(st), mfs_strerror(pst), ip.info, ip.routine);
    CHECK_NEAR(lp, ls, 1e-12 * ls, "%s: lambda_max PARPACK against ARPACK", what);
    CHECK(ip.residual < 1e-9 && ip.matvecs > 0 && ip.iterations > 0 && ip.runs == 1,
          "%s: PARPACK residual %.3g, %d matvecs, %d iterations", what, ip.residual, ip.matvecs,
          ip.iterations);
    double lall = 0.0;
    MPI_Allreduce(&lp, &lall, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    CHECK(lall == lp, "%s: lambda_max differs over the ranks: %.17g, max %.17g", what, lp, lall);
    /* without the plan: the rows and lambda_max stay, the plan's bounds are refused */
    mfs_pmodel_release_plan(pm);
    double l2 = 0.0;
    pst = mfs_peig_max(pm, &eo, &l2, &ip);
    CHECK(pst == MFS_OK && l2 == lp, "%s: lambda_max after the plan's release %.17g, before %.17g (%s)",
          what, l2, lp, mfs_strerror(pst));
    CHECK(mfs_pmodel_bound(pm, &bp) == MFS_EINVAL, "%s: the element bound without the plan", what);
    st = mfs_pmodel_gershgorin(pm, &gp);
    CHECK(st == MFS_OK && gp.lambda == gs.lambda, "%s: the assembled Gershgorin bound after the release",
          what);
    mfs_pmodel_sizes(pm, &in);
    CHECK(in.plan_nnz > 0 && in.local_points > 0, "%s: the plan's sizes are kept", what);
  }
  mfs_pmodel_free(pm);

  /* not assembled: the streamed Gershgorin bound, mfs_gershgorin_plan bit for bit */
  if (m->m) {
    pm = mfs_pmodel_alloc(s, fcomm, 0, &pst, NULL);
    CHECK(pm != NULL, "%s: the distributed plan: %s", what, mfs_strerror(pst));
    if (pm) {
      mfs_gershgorin_plan(m->pl, &m->mat, s->fixed != MFS_FIX_NONE ? m->fixed : NULL, &gs);
      st = mfs_pmodel_gershgorin(pm, &gp);
      CHECK(st == MFS_OK && gp.lambda == gs.lambda && gp.argmax == gs.argmax &&
                gp.min_mass == gs.min_mass && gp.argmin_mass == gs.argmin_mass,
            "%s: streamed Gershgorin %.17g at %zu (mass %.17g at %zu), the whole plan's %.17g at "
            "%zu (%.17g at %zu)",
            what, gp.lambda, gp.argmax, gp.min_mass, gp.argmin_mass, gs.lambda, gs.argmax,
            gs.min_mass, gs.argmin_mass);
      double lam;
      CHECK(mfs_peig_max(pm, NULL, &lam, NULL) == MFS_EINVAL,
            "%s: mfs_peig_max without the rows is not MFS_EINVAL", what);
      CHECK(mfs_pmodel_matvec(pm, x, y) == MFS_EINVAL, "%s: a product without the rows", what);
      mfs_pmodel_free(pm);
    }
  }
  free(xg);
  free(yg);
  free(x);
  free(y);
  mfs_model_free(m);
}

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

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  fcomm = (int)MPI_Comm_c2f(MPI_COMM_WORLD);
  CHECK(mfs_peigs_available(), "built with MPI: mfs_peigs_available() = 0");

  mfs_model_spec s = spec1(61, 2.3, "gauss2");
  s.disc.material.modulus = 2.385;
  compare(&s, "1D free gauss2", 1);
  s = spec1(53, 1.7, "nodal");
  s.fixed = MFS_FIX_ENDS;
  s.disc.kernel = &mfs_kernel_quartic;
  compare(&s, "1D fixed nodal quartic", 1);
  s = spec1(64, 2.0, "stress");
  s.disc.source.periodic = 1;
  s.disc.shape = &mfs_shape_sph;
  compare(&s, "1D periodic sph stress", 1);
  s = spec2(19, 23, 2.1, "gauss2");
  compare(&s, "2D anti-plane free gauss2", 1);
  s = spec2(17, 15, 2.2, "stress-quad");
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.disc.material.poisson = 0.3;
  s.fixed = MFS_FIX_BOUNDARY;
  compare(&s, "2D plane strain fixed stress-quad", 1);
  s = spec2(16, 14, 2.0, "stress-tri");
  s.disc.source.periodic = 1;
  compare(&s, "2D periodic stress-tri", 1);
  s = spec2(18, 16, 2.4, "gauss2");
  s.disc.source.perturb = 0.2;
  s.disc.source.seed = 7;
  s.disc.material.physics = MFS_PHYS_PLANE_STRAIN;
  s.disc.material.poisson = 0.27;
  compare(&s, "2D perturbed plane strain", 1);
  s = spec2(14, 13, 2.0, "nodal");
  s.disc.shape = &mfs_shape_rl;
  s.fixed = MFS_FIX_BOUNDARY;
  compare(&s, "2D fixed nodal rl", 1);

  /* a particle set: an irregular cloud with its Delaunay cells */
  {
    enum { NS = 300 };
    double *xs = malloc(2 * NS * sizeof *xs);
    for (int i = 0; i < NS; i++) { /* a jittered 20 x 15 grid */
      int ix = i % 20, iy = i / 20;
      xs[2 * i] = 0.05 * ix + 0.013 * sin(7.1 * i);
      xs[2 * i + 1] = 0.05 * iy + 0.011 * cos(5.3 * i);
    }
    mfs_point_set ps = {.dim = 2, .n = NS, .x = xs, .vol = NULL};
    s = spec2(2, 2, 2.0, "stress-tri");
    s.disc.source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &ps};
    s.disc.support = 0.11;
    compare(&s, "2D particle set stress-tri", 1);
    unsigned char *mask = calloc(NS, 1);
    for (int i = 0; i < NS; i++)
      mask[i] = i % 20 == 0; /* the left column */
    s.fixed = MFS_FIX_MASK;
    s.fix_mask = mask;
    s.disc.quadrature = mfs_quad_find("gauss1");
    compare(&s, "2D particle set gauss1 with a mask", 1);
    free(mask);
    free(xs);
  }

  /* statuses, the same on every rank */
  mfs_status st = MFS_OK;
  size_t bad = 0, pbad = 0;
  s = spec1(41, 2.0, "gauss2");
  s.disc.dilation = -1.0;
  CHECK(mfs_pmodel_alloc(&s, fcomm, 1, &st, NULL) == NULL && st == MFS_EINVAL,
        "a bad spec: %s, want MFS_EINVAL", mfs_strerror(st));
  s = spec1(41, 0.6, "gauss2"); /* too few neighbours for MLS somewhere */
  mfs_model *m = mfs_model_alloc(&s, &st, &bad);
  mfs_status pst;
  mfs_pmodel *pm = mfs_pmodel_alloc(&s, fcomm, 1, &pst, &pbad);
  CHECK(!m && !pm && st == MFS_ESINGULAR && pst == MFS_ESINGULAR && bad == pbad,
        "a singular moment matrix: %s at point %zu, the whole model %s at %zu", mfs_strerror(pst),
        pbad, mfs_strerror(st), bad);
  mfs_model_free(m);
  {
    unsigned char mask[41] = {0};
    for (int i = 1; i < 41; i++)
      mask[i] = 1; /* one free particle, at one end: the other rank has no rows */
    s = spec1(41, 2.0, "gauss2");
    s.fixed = MFS_FIX_MASK;
    s.fix_mask = mask;
    pm = mfs_pmodel_alloc(&s, fcomm, 1, &pst, NULL);
    if (size > 1)
      CHECK(!pm && pst == MFS_ETOOSMALL, "a rank without rows: %s, want MFS_ETOOSMALL",
            mfs_strerror(pst));
    else
      CHECK(pm != NULL, "one free particle on one rank: %s", mfs_strerror(pst));
    if (pm) {
      double lam;
      CHECK(mfs_peig_max(pm, NULL, &lam, NULL) == MFS_EINVAL, "lambda_max of one dof");
      mfs_pmodel_free(pm);
    }
    memset(mask, 1, sizeof mask);
    pm = mfs_pmodel_alloc(&s, fcomm, 1, &pst, NULL);
    CHECK(!pm && pst == MFS_EINVAL, "every particle fixed: %s, want MFS_EINVAL", mfs_strerror(pst));
  }
  s = spec2(12, 12, 2.0, "gauss2");
  s.disc.consistent_mass = 1;
  pm = mfs_pmodel_alloc(&s, fcomm, 1, &pst, NULL);
  CHECK(pm != NULL, "consistent mass: the bounds' model: %s", mfs_strerror(pst));
  if (pm) {
    double lam;
    mfs_gershgorin_result g;
    CHECK(mfs_peig_max(pm, NULL, &lam, NULL) == MFS_EINVAL, "lambda_max with a consistent mass");
    CHECK(mfs_pmodel_gershgorin(pm, &g) == MFS_EINVAL, "Gershgorin with a consistent mass");
    mfs_pmodel_free(pm);
  }
  int failed = 0, anyfailed = 0;
  failed = check_failed > 0;
  MPI_Allreduce(&failed, &anyfailed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  char name[64];
  snprintf(name, sizeof name, "test_peigs rank %d of %d", rank, size);
  check_summary(name);
  MPI_Finalize();
  return anyfailed ? 1 : 0;
}

#endif
