#!/usr/bin/env bash
# Install what mfstab needs on Debian 12 (as root), skipping what is there.
set -euo pipefail
pkgs=(build-essential meson ninja-build pkg-config libgsl-dev liblapacke-dev libarpack2-dev
      libsuitesparse-dev libinih-dev libqhull-dev python3-matplotlib
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
fi
