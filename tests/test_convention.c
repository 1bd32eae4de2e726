/* The peers' conventions (lib/core/mfs_convention): for every preset, the
 * peer's own W(r, h), written here as the peer's code writes it (constants
 * included; files cited in docs/conventions.md), equals mfstab's kernel with
 * the mapped support radius a = support_per_h * h, at 400 radii on
 * [0, 1.1 a] for a stated h; and every step rule equals the peer's formula
 * evaluated by hand with the Lame constants. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "mfstab.h"

static double pos(double x)
{
  return x > 0.0 ? x : 0.0;
}

/* ---- the peers' kernels, W(r, h) in dimension d ------------------------ */

/* LAMMPS src/MACHDYN/smd_kernels.h, spiky_kernel_and_derivative (2D branch), with
 * h the pair support radius_i + radius_j: its 10-digit pi/10 is kept. */
static double lammps_spiky(double r, double hpair, int d)
{
  (void)d;
  if (r >= hpair)
    return 0.0;
  double hr = hpair - r;
  double n = 0.3141592654e0 * hpair * hpair * hpair * hpair * hpair;
  double wfd = -3.0e0 * hr * hr / n;
  return -0.333333333333e0 * hr * wfd;
}
static double lammps_diameter(double r, double h, int d)
{
  return lammps_spiky(r, h, d); /* set diameter h: radius h/2, pair h = h */
}
static double lammps_radius(double r, double h, int d)
{
  return lammps_spiky(r, 2.0 * h, d); /* data-file radius h: pair h = 2h */
}

/* SPHinXsys kernel_wendland_c2.cpp: factor_W_1D = 3/(4h), _2D = 7/(4 pi h^2);
 * W = (1 - q/2)^4 (1 + 2q); cut-off 2h. */
static double sphinxsys_wendland(double r, double h, int d)
{
  double q = r / h;
  if (q >= 2.0)
    return 0.0;
  double f = d == 1 ? 3.0 / 4.0 / h : 7.0 / (4.0 * M_PI) / (h * h);
  return f * pow(1.0 - 0.5 * q, 4) * (1.0 + 2.0 * q);
}
/* SPHinXsys kernel_cubic_B_spline.cpp: 2/(3h), 10/(7 pi h^2); 1 - 1.5 q^2 (1 - q/2), (2-q)^3/4. */
static double sphinxsys_cubic(double r, double h, int d)
{
  double q = r / h;
  if (q >= 2.0)
    return 0.0;
  double f = d == 1 ? 2.0 / 3.0 / h : 10.0 / (7.0 * M_PI) / (h * h);
  return f * (q < 1.0 ? 1.0 - 1.5 * q * q * (1.0 - 0.5 * q) : 0.25 * pow(2.0 - q, 3));
}

/* TrixiParticles.jl src/general/smoothing_kernels.jl: W = sigma_d h^-d w(q). */
static double hd(double h, int d)
{
  return d == 1 ? h : h * h;
}
static double trixi_wendland_c2(double r, double h, int d)
{
  double q = r / h;
  return q < 2.0 ? 7.0 / (4.0 * M_PI) / hd(h, d) * pow(1 - q / 2, 4) * (2 * q + 1) : 0.0;
}
static double trixi_wendland_c4(double r, double h, int d)
{
  double q = r / h;
  return q < 2.0 ? 9.0 / (M_PI * 4) / hd(h, d) * pow(1 - q / 2, 6) * (35 * q * q / 12 + 3 * q + 1)
                 : 0.0;
}
static double trixi_wendland_c6(double r, double h, int d)
{
  double q = r / h;
  return q < 2.0 ? 39.0 / (M_PI * 14) / hd(h, d) * pow(1 - q / 2, 8) *
                     (4 * q * q * q + 25 * q * q / 4 + 4 * q + 1)
                 : 0.0;
}
static double trixi_cubic(double r, double h, int d)
{
  double q = r / h, s = d == 1 ? 2.0 / 3.0 : 10.0 / (M_PI * 7);
  if (q >= 2.0)
    return 0.0;
  return s / hd(h, d) * (pow(2 - q, 3) / 4 - (q < 1) * pow(1 - q, 3));
}
static double trixi_quartic(double r, double h, int d)
{
  double q = r / h, s = d == 1 ? 1.0 / 24 : 96.0 / (M_PI * 1199);
  if (q >= 2.5)
    return 0.0;
  return s / hd(h, d) *
         (pow(2.5 - q, 4) - 5 * (q < 1.5) * pow(1.5 - q, 4) + 10 * (q < 0.5) * pow(0.5 - q, 4));
}
static double trixi_quintic(double r, double h, int d)
{
  double q = r / h, s = d == 1 ? 1.0 / 120 : 7.0 / (M_PI * 478);
  if (q >= 3.0)
    return 0.0;
  return s / hd(h, d) *
         (pow(3 - q, 5) - 6 * (q < 2) * pow(2 - q, 5) + 15 * (q < 1) * pow(1 - q, 5));
}
static double trixi_spiky(double r, double h, int d)
{
  double q = r / h;
  return q < 1.0 ? 10.0 / M_PI / hd(h, d) * pow(1 - q, 3) : 0.0;
}
static double trixi_poly6(double r, double h, int d)
{
  double q = r / h;
  return q < 1.0 ? 4.0 / M_PI / hd(h, d) * pow(1 - q * q, 3) : 0.0;
}

