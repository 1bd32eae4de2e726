/* mfstab stencil: the stiffness and mass entries K_jk, M_jk coupling an
 * interior particle with the particle at lattice offset (j, k) on an
 * infinite lattice (paper 003 eq. 114 and Table I). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mfs_alloc.h"
#include "commands.h"

static const char usage[] = "mfstab stencil [options] [-o FILE]";
static const char about[] =
  "Stiffness K_jk (1D bar: C int phi_I' phi_J'; 2D anti-plane: C int grad phi_I . grad phi_J,\n"
  "paper 003 eq. 113) and mass M_jk (eq. 112; lumped: row sum, eq. 131) between an interior\n"
  "particle and the particle at lattice offset (j, k) of an infinite lattice (eq. 114).\n"
  "Offsets are in the lattice basis a1 = (dx, 0), a2 = (0, dy) (square) or (dx/2, sqrt(3)/2 dx)\n"
  "(hex).  Every structurally coupled offset is listed, zeros included.\n"
  "CSV columns: j,k,K_n_m (stiffness, N/m),M_kg (mass, kg), per unit cross-section (1D) or\n"
  "thickness (2D)\n";

typedef struct {
  const char *out;
} stencil_opts;

static const cli_opt opts[] = {
  {.name = "-o", .type = CLI_TEXT, .arg = "FILE",
   .help = "output file (default: standard output)", .offset = offsetof(stencil_opts, out)},
  {.type = CLI_END}};

int cmd_stencil(int argc, char **argv)
{
  cli_disc d;
  cli_disc_defaults(&d);
  stencil_opts o = {0};
  unsigned char seen_d[CLI_DISC_NOPTS], seen_o[2];
  cli_group g[2] = {{cli_disc_opts, &d, seen_d}, {opts, &o, seen_o}};
  cli_parse(argc, argv, usage, about, g, 2);
  if (d.dilation.n > 1)
    cli_die(2, "--dilation: one value, not a list");
  mfs_disc disc = cli_disc_build(&d, seen_d);
  char what[96];
  double side = 4.0 * ceil(2.0 * disc.dilation) + 4.0; /* the periodic box of mfs_stencil */
  snprintf(what, sizeof what, "--dilation %g", disc.dilation);
  cli_check_work(&d, &disc, disc.dim == 1 ? side : side * side, what);
  mfs_stencil_entry *e;
  size_t n, bad = 0;
  mfs_status st = mfs_stencil(&disc, &e, &n, &bad);
  if (st != MFS_OK)
    cli_die_status(st, &d, disc.dilation, "at a quadrature point of the lattice");
  cli_out out;
  cli_out_open(&out, o.out);
  fprintf(out.f, "j,k,K_n_m,M_kg\n");
  for (size_t i = 0; i < n; i++) {
    char k[32], m[32];
    cli_fmt(k, sizeof k, e[i].K);
    cli_fmt(m, sizeof m, e[i].M);
    fprintf(out.f, "%d,%d,%s,%s\n", e[i].j, e[i].k, k, m);
  }
  mfs_free(e);
  mfs_free(d.dilation.v);
  cli_out_commit(&out);
  return 0;
}
