/* The evaluators of the dispersion analysis (issue 14): the folded lattice
 * sums of mfs_disp_omega2 / mfs_disp_ray / mfs_disp_omega2_states against
 * the direct term-by-term symbols (mfs_disp_symbols) with an eigen solve of
 * the test's own (LAPACKE zggev), over every kind of plan (1D and 2D, every
 * frame, lattice and quadrature family, lumped and consistent mass, least
 * squares, plane strain under stress and a finite stretch); the same bits
 * from every entry point, however a ray is split; long waves exact to
 * rounding (the versine form: omega^2 / kappa^2 at kappa dx = 1e-6 against
 * the continuum, where a cosine sum would keep 1e-4); the error returns. */
#include <complex.h>
#undef I
#include <lapacke.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static mfs_disc disc(int dim, mfs_lattice_kind lat, const char *quad, const mfs_shape_type *s,
                     double D, mfs_frame fr, mfs_physics_kind ph, int consistent)
{
  mfs_disc d = mfs_disc_default();
  d.dim = dim;
  d.source = (mfs_source){.lattice = lat, .spacing = 1.0, .gamma = 1.0};
  d.quadrature = mfs_quad_find(quad);
  d.kernel = &mfs_kernel_quartic;
  d.shape = s;
  d.dilation = D;
  d.frame = fr;
  d.material.physics = ph;
  d.material.poisson = 0.2385;
  d.consistent_mass = consistent;
  return d;
}

static int cmp_re(const void *a, const void *b)
{
  double x = creal(*(const double complex *)a), y = creal(*(const double complex *)b);
  return (x > y) - (x < y);
}

/* omega^2 from the direct symbols: the generalized eigenvalues by zggev;
 * *cond the loss of digits in the mass symbol, max_i M_ii(0) / |M_ii(k)|
 * (a consistent mass nearly vanishes at some zone corners: there two
 * accurate evaluations of these sums differ by that factor more). */
static void direct(const mfs_disp_plan *pl, double sbar, double kap, double th, double complex *w,
                   double *cond)
{
  int n = mfs_disp_branches(pl);
  double k[2] = {kap * M_PI * cos(th), kap * M_PI * sin(th)}, k0[2] = {0.0, 0.0};
  if (mfs_disp_plan_spec(pl)->disc.dim == 1)
    k[0] = kap * M_PI, k[1] = 0.0;
  double complex K[16], M[16], al[4], be[4], vl[1], vr[1];
  CHECK(mfs_disp_symbols(pl, sbar, k0, K, M) == MFS_OK, "direct symbols at 0");
  double m0[4];
  for (int i = 0; i < n; i++)
    m0[i] = cabs(M[i * n + i]);
  CHECK(mfs_disp_symbols(pl, sbar, k, K, M) == MFS_OK, "direct symbols");
  *cond = 1.0;
  for (int i = 0; i < n; i++)
    *cond = fmax(*cond, m0[i] / cabs(M[i * n + i]));
  lapack_int info = LAPACKE_zggev(LAPACK_ROW_MAJOR, 'N', 'N', n, K, n, M, n, al, be, vl, 1, vr, 1);
  CHECK(info == 0, "zggev info %d", (int)info);
  for (int i = 0; i < n; i++)
    w[i] = al[i] / be[i];
  qsort(w, (size_t)n, sizeof *w, cmp_re);
}

typedef struct {
  const char *what;
  mfs_disp_spec spec;
  double sig[3];
  int nsig;
} config;

enum { NK = 61, NTH = 3 };

