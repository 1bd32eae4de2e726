#!/usr/bin/env bash
# Build mfstab in release mode in $BUILD (default /tmp/build-bench) and run the
# assembly benchmark: sizes 250, 500, 1000, three runs each, into
# notebooks-data/bench_assembly.csv.  Extra arguments replace the sizes.
# The library is single-threaded (one core); CORE=n pins the run to core n.
#
# REF=DIR (a build of another commit, e.g. main's): instead, the model mode at
# 10^6 nodes (--no-checks 1000) side by side, RUNS times (default 3) at 1 and
# 2 threads, alternating this build and DIR's (ref, new, ref, new, ...), each
# run a fresh process, into $OUT (default $TMPDIR/bench_assembly_ab.csv) with
# the columns build (ref or new), ab_rep and load_start (the 1-minute load
# when the run started); load_1min is the new build's (empty for an old one).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-/tmp/build-bench}
[ -f "$BUILD/build.ninja" ] || meson setup "$BUILD" --buildtype=release >/dev/null
meson compile -C "$BUILD" bench_assembly >/dev/null
pin=()
[ -z "${CORE:-}" ] || pin=(taskset -c "$CORE")
if [ -n "${REF:-}" ]; then
  out=${OUT:-${TMPDIR:-/tmp}/bench_assembly_ab.csv}
  tmp=$(mktemp)
  trap 'rm -f "$tmp"' EXIT
  echo "build,ab_rep,load_start,$("$BUILD/analysis/bench/bench_assembly" -o "$tmp" --mode model --no-checks 8 2>/dev/null; head -1 "$tmp")" >"$out"
  for rep in $(seq 1 "${RUNS:-3}"); do
    for th in 1 2; do
      for b in ref new; do
        exe="$BUILD/analysis/bench/bench_assembly"
        [ "$b" = new ] || exe="$REF/analysis/bench/bench_assembly"
        load=$(cut -d' ' -f1 /proc/loadavg)
        OMP_NUM_THREADS=$th "${pin[@]}" "$exe" --mode model --no-checks 1000 -o "$tmp" 2>/dev/null
        # the old build has no load_1min column: an empty cell
        tail -n +2 "$tmp" | awk -F, -v b="$b" -v r="$rep" -v l="$load" \
          '{ printf "%s,%s,%s,%s%s\n", b, r, l, $0, (b == "ref" && NF == 18) ? "," : "" }' >>"$out"
      done
    done
  done
  echo "wrote $out" >&2
  exit 0
fi
mkdir -p notebooks-data
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(250 500 1000)
"${pin[@]}" "$BUILD/analysis/bench/bench_assembly" --repeat 3 "${sizes[@]}" \
  -o notebooks-data/bench_assembly.csv
echo "wrote notebooks-data/bench_assembly.csv" >&2
