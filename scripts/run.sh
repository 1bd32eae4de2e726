#!/usr/bin/env bash
# Install what is missing, build, and run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
build/tools/mfstab stencil --dim 2 --kernel cubic --dilation 2 --shape mls --quadrature gauss2