/* The folded sums against the direct ones, the entry points against each other. */
static void one(const config *c)
{
  mfs_status st;
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&c->spec, &st);
  CHECK(pl != NULL, "%s: plan %s", c->what, mfs_strerror(st));
  if (!pl)
    return;
  const int nb = mfs_disp_branches(pl), dim = c->spec.disc.dim, nth = dim == 1 ? 1 : NTH;
  const double ths[NTH] = {0.0, 0.4137, 1.1};
  double kap[NK];
  double complex w[3 * NK * 4], wp[4], wd[NK * 4], wpiece[3 * NK * 4];
  double worst = 0.0;
  int bits = 0, split = 0;
  for (int t = 0; t < nth; t++) {
    double km = mfs_disp_kappa_max(pl, ths[t]);
    for (int i = 0; i < NK; i++) /* long waves, the zone, beyond it */
      kap[i] = i < 5 ? 1e-4 * (i + 1) : km * (i - 5) / (NK - 10) * 1.07;
    st = mfs_disp_ray(pl, c->sig, (size_t)c->nsig, ths[t], kap, NK, w, 0);
    CHECK(st == MFS_OK, "%s: ray %s", c->what, mfs_strerror(st));
    /* the ray in pieces of 1, 7 and the rest, stresses one at a time */
    for (int s = 0; s < c->nsig; s++) {
      const int cut[4] = {0, 1, 8, NK};
      for (int q = 0; q < 3; q++)
        mfs_disp_ray(pl, c->sig + s, 1, ths[t], kap + cut[q], (size_t)(cut[q + 1] - cut[q]),
                     wpiece + ((size_t)s * NK + cut[q]) * nb, 0);
    }
    split += memcmp(w, wpiece, (size_t)c->nsig * NK * nb * sizeof *w) != 0;
    for (int s = 0; s < c->nsig; s++) {
      double scale = 0.0, diff = 0.0, cond[NK];
      for (int i = 0; i < NK; i++) {
        const double complex *wr = w + ((size_t)s * NK + i) * nb;
        mfs_disp_omega2(pl, c->sig[s], kap[i], ths[t], wp);
        bits += memcmp(wp, wr, (size_t)nb * sizeof *wp) != 0;
        direct(pl, c->sig[s], kap[i], ths[t], wd + i * nb, cond + i);
        for (int b = 0; b < nb; b++)
          scale = fmax(scale, cabs(wd[i * nb + b]));
      }
      for (int i = 0; i < NK; i++) /* relative to the scale, times the mass's loss of digits */
        for (int b = 0; b < nb; b++)
          diff = fmax(diff, cabs(w[((size_t)s * NK + i) * nb + b] - wd[i * nb + b]) /
                              (scale * cond[i]));
      worst = fmax(worst, diff);
      CHECK(diff <= 2e-13, "%s: folded vs direct sums at sigma %g, theta %g: %.3g of the scale %.3g "
            "(times the mass's conditioning)", c->what, c->sig[s], ths[t], diff, scale);
    }
  }
  CHECK(bits == 0, "%s: mfs_disp_ray and mfs_disp_omega2 differ in %d points", c->what, bits);
  CHECK(split == 0, "%s: a ray in pieces differs from the whole (%d rays)", c->what, split);
  /* plane strain: the states entry point, point by point and all at once */
  if (c->spec.disc.material.physics == MFS_PHYS_PLANE_STRAIN) {
    mfs_plane_state ps;
    CHECK(mfs_disp_state(pl, c->sig[0], &ps) == MFS_OK, "%s: state", c->what);
    double kv[2 * NK];
    for (int i = 0; i < NK; i++) {
      kv[2 * i] = kap[i] * 2.1 * cos(0.3 + i);
      kv[2 * i + 1] = kap[i] * 2.1 * sin(0.3 + i);
    }
    CHECK(mfs_disp_omega2_states(pl, &ps, NK, kv, w) == MFS_OK, "%s: states", c->what);
    int sb = 0;
    for (int i = 0; i < NK; i++) {
      mfs_disp_omega2_state(pl, &ps, kv + 2 * i, wp);
      sb += memcmp(wp, w + (size_t)i * nb, (size_t)nb * sizeof *wp) != 0;
    }
    CHECK(sb == 0, "%s: mfs_disp_omega2_states and _state differ in %d points", c->what, sb);
    mfs_disp_sample *smp = mfs_disp_sample_alloc(pl, NK, kv, &st);
    CHECK(smp != NULL, "%s: sample", c->what);
    sb = 0;
    for (int i = 0; smp && i < NK; i++) {
      mfs_disp_sample_omega2(smp, (size_t)i, &ps, wp);
      sb += memcmp(wp, w + (size_t)i * nb, (size_t)nb * sizeof *wp) != 0;
    }
    CHECK(sb == 0, "%s: the sample and mfs_disp_omega2_states differ in %d points", c->what, sb);
    mfs_disp_sample_free(smp);
  }
  size_t no;
  int nc;
  mfs_disp_plan_work(pl, &no, &nc); /* the work bench_dispersion states its limit from */
  CHECK(no >= 1 && nc >= 1 && nc <= 72, /* the raw components, real and imaginary */ "%s: plan work %zu offsets x %d components",
        c->what, no, nc);
  printf("  %-44s folded vs direct %.2g\n", c->what, worst);
  mfs_disp_plan_free(pl);
}

