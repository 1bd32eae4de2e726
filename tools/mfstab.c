/* mfstab: stability and dispersion analysis of meshfree particle methods. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

static const char usage[] =
  "usage: mfstab COMMAND [options]    (mfstab COMMAND --help for its options)\n"
  "commands:\n"
  "  stencil      stiffness and mass stencil of an interior node of an infinite lattice\n"
  "  dispersion   von Neumann dispersion curves and stability classification\n"
  "  eigs         extreme eigenvalues, zero-energy modes and critical time step of a finite model\n"
  "  bound        cheap element eigenvalue bound and critical time step (eqs 123-146)\n"
  "  run          explicit reference solver on a scene file (INI)\n"
  "  reproduce    regenerate the reproduced tables and figures into notebooks-data/\n";

void opt_init(opt_iter *it, int argc, char **argv, const char *help, const char *const *flags)
{
  it->argc = argc;
  it->argv = argv;
  it->i = 1;
  it->help = help;
  it->flags = flags;
}

static int is_flag(const opt_iter *it, const char *opt)
{
  for (int k = 0; it->flags && it->flags[k]; k++)
    if (strcmp(it->flags[k], opt) == 0)
      return 1;
  return 0;
}

int opt_next(opt_iter *it, const char **opt, const char **val)
{
  if (it->i >= it->argc)
    return 0;
  const char *a = it->argv[it->i++];
  if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
    fputs(it->help, stdout);
    exit(0);
  }
  if (a[0] != '-' || a[1] == '\0') {
    *opt = NULL;
    *val = a; /* positional */
    return 1;
  }
  const char *eq = strchr(a, '=');
  if (eq && a[1] == '-') {
    size_t n = (size_t)(eq - a);
    if (n >= sizeof it->buf)
      n = sizeof it->buf - 1;
    memcpy(it->buf, a, n);
    it->buf[n] = '\0';
    *opt = it->buf;
    *val = eq + 1;
    return 1;
  }
  *opt = a;
  if (is_flag(it, a)) {
    *val = NULL;
    return 1;
  }
  if (it->i >= it->argc)
    cli_die(2, "%s: missing value", a);
  *val = it->argv[it->i++];
  return 1;
}

_Noreturn void opt_unknown(const char *opt)
{
  if (!opt)
    cli_die(2, "unexpected argument; see 'mfstab %s --help'", cli_command);
  cli_die(2, "%s: unknown option; see 'mfstab %s --help'", opt, cli_command);
}

int main(int argc, char **argv)
{
  gsl_set_error_handler_off();
  if (argc < 2) {
    fputs(usage, stderr);
    return 2;
  }
  if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
      strcmp(argv[1], "help") == 0) {
    fputs(usage, stdout);
    return 0;
  }
  static const struct {
    const char *name;
    int (*run)(int, char **);
  } cmds[] = {{"stencil", cmd_stencil}, {"dispersion", cmd_dispersion}, {"reproduce", cmd_reproduce},
                 {"eigs", cmd_eigs}, {"bound", cmd_bound}, {"run", cmd_run}};
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++)
    if (strcmp(argv[1], cmds[i].name) == 0) {
      cli_command = cmds[i].name;
      return cmds[i].run(argc - 1, argv + 1);
    }
  fprintf(stderr, "mfstab: '%s': unknown command; allowed: stencil, dispersion, eigs, bound, run, reproduce\n", argv[1]);
  return 2;
}
