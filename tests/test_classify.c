/* The stability classification (mfs_classify.h): each label where the
 * analysis says it and nowhere else.
 *   - paper 003 Fig. 4 (sbar = -1, C + sigma = 0): omega^2 >= 0 at every
 *     kappa, so no label `material` (the continuum is marginal, q_min = 0);
 *   - a PDE instability seen by the discretization: `material` (1D Lagrangian
 *     sbar = -1.2; plane strain sigma_xx = -1.5 mu, the transverse wave; the
 *     paper 000 material at J > e);
 *   - discrete instabilities the PDE does not have: `tensile` under tension
 *     (Eulerian MLS 1D; the paper 000 material stretched, Eulerian kernel),
 *     `compressive` under compression (Eulerian SPH with Gauss points);
 *   - the long-wave deviation: zero for Lagrangian MLS, errata E2's value for
 *     the paper-style Eulerian MLS (1.084 against 1.3);
 *   - the label function and the label text. */
#include <complex.h>
#undef I
#include <string.h>

#include "check.h"
#include "mfstab.h"

static mfs_disp_plan *plan(int dim, const char *quad, const mfs_kernel_type *k, const mfs_shape_type *sh,
                           double D, mfs_frame fr, const mfs_hyper *mat, double l1, double l2)
{
  mfs_disc d = mfs_disc_default();
  d.dim = dim;
  d.source.lattice = dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE;
  d.quadrature = mfs_quad_find(quad);
  d.kernel = k;
  d.shape = sh;
  d.dilation = D;
  d.frame = fr;
  if (dim == 2) {
    d.material.physics = MFS_PHYS_PLANE_STRAIN;
    d.material.poisson = 0.3;
  }
  mfs_disp_spec sp = {.disc = d, .stretch = l1, .stretch_y = l2};
  if (mat)
    sp.material = *mat;
  mfs_status st;
  mfs_disp_plan *p = mfs_disp_plan_alloc(&sp, &st);
  CHECK(p != NULL, "plan %s: %s", quad, mfs_strerror(st));
  return p;
}

static mfs_class classify1(const mfs_disp_plan *p, double sbar, int ntheta)
{
  double th[4] = {0.0, M_PI / 8, M_PI / 4, M_PI / 2};
  mfs_sampling smp = {.theta = th, .ntheta = (size_t)ntheta, .npoints = 101};
  mfs_class c = {0};
  if (!p)
    return c;
  mfs_status st = mfs_classify(p, &smp, &sbar, 1, &c);
  CHECK(st == MFS_OK, "classify: %s", mfs_strerror(st));
  return c;
}