static void configs(void)
{
  const mfs_frame L = MFS_FRAME_LAGRANGIAN, E = MFS_FRAME_EULERIAN,
                  C = MFS_FRAME_EULERIAN_CONSISTENT;
  const mfs_physics_kind S = MFS_PHYS_SCALAR, A = MFS_PHYS_SCALAR, P = MFS_PHYS_PLANE_STRAIN;
  const mfs_lattice_kind LN = MFS_LATTICE_LINE, SQ = MFS_LATTICE_SQUARE, HX = MFS_LATTICE_HEX;
  mfs_hyper neo = mfs_hyper_isotropic(&mfs_hyper_neo_hookean, 1.0, 0.3, 1.0);
  config cs[] = {
    {"1D Lagrangian nodal mls D=2.385", {.disc = disc(1, LN, "nodal", &mfs_shape_mls, 2.385, L, S, 0)},
     {0.0, 0.61, -0.37}, 3},
    {"1D Eulerian stress mls D=1.5, F=1.15",
     {.disc = disc(1, LN, "stress", &mfs_shape_mls, 1.5, E, S, 0), .stretch = 1.15}, {0.2385, -0.4}, 2},
    {"1D consistent nodal sph D=1.87", {.disc = disc(1, LN, "nodal", &mfs_shape_sph, 1.87, C, S, 0)},
     {0.31}, 1},
    {"1D gauss3 consistent mass, least squares",
     {.disc = disc(1, LN, "gauss3", &mfs_shape_mls, 2.1, L, S, 1), .ls_beta = 0.0548}, {0.0}, 1},
    {"1D nodal D=9.3 (offsets beyond the tables)",
     {.disc = disc(1, LN, "nodal", &mfs_shape_mls, 9.3, E, S, 0)}, {0.5}, 1},
    {"2D anti-plane stress-tri", {.disc = disc(2, SQ, "stress-tri", &mfs_shape_mls, 2.0, L, A, 0)},
     {0.0, 0.7}, 2},
    {"2D anti-plane hex gauss2 consistent mass",
     {.disc = disc(2, HX, "gauss2", &mfs_shape_mls, 2.2, L, A, 1)}, {0.3}, 1},
    {"2D anti-plane star (two particles)",
     {.disc = disc(2, SQ, "stress-star", &mfs_shape_mls, 2.1, L, A, 0)}, {0.0}, 1},
    {"2D plane strain stress-quad under stress",
     {.disc = disc(2, SQ, "stress-quad", &mfs_shape_mls, 2.0, L, P, 0), .stress_yy = -0.2,
      .stress_xy = 0.13},
     {0.3, -0.6}, 2},
    {"2D plane strain Eulerian stress-tri",
     {.disc = disc(2, SQ, "stress-tri", &mfs_shape_mls, 2.0, E, P, 0), .stress_xy = 0.1}, {0.25}, 1},
    {"2D plane strain consistent stress-tri, sigma_xy (complex)",
     {.disc = disc(2, SQ, "stress-tri", &mfs_shape_mls, 2.0, C, P, 0), .stress_yy = -0.2,
      .stress_xy = 0.1},
     {0.3}, 1},
    {"2D plane strain consistent hex nodal",
     {.disc = disc(2, HX, "nodal", &mfs_shape_mls, 2.3, C, P, 0)}, {-0.2}, 1},
    {"2D plane strain star (four branches)",
     {.disc = disc(2, SQ, "stress-star", &mfs_shape_mls, 2.0, L, P, 0)}, {0.1}, 1},
    {"2D neo-hookean Eulerian stretch (1.2, 0.9)",
     {.disc = disc(2, SQ, "stress-tri", &mfs_shape_mls, 2.0, C, P, 0), .material = neo,
      .stretch = 1.2, .stretch_y = 0.9},
     {0.0}, 1},
  };
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
    if (cs[i].spec.stretch == 0.0 && cs[i].spec.disc.dim == 1)
      cs[i].spec.stretch = 1.0;
    one(cs + i);
  }
}

