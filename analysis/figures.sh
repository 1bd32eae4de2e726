#!/usr/bin/env bash
# Write the data of the reproduced tables and figures (every row of `mfstab reproduce`:
# the four papers) as CSV into DIR (default notebooks-data) with `mfstab reproduce`,
# paper 000 Fig. 1 at the figure's resolution with `mfstab map`, the time series of the shipped
# scenes behind paper 003 Fig. 6 and paper 001 Figs 4 and 8 with `mfstab run`,
# then one PNG per figure made from that CSV only (analysis/plot_figures.py,
# Debian's python3-matplotlib), workprec.png included: it is re-plotted from
# the committed workprec_*.csv (analysis/bench/workprec.sh measures them; the
# main job does not re-run the benchmark, and the figure says where and when
# the times were measured).
# usage: analysis/figures.sh [BUILD_DIR] [DIR]
# FIGURES_PLOTS=0 writes the CSV only (the notebooks run it so into a
# temporary directory and compare with the committed notebooks-data/).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
dir=${2:-notebooks-data}
"$build/tools/mfstab" reproduce --out "$dir"
# paper 000 Fig. 1 at the figure's resolution (reproduce's rows use a 10 x 10 map): 35 x 35
# states on [0.3, 2]^2 for both stress-point layouts, and a zoom around F = I
map() { "$build/tools/mfstab" map --material paper000 --kernel cubic --shape mls --dilation 2 \
  --frame lagrangian,eulerian,eulerian-consistent "$@"; }
map --stretch-range 0.3:2.0:35 --quadrature stress-quad -o "$dir/fig01_000_stress-quad.csv"
map --stretch-range 0.3:2.0:35 --quadrature stress-tri -o "$dir/fig01_000_stress-tri.csv"
map --stretch-range 0.85:1.15:25 --quadrature stress-quad -o "$dir/fig01_000_zoom.csv"
echo "wrote the maps fig01_000_*.csv" >&2
run() { "$build/tools/mfstab" run "$@"; }
run analysis/scenes/rod-tensile.ini --set discretization.frame=lagrangian --set output.every=1 \
  -o "$dir/run_rod_tensile_lagrangian.csv"
run analysis/scenes/rod-tensile.ini --set discretization.shape=sph --set time.end=1.2e-5 \
  --set output.every=1 -o "$dir/run_rod_tensile_eulerian_sph.csv"
run analysis/scenes/tsph-elastic-bar.ini --set discretization.interpolation=shepard \
  --set discretization.artificial_viscosity=0 \
  -o "$dir/run_tsph_elastic_paper.csv"
run analysis/scenes/tsph-elastic-bar.ini -o "$dir/run_tsph_elastic_scene.csv"
run analysis/scenes/tsph-viscoplastic-bar.ini --set discretization.interpolation=shepard \
  --set discretization.artificial_viscosity=0 \
  -o "$dir/run_tsph_viscoplastic_paper.csv"
run analysis/scenes/tsph-viscoplastic-bar.ini -o "$dir/run_tsph_viscoplastic_scene.csv"
echo "wrote the scene runs run_*.csv" >&2
if [ "${FIGURES_PLOTS:-1}" != 0 ]; then
  /usr/bin/python3 analysis/plot_figures.py "$dir"
  # paper 000 Fig. 1 (the maps of mfstab reproduce)
  for m in stress-quad stress-tri zoom; do
    /usr/bin/python3 analysis/plot_map.py "$dir/fig01_000_$m.csv" "$dir/fig01_000_$m.png"
  done
  # paper 004 Figs 5-6, 8-9: re-plotted from the committed studies at the paper's levels
  # (analysis/static_studies.sh measures them, outside the main job, as workprec.sh does)
  if [ -s "$dir/static_beam.csv" ] && [ -s "$dir/static_plate.csv" ]; then
    /usr/bin/python3 analysis/plot_static.py "$dir"
  fi
fi
