#!/usr/bin/env bash
# Write the outputs that the regression test (test_golden.sh) compares into DIR:
# `mfstab reproduce`, every scene of analysis/scenes/ with its defaults, the
# scene runs of analysis/figures.sh, and a set of command lines that cover
# each command's paths (kernels, shapes, quadratures, frames, mass, physics).
# usage: generate.sh MFSTAB SCENES_DIR DIR
# The reference copies in tests/golden/data/ were made with this script from
# main at commit aad0a6a (before the middle layer was rebuilt, issue 9).
set -euo pipefail
M=${1:?usage: generate.sh MFSTAB SCENES_DIR DIR}
S=${2:?}
D=${3:?}
mkdir -p "$D/reproduce"
"$M" reproduce --out "$D/reproduce" >"$D/reproduce/table.txt"
for s in "$S"/*.ini; do
  "$M" run "$s" -o "$D/scene_$(basename "$s" .ini).csv"
done
"$M" run "$S/rod-tensile.ini" --set discretization.frame=lagrangian --set output.every=1 \
  -o "$D/scene_rod_tensile_lagrangian.csv"
"$M" run "$S/rod-tensile.ini" --set discretization.shape=sph --set time.end=1.2e-5 \
  --set output.every=1 -o "$D/scene_rod_tensile_eulerian_sph.csv"
"$M" run "$S/rod-tensile.ini" --set discretization.quadrature=stress -o "$D/scene_rod_tensile_stress.csv"
"$M" run "$S/rod-tensile.ini" --set discretization.quadrature=gauss2 --set discretization.frame=lagrangian \
  -o "$D/scene_rod_tensile_gauss2.csv"
"$M" run "$S/tsph-elastic-bar.ini" --set discretization.interpolation=shepard \
  --set discretization.artificial_viscosity=0 -o "$D/scene_tsph_elastic_paper.csv"
n=0
cmd() { # one command line, output into cmd_NN.csv
  n=$((n + 1))
  "$M" "$@" -o "$D/$(printf 'cmd_%02d' $n).csv"
}
cmd stencil --dim 1 --kernel quartic --dilation 1.5 --quadrature stress
cmd stencil --dim 2 --lattice hex --kernel cubic --dilation 2.2 --quadrature stress-hex --mass consistent
cmd stencil --dim 2 --shape kb --dilation 2.5 --quadrature gauss2 --gamma 1.3
cmd stencil --dim 2 --shape rl --dilation 2.1 --quadrature stress-star
cmd dispersion --dim 1 --kernel quartic --dilation 1.5,2.5 --frame eulerian --quadrature stress --stress -0.3,0.2
cmd dispersion --dim 1 --shape sph --frame eulerian-consistent --stress 0.1,0.3
cmd dispersion --dim 1 --quadrature gauss3 --mass consistent --ls-alpha 0.01 --ls-length 1
cmd dispersion --dim 2 --physics plane-strain --poisson 0.3 --quadrature stress-tri --theta 0,30,45
cmd dispersion --dim 2 --lattice hex --quadrature stress-hex --shape shepard --theta 0,15
cmd dispersion --dim 1 --kernel cubic --dilation 1.5,2,3 --frame eulerian --stress -0.5,0,0.5 --classify
cmd dispersion --dim 2 --quadrature nodal --dilation 2,2.5 --classify
cmd eigs --dim 1 --nodes 61 --quadrature stress --zero-modes
cmd eigs --dim 1 --nodes 41 --mass consistent --shape shepard
cmd eigs --dim 2 --nodes 15,13 --physics plane-strain --quadrature stress-quad --zero-modes
cmd eigs --dim 2 --nodes 14,14 --periodic --quadrature nodal --zero-modes
cmd bound --dim 1 --nodes 101 --kernel quartic --dilation 2.3
cmd bound --dim 2 --nodes 21,17 --quadrature gauss2 --physics plane-strain
# issue 10: plane strain under stress and stretch, the map (references made by this code)
cmd dispersion --dim 2 --physics plane-strain --quadrature stress-tri --stress 0.3 --stress-yy -0.2 \
  --stress-xy 0.1 --frame eulerian-consistent --theta 0,30 --points 11
cmd dispersion --dim 2 --physics plane-strain --material paper000 --stretch 1.1 --stretch-y 0.95 \
  --quadrature stress-quad --frame eulerian --theta 0,45 --classify
cmd map --material paper000 --stretch-range 0.8:1.3:4 --quadrature stress-tri \
  --frame lagrangian,eulerian,eulerian-consistent
cmd map --stress-range -1.2:0.6:4 --stress-xy 0.2 --quadrature nodal --shape sph --frame lagrangian,eulerian