/* Long waves: (omega^2(kappa) - omega^2(0)) / kappa^2 of a Lagrangian MLS
 * lattice tends to the continuum's (F^2 + sbar; anti-plane 1 + sbar) with an
 * error O(kappa^2): at kappa dx = 1e-6 the discretization's part is ~1e-12,
 * so a value exact to rounding is within 1e-9, while a sum of cosines (1 -
 * 5e-13 cancelling against sum_t c_t) would keep only ~1e-4.  omega^2(0) is
 * the assembled rows' sum, zero but for rounding (~1e-16: at kappa dx = 1e-6
 * it is 1e-4 of omega^2, the same for every evaluation of these rows). */
static void long_waves(void)
{
  const double h = 1e-6;
  struct {
    mfs_disp_spec spec;
    double sbar, q;
  } cs[] = {
    {{.disc = disc(1, MFS_LATTICE_LINE, "nodal", &mfs_shape_mls, 2.385, MFS_FRAME_LAGRANGIAN,
                   MFS_PHYS_SCALAR, 0),
      .stretch = 1.0},
     0.2385, 1.2385},
    {{.disc = disc(1, MFS_LATTICE_LINE, "stress", &mfs_shape_mls, 1.7, MFS_FRAME_LAGRANGIAN,
                   MFS_PHYS_SCALAR, 1),
      .stretch = 1.1},
     -0.3, 1.21 - 0.3},
    {{.disc = disc(2, MFS_LATTICE_HEX, "stress-hex", &mfs_shape_mls, 2.0, MFS_FRAME_LAGRANGIAN,
                   MFS_PHYS_SCALAR, 0)},
     0.5, 1.5},
  };
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
    mfs_status st;
    mfs_disp_plan *pl = mfs_disp_plan_alloc(&cs[i].spec, &st);
    CHECK(pl != NULL, "long waves: plan %s", mfs_strerror(st));
    if (!pl)
      continue;
    double complex w, w0;
    mfs_disp_omega2(pl, cs[i].sbar, h / M_PI, 0.3, &w);
    mfs_disp_omega2(pl, cs[i].sbar, 0.0, 0.3, &w0);
    CHECK(fabs(creal(w0)) < 1e-15, "long waves, case %zu: omega^2(0) = %g, rounding", i, creal(w0));
    double r = (creal(w) - creal(w0)) / (h * h);
    CHECK_NEAR(r, cs[i].q, 1e-9 * cs[i].q, "long waves, case %zu: omega^2 / kappa^2 at kappa dx = %g",
               i, h);
    mfs_disp_plan_free(pl);
  }
}

/* The Hermitian solves (lumped mass: the closed 2 x 2 form, the 4 x 4 kernel
 * of Householder and Jacobi) against LAPACK's zheev of M^-1/2 K M^-1/2 from
 * the direct symbols, to 4e-15 of the scale (seen: 1.2e-15; the Jacobi test
 * stops at eps / 3 of the Frobenius norm): at kappa = 0 (the rigid modes: a
 * double root at 0 in plane strain), along the symmetric directions theta = 0,
 * pi/4, pi/2 where branches cross (double roots; there the tridiagonal
 * splits), and across the zone and beyond it. */