/* PySPH pysph/base/kernels.py: W = fac h^-d val(q). */
static double pysph_cubic(double r, double h, int d)
{
  double q = r / h, fac = d == 1 ? 2.0 / 3.0 : 10 * M_1_PI / 7.0, tmp2 = 2. - q, val;
  if (q > 2.0)
    val = 0.0;
  else if (q > 1.0)
    val = 0.25 * tmp2 * tmp2 * tmp2;
  else
    val = 1 - 1.5 * q * q * (1 - 0.5 * q);
  return fac / hd(h, d) * val;
}
static double pysph_wendland(double r, double h, int d)
{
  double q = r / h, tmp = 1.0 - 0.5 * q;
  return q < 2.0 ? 7.0 * M_1_PI / 4.0 / hd(h, d) * tmp * tmp * tmp * tmp * (2.0 * q + 1.0) : 0.0;
}
static double pysph_wendland_c2_1d(double r, double h, int d)
{
  double q = r / h, tmp = 1.0 - 0.5 * q;
  return q < 2.0 ? 5.0 / 8.0 / hd(h, d) * tmp * tmp * tmp * (1.5 * q + 1.0) : 0.0;
}
static double pysph_wendland_c4(double r, double h, int d)
{
  double q = r / h, tmp = 1.0 - 0.5 * q;
  return q < 2.0 ? 9.0 * M_1_PI / 4.0 / hd(h, d) * pow(tmp, 6) *
                     (35.0 / 12.0 * q * q + 3.0 * q + 1.0)
                 : 0.0;
}
static double pysph_wendland_c6(double r, double h, int d)
{
  double q = r / h, tmp = 1.0 - 0.5 * q;
  return q < 2.0 ? 78.0 * M_1_PI / 28.0 / hd(h, d) * pow(tmp, 8) *
                     (4.0 * q * q * q + 6.25 * q * q + 4.0 * q + 1.0)
                 : 0.0;
}
static double pysph_quintic(double r, double h, int d)
{
  double q = r / h, fac = d == 1 ? 1.0 / 120.0 : M_1_PI * 7.0 / 478.0;
  double t3 = pos(3 - q), t2 = pos(2 - q), t1 = pos(1 - q);
  return fac / hd(h, d) * (pow(t3, 5) - 6 * pow(t2, 5) + 15 * pow(t1, 5));
}

/* DualSPHysics src/source/FunSphKernel.h: Wendland awen = 0.557/h^2 (2D, rounded; the
 * exact 7/(4 pi) here, the rounding checked separately), cubic a2 = 10/(7 pi h^2). */
static double dsph_wendland_exact(double r, double h, int d)
{
  (void)d;
  double qq = r / h;
  if (qq >= 2.0)
    return 0.0;
  double wqq = qq + qq + 1.0, wqq1 = 1.0 - 0.5 * qq, wqq2 = wqq1 * wqq1;
  return 7.0 / (4.0 * M_PI) / (h * h) * wqq * wqq2 * wqq2;
}
static double dsph_wendland_peer(double r, double h, int d)
{
  return dsph_wendland_exact(r, h, d) * 0.557 / (7.0 / (4.0 * M_PI));
}
static double dsph_cubic(double r, double h, int d)
{
  (void)d;
  double qq = r / h, a2 = 10.0 / (7.0 * M_PI) / (h * h);
  if (qq >= 2.0)
    return 0.0;
  if (qq <= 1.0)
    return a2 * (1.0 + (0.75 * qq - 1.5) * qq * qq);
  return a2 * 0.25 * pow(2.0 - qq, 3);
}

