#!/usr/bin/env bash
# Build mfstab in release mode in $BUILD (default /tmp/build-bench) and run the
# assembly benchmark: sizes 250, 500, 1000, three runs each, into
# notebooks-data/bench_assembly.csv.  Extra arguments replace the sizes.
# The library is single-threaded (one core); CORE=n pins the run to core n.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-/tmp/build-bench}
[ -f "$BUILD/build.ninja" ] || meson setup "$BUILD" --buildtype=release >/dev/null
meson compile -C "$BUILD" bench_assembly >/dev/null
mkdir -p notebooks-data
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(250 500 1000)
pin=()
[ -z "${CORE:-}" ] || pin=(taskset -c "$CORE")
"${pin[@]}" "$BUILD/analysis/bench/bench_assembly" --repeat 3 "${sizes[@]}" \
  -o notebooks-data/bench_assembly.csv
echo "wrote notebooks-data/bench_assembly.csv" >&2