static void hermitian_solves(void)
{
  const mfs_frame L = MFS_FRAME_LAGRANGIAN;
  const mfs_lattice_kind SQ = MFS_LATTICE_SQUARE;
  struct {
    const char *what;
    mfs_disp_spec spec;
    double sbar;
  } cs[] = {
    {"plane strain star", {.disc = disc(2, SQ, "stress-star", &mfs_shape_mls, 2.0, L,
                                        MFS_PHYS_PLANE_STRAIN, 0)}, 0.1},
    {"plane strain star D=2.6", {.disc = disc(2, SQ, "stress-star", &mfs_shape_mls, 2.6, L,
                                              MFS_PHYS_PLANE_STRAIN, 0)}, -0.3},
    {"anti-plane star", {.disc = disc(2, SQ, "stress-star", &mfs_shape_mls, 2.1, L,
                                      MFS_PHYS_SCALAR, 0)}, 0.0},
    {"plane strain stress-tri", {.disc = disc(2, SQ, "stress-tri", &mfs_shape_mls, 2.0, L,
                                              MFS_PHYS_PLANE_STRAIN, 0)}, 0.2},
  };
  const double ths[6] = {0.0, M_PI / 4, M_PI / 2, 0.1234, -M_PI / 4, M_PI};
  enum { NKH = 41 };
  for (size_t c = 0; c < sizeof cs / sizeof cs[0]; c++) {
    mfs_status st;
    mfs_disp_plan *pl = mfs_disp_plan_alloc(&cs[c].spec, &st);
    CHECK(pl != NULL, "%s: plan %s", cs[c].what, mfs_strerror(st));
    if (!pl)
      continue;
    const int n = mfs_disp_branches(pl);
    const int rigid = cs[c].spec.disc.material.physics == MFS_PHYS_PLANE_STRAIN ? 2 : 1;
    double worst = 0.0;
    for (int t = 0; t < 6; t++) {
      double kap[NKH], km = mfs_disp_kappa_max(pl, ths[t]);
      for (int i = 0; i < NKH; i++) /* 0, the zone's edge (i = 30), beyond */
        kap[i] = km * i / 30.0;
      double complex w[NKH * 4];
      CHECK(mfs_disp_ray(pl, &cs[c].sbar, 1, ths[t], kap, NKH, w, 0) == MFS_OK, "%s: ray",
            cs[c].what);
      double ref[NKH * 4], scale = 0.0, diff = 0.0;
      for (int i = 0; i < NKH; i++) {
        double k[2] = {kap[i] * M_PI * cos(ths[t]), kap[i] * M_PI * sin(ths[t])};
        double complex K[16], M[16], A[16];
        CHECK(mfs_disp_symbols(pl, cs[c].sbar, k, K, M) == MFS_OK, "%s: symbols", cs[c].what);
        for (int r = 0; r < n; r++)
          for (int q = 0; q < n; q++)
            A[r * n + q] = K[r * n + q] / sqrt(creal(M[r * n + r]) * creal(M[q * n + q]));
        lapack_int info = LAPACKE_zheev(LAPACK_ROW_MAJOR, 'N', 'U', n, A, n, ref + i * n);
        CHECK(info == 0, "%s: zheev info %d", cs[c].what, (int)info);
        for (int b = 0; b < n; b++)
          scale = fmax(scale, fabs(ref[i * n + b]));
      }
      for (int i = 0; i < NKH * n; i++) {
        diff = fmax(diff, cabs(w[i] - ref[i]));
        if (i < rigid) /* kappa = 0: the rigid translations (the optical branches are not 0) */
          CHECK(fabs(creal(w[i])) <= 4e-15 * scale, "%s: theta %g, kappa 0: omega^2 %g of %g",
                cs[c].what, ths[t], creal(w[i]), scale);
      }
      worst = fmax(worst, diff / scale);
      CHECK(diff <= 4e-15 * scale, "%s: theta %g: against zheev %.3g of the scale %.3g",
            cs[c].what, ths[t], diff / scale, scale);
    }
    printf("  %-44s Hermitian solve vs zheev %.2g\n", cs[c].what, worst);
    mfs_disp_plan_free(pl);
  }
}