typedef struct {
  const char *preset;
  double (*W)(double r, double h, int d);
  double h;     /* the stated h */
  double rtol;  /* the peer's rounded constants (LAMMPS: pi/10 to 10 digits) */
} peer_case;

static const peer_case cases[] = {
  {"lammps-smd", lammps_diameter, 2.01e-3, 1e-9},
  {"lammps-smd-radius", lammps_radius, 1.005e-3, 1e-9},
  {"sphinxsys", sphinxsys_wendland, 1.3e-2, 1e-14},
  {"sphinxsys:KernelCubicBSpline", sphinxsys_cubic, 1.3e-2, 1e-14},
  {"trixiparticles:WendlandC2Kernel", trixi_wendland_c2, 0.1414213562373095, 1e-14},
  {"trixiparticles:WendlandC4Kernel", trixi_wendland_c4, 0.137, 1e-14},
  {"trixiparticles:WendlandC6Kernel", trixi_wendland_c6, 0.137, 1e-14},
  {"trixiparticles:SchoenbergCubicSplineKernel", trixi_cubic, 0.0123, 1e-14},
  {"trixiparticles:SchoenbergQuarticSplineKernel", trixi_quartic, 0.0123, 1e-13},
  {"trixiparticles:SchoenbergQuinticSplineKernel", trixi_quintic, 1.0, 1e-13},
  {"trixiparticles:SpikyKernel", trixi_spiky, 0.0371, 1e-14},
  {"trixiparticles:Poly6Kernel", trixi_poly6, 0.0371, 1e-14},
  {"pysph", pysph_cubic, 1.5, 1e-14},
  {"pysph:CubicSpline", pysph_cubic, 0.013, 1e-14},
  {"pysph:WendlandQuintic", pysph_wendland, 0.013, 1e-14},
  {"pysph:WendlandQuinticC2_1D", pysph_wendland_c2_1d, 0.013, 1e-14},
  {"pysph:WendlandQuinticC4", pysph_wendland_c4, 0.013, 1e-14},
  {"pysph:WendlandQuinticC6", pysph_wendland_c6, 0.013, 1e-14},
  {"pysph:QuinticSpline", pysph_quintic, 0.0277, 1e-13},
  {"dualsphysics", dsph_wendland_exact, 0.0070710678118654755, 1e-14},
  {"dualsphysics:CubicSpline", dsph_cubic, 0.0070710678118654755, 1e-14},
};
enum { NCASES = sizeof cases / sizeof cases[0] };

/* The peer's W against mfstab's kernel at a = support_per_h * h; returns the
 * largest relative difference (relative to W(0)). */
static double compare(const mfs_convention *c, double (*W)(double, double, int), double h, int d)
{
  double a = mfs_convention_support(c, h);
  double scale = fabs(W(0.0, h, d)), worst = 0.0;
  for (int i = 0; i <= 400; i++) {
    double r = 1.1 * a * i / 400.0;
    double mine = mfs_kernel_radial(c->kernel, d, a, r).W;
    double e = fabs(mine - W(r, h, d)) / scale;
    worst = e > worst ? e : worst;
  }
  return worst;
}

