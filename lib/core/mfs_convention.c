#include "mfs_convention.h"

#include <math.h>
#include <string.h>

/* Every formula, default and mapping below is the peer's own, read in its
 * source; docs/conventions.md quotes the lines with their files. */

static int args_ok(const mfs_rule_args *r)
{
  return r && r->h > 0.0 && isfinite(r->h) && r->young > 0.0 && isfinite(r->young) &&
         r->density > 0.0 && isfinite(r->density) && r->poisson > -1.0 && r->poisson < 0.5;
}

double mfs_speed_p(const mfs_rule_args *r)
{
  double E = r->young, nu = r->poisson;
  return sqrt(E * (1.0 - nu) / (r->density * (1.0 + nu) * (1.0 - 2.0 * nu)));
}

double mfs_speed_bulk(const mfs_rule_args *r)
{
  return sqrt(r->young / (3.0 * (1.0 - 2.0 * r->poisson) * r->density));
}

/* TrixiParticles' "bulk modulus" E / (ndims (1 - 2 nu)) (system.jl, calculate_dt):
 * the 3D bulk modulus in 3D, neither bulk modulus in 2D (docs/conventions.md). */
static double speed_trixi(const mfs_rule_args *r)
{
  return sqrt(r->young / ((double)r->dim * (1.0 - 2.0 * r->poisson) * r->density));
}

const mfs_step_rule mfs_rule_lammps_smd = {
  .name = "lammps_smd",
  .peer = "LAMMPS MACHDYN (pair smd/tlsph, fix smd/adjust_dt)",
  .formula = "s_fact * 2 radius / c_P, 2 radius = the kernel diameter h = a",
  .factor = 0.1,
  .factor_source = "no default (s_fact is required); 0.1 in the documentation and every example",
  .support_per_h = 1.0,
  .speed = mfs_speed_p};
const mfs_step_rule mfs_rule_sphinxsys = {
  .name = "sphinxsys",
  .peer = "SPHinXsys (solid_dynamics::AcousticTimeStep)",
  .formula = "CFL * h / c0, c0 = sqrt(K/rho), K = E/(3(1-2nu))",
  .factor = 0.6,
  .factor_source = "AcousticTimeStep(SPHBody &, Real CFL = 0.6)",
  .support_per_h = 2.0,
  .speed = mfs_speed_bulk};
const mfs_step_rule mfs_rule_sphinxsys_pwave = {
  .name = "sphinxsys_pwave",
  .peer = "SPHinXsys with the P-wave sound speed (PR #688)",
  .formula = "CFL * h / c0, c0 = sqrt((K + 4G/3)/rho) = c_P",
  .factor = 0.6,
  .factor_source = "AcousticTimeStep(SPHBody &, Real CFL = 0.6)",
  .support_per_h = 2.0,
  .speed = mfs_speed_p};
const mfs_step_rule mfs_rule_trixiparticles = {
  .name = "trixiparticles",
  .peer = "TrixiParticles.jl (TotalLagrangianSPHSystem, StepsizeCallback)",
  .formula = "cfl * h / sqrt(K/rho), K = E/(ndims (1-2nu))",
  .factor = 1.6,
  .factor_source = "no default (cfl is required); 1.6 in the SplitIntegrationCallback docstring, "
                   "for CarpenterKennedy2N54",
  .support_per_h = 2.0,
  .speed = speed_trixi};
const mfs_step_rule mfs_rule_dualsphysics = {
  .name = "dualsphysics",
  .peer = "DualSPHysics (FlexStruc, JSphCpu::DtVariable)",
  .formula = "CFLnumber * h / c_P",
  .factor = 0.2,
  .factor_source = "JCaseCtes::LoadDefault SetCFLnumber(0.2); the FlexStruc examples use 0.1",
  .support_per_h = 2.0,
  .speed = mfs_speed_p};

