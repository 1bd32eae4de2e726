/* The critical time step of an explicit central-difference run of a steel
 * bar (E = 210 GPa, rho = 7800 kg/m^3, L = 1 m, 101 particles, free ends)
 * discretized by MLS shape functions (cubic spline, D = 2) with two-point
 * Gauss quadrature between particles, two ways:
 *
 *   1. the largest eigenvalue of K v = lambda M v by ARPACK (mfs_eig_max):
 *      dt_crit = 2 / sqrt(lambda_max);
 *   2. the element bound of paper 003 (eq. 124, mfs_bound_of_model): the
 *      largest eigenvalue of any one quadrature point's contribution, an
 *      upper bound on lambda_max wherever the shape functions are positive,
 *      so its step is a safe one.
 *
 * Prints both steps in seconds and exits 1 if the bound is not an upper
 * bound (beyond rounding).
 * Build: cc critical_dt.c $(pkg-config --cflags --libs mfstab) -o critical_dt */
#include <math.h>
#include <stdio.h>

#include <mfstab.h>

int main(void)
{
  mfs_model_spec spec = mfs_model_spec_default();
  spec.disc.source.nx = 101;
  spec.disc.source.lx = 1.0; /* m */
  spec.disc.material.modulus = 210e9; /* Pa */
  spec.disc.material.density = 7800.0; /* kg/m^3 */
  /* the default rule: gauss2 (mfs_model_spec_default) */
  mfs_status st;
  size_t bad = 0;
  mfs_model *m = mfs_model_alloc(&spec, &st, &bad);
  if (!m) {
    fprintf(stderr, "critical_dt: the model: %s\n", mfs_strerror(st));
    return 1;
  }
  mfs_pencil P = {.K = m->K, .M = m->M, .m = m->m};
  double lambda = 0.0;
  st = mfs_eig_max(&P, NULL, &lambda, NULL, NULL);
  mfs_bound_result b;
  if (st == MFS_OK)
    st = mfs_bound_of_model(m, &b);
  mfs_model_free(m);
  if (st != MFS_OK) {
    fprintf(stderr, "critical_dt: %s\n", mfs_strerror(st));
    return 1;
  }
  printf("lambda_max_1_per_s2,lambda_bound_1_per_s2,dt_crit_s,dt_bound_s,points_without_guarantee\n");
  printf("%.10g,%.10g,%.10g,%.10g,%zu\n", lambda, b.lambda, mfs_dt_crit(lambda),
         mfs_dt_crit(b.lambda), b.negative_phi);
  if (b.negative_phi == 0 && !(b.lambda >= lambda * (1.0 - 1e-10))) {
    fprintf(stderr, "critical_dt: the bound %g is below lambda_max %g\n", b.lambda, lambda);
    return 1;
  }
  return 0;
}