static void test_presets(void)
{
  int tested[64] = {0};
  for (size_t i = 0; i < NCASES; i++) {
    const mfs_convention *c = mfs_convention_find(cases[i].preset);
    CHECK(c != NULL, "preset %s not found", cases[i].preset);
    if (!c)
      continue;
    for (int k = 0; mfs_conventions[k]; k++)
      tested[k] += mfs_conventions[k] == c;
    int ndims = 0;
    for (int d = 1; d <= 2; d++) {
      if (!mfs_convention_applies(c, d))
        continue;
      ndims++;
      double e = compare(c, cases[i].W, cases[i].h, d);
      CHECK(e <= cases[i].rtol, "%s d=%d h=%g: W differs from the peer's by %.3g (relative to W(0))",
            c->name, d, cases[i].h, e);
    }
    CHECK(ndims > 0, "%s: defined in no dimension of mfstab", c->name);
    /* the kernel is zero from a on and positive just inside: a is the support */
    double a = mfs_convention_support(c, cases[i].h);
    int d = mfs_convention_applies(c, 2) ? 2 : 1;
    CHECK(cases[i].W(a * (1 + 1e-12), cases[i].h, d) == 0.0 &&
            cases[i].W(a * (1 - 1e-3), cases[i].h, d) > 0.0,
          "%s: the peer's support is not a = %g h", c->name, c->support_per_h);
  }
  for (int k = 0; mfs_conventions[k]; k++)
    CHECK(tested[k] == 1, "preset %s tested %d times, want 1", mfs_conventions[k]->name,
          tested[k]);

  /* the peer's rounded constant: DualSPHysics 0.557 for 7/(4 pi), 7.6e-5 low */
  const mfs_convention *ds = mfs_convention_find("dualsphysics");
  double h = 0.0070710678118654755;
  CHECK_NEAR(compare(ds, dsph_wendland_peer, h, 2), 7.6e-5, 0.2e-5,
             "DualSPHysics' rounded awen = 0.557");
  /* reference values of docs/conventions.md (the peer's formula evaluated with 30 digits) */
  CHECK_NEAR(mfs_kernel_radial(mfs_convention_find("sphinxsys")->kernel, 2, 2.6, 1.0).W,
             0.119993742190686, 1e-14, "SPHinXsys WendlandC2, 2D, h = 1.3, r = 1");
  CHECK_NEAR(mfs_kernel_radial(&mfs_kernel_cubic, 2, 2.6, 1.0).W, 0.122104166684393, 1e-14,
             "SPHinXsys CubicBSpline, 2D, h = 1.3, r = 1");
  CHECK_NEAR(mfs_kernel_radial(&mfs_kernel_quintic, 2, 3.0, 1.5).W, 0.0345238036858596, 1e-15,
             "TrixiParticles SchoenbergQuintic, 2D, h = 1, r = 1.5");
  CHECK_NEAR(mfs_kernel_radial(&mfs_kernel_cubic, 1, 3.0, 1.0).W, 0.246913580246914, 1e-15,
             "PySPH CubicSpline, 1D, h = 1.5, r = 1");
  CHECK_NEAR(mfs_kernel_radial(&mfs_kernel_spiky, 2, 2.01, 1.0).W, 0.0999617755417356, 1e-15,
             "LAMMPS spiky, 2D, diameter 2.01, r = 1 (exact 10/pi)");
  CHECK_NEAR(lammps_diameter(1.0, 2.01, 2), 0.0999617755285833, 1e-15,
             "LAMMPS spiky with its own 0.3141592654");
  CHECK_NEAR(mfs_kernel_radial(&mfs_kernel_wendland2, 2, 2.0 * h, 0.005).W, 4697.04266145798,
             1e-9, "DualSPHysics Wendland, exact 7/(4 pi), h = sqrt(2) 0.005, r = 0.005");

  CHECK(mfs_convention_find("trixiparticles") == NULL,
        "TrixiParticles has no default kernel: the name alone is not a preset");
  CHECK(mfs_convention_find("pysph")->kernel == &mfs_kernel_cubic,
        "PySPH's default (ElasticSolidsScheme) is CubicSpline");
  CHECK(mfs_convention_find("pysph:WendlandQuinticC2_1D")->kernel == &mfs_kernel_quartic,
        "PySPH's 1D Wendland C2 is Lucy's quartic");
  CHECK(!mfs_convention_applies(mfs_convention_find("lammps-smd"), 1),
        "LAMMPS MACHDYN has no 1D kernel");
  CHECK(mfs_convention_find("nosuch") == NULL && mfs_convention_find(NULL) == NULL, "unknown");
}

/* ---- step rules -------------------------------------------------------- */

