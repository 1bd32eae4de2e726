#!/usr/bin/env bash
# Build mfstab in release mode in $BUILD (default /tmp/build-bench) and run the
# benchmarks of `mfstab static` (paper 004), one core at a time:
#   notebooks-data/bench_static.csv   the beam with EFG at dx = 1/16, 1/32, 1/64 and the
#                                     10^5-node level 897 x 113 (dx = 1/112): geometry,
#                                     assembly, solve and error seconds, peak memory
#   notebooks-data/bench_table4.csv   Table IV: corrected derivatives (kb) against MLS
# Takes several minutes (the 10^5-node factorization with the reference BLAS);
# SIZES="..." replaces the sizes; CORE=n pins the run to core n.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-/tmp/build-bench}
[ -f "$BUILD/build.ninja" ] || meson setup "$BUILD" --buildtype=release >/dev/null
meson compile -C "$BUILD" bench_static >/dev/null
mkdir -p notebooks-data
pin=()
[ -z "${CORE:-}" ] || pin=(taskset -c "$CORE")
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
"${pin[@]}" "$BUILD/analysis/bench/bench_static" table4 --repeat 5 -o notebooks-data/bench_table4.csv
# shellcheck disable=SC2086
"${pin[@]}" "$BUILD/analysis/bench/bench_static" ${SIZES:-129,17 257,33 513,65 897,113} \
  -o notebooks-data/bench_static.csv
echo "wrote notebooks-data/bench_static.csv and notebooks-data/bench_table4.csv" >&2
