/* The subcommands of the mfstab program. */
#ifndef MFSTAB_COMMANDS_H
#define MFSTAB_COMMANDS_H

int cmd_stencil(int argc, char **argv);
int cmd_dispersion(int argc, char **argv);
int cmd_reproduce(int argc, char **argv);
int cmd_eigs(int argc, char **argv);
int cmd_bound(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_map(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_static(int argc, char **argv);

#endif
