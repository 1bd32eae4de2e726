/* Plain Lanczos lambda_max (lib/analysis/mfs_lanczos): against matrices
 * whose top eigenvalue is known in closed form and whose spectrum is
 * clustered at the top (the Laplacian: relative gap ~ 5e-5 at order 400, the
 * case where a stopping rule that looks only at the change of theta would
 * stop early), against ARPACK (mfs_eig_max at 1e-12) and dense LAPACK on
 * finite models, both storages (scalar and 2 x 2 blocks, sorted pairs and
 * the general path), the reported error estimate against the true error,
 * bad input, and the same bits with 1 and 2 threads; the stored operator
 * (lib/analysis/mfs_symop) of the 2 x 2 fill against the general build of
 * the same matrix, its first product against K's rows. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "check.h"
#include "mfs_symop.h"
#include "mfstab.h"

/* K = diag(sqrt m) (L (x) B) diag(sqrt m): L the Laplacian of order nl (1D)
 * or the 5-point one on nl x nl nodes (2D), B a bs x bs block (bs 1 or 2),
 * rows sorted ascending (reverse: descending, so that the pairs test fails
 * and the general build runs).  A = M^-1/2 K M^-1/2 = L (x) B. */
static mfs_csr *kron(int nl, int dim, int bs, const double *B, const double *m, int reverse)
{
  size_t nn = dim == 1 ? (size_t)nl : (size_t)nl * (size_t)nl, n = nn * (size_t)bs;
  mfs_csr *K = mfs_csr_alloc(n, n, n * (size_t)(2 * dim + 1) * (size_t)bs);
  if (!K)
    return NULL;
  size_t p = 0;
  for (size_t node = 0; node < nn; node++) {
    long nb[5];
    double lv[5];
    int c = 0;
    long ix = dim == 1 ? (long)node : (long)(node % (size_t)nl), iy = dim == 1 ? 0 : (long)(node / (size_t)nl);
    /* neighbours in ascending node order */
    if (dim == 2 && iy > 0) {
      nb[c] = (long)node - nl;
      lv[c++] = -1.0;
    }
    if (ix > 0) {
      nb[c] = (long)node - 1;
      lv[c++] = -1.0;
    }
    nb[c] = (long)node;
    lv[c++] = 2.0 * dim;
    if (ix < nl - 1) {
      nb[c] = (long)node + 1;
      lv[c++] = -1.0;
    }
    if (dim == 2 && iy < nl - 1) {
      nb[c] = (long)node + nl;
      lv[c++] = -1.0;
    }
    for (int a = 0; a < bs; a++) {
      size_t r = node * (size_t)bs + (size_t)a;
      K->ptr[r] = p;
      for (int q = 0; q < c; q++) {
        int qq = reverse ? c - 1 - q : q;
        for (int b = 0; b < bs; b++) {
          int bb = reverse ? bs - 1 - b : b;
          size_t col = (size_t)nb[qq] * (size_t)bs + (size_t)bb;
          K->idx[p] = (int)col;
          K->val[p++] = sqrt(m[r]) * lv[qq] * B[a * bs + bb] * sqrt(m[col]);
        }
      }
    }
  }
  K->ptr[n] = p;
  return K;
}

static double *masses(size_t n)
{
  double *m = malloc(n * sizeof *m);
  for (size_t i = 0; m && i < n; i++)
    m[i] = 1.0 + 0.5 * sin(2.385 * (double)i);
  return m;
}

/* The largest eigenvalue of L (x) B: that of L times B's larger one. */
static double kron_top(int nl, int dim, int bs, const double *B)
{
  double l = dim * (2.0 - 2.0 * cos(M_PI * nl / (nl + 1.0)));
  if (bs == 1)
    return l * B[0];
  double h = 0.5 * (B[0] + B[3]), d = 0.5 * (B[0] - B[3]);
  return l * (h + sqrt(d * d + B[1] * B[1]));
}

/* The stopping rule against the exact top eigenvalue ex: at the stop the
 * error is below tol theta and below the reported estimate (the top of a
 * symmetric matrix: |theta - ex| <= ||A y - theta y||), theta is a lower
 * bound, and one step fewer does not meet the rule. */
