#!/usr/bin/env bash
# Write the data of the reproduced tables and figures (paper 003 Tables I-II,
# Figs 3, 4, 9, 10, 11, 13, 14, 15, 17, 18) as CSV into DIR (default
# notebooks-data) with `mfstab reproduce`, then one PNG per figure made from
# that CSV only (analysis/plot_figures.py, Debian's python3-matplotlib).
# usage: analysis/figures.sh [BUILD_DIR] [DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
dir=${2:-notebooks-data}
"$build/tools/mfstab" reproduce --out "$dir"
/usr/bin/python3 analysis/plot_figures.py "$dir"