static void errors(void)
{
  mfs_status st;
  mfs_hyper neo = mfs_hyper_isotropic(&mfs_hyper_neo_hookean, 1.0, 0.3, 1.0);
  mfs_disp_spec sp = {.disc = disc(2, MFS_LATTICE_SQUARE, "stress-tri", &mfs_shape_mls, 2.0,
                                   MFS_FRAME_LAGRANGIAN, MFS_PHYS_PLANE_STRAIN, 0),
                      .material = neo, .stretch = 1.1, .stretch_y = 1.0};
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&sp, &st);
  CHECK(pl != NULL, "finite plan: %s", mfs_strerror(st));
  if (!pl)
    return;
  double sig[2] = {0.0, 0.2}, kap[3] = {0.1, 0.2, 0.3};
  double complex w[12];
  CHECK(mfs_disp_ray(pl, sig, 2, 0.0, kap, 3, w, 0) == MFS_EINVAL,
        "a stress with a finite material: MFS_EINVAL");
  CHECK(mfs_disp_ray(pl, sig, 1, 0.0, kap, 3, w, 0) == MFS_OK, "sbar 0 with a finite material");
  CHECK(mfs_disp_ray(pl, sig, 1, 0.0, kap, 0, w, 0) == MFS_OK, "an empty ray");
  mfs_plane_state other;
  mfs_plane_state_stretch(&neo, 1.3, 1.0, &other);
  mfs_disp_spec se = sp;
  se.disc.frame = MFS_FRAME_EULERIAN;
  mfs_disp_plan *pe = mfs_disp_plan_alloc(&se, &st);
  double kv[2] = {0.3, 0.1};
  CHECK(pe && mfs_disp_omega2_states(pe, &other, 1, kv, w) == MFS_EINVAL,
        "an Eulerian plan at another stretch: MFS_EINVAL");
  mfs_disp_plan_free(pe);
  mfs_disp_plan_free(pl);
}

/* A value that is not finite: the block kernels' lanewise tests send its
 * points to the general path, which writes NaN there and returns
 * MFS_EDOMAIN; the other points of the same blocks keep their values, the
 * same as each point alone.  A stress of 5e307 makes K / m overflow (or
 * inf - inf) at some wave numbers; 10 points: a full block and a partial one. */
static void overflow(void)
{
  mfs_status st;
  mfs_disp_spec sp = {.disc = disc(1, MFS_LATTICE_LINE, "nodal", &mfs_shape_mls, 1.5,
                                   MFS_FRAME_EULERIAN, MFS_PHYS_SCALAR, 0),
                      .stretch = 1.0};
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&sp, &st);
  CHECK(pl != NULL, "1D plan: %s", mfs_strerror(st));
  if (!pl)
    return;
  double kap[10], big = 5e307, mild = 0.25;
  double complex w[10], wm[10], w1;
  for (int i = 0; i < 10; i++)
    kap[i] = 0.1 * i;
  st = mfs_disp_ray(pl, &big, 1, 0.0, kap, 10, w, 0);
  CHECK(st == MFS_EDOMAIN, "sbar 5e307: %s, want MFS_EDOMAIN", mfs_strerror(st));
  int nan = 0, fin = 0, differ = 0;
  for (int i = 0; i < 10; i++) {
    const int n = isnan(creal(w[i])) && isnan(cimag(w[i]));
    nan += n;
    fin += isfinite(creal(w[i])) && isfinite(cimag(w[i]));
    mfs_status s1 = mfs_disp_omega2(pl, big, kap[i], 0.0, &w1);
    differ += n ? !(s1 == MFS_EDOMAIN && isnan(creal(w1)))
                : (s1 != MFS_OK || memcmp(&w1, w + i, sizeof w1) != 0);
  }
  CHECK(nan == 4 && fin == 6,
        "sbar 5e307: %d NaN and %d finite points of 10, want 4 and 6 (kappa dx / pi >= 0.6)", nan,
        fin);
  CHECK(differ == 0, "sbar 5e307: %d points differ from the same point alone", differ);
  CHECK(mfs_disp_ray(pl, &mild, 1, 0.0, kap, 10, wm, 0) == MFS_OK, "sbar 0.25: not MFS_OK");
  for (int i = 0; i < 10; i++)
    CHECK(isfinite(creal(wm[i])) && isfinite(cimag(wm[i])), "sbar 0.25, point %d not finite", i);
  mfs_disp_plan_free(pl);
}

int main(void)
{
  configs();
  long_waves();
  hermitian_solves();
  errors();
  overflow();
  return check_summary("test_dispersion_fast");
}