static void check_rule(const mfs_pencil *P, double tol, double ex, int want_block, const char *what)
{
  mfs_lanczos_opts o = {.tol = tol};
  mfs_lanczos_info li;
  double th = 0.0;
  mfs_status st = mfs_lanczos_max(P, &o, &th, &li);
  CHECK(st == MFS_OK, "%s: status %s", what, mfs_strerror(st));
  if (st != MFS_OK)
    return;
  double err = (ex - th) / ex;
  CHECK(err <= tol, "%s tol %g: relative error %.3g above the tolerance (%d steps)", what, tol, err,
        li.matvecs);
  CHECK(err >= -1e-13, "%s tol %g: theta %.17g above lambda_max %.17g by %.3g", what, tol, th, ex,
        -err);
  CHECK(li.bound <= tol, "%s tol %g: stopped with the estimate %.3g above tol", what, tol, li.bound);
  CHECK(fabs(err) <= li.bound * (1.0 + 1e-6) + 1e-14, "%s tol %g: error %.3g above its estimate %.3g",
        what, tol, err, li.bound);
  CHECK(li.block == want_block, "%s: block size %d, want %d", what, li.block, want_block);
  CHECK(li.bytes > 0.0 && li.op_seconds >= 0.0 && li.setup_seconds >= 0.0, "%s: info", what);
  if (li.matvecs > 1) {
    mfs_lanczos_opts o1 = {.tol = tol, .maxiter = li.matvecs - 1};
    mfs_lanczos_info l1;
    double t1 = 0.0;
    st = mfs_lanczos_max(P, &o1, &t1, &l1);
    CHECK(st == MFS_ENOCONV && l1.matvecs == li.matvecs - 1 && l1.bound > tol,
          "%s tol %g: %d steps: status %s, estimate %.3g (the rule met one step early)", what, tol,
          li.matvecs - 1, mfs_strerror(st), l1.bound);
    CHECK(t1 <= th, "%s: theta fell from %.17g to %.17g in the last step", what, t1, th);
  }
}

static void closed_forms(void)
{
  const double one[1] = {1.0}, B[4] = {2.385, -0.731, -0.731, 1.19};
  /* 1D Laplacian, order 400, scalar storage (the general build) */
  double *m = masses(800);
  mfs_csr *K = kron(400, 1, 1, one, m, 0);
  mfs_pencil P = {K, NULL, m};
  for (double tol = 1e-6; tol >= 1e-10; tol *= 1e-2)
    check_rule(&P, tol, kron_top(400, 1, 1, one), 1, "laplacian 1D n 400");
  mfs_csr_free(K);
  /* L (x) B, 2 x 2 blocks: sorted pairs, and the same matrix in reversed rows */
  for (int rev = 0; rev < 2; rev++) {
    K = kron(300, 1, 2, B, m, rev);
    P.K = K;
    check_rule(&P, 1e-8, kron_top(300, 1, 2, B), 2, rev ? "L(x)B reversed rows" : "L(x)B pairs");
    mfs_csr_free(K);
  }
  /* 2D: 20 x 20 nodes (x) B */
  K = kron(20, 2, 2, B, m, 0);
  P.K = K;
  check_rule(&P, 1e-8, kron_top(20, 2, 2, B), 2, "L2D(x)B");
  mfs_csr_free(K);
  free(m);
}

static mfs_model_spec spec(int dim, int nx, mfs_physics_kind phys)
{
  mfs_model_spec s = mfs_model_spec_default();
  s.disc.dim = dim;
  s.disc.source.nx = nx;
  s.disc.dilation = 2.0;
  s.disc.quadrature = mfs_quad_find(dim == 2 ? "stress-quad" : "gauss2");
  if (dim == 2) {
    s.disc.source.lattice = MFS_LATTICE_SQUARE;
    s.disc.source.ny = nx - 3;
    s.disc.source.lx = 1.137;
    s.disc.source.ly = 0.8725;
    s.disc.material.physics = phys;
    s.disc.material.poisson = 0.3;
  }
  return s;
}

