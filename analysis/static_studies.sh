#!/usr/bin/env bash
# The refinement studies and patch tests of paper 004 (mfstab static) at the
# levels of the paper's Figs 5-9, into DIR (default notebooks-data):
#   static_beam.csv         beam, the seven methods, dx = 1/2 .. 1/64 (6 levels, 51 .. 33345 nodes)
#   static_plate.csv        plate with a hole, the seven methods, h = 1 .. 1/16 (5 levels, 35 .. 6356 nodes)
#   static_beam_ghost.csv   the beam with --ebc ghost (exact parameters on 6 columns at x <= 0: no EBC error)
#   static_beam_gauss.csv   cd1, cd2, rl, sph with 5 x 5 Gauss cells instead of nodal quadrature (diagnostic)
#   static_patch_*.csv      patch test, reproduction, integration constraint, test-gradient lambda
# and the plots static_beam.png, static_plate.png (analysis/plot_static.py).
# Not part of `mfstab reproduce` (which runs coarse levels in 2 s): about 25 minutes.
# usage: bash analysis/static_studies.sh [BUILD_DIR] [DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
D=${2:-notebooks-data}
M=$B/tools/mfstab
mkdir -p "$D"
"$M" static --method all --patch --nodes 33,5 -o "$D/static_patch_beam.csv"
"$M" static --method all --patch --length 4 --depth 4 --nodes 33,33 -o "$D/static_patch_square.csv"
"$M" static --method all --patch --length 4 --depth 4 --nodes 33,33 --perturb 0.2 \
  -o "$D/static_patch_square_perturbed.csv"
"$M" static --method all --patch --problem plate-hole --nodes 11 -o "$D/static_patch_plate.csv"
"$M" static --method all --refine 6 --nodes 17,3 -o "$D/static_beam.csv"
"$M" static --method all --refine 6 --nodes 17,3 --ebc ghost -o "$D/static_beam_ghost.csv"
"$M" static --method all --refine 5 --problem plate-hole --nodes 6 -o "$D/static_plate.csv"
"$M" static --method cd1,cd2,rl,sph --quadrature gauss5 --refine 5 --nodes 17,3 -o "$D/static_beam_gauss.csv"
if [ -x /usr/bin/python3 ]; then
  /usr/bin/python3 analysis/plot_static.py "$D"
fi