static void one_d(void)
{
  /* Fig. 4: quartic EFG, nodal, Eulerian, D = 1.5 and 2.5, sbar = -1 */
  const double dils[2] = {1.5, 2.5};
  for (int i = 0; i < 2; i++) {
    mfs_disp_plan *p = plan(1, "nodal", &mfs_kernel_quartic, &mfs_shape_mls, dils[i],
                            MFS_FRAME_EULERIAN, NULL, 1, 1);
    mfs_class c = classify1(p, -1.0, 1);
    CHECK(!c.unstable && c.min_omega2 > -1e-12, "Fig. 4 D = %g: unstable %d, min omega2 %g", dils[i],
          c.unstable, c.min_omega2);
    CHECK(!(c.labels & MFS_LABEL_MATERIAL), "Fig. 4 D = %g: no material label (labels %u)", dils[i],
          c.labels);
    CHECK(c.pde.q_min == 0.0 && mfs_pde_stable(&c.pde), "Fig. 4: the continuum is marginal, q = %g",
          c.pde.q_min);
    mfs_disp_plan_free(p);
  }
  /* a PDE instability: Lagrangian, sbar = -1.2 */
  mfs_disp_plan *p = plan(1, "nodal", &mfs_kernel_quartic, &mfs_shape_mls, 1.5, MFS_FRAME_LAGRANGIAN,
                          NULL, 1, 1);
  mfs_class c = classify1(p, -1.2, 1);
  CHECK(c.unstable && (c.labels & MFS_LABEL_MATERIAL) && !(c.labels & MFS_LABEL_COMPRESSIVE),
        "Lagrangian sbar = -1.2: material (labels %u)", c.labels);
  CHECK_NEAR(c.pde.q_min, -0.2, 1e-15, "Lagrangian sbar = -1.2: q_min");
  CHECK(c.longwave_deviation < 1e-8, "Lagrangian MLS long-wave deviation %g", c.longwave_deviation);
  mfs_disp_plan_free(p);
  /* tensile: Eulerian MLS, cubic D = 2, sbar = 0.5 */
  p = plan(1, "nodal", &mfs_kernel_cubic, &mfs_shape_mls, 2.0, MFS_FRAME_EULERIAN, NULL, 1, 1);
  c = classify1(p, 0.5, 1);
  CHECK((c.labels & MFS_LABEL_TENSILE) && !(c.labels & (MFS_LABEL_MATERIAL | MFS_LABEL_COMPRESSIVE)),
        "Eulerian MLS sbar = 0.5: tensile (labels %u)", c.labels);
  CHECK(c.sigma_nn == 0.5, "sigma_nn %g", c.sigma_nn);
  mfs_disp_plan_free(p);
  /* compressive: Eulerian SPH with Gauss points (not a partition of unity: the
   * long-wave term sigma sum V H (sum phi - 1)), cubic D = 1.5, sbar = -0.5 */
  p = plan(1, "gauss2", &mfs_kernel_cubic, &mfs_shape_sph, 1.5, MFS_FRAME_EULERIAN, NULL, 1, 1);
  c = classify1(p, -0.5, 1);
  CHECK(c.unstable && (c.labels & MFS_LABEL_COMPRESSIVE) &&
          !(c.labels & (MFS_LABEL_TENSILE | MFS_LABEL_MATERIAL)),
        "Eulerian SPH gauss2 sbar = -0.5: compressive (labels %u)", c.labels);
  mfs_disp_plan_free(p);
  /* errata E2: eq. 74, quartic MLS, D = 1.5, sbar = 0.3: the limit 1.084 instead of 1.3 */
  p = plan(1, "nodal", &mfs_kernel_quartic, &mfs_shape_mls, 1.5, MFS_FRAME_EULERIAN, NULL, 1, 1);
  c = classify1(p, 0.3, 1);
  CHECK_NEAR(c.longwave_deviation, (1.3 - 1.084) / 1.3, 1e-3, "E2 long-wave deviation");
  mfs_disp_plan_free(p);
  p = plan(1, "nodal", &mfs_kernel_quartic, &mfs_shape_mls, 1.5, MFS_FRAME_EULERIAN_CONSISTENT, NULL, 1, 1);
  c = classify1(p, 0.3, 1);
  CHECK(c.longwave_deviation < 1e-8, "consistent frame long-wave deviation %g", c.longwave_deviation);
  mfs_disp_plan_free(p);
  /* the place of the minimum where it is a rounding's size: cubic MLS, nodal,
   * D = 3, unstressed, zeros at kappa = 0 and at the spurious zero kappa = 1
   * (rank deficiency), omega^2 a few 1e-17 either side of 0: the first
   * sample (kappa = 0), not whichever zero the rounding makes lower (it was
   * kappa = 1 with this build's rounding before the tie rule) */
  p = plan(1, "nodal", &mfs_kernel_cubic, &mfs_shape_mls, 3.0, MFS_FRAME_EULERIAN, NULL, 1, 1);
  c = classify1(p, 0.0, 1);
  CHECK((c.labels & MFS_LABEL_RANK_DEFICIENCY) && !c.unstable && fabs(c.min_omega2) < 1e-14,
        "D = 3 unstressed: stable, rank-deficient, least omega2 %g (labels %u)", c.min_omega2,
        c.labels);
  CHECK(c.kappa_at_min == 0.0 && c.theta_at_min == 0, "D = 3 unstressed: the least omega2 at "
        "kappa %g (the first sample, 0)", c.kappa_at_min);
  mfs_disp_plan_free(p);
}