/* Finite models: Lanczos at 1e-8 against ARPACK at 1e-12 and dense LAPACK. */
static void models(void)
{
  struct {
    int dim, nx;
    mfs_physics_kind phys;
    int block;
    const char *what;
  } c[] = {{1, 61, MFS_PHYS_SCALAR, 1, "rod 61 nodes"},
           /* scalar, but pairs of particles in 2 x 2 blocks read fewer bytes (choose_block) */
           {2, 15, MFS_PHYS_SCALAR, 2, "anti-plane 15 x 12"},
           {2, 15, MFS_PHYS_PLANE_STRAIN, 2, "plane strain 15 x 12"}};
  for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
    mfs_model_spec s = spec(c[k].dim, c[k].nx, c[k].phys);
    mfs_status st;
    mfs_model *m = mfs_model_alloc(&s, &st, NULL);
    CHECK(m != NULL, "%s: model: %s", c[k].what, mfs_strerror(st));
    if (!m)
      continue;
    mfs_pencil P = {m->K, NULL, m->m};
    double la = 0.0, th = 0.0, *w = malloc(m->n * sizeof *w);
    mfs_eig_opts eo = {.tol = 1e-12};
    st = mfs_eig_max(&P, &eo, &la, NULL, NULL);
    CHECK(st == MFS_OK, "%s: ARPACK: %s", c[k].what, mfs_strerror(st));
    CHECK(mfs_eig_dense(&P, w) == MFS_OK, "%s: dense", c[k].what);
    double ex = w[m->n - 1];
    CHECK(fabs(la - ex) <= 1e-11 * ex, "%s: ARPACK %.17g dense %.17g", c[k].what, la, ex);
    check_rule(&P, 1e-8, ex, c[k].block, c[k].what);
    mfs_lanczos_opts o = {.tol = 1e-8};
    st = mfs_lanczos_max(&P, &o, &th, NULL);
    CHECK(st == MFS_OK && fabs(th - la) <= 1e-8 * la, "%s: Lanczos %.17g ARPACK %.17g (rel %.3g)",
          c[k].what, th, la, (th - la) / la);
    /* consistent mass: not this solver's */
    if (m->M == NULL) {
      mfs_model_spec sc = s;
      sc.disc.consistent_mass = 1;
      mfs_model *mc = mfs_model_alloc(&sc, &st, NULL);
      if (mc) {
        mfs_pencil Pc = {mc->K, mc->M, NULL};
        CHECK(mfs_lanczos_max(&Pc, NULL, &th, NULL) == MFS_ENOTSUP, "%s: consistent mass accepted",
              c[k].what);
        mfs_model_free(mc);
      }
    }
    free(w);
    mfs_model_free(m);
  }
}

static void bad_input(void)
{
  const double one[1] = {1.0};
  double *m = masses(50), th = 0.0;
  mfs_csr *K = kron(50, 1, 1, one, m, 0);
  mfs_pencil P = {K, NULL, m};
  mfs_lanczos_opts o[] = {{.tol = 1e-15}, {.tol = 1.0}, {.tol = NAN}, {.tol = -1e-8}, {.maxiter = -1}};
  for (size_t k = 0; k < sizeof o / sizeof o[0]; k++)
    CHECK(mfs_lanczos_max(&P, o + k, &th, NULL) == MFS_EINVAL, "option set %zu accepted", k);
  m[7] = 0.0;
  CHECK(mfs_lanczos_max(&P, NULL, &th, NULL) == MFS_EINVAL, "a zero mass accepted");
  m[7] = 1.0;
  mfs_pencil P2 = {K, K, NULL};
  CHECK(mfs_lanczos_max(&P2, NULL, &th, NULL) == MFS_ENOTSUP, "consistent mass accepted");
  mfs_pencil P3 = {K, K, m};
  CHECK(mfs_lanczos_max(&P3, NULL, &th, NULL) == MFS_EINVAL, "both masses accepted");
  CHECK(mfs_lanczos_max(NULL, NULL, &th, NULL) == MFS_EINVAL, "no pencil accepted");
  K->val[13] = NAN;
  CHECK(mfs_lanczos_max(&P, NULL, &th, NULL) == MFS_EDOMAIN, "a NaN in K gave no EDOMAIN");
  mfs_csr_free(K);
  K = kron(1, 1, 1, one, m, 0);
  P.K = K;
  CHECK(mfs_lanczos_max(&P, NULL, &th, NULL) == MFS_EINVAL, "n = 1 accepted");
  mfs_csr_free(K);
  free(m);
}

/* Above the parallel threshold (2^21 stored entries): the same bits with 1
 * and 2 threads (25 steps of a 600 x 600 L (x) B, 720 000 unknowns). */
