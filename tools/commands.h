/* The subcommands of the mfstab program. */
#ifndef MFSTAB_COMMANDS_H
#define MFSTAB_COMMANDS_H

int cmd_stencil(int argc, char **argv);
int cmd_dispersion(int argc, char **argv);
int cmd_reproduce(int argc, char **argv);
int cmd_eigs(int argc, char **argv);
int cmd_bound(int argc, char **argv);
int cmd_run(int argc, char **argv);

/* Iterate "--opt value", "--opt=value" and "-o value" pairs.  Returns 0 at
 * the end, 1 with *opt and *val set (val NULL for a flag listed in flags,
 * a NULL-terminated list), and handles --help by printing help and exiting 0. */
typedef struct {
  int argc, i;
  char **argv;
  const char *help;
  const char *const *flags;
  char buf[256];
} opt_iter;
void opt_init(opt_iter *it, int argc, char **argv, const char *help, const char *const *flags);
int opt_next(opt_iter *it, const char **opt, const char **val);
_Noreturn void opt_unknown(const char *opt);

#endif
