#!/usr/bin/env bash
# All the benchmarks (issue 14 item 8; not a test, not part of `mfstab reproduce`):
# the machine's limits first (bench_bandwidth: memory bandwidth and flop rate with
# 1 and 2 threads), then every benchmark with those limits, then each CSV gains
# limit_kind, limit_s and fraction (analysis/bench/limits.py, docs/benchmarks.md)
# and the summary plot bench_summary.png: the fraction of its limit each
# benchmark's work reaches (/usr/bin/python3 matplotlib).
#
#   analysis/bench/run.sh [BUILD_DIR]       (default build; a release build)
#   QUICK=1   small sizes and one repetition (a few minutes), into $TMPDIR/mfstab-bench-quick
#             unless OUT is given: it does not overwrite the committed full-run CSVs
#   OUT=DIR   where the CSVs and the plot go (default notebooks-data)
#   SKIP="eigs blas ..."  benchmarks left out (names below)
#   LIMITS_ONLY=1  run nothing: the limit columns and the plot for the CSVs already in OUT,
#             with the limits of OUT/bench_bandwidth.csv (measured first if it is missing)
# The full run takes long (bench_check's 10^6 particles, bench_static's 10^5 nodes,
# bench_eigs at 10^6 nodes, bench_blas over four libraries, bench_mpi over MPI when
# the build has it).  The machine is shared: each CSV that runs in turns records
# load_1min; this script prints the load before every benchmark.
set -euo pipefail
BUILD=${1:-build}
B=$BUILD/analysis/bench
QUICK=${QUICK:-0}
if [ "$QUICK" = 1 ]; then OUT=${OUT:-${TMPDIR:-/tmp}/mfstab-bench-quick}; else OUT=${OUT:-notebooks-data}; fi
SKIP=" ${SKIP:-} "
PY=/usr/bin/python3
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
[ -x "$B/bench_bandwidth" ] || { echo "run.sh: $B/bench_bandwidth not found (meson compile -C $BUILD)" >&2; exit 2; }
want() { [[ "$SKIP" != *" $1 "* ]]; }
say() { echo "run.sh: $1 (load $(cut -d' ' -f1 /proc/loadavg))" >&2; }

LIMITS_ONLY=${LIMITS_ONLY:-0}
if [ "$LIMITS_ONLY" != 1 ] || [ ! -f "$OUT/bench_bandwidth.csv" ]; then
  say bandwidth
  l=$(cut -d' ' -f1 /proc/loadavg)
  "$B/bench_bandwidth" --header | awk -v l="$l" 'NR==1{print $0",load_1min";next}{print $0","l}' \
    > "$OUT/bench_bandwidth.csv"