const mfs_step_rule *const mfs_step_rules[] = {&mfs_rule_lammps_smd, &mfs_rule_sphinxsys,
                                               &mfs_rule_sphinxsys_pwave,
                                               &mfs_rule_trixiparticles, &mfs_rule_dualsphysics,
                                               NULL};

double mfs_rule_dt(const mfs_step_rule *rule, const mfs_rule_args *args, double factor)
{
  if (!rule || !args_ok(args) || (args->dim != 1 && args->dim != 2))
    return NAN;
  double f = factor > 0.0 ? factor : rule->factor;
  return f * args->h / rule->speed(args);
}

#define D1 (1u << 1)
#define D2 (1u << 2)

static const mfs_convention lammps = {
  .name = "lammps-smd", .peer = "LAMMPS MACHDYN", .peer_kernel = "spiky_kernel_and_derivative",
  .kernel = &mfs_kernel_spiky, .support_per_h = 1.0, .dims = D2, .rule = &mfs_rule_lammps_smd,
  .rule_support_per_h = 1.0, .h_is = "the kernel diameter of 'set group all diameter h' (the examples' h): a = h"};
static const mfs_convention lammps_radius = {
  .name = "lammps-smd-radius", .peer = "LAMMPS MACHDYN",
  .peer_kernel = "spiky_kernel_and_derivative", .kernel = &mfs_kernel_spiky,
  .support_per_h = 2.0, .dims = D2, .rule = &mfs_rule_lammps_smd, .rule_support_per_h = 1.0,
  .h_is = "the per-atom kernel radius (kernel-radius column of atom_style smd): a = 2h"};
static const mfs_convention sphinxsys = {
  .name = "sphinxsys", .peer = "SPHinXsys", .peer_kernel = "KernelWendlandC2",
  .kernel = &mfs_kernel_wendland2, .support_per_h = 2.0, .dims = D1 | D2,
  .rule = &mfs_rule_sphinxsys, .rule_support_per_h = 2.0,
  .h_is = "the reference smoothing length of SPHAdaptation (default 1.3 dp): a = 2h"};
static const mfs_convention sphinxsys_cubic = {
  .name = "sphinxsys:KernelCubicBSpline", .peer = "SPHinXsys", .peer_kernel = "KernelCubicBSpline",
  .kernel = &mfs_kernel_cubic, .support_per_h = 2.0, .dims = D1 | D2, .rule = &mfs_rule_sphinxsys,
  .rule_support_per_h = 2.0, .h_is = "the reference smoothing length of SPHAdaptation: a = 2h"};
#define TRIXI(pk, k, s, d)                                                                     \
  static const mfs_convention trixi_##pk = {                                                   \
    .name = "trixiparticles:" #pk, .peer = "TrixiParticles.jl", .peer_kernel = #pk,            \
    .kernel = &mfs_kernel_##k, .support_per_h = s, .dims = d, .rule = &mfs_rule_trixiparticles, \
    .rule_support_per_h = s,                                                                   \
    .h_is = "the smoothing_length of the system: a = compact_support(kernel, h)"}
TRIXI(WendlandC2Kernel, wendland2, 2.0, D2);
TRIXI(WendlandC4Kernel, wendland4, 2.0, D2);
TRIXI(WendlandC6Kernel, wendland6, 2.0, D2);
TRIXI(SchoenbergCubicSplineKernel, cubic, 2.0, D1 | D2);
TRIXI(SchoenbergQuarticSplineKernel, m5, 2.5, D1 | D2);
TRIXI(SchoenbergQuinticSplineKernel, quintic, 3.0, D1 | D2);
TRIXI(SpikyKernel, spiky, 1.0, D2);
TRIXI(Poly6Kernel, poly6, 1.0, D2);
#undef TRIXI
#define PYSPH(id, nm, pk, k, s, d)                                                            \
  static const mfs_convention pysph_##id = {                                                  \
    .name = nm, .peer = "PySPH", .peer_kernel = #pk, .kernel = &mfs_kernel_##k,               \
    .support_per_h = s, .dims = d, .rule = NULL, .rule_support_per_h = s,                     \
    .h_is = "the particle array's h (symmetrized h_ij): a = radius_scale * h"}