static void test_rules(void)
{
  double E = 2.1e11, nu = 0.3, rho = 7850.0, a = 2.6e-3;
  double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  double cP = sqrt((lam + 2 * mu) / rho), K = lam + 2.0 * mu / 3.0, cK = sqrt(K / rho);
  for (int dim = 1; dim <= 2; dim++) {
    mfs_rule_args r = {.dim = dim, .young = E, .poisson = nu, .density = rho};
    CHECK_NEAR(mfs_speed_p(&r) / cP, 1.0, 1e-15, "c_P from the Lame constants");
    CHECK_NEAR(mfs_speed_bulk(&r) / cK, 1.0, 1e-15, "c_K from the Lame constants");
    r.h = a; /* LAMMPS: h = the diameter = a */
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_lammps_smd, &r, 0) / (0.1 * a / cP), 1.0, 1e-15,
               "LAMMPS: 0.1 a / c_P");
    r.h = a / 2;
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_sphinxsys, &r, 0) / (0.6 * (a / 2) / cK), 1.0, 1e-15,
               "SPHinXsys: 0.6 h / c_K");
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_sphinxsys_pwave, &r, 0) / (0.6 * (a / 2) / cP), 1.0, 1e-15,
               "SPHinXsys (PR 688): 0.6 h / c_P");
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_dualsphysics, &r, 0) / (0.2 * (a / 2) / cP), 1.0, 1e-15,
               "DualSPHysics: 0.2 h / c_P");
    double Kd = E / (dim * (1 - 2 * nu));
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_trixiparticles, &r, 0) / (1.6 * (a / 2) / sqrt(Kd / rho)),
               1.0, 1e-15, "TrixiParticles %dD: 1.6 h / sqrt(E/(d(1-2nu))/rho)", dim);
    CHECK_NEAR(mfs_rule_dt(&mfs_rule_dualsphysics, &r, 0.1) / (0.1 * (a / 2) / cP), 1.0, 1e-15,
               "a factor given replaces the default");
  }
  /* docs/conventions.md: the rules as multiples of a / c_P at nu = 0.3 */
  mfs_rule_args r = {.dim = 2, .h = 0.5, .young = 1.0, .poisson = 0.3, .density = 1.0};
  double unit = 1.0 / mfs_speed_p(&r); /* a / c_P with a = 1 */
  CHECK_NEAR(mfs_rule_dt(&mfs_rule_sphinxsys, &r, 0) / unit, 0.381, 0.0005,
             "SPHinXsys 0.381 a/c_P at nu = 0.3");
  CHECK_NEAR(mfs_rule_dt(&mfs_rule_trixiparticles, &r, 1.0) / unit, 0.519, 0.0005,
             "TrixiParticles 2D 0.519 cfl a/c_P at nu = 0.3");
  r.poisson = 0.5;
  CHECK(isnan(mfs_rule_dt(&mfs_rule_sphinxsys, &r, 0)), "nu = 0.5 is refused (NAN)");
  r.poisson = 0.3;
  r.h = 0.0;
  CHECK(isnan(mfs_rule_dt(&mfs_rule_sphinxsys, &r, 0)), "h = 0 is refused (NAN)");
  /* the length each rule takes under a convention */
  const mfs_convention *lr = mfs_convention_find("lammps-smd-radius");
  const mfs_convention *tq = mfs_convention_find("trixiparticles:SchoenbergQuinticSplineKernel");
  const mfs_convention *sx = mfs_convention_find("sphinxsys");
  double A = 0.3;
  CHECK(mfs_rule_h(&mfs_rule_lammps_smd, lr, A) == A,
        "LAMMPS radius preset: the rule's 2 radius is a (radius h = a/2)");
  CHECK(mfs_rule_h(&mfs_rule_trixiparticles, tq, A) == A / 3.0,
        "TrixiParticles quintic: the rule takes the smoothing length a/3");
  CHECK(mfs_rule_h(&mfs_rule_trixiparticles, NULL, A) == A / 2.0,
        "TrixiParticles without a convention: its example kernel WendlandC2, h = a/2");
  CHECK(mfs_rule_h(&mfs_rule_sphinxsys_pwave, sx, A) == A / 2.0 &&
          mfs_rule_of(&mfs_rule_sphinxsys_pwave, sx) && !mfs_rule_of(&mfs_rule_dualsphysics, sx),
        "both SPHinXsys rules belong to the sphinxsys preset, DualSPHysics' does not");
  CHECK(mfs_rule_h(&mfs_rule_lammps_smd, tq, A) == A, "LAMMPS under another peer's preset: h = a");
  int n = 0;
  for (; mfs_step_rules[n]; n++)
    ;
  CHECK(n == 5, "%d step rules, want 5", n);
}

int main(void)
{
  test_presets();
  test_rules();
  return check_summary("test_convention");
}