static void two_d(void)
{
  /* plane strain, linear, sigma_xx = -1.5 mu: the transverse wave along x is unstable in the
   * continuum (q = 1 - 1.5) and in the Lagrangian discretization */
  mfs_disp_plan *p = plan(2, "stress-tri", &mfs_kernel_cubic, &mfs_shape_mls, 2.0,
                          MFS_FRAME_LAGRANGIAN, NULL, 1, 1);
  mfs_class c = classify1(p, -1.5, 4);
  CHECK(c.unstable && (c.labels & MFS_LABEL_MATERIAL), "plane strain sigma_xx = -1.5: material (%u)",
        c.labels);
  CHECK_NEAR(c.pde.q_min, -0.5, 1e-12, "plane strain sigma_xx = -1.5: q_min");
  c = classify1(p, 0.6, 4);
  CHECK(!c.unstable && c.labels == 0, "plane strain Lagrangian sigma_xx = 0.6: stable (%u)", c.labels);
  CHECK(c.longwave_deviation < 1e-8, "plane strain Lagrangian long-wave deviation %g",
        c.longwave_deviation);
  mfs_disp_plan_free(p);
  /* paper 000 material at diag(1.05, 1): sigma about 7 mu0 in tension; Eulerian: tensile;
   * Lagrangian: stable */
  mfs_hyper m = mfs_hyper_paper000_constants();
  p = plan(2, "stress-tri", &mfs_kernel_cubic, &mfs_shape_mls, 2.0, MFS_FRAME_EULERIAN_CONSISTENT, &m,
           1.05, 1.0);
  c = classify1(p, 0.0, 4);
  CHECK(c.unstable && (c.labels & MFS_LABEL_TENSILE) && c.sigma_nn > 0 && mfs_pde_stable(&c.pde),
        "paper000 (1.05, 1) Eulerian: tensile (labels %u, sigma_nn %g)", c.labels, c.sigma_nn);
  CHECK(isnan(c.onset_tension) && isnan(c.onset_compression), "finite material: no onsets");
  mfs_disp_plan_free(p);
  p = plan(2, "stress-tri", &mfs_kernel_cubic, &mfs_shape_mls, 2.0, MFS_FRAME_LAGRANGIAN, &m, 1.05, 1.0);
  c = classify1(p, 0.0, 4);
  CHECK(!c.unstable && c.labels == 0, "paper000 (1.05, 1) Lagrangian: stable (labels %u)", c.labels);
  mfs_disp_plan_free(p);
  /* J = 3.61 > e: the PDE and the Lagrangian scheme are unstable: material */
  p = plan(2, "stress-tri", &mfs_kernel_cubic, &mfs_shape_mls, 2.0, MFS_FRAME_LAGRANGIAN, &m, 1.9, 1.9);
  c = classify1(p, 0.0, 4);
  CHECK(c.unstable && c.labels == MFS_LABEL_MATERIAL && !mfs_pde_stable(&c.pde),
        "paper000 (1.9, 1.9) Lagrangian: material (labels %u, q %g)", c.labels, c.pde.q_min);
  mfs_disp_plan_free(p);
}

static void labels(void)
{
  mfs_ellipticity ok = {.stable = 1, .q_min = 0.3}, bad = {.q_min = -0.2}, marg = {.q_min = 0.0};
  CHECK(mfs_class_labels(0, &bad, NAN, NAN, 0) == 0, "no unstable wave: no label, PDE or not");
  CHECK(mfs_class_labels(1, &bad, -1.0, -1.0, 0) == MFS_LABEL_MATERIAL, "material");
  CHECK(mfs_class_labels(1, &ok, 0.4, -1.0, 0) == MFS_LABEL_TENSILE, "tensile by sigma_nn");
  CHECK(mfs_class_labels(1, &ok, -0.4, 1.0, 0) == MFS_LABEL_COMPRESSIVE, "compressive by sigma_nn");
  CHECK(mfs_class_labels(1, &marg, 0.0, -0.1, 2) == (MFS_LABEL_COMPRESSIVE | MFS_LABEL_RANK_DEFICIENCY),
        "tie-break by the mean stress");
  char b[96];
  CHECK(!strcmp(mfs_class_label(MFS_LABEL_COMPRESSIVE | MFS_LABEL_RANK_DEFICIENCY, b, sizeof b),
                "compressive+rank-deficiency"),
        "label text '%s'", b);
  CHECK(!strcmp(mfs_class_label(0, b, sizeof b), "stable"), "stable text");
}

int main(void)
{
  one_d();
  two_d();
  labels();
  return check_summary("test_classify");
}