PYSPH(CubicSpline, "pysph", CubicSpline, cubic, 2.0, D1 | D2);
PYSPH(CubicSplineNamed, "pysph:CubicSpline", CubicSpline, cubic, 2.0, D1 | D2);
PYSPH(WendlandQuintic, "pysph:WendlandQuintic", WendlandQuintic, wendland2, 2.0, D2);
PYSPH(WendlandQuinticC2_1D, "pysph:WendlandQuinticC2_1D", WendlandQuinticC2_1D, quartic, 2.0, D1);
PYSPH(WendlandQuinticC4, "pysph:WendlandQuinticC4", WendlandQuinticC4, wendland4, 2.0, D2);
PYSPH(WendlandQuinticC6, "pysph:WendlandQuinticC6", WendlandQuinticC6, wendland6, 2.0, D2);
PYSPH(QuinticSpline, "pysph:QuinticSpline", QuinticSpline, quintic, 3.0, D1 | D2);
#undef PYSPH
static const mfs_convention dualsphysics = {
  .name = "dualsphysics", .peer = "DualSPHysics", .peer_kernel = "Wendland (Kernel 2)",
  .kernel = &mfs_kernel_wendland2, .support_per_h = 2.0, .dims = D2,
  .rule = &mfs_rule_dualsphysics, .rule_support_per_h = 2.0,
  .h_is = "the final kernel h of the run log (KernelH = coefh sqrt(d) dp or hdp dp): a = 2h"};
static const mfs_convention dualsphysics_cubic = {
  .name = "dualsphysics:CubicSpline", .peer = "DualSPHysics", .peer_kernel = "Cubic Spline (Kernel 1)",
  .kernel = &mfs_kernel_cubic, .support_per_h = 2.0, .dims = D2, .rule = &mfs_rule_dualsphysics,
  .rule_support_per_h = 2.0, .h_is = "the final kernel h of the run log: a = 2h"};

const mfs_convention *const mfs_conventions[] = {
  &lammps, &lammps_radius, &sphinxsys, &sphinxsys_cubic,
  &trixi_WendlandC2Kernel, &trixi_WendlandC4Kernel, &trixi_WendlandC6Kernel,
  &trixi_SchoenbergCubicSplineKernel, &trixi_SchoenbergQuarticSplineKernel,
  &trixi_SchoenbergQuinticSplineKernel, &trixi_SpikyKernel, &trixi_Poly6Kernel,
  &pysph_CubicSpline, &pysph_CubicSplineNamed, &pysph_WendlandQuintic,
  &pysph_WendlandQuinticC2_1D, &pysph_WendlandQuinticC4, &pysph_WendlandQuinticC6,
  &pysph_QuinticSpline, &dualsphysics, &dualsphysics_cubic, NULL};

const mfs_convention *mfs_convention_find(const char *name)
{
  for (int i = 0; name && mfs_conventions[i]; i++)
    if (strcmp(name, mfs_conventions[i]->name) == 0)
      return mfs_conventions[i];
  return NULL;
}

double mfs_convention_support(const mfs_convention *c, double h)
{
  return c->support_per_h * h;
}

int mfs_rule_of(const mfs_step_rule *rule, const mfs_convention *c)
{
  return rule && c && strncmp(rule->peer, c->peer, strlen(c->peer)) == 0;
}

double mfs_rule_h(const mfs_step_rule *rule, const mfs_convention *c, double a)
{
  return mfs_rule_of(rule, c) ? a / c->rule_support_per_h : a / rule->support_per_h;
}

int mfs_convention_applies(const mfs_convention *c, int dim)
{
  return c && dim >= 1 && dim <= 3 && (c->dims >> dim & 1u);
}
