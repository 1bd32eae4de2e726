#!/usr/bin/env bash
# Install what is missing, build, and run the main job: mfstab reproduce
# (tables and figure data into notebooks-data/), then the plots from the CSV.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bash analysis/figures.sh build notebooks-data
echo "plots: notebooks-data/*.png"
