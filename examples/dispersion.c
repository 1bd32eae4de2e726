/* The dispersion of a 1D bar discretized by MLS shape functions with the
 * cubic spline kernel (D = 2) and nodal integration, two ways:
 *
 *   1. the library's Bloch analysis (mfs_disp_omega2), normalized:
 *      omega2 = (omega dx / c)^2 at kappa = k dx / pi;
 *   2. the stencil of an interior particle (mfs_stencil) summed by hand:
 *      omega^2 = sum_j K_j cos(j pi kappa) / M_0 (the lumped mass).
 *
 * Prints kappa, both omega dx / c and the continuum's pi kappa; exits 1 if
 * the two paths differ by more than 1e-12.
 * Build: cc dispersion.c $(pkg-config --cflags --libs mfstab) -o dispersion */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <mfstab.h>

int main(void)
{
  mfs_disc d = mfs_disc_default(); /* 1D, cubic, D = 2, MLS, nodal, lumped */
  mfs_status st;
  mfs_disp_spec spec = {.disc = d};
  mfs_disp_plan *pl = mfs_disp_plan_alloc(&spec, &st);
  if (!pl) {
    fprintf(stderr, "dispersion: %s\n", mfs_strerror(st));
    return 1;
  }
  mfs_stencil_entry *s = NULL;
  size_t n = 0, bad = 0;
  st = mfs_stencil(&d, &s, &n, &bad);
  if (st != MFS_OK) {
    fprintf(stderr, "stencil: %s\n", mfs_strerror(st));
    mfs_disp_plan_free(pl);
    return 1;
  }
  double m0 = 0.0;
  for (size_t e = 0; e < n; e++)
    if (s[e].j == 0)
      m0 = s[e].M;

  int ok = 1;
  printf("kappa,omega_bloch,omega_stencil,omega_continuum\n");
  for (int i = 0; i <= 10; i++) {
    double kappa = 0.1 * i, sum = 0.0;
    double _Complex w2[1];
    st = mfs_disp_omega2(pl, 0.0, kappa, 0.0, w2);
    if (st != MFS_OK) {
      fprintf(stderr, "omega2: %s\n", mfs_strerror(st));
      ok = 0;
      break;
    }
    for (size_t e = 0; e < n; e++)
      sum += s[e].K * cos(s[e].j * M_PI * kappa);
    double wb = sqrt(fmax(creal(w2[0]), 0.0)), ws = sqrt(fmax(sum / m0, 0.0));
    printf("%.2f,%.12f,%.12f,%.12f\n", kappa, wb, ws, M_PI * kappa);
    if (fabs(wb * wb - ws * ws) > 1e-12 * (1.0 + ws * ws))
      ok = 0;
  }
  mfs_free(s);
  mfs_disp_plan_free(pl);
  if (!ok)
    fprintf(stderr, "dispersion: the Bloch symbol and the stencil disagree\n");
  return ok ? 0 : 1;
}
