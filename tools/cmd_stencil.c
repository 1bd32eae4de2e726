/* mfstab stencil: the stiffness and mass entries K_jk, M_jk coupling an
 * interior particle with the particle at lattice offset (j, k) on an
 * infinite lattice (paper 003 eq. 114 and Table I). */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

static const char help[] =
  "usage: mfstab stencil [options] [-o FILE]\n"
  "Stiffness K_jk (1D bar: C int phi_I' phi_J'; 2D anti-plane: C int grad phi_I . grad phi_J,\n"
  "paper 003 eq. 113) and mass M_jk (eq. 112; lumped: row sum, eq. 131) between an interior\n"
  "particle and the particle at lattice offset (j, k) of an infinite lattice (eq. 114).\n"
  "Offsets are in the lattice basis a1 = (dx, 0), a2 = (0, dy) (square) or (dx/2, sqrt(3)/2 dx)\n"
  "(hex).  Every structurally coupled offset is listed, zeros included.\n"
  "CSV columns: j,k,K,M\n"
  "options:\n"
  "%s"
  "  -o FILE                 output file (default: standard output)\n";

int cmd_stencil(int argc, char **argv)
{
  char helptext[4096];
  snprintf(helptext, sizeof helptext, help, cli_disc_help);
  cli_disc d;
  cli_disc_defaults(&d);
  const char *outpath = NULL, *opt, *val;
  opt_iter it;
  opt_init(&it, argc, argv, helptext, NULL);
  while (opt_next(&it, &opt, &val)) {
    if (opt && cli_disc_option(&d, opt, val))
      continue;
    if (opt && strcmp(opt, "-o") == 0)
      outpath = val;
    else
      opt_unknown(opt);
  }
  mfs_lattice_kind lattice;
  mfs_quad_rule rule;
  cli_disc_finish(&d, &lattice, &rule);

  mfs_stencil_spec s = {
    .dim = d.dim,
    .lattice = lattice,
    .dx = d.spacing,
    .gamma = d.gamma,
    .quadrature = d.quadrature,
    .plan = {d.kernel, d.shape, d.dilation, 1, 1e-12},
    .mat = {MFS_PHYS_SCALAR, d.modulus, 0.0, d.density},
    .consistent_mass = d.consistent_mass,
  };
  mfs_stencil_entry *e;
  size_t n, bad = 0;
  int st = mfs_stencil(&s, &e, &n, &bad);
  if (st != MFS_OK)
    cli_die_status(st, &d, "at a quadrature point of the lattice");
  cli_out o;
  cli_out_open(&o, outpath);
  fprintf(o.f, "j,k,K,M\n");
  for (size_t i = 0; i < n; i++) {
    char k[32], m[32];
    cli_fmt(k, sizeof k, e[i].K);
    cli_fmt(m, sizeof m, e[i].M);
    fprintf(o.f, "%d,%d,%s,%s\n", e[i].j, e[i].k, k, m);
  }
  free(e);
  cli_out_commit(&o);
  return 0;
}