static void threads(void)
{
#ifdef _OPENMP
  const double B[4] = {2.385, -0.731, -0.731, 1.19};
  double *m = masses(720000);
  mfs_csr *K = kron(600, 2, 2, B, m, 0);
  CHECK(K != NULL && m != NULL, "threads: allocation");
  if (!K || !m) {
    free(m);
    mfs_csr_free(K);
    return;
  }
  mfs_pencil P = {K, NULL, m};
  mfs_lanczos_opts o = {.tol = 1e-12, .maxiter = 25};
  double th[2] = {0.0, 0.0}, bd[2] = {0.0, 0.0};
  int keep = omp_get_max_threads();
  for (int t = 0; t < 2; t++) {
    omp_set_num_threads(t + 1);
    mfs_lanczos_info li;
    mfs_status st = mfs_lanczos_max(&P, &o, th + t, &li);
    CHECK(st == MFS_ENOCONV && li.matvecs == 25, "threads %d: status %s after %d steps", t + 1,
          mfs_strerror(st), li.matvecs);
    bd[t] = li.bound;
  }
  omp_set_num_threads(keep);
  CHECK(memcmp(th, th + 1, sizeof th[0]) == 0 && memcmp(bd, bd + 1, sizeof bd[0]) == 0,
        "threads: 1 thread theta %.17g bound %.17g, 2 threads %.17g %.17g", th[0], bd[0], th[1],
        bd[1]);
  mfs_csr_free(K);
  free(m);
#endif
}

/* Two stored operators hold the same bits (sizes, cuts, bands, row
 * pointers, runs, values, diagonal blocks). */
static int symop_same(const mfs_symop *a, const mfs_symop *b)
{
  if (a->n != b->n || a->nb != b->nb || a->b != b->b || a->stored != b->stored ||
      a->runs != b->runs || memcmp(a->cut, b->cut, sizeof a->cut) ||
      memcmp(a->zoff, b->zoff, sizeof a->zoff))
    return 0;
  size_t bb = (size_t)(a->b * a->b);
  return !memcmp(a->ptr, b->ptr, (a->nb + 1) * sizeof *a->ptr) &&
         !memcmp(a->rptr, b->rptr, (a->nb + 1) * sizeof *a->rptr) &&
         !memcmp(a->run, b->run, a->runs * sizeof *a->run) &&
         !memcmp(a->val, b->val, a->stored * sizeof *a->val) &&
         !memcmp(a->diag, b->diag, a->nb * bb * sizeof *a->diag);
}

/* K with each row's entries in reverse (descending columns): the same
 * matrix, which the 2 x 2 fill declines (the general build then runs). */
static mfs_csr *reversed(const mfs_csr *K)
{
  size_t n = K->nrow;
  mfs_csr *R = mfs_csr_alloc(n, K->ncol, K->ptr[n]);
  if (!R)
    return NULL;
  for (size_t r = 0; r <= n; r++)
    R->ptr[r] = K->ptr[r];
  for (size_t r = 0; r < n; r++)
    for (size_t e = K->ptr[r], f = K->ptr[r + 1]; e < K->ptr[r + 1]; e++) {
      R->idx[--f] = K->idx[e];
      R->val[f] = K->val[e];
    }
  return R;
}

/* The 2 x 2 fill of K (sorted pairs: one pass that also writes the runs,
 * the bands and the first product) against the general build of the same
 * matrix with its rows reversed (the fill declines it): the same operator,
 * bit for bit, with and without the scaling s, with 1 and 2 threads (par:
 * the build's loops on the threads however small); the first product y0 =
 * A x0 from the fill and the product of the stored operator against
 * diag(s) K diag(s) x0 summed from K's rows here.  want_runs, want_band:
 * the runs and band buffer entries expected (0: not checked). */
