#!/usr/bin/env bash
# Install what mfstab needs on Debian 12 (as root), skipping what is there.
set -euo pipefail
pkgs=(build-essential meson ninja-build pkg-config libgsl-dev liblapacke-dev libarpack2-dev
      libsuitesparse-dev libinih-dev libqhull-dev libopenblas-dev libopenblas-serial-dev
      libopenblas0-serial python3-matplotlib
      python3-nbclient python3-ipykernel python3-nbformat
      libparpack2-dev libopenmpi-dev openmpi-bin)  # MPI: optional (docs/parallel.md)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  # BLAS and LAPACK: OpenBLAS's serial build, the fastest of the three for
  # ARPACK's lambda_max here (notebooks-data/bench_blas.csv, docs/parallel.md);
  # LAPACKE, ARPACK and CHOLMOD load it through Debian's alternatives.  Set only
  # when this script installed something; to switch back:
  #   update-alternatives --config libblas.so.3-x86_64-linux-gnu (and liblapack.so.3-...)
  # The libopenblas.so.0 alternative is left alone (the pthread build, Debian's
  # default): the serial libblas.so.3 loads libopenblas.so.0 through $ORIGIN, the
  # alternatives' directory, so that build's kernels run, and unlike the serial
  # libopenblas.so.0 it is safe to call from several OpenMP threads at once (with
  # the serial one, tests/test_threads_dispersion.sh's zhegv sweep differed
  # between thread counts in 1 of 15 runs, with the pthread one in 0 of 25).
  a=/usr/lib/x86_64-linux-gnu
  for l in libblas.so.3 liblapack.so.3; do
    [ -e "$a/openblas-serial/$l" ] &&
      update-alternatives --set "$l-x86_64-linux-gnu" "$a/openblas-serial/$l" >/dev/null
  done
fi
