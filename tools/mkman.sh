#!/bin/sh
# The manual page mfstab.1, made from the program's own help (mfstab --help
# and mfstab help COMMAND for each command it lists), so that it cannot
# drift from the options.  usage: sh tools/mkman.sh MFSTAB OUT
set -eu
m=$1
out=$2
version=$("$m" --version | sed -n '1s/^mfstab //p')
# troff: backslashes doubled, a leading dot or quote protected
esc() { sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }
{
  printf '.TH MFSTAB 1 "" "mfstab %s" "User Commands"\n' "$version"
  printf '.SH NAME\nmfstab \\- stability, dispersion and time-step analysis of meshfree particle methods\n'
  printf '.SH SYNOPSIS\n.B mfstab\n.I COMMAND\n[\\fIoptions\\fR]\n.br\n.B mfstab help\n.I COMMAND\n.br\n.B mfstab \\-\\-version\n'
  printf '.SH DESCRIPTION\n'
  printf 'mfstab assembles the linearized stiffness and mass of a meshfree discretization (SPH, MLS/EFG, RKPM; nodal, stress-point or Gauss quadrature), computes its dispersion curves, the spectra of finite models, eigenvalue bounds and critical time steps, and checks them with an explicit reference solver.  Every command writes CSV, to standard output or to the file of \\fB\\-o\\fR; the columns are named in the first row and carry their unit or say they are normalized; an undefined value is an empty cell.\n'
  printf '.PP\nAn output file is written through a temporary file in its directory, renamed on success; a symbolic link is followed; a device or FIFO is written in place; the umask is honoured; the temporary file is removed on failure and on SIGINT, SIGTERM, SIGHUP and SIGPIPE.\n'
  printf '.SH COMMANDS\n'
  "$m" --help | sed -n '/^commands:/,$p' | sed -n 's/^  \([a-z][a-z-]*\)  .*/\1/p' | while read -r c; do
    printf '.SS %s\n.nf\n' "$c"
    "$m" help "$c" | esc
    printf '.fi\n'
  done
  printf '.SH EXIT STATUS\n.TP\n0\nsuccess\n.TP\n1\na numerical failure (a singular moment matrix, ARPACK without convergence, a non-finite result, out of memory, an I/O error); one line on standard error\n.TP\n2\nbad input (an unknown option, a value out of its range, a scene key missing or in conflict, work over the limit); one line on standard error naming the parameter, the value and what is allowed; no output file\n'
  printf '.SH FILES\nThe scene files of \\fBmfstab run\\fR are INI files (see \\fBmfstab help run\\fR); examples are in analysis/scenes/ of the source tree.\n'
  printf '.SH SEE ALSO\nThe commands with the papers'"'"' equation numbers: docs/commands.md; a user guide: docs/user-guide.md; the library: docs/api.md of the source tree, and the headers in PREFIX/include/mfstab/ (pkg-config mfstab).\n'
} >"$out"