static void symop_compare(const mfs_csr *K, const double *s, const char *what, size_t want_runs,
                          size_t want_band)
{
  size_t n = K->nrow;
  double *x = malloc(n * sizeof *x), *y0 = malloc(n * sizeof *y0), *y1 = malloc(n * sizeof *y1),
         *y2 = malloc(n * sizeof *y2);
  mfs_csr *R = reversed(K);
  CHECK(x && y0 && y1 && y2 && R, "%s: allocation", what);
  if (x && y0 && y1 && y2 && R) {
    for (size_t i = 0; i < n; i++)
      x[i] = sin(0.731 * (double)i + 0.3);
    int keep = 1;
#ifdef _OPENMP
    keep = omp_get_max_threads();
#endif
    for (int sc = 0; sc < 2; sc++)
      for (int nt = 1; nt <= 2; nt++) {
#ifdef _OPENMP
        omp_set_num_threads(nt);
#endif
        const double *ss = sc ? s : NULL;
        mfs_symop A = {0}, G = {0};
        int hy = 0, hg = 0;
        int st = mfs_symop_build(K, ss, x, y0, nt, 1, &A, &hy);
        int sg = mfs_symop_build(R, ss, NULL, NULL, nt, 1, &G, &hg);
        CHECK(st == MFS_OK && sg == MFS_OK && hy == 1 && hg == 0 && A.b == 2 && G.b == 2,
              "%s (scaled %d, %d threads): status %d %d, first product %d %d, block %d %d", what,
              sc, nt, st, sg, hy, hg, A.b, G.b);
        if (st == MFS_OK && sg == MFS_OK) {
          CHECK(symop_same(&A, &G),
                "%s (scaled %d, %d threads): the 2 x 2 fill and the general build differ "
                "(stored %zu %zu, runs %zu %zu, band %zu %zu)", what, sc, nt, A.stored, G.stored,
                A.runs, G.runs, A.zoff[8], G.zoff[8]);
          CHECK((!want_runs || A.runs == want_runs) && (!want_band || A.zoff[8] == want_band),
                "%s (scaled %d, %d threads): %zu runs, band %zu; want %zu, %zu", what, sc, nt,
                A.runs, A.zoff[8], want_runs, want_band);
          mfs_symop_apply(&A, x, y1);
          mfs_symop_apply(&G, x, y2);
          CHECK(memcmp(y1, y2, n * sizeof *y1) == 0, "%s (scaled %d, %d threads): products differ",
                what, sc, nt);
          double e0 = 0.0, e1 = 0.0, ny = 0.0;
          for (size_t r = 0; r < n; r++) { /* y = diag(s) K diag(s) x from K's rows */
            double acc = 0.0, sr = ss ? ss[r] : 1.0;
            for (size_t e = K->ptr[r]; e < K->ptr[r + 1]; e++) {
              size_t c = (size_t)K->idx[e];
              acc += sr * K->val[e] * (ss ? ss[c] : 1.0) * x[c];
            }
            e0 = fmax(e0, fabs(y0[r] - acc));
            e1 = fmax(e1, fabs(y1[r] - acc));
            ny = fmax(ny, fabs(acc));
          }
          CHECK(e0 <= 1e-13 * ny && e1 <= 1e-13 * ny,
                "%s (scaled %d, %d threads): first product off by %.3g, product by %.3g "
                "(max |y| %.3g)", what, sc, nt, e0, e1, ny);
        }
        mfs_symop_free(&A);
        mfs_symop_free(&G);
      }
#ifdef _OPENMP
    omp_set_num_threads(keep);
#endif
  }
  free(x);
  free(y0);
  free(y1);
  free(y2);
  mfs_csr_free(R);
}

/* symop_compare on L (x) B of 300 x 300 nodes (the upper neighbours +1 and
 * +300: one block each, never consecutive; 8 row blocks whose bands, but
 * block 7's, reach 300 block columns beyond their ends) and on a plane
 * strain model of 60 x 57 nodes (cubic MLS: runs of several blocks, some
 * cut at the row blocks' ends). */
static void symop_paths(void)
{
  const double B[4] = {2.385, -0.731, -0.731, 1.19};
  const int nl = 300;
  size_t n = (size_t)nl * (size_t)nl * 2;
  double *m = masses(n), *s = malloc(n * sizeof *s);
  mfs_csr *K = kron(nl, 2, 2, B, m, 0);
  CHECK(m && s && K, "symop: allocation");
  if (m && s && K) {
    for (size_t i = 0; i < n; i++)
      s[i] = 1.0 / sqrt(m[i]);
    symop_compare(K, s, "symop L (x) B", 2 * (size_t)nl * (size_t)(nl - 1), 2 * 7 * (size_t)nl);
  }
  free(m);
  free(s);
  mfs_csr_free(K);
  mfs_model_spec sp = spec(2, 60, MFS_PHYS_PLANE_STRAIN);
  mfs_status st;
  mfs_model *md = mfs_model_alloc(&sp, &st, NULL);
  CHECK(md != NULL, "symop model: %s", mfs_strerror(st));
  if (!md)
    return;
  double *sm = malloc(md->n * sizeof *sm);
  CHECK(sm != NULL, "symop model: allocation");
  for (size_t i = 0; sm && i < md->n; i++)
    sm[i] = 1.0 / sqrt(md->m[i]);
  if (sm)
    symop_compare(md->K, sm, "symop plane strain 60 x 57", 0, 0);
  free(sm);
  mfs_model_free(md);
}

int main(void)
{
  closed_forms();
  models();
  bad_input();
  threads();
  symop_paths();
  return check_summary("test_lanczos");
}