fi
lim() { awk -F, -v t="$1" -v c="$2" 'NR==1{for(i=1;i<=NF;i++)h[$i]=i;next}
  $1=="limit" && $2==t {print $h[c]}' "$OUT/bench_bandwidth.csv"; }
GBS1=$(lim 1 gbs) GBS2=$(lim 2 gbs) GF1=$(lim 1 gflops)
echo "run.sh: limits: $GBS1 GB/s (1 thread), $GBS2 GB/s (2 threads), $GF1 Gflop/s (dgemm, 1 thread)" >&2
export MFS_BENCH_GBS=$GBS1 MFS_BENCH_GBS_1=$GBS1 MFS_BENCH_GBS_2=$GBS2 MFS_BENCH_GFLOPS=$GF1

[ "$LIMITS_ONLY" = 1 ] && SKIP=" lambda eigs assembly solver map step dispersion static check blas mpi "
if want lambda; then
  say "lambda (mfstab lambda_max, SciPy eigsh, certified step)"
  if [ "$QUICK" = 1 ]; then REPS=1 CERTIFY=0 OUT=$OUT/bench_lambda.csv bash "$HERE/bench_lambda.sh" "$BUILD" 100
  else REPS=5 OUT=$OUT/bench_lambda.csv bash "$HERE/bench_lambda.sh" "$BUILD" 100 316; fi
fi
if want eigs; then
  say eigs
  if [ "$QUICK" = 1 ]; then OUT=$OUT/bench_eigs.csv bash "$HERE/bench_eigs.sh" "$BUILD" 100
  else REPS=3 OUT=$OUT/bench_eigs.csv bash "$HERE/bench_eigs.sh" "$BUILD" 100 316 1000; fi
fi
if want assembly; then
  say assembly
  if [ "$QUICK" = 1 ]; then "$B/bench_assembly" --repeat 1 --no-checks 250 -o "$OUT/bench_assembly.csv"
  else "$B/bench_assembly" --repeat 3 250 500 1000 -o "$OUT/bench_assembly.csv"; fi
fi
if want solver; then
  say solver
  if [ "$QUICK" = 1 ]; then "$B/bench_solver" 20000 100 -o "$OUT/bench_solver.csv"
  else "$B/bench_solver" 100000 400 -o "$OUT/bench_solver.csv"; fi
fi
if want map; then # bench_map, then the command itself (bench_map_command.csv)
  say map
  ABS_BUILD=$(cd "$BUILD" && pwd) ABS_OUT=$(cd "$OUT" && pwd)
  if [ "$QUICK" = 1 ]; then BUILD=$ABS_BUILD OUTDIR=$ABS_OUT REPEATS=1 bash "$HERE/run_bench_map.sh" 16
  else BUILD=$ABS_BUILD OUTDIR=$ABS_OUT REPEATS=3 bash "$HERE/run_bench_map.sh" 60; fi
fi
if want step; then
  say "step (the step rules: power, gershgorin, certified)"
  if [ "$QUICK" = 1 ]; then "$B/bench_step" --reps 1 --certified-max 0 -o "$OUT/bench_step.csv" 2000
  else "$B/bench_step" -o "$OUT/bench_step.csv" 10000 100000; fi
fi
if want dispersion; then
  say dispersion
  if [ "$QUICK" = 1 ]; then "$B/bench_dispersion" --repeat 3 -o "$OUT/bench_dispersion.csv"
  else "$B/bench_dispersion" --repeat 7 -o "$OUT/bench_dispersion.csv"; fi
  say "dispersion against NumPy"
  $PY "$HERE/bench_dispersion_numpy.py" --runs 5 --bench "$B/bench_dispersion" \
    -o "$OUT/bench_dispersion_numpy.csv" > /dev/null
fi
if want static; then
  say static
  if [ "$QUICK" = 1 ]; then OMP_NUM_THREADS=1 "$B/bench_static" 129,17 -o "$OUT/bench_static.csv"
  else OMP_NUM_THREADS=1 "$B/bench_static" 129,17 257,33 513,65 897,113 -o "$OUT/bench_static.csv"
    OMP_NUM_THREADS=1 "$B/bench_static" table4 --repeat 5 -o "$OUT/bench_table4.csv"; fi
fi
if [ "$QUICK" != 1 ] && [ "$LIMITS_ONLY" != 1 ]; then # long, or needing other libraries: the full run only
  if want check; then say check; OUT=$OUT/bench_check.csv bash "$HERE/bench_check.sh" "$BUILD" || true; fi
  if want blas; then say blas; OUT=$OUT/bench_blas.csv bash "$HERE/bench_blas.sh" "$BUILD" 100 || true; fi
  if want mpi && [ -x "$B/bench_peigs" ] && command -v mpirun > /dev/null; then
    say mpi; OUT=$OUT/bench_mpi.csv bash "$HERE/bench_mpi.sh" "$BUILD" 150 300 || true
  fi
fi

say "limits and summary"
for f in "$OUT"/bench_*.csv; do
  $PY "$HERE/limits.py" "$f" --gbs "$GBS1" --gbs2 "$GBS2" --gflops "$GF1"
done
$PY "$HERE/summary_plot.py" "$OUT" "$OUT/bench_summary.png"
# the targets of issues 14 and 15 against these CSVs (docs/bench_acceptance.md for the committed run)
if [ "$OUT" = notebooks-data ]; then MD=(--markdown docs/bench_acceptance.md); else MD=(); fi
$PY "$HERE/acceptance.py" --data "$OUT" -o "$OUT/bench_acceptance.csv" "${MD[@]}"
echo "run.sh: wrote $OUT/bench_*.csv and $OUT/bench_summary.png" >&2
