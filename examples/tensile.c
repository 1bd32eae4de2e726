/* The tensile instability of SPH (Swegle et al.; paper 003 section 4):
 * classify the 1D SPH discretization (cubic spline, D = 1.5, nodal
 * integration) at stresses sigma / E from -0.1 to 0.1 with an Eulerian
 * kernel (the particles' neighbours move with them: the classical SPH) and
 * with a Lagrangian one (paper 001: neighbours and weights of the reference
 * configuration).  The Eulerian kernel is unstable in tension; the
 * Lagrangian one is not.
 *
 * Prints one row per (frame, stress) with the label; exits 1 if the
 * Eulerian kernel is not tensile-unstable at sigma / E = 0.1 or the
 * Lagrangian one is.
 * Build: cc tensile.c $(pkg-config --cflags --libs mfstab) -o tensile */
#include <stdio.h>

#include <mfstab.h>

int main(void)
{
  const double sbar[] = {-0.1, -0.05, 0.0, 0.05, 0.1};
  const size_t ns = sizeof sbar / sizeof sbar[0];
  const double theta = 0.0;
  mfs_sampling smp = {.theta = &theta, .ntheta = 1, .npoints = 101};
  int tensile_at_01[2] = {0, 0};
  printf("frame,sigma_over_E,label\n");
  for (int f = 0; f < 2; f++) {
    mfs_disc d = mfs_disc_default();
    d.shape = &mfs_shape_sph;
    d.dilation = 1.5;
    d.frame = f == 0 ? MFS_FRAME_EULERIAN : MFS_FRAME_LAGRANGIAN;
    mfs_disp_spec spec = {.disc = d};
    mfs_status st;
    mfs_disp_plan *pl = mfs_disp_plan_alloc(&spec, &st);
    mfs_class out[5];
    if (pl)
      st = mfs_classify(pl, &smp, sbar, ns, out);
    mfs_disp_plan_free(pl);
    if (st != MFS_OK) {
      fprintf(stderr, "tensile: %s\n", mfs_strerror(st));
      return 1;
    }
    for (size_t i = 0; i < ns; i++) {
      char label[64];
      printf("%s,%g,%s\n", mfs_frame_name(d.frame), sbar[i],
             mfs_class_label(out[i].labels, label, sizeof label));
    }
    tensile_at_01[f] = (out[ns - 1].labels & MFS_LABEL_TENSILE) != 0;
  }
  if (!tensile_at_01[0] || tensile_at_01[1]) {
    fprintf(stderr, "tensile: expected the Eulerian kernel alone to be unstable in tension\n");
    return 1;
  }
  return 0;
}
