#!/usr/bin/env bash
# Benchmark (not a test): weak scaling of the distributed model (lib/analysis/
# mfs_peigs.h) on this machine, 1 and 2 MPI ranks, with the one-process
# library calls as the reference (analysis/bench/bench_peigs.c says what is
# timed).  Per side S the model is plane strain on S x S nodes per rank:
#   serial  S x S    one process, mfs_model_alloc + ARPACK (the reference of the error)
#   mpi 1   S x S    one rank
#   serial  S x 2S   the reference of the 2-rank model
#   mpi 2   S x 2S   two ranks, each S x S (weak scaling)
#   mpi 2   S x S    two ranks, each half (strong scaling, for comparison)
# each REPS times, interleaved.  The machine is shared: the 1-minute load
# average before each run is a column (2 cores; a load above 2 means other
# work competed for them).
#
#   analysis/bench/bench_mpi.sh [BUILD_DIR] [SIDES...]
#     BUILD_DIR  meson build directory with MPI (default: build)
#     SIDES      nodes per side and rank (default: 200 400)
#   environment: REPS (default 3), OUT (default notebooks-data/bench_mpi.csv),
#   TOL (ARPACK/PARPACK tolerance, default 1e-10)
#
# CSV: case,rep,load_1min, then bench_peigs's columns (mode,ranks,nodes,dofs,
#   build_s,gershgorin_s,bound_s,eig_s,total_s,matvecs,eig_s_per_matvec,
#   lambda_max,lambda_gershgorin,error,rows_max,halo_max,halo_bytes_per_matvec,
#   nnz_max,plan_nnz_max,peak_rss_mb_max,peak_rss_mb_sum)
#   error: |lambda - lambda_serial| / lambda_serial of the same model.
set -euo pipefail
BUILD=${1:-build}
shift || true
SIDES=("$@")
[ ${#SIDES[@]} -eq 0 ] && SIDES=(200 400)
REPS=${REPS:-3}
TOL=${TOL:-1e-10}
OUT=${OUT:-notebooks-data/bench_mpi.csv}
B=$BUILD/analysis/bench/bench_peigs
[ -x "$B" ] || { echo "bench_mpi.sh: $B not found (a build with MPI: libopenmpi-dev, libparpack2-dev)" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "bench_mpi.sh: mpirun not found (openmpi-bin)" >&2; exit 2; }
MR=(mpirun -q --oversubscribe)
[ "$(id -u)" -eq 0 ] && MR+=(--allow-run-as-root)
mkdir -p "$(dirname "$OUT")"
tmpout="$OUT.tmp.$$"
trap 'rm -f "$tmpout"' EXIT
load() { cut -d' ' -f1 /proc/loadavg; }
{
  printf 'case,rep,load_1min,'
  "$B" 3 3 --serial --header | head -1
} >"$tmpout"
row() { # row CASE REP CMD...: one CSV row, the load before it
  local c=$1 r=$2 l
  shift 2
  l=$(load)
  printf '%s,%s,%s,' "$c" "$r" "$l" >>"$tmpout"
  "$@" | tail -1 >>"$tmpout"
}
lam() { tail -1 "$tmpout" | cut -d, -f15; }
for s in "${SIDES[@]}"; do
  for ((r = 1; r <= REPS; r++)); do
    row "serial ${s}x${s}" "$r" "$B" "$s" "$s" --serial --tol "$TOL"
    ref1=$(lam)
    row "weak 1 rank ${s}x${s}" "$r" "${MR[@]}" -np 1 "$B" "$s" "$s" --ref "$ref1" --tol "$TOL"
    row "strong 2 ranks ${s}x${s}" "$r" "${MR[@]}" -np 2 "$B" "$s" "$s" --ref "$ref1" --tol "$TOL"
    row "serial ${s}x$((2 * s))" "$r" "$B" "$s" $((2 * s)) --serial --tol "$TOL"
    ref2=$(lam)
    row "weak 2 ranks ${s}x$((2 * s))" "$r" "${MR[@]}" -np 2 "$B" "$s" $((2 * s)) --ref "$ref2" --tol "$TOL"
    echo "bench_mpi: side $s, run $r done (load $(load))" >&2
  done
done
# limit_kind, limit_s, fraction (docs/benchmarks.md; the limits of notebooks-data/bench_bandwidth.csv)
/usr/bin/python3 "$(dirname "$0")/limits.py" "$tmpout" --rule bench_mpi || true
mv "$tmpout" "$OUT"
trap - EXIT
echo "bench_mpi: $OUT" >&2
