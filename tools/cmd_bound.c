/* mfstab bound: the cheap element eigenvalue bound of a finite model
 * (paper 003 eqs 123-133, 139-144) and the critical time steps it and the
 * closed forms give, without assembling the model or computing eigenvalues:
 * for models too large for `mfstab eigs`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "eigs_figures.h"

static const char usage[] = "mfstab bound [options] [-o FILE]";
static const char about[] =
  "Element eigenvalue bound lambda_max <= max_Q lambda^Q of a finite model with lumped mass\n"
  "(paper 003 eqs 121-133; 2D: the exact largest eigenvalue of the 2 x 2 matrix\n"
  "c^2 sum_I g_I g_I^T / phi_I, eqs 139-144 without assuming eq. 141), streamed over the\n"
  "quadrature points without assembling the model or storing a shape table (O(N)), with\n"
  "the critical time steps dt = 2/sqrt(lambda) of the central difference method from it, from\n"
  "the closed form alpha c^2/h^2 (eq. 136 1D, eq. 146 2D), from the Fourier maximum of the\n"
  "uniform lattice, and the rules of thumb 0.3 h/c (h = a/2; P-wave and bulk speeds).\n"
  "The bound is proven only where every phi_I > 0 at the quadrature points and the mass is\n"
  "lumped (bound_valid = 1); negative_phi_points counts the points where some phi_I <= 0.\n"
  "Models and options as 'mfstab eigs' (no eigenvalue options).\n"
  "CSV (one row): dim,nodes_x,nodes_y,length_x,length_y,dx,dy,kernel,shape,quadrature,mass,\n"
  "  dilation,support_radius,fixed,periodic,physics,modulus,density,poisson,wave_speed,\n"
  "  particles,quadrature_points,evaluated_points,bound,bound_valid,negative_phi_points,\n"
  "  x_at_bound,y_at_bound,bound_alpha,alpha,lambda_fourier,kappa_fourier,theta_fourier,\n"
  "  dt_bound,dt_alpha,dt_fourier,dt_rule_p,dt_rule_bulk\n";

int cmd_bound(int argc, char **argv)
{
  model_cmd c = {.m = {.fourier_points = 201, .fourier_angles = 7}};
  cli_disc_defaults(&c.d);
  unsigned char sd[CLI_DISC_NOPTS], sp[CLI_PHYSICS_NOPTS], sm[MODEL_NOPTS];
  cli_group g[3] = {
    {cli_disc_opts, &c.d, sd}, {cli_physics_opts, &c.d, sp}, {model_opts_table, &c.m, sm}};
  cli_parse(argc, argv, usage, about, g, 3);
  model_finish(&c, &g[0], &g[2]);
  eigs_derived dv;
  eigs_derive(&c.s, &dv);
  const mfs_disc *d = &c.s.disc;
  mfs_bound_result br;
  size_t bad = 0;
  mfs_status st = mfs_bound_model(&c.s, &br, &bad);
  if (st != MFS_OK)
    cli_die_status(st, &c.d, d->dilation, "at a quadrature point of the model");
  if (!(br.lambda > 0.0))
    cli_die(1, "the element bound is %g: no quadrature point with a positive lambda^Q", br.lambda);
  double lf, kf, tf;
  st = mfs_bound_fourier(&c.s, (int)c.m.fourier_points, (int)c.m.fourier_angles, &lf, &kf, &tf);
  if (st != MFS_OK)
    cli_die_status(st, &c.d, d->dilation, "Fourier estimate on the uniform lattice");
  int bvalid = !d->consistent_mass && br.negative_phi == 0;
  size_t np = (size_t)d->source.nx * (size_t)(d->dim == 1 ? 1 : d->source.ny);

  cli_out out;
  cli_out_open(&out, c.m.out);
  FILE *f = out.f;
  eigs_config_header(f);
  fputs(",particles,quadrature_points,evaluated_points,bound,bound_valid,negative_phi_points,"
        "x_at_bound,y_at_bound,bound_alpha,alpha,lambda_fourier,kappa_fourier,theta_fourier,"
        "dt_bound,dt_alpha,dt_fourier,dt_rule_p,dt_rule_bulk\n",
        f);
  eigs_config_row(f, &c.s, &dv);
  fprintf(f, ",%zu,%zu,%zu,", np, br.points, br.evaluated);
  eigs_put(f, br.lambda, 0);
  fprintf(f, "%d,%zu,", bvalid, br.negative_phi);
  eigs_put(f, br.xmax[0], 0);
  eigs_put(f, br.xmax[1], 0);
  eigs_put_estimates(f, &dv, lf, kf, tf);
  eigs_put(f, mfs_dt_crit(br.lambda), 0);
  eigs_put(f, mfs_dt_crit(dv.bound_alpha), 0);
  eigs_put(f, mfs_dt_crit(lf), 0);
  eigs_put(f, dv.dt_rule_p, 0);
  eigs_put(f, dv.dt_rule_bulk, 1);
  cli_out_commit(&out);
  free(c.d.dilation.v);
  return 0;
}
