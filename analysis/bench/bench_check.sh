#!/usr/bin/env bash
# Benchmark (not a test) of issue 15, into notebooks-data/bench_check.csv:
#  1. a 2D particle file of 10^6 particles (a 1000 x 1000 lattice of the unit
#     square perturbed by 20%, with its volumes; and the same without volumes,
#     whose volumes come from the Delaunay triangulation): read, plan and
#     dt_gershgorin, phase by phase (bench_check gershgorin), and the whole
#     command 'mfstab bound --particles FILE --support 0.002' (which also
#     computes the element bound and the Fourier estimate) with its wall time
#     and peak memory (/usr/bin/time);
#  2. dt_certified against lambda_max by ARPACK on the same model at 10^4 and
#     10^5 particles (bench_check certify): the perturbed lattice with nodal
#     integration and the lattice with 2 x 2 Gauss cells, lumped mass; and the
#     perturbed lattice with consistent mass.
# One core: the library is single-threaded, OMP_NUM_THREADS=1 keeps CHOLMOD on one thread;
# CHOLMOD's BLAS is Debian's default
# (the reference BLAS on the machine of the committed CSV).  BLAS_DIR=DIR runs
# the certification rows again with LD_LIBRARY_PATH=DIR (e.g. the libblas.so.3
# of an extracted libopenblas0-serial package), labelled blas=DIR.
#   analysis/bench/bench_check.sh [BUILD_DIR]      (default: build)
# CSV: job,particles,variant,phase,seconds,cpu_seconds,value,peak_rss_mb,blas
#   seconds: wall clock; cpu_seconds: user + system of the process (the total rows);
#   value: particles total and mfstab_bound: dt_gershgorin (s); certify arpack_lambda_max:
#   lambda_max (1/s^2); factorizations: their count; dt_certified: dt_certified/dt_crit;
#   time_ratio: seconds = (lanczos + factorizations) / arpack (wall), cpu_seconds the same
#   in CPU time, value the entries of the factor.  peak_rss_mb: the process's peak.
#   gflop: factorizations: the flops of all of them (10^9; CHOLMOD's count), the work
#   that analysis/bench/limits.py states against the dgemm rate.
set -euo pipefail
# one core: CHOLMOD's supernodal factorization runs OpenMP threads unless told not to
export OMP_NUM_THREADS=1
BUILD=${1:-build}
B=$BUILD/analysis/bench/bench_check
M=$BUILD/tools/mfstab
OUT=${OUT:-notebooks-data/bench_check.csv}
for b in "$B" "$M"; do
  [ -x "$b" ] || { echo "bench_check.sh: $b not found (build first)" >&2; exit 2; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_check.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$OUT")"
tmp="$OUT.tmp.$$"
echo "job,particles,variant,phase,seconds,cpu_seconds,value,peak_rss_mb,blas,gflop" >"$tmp"

# 1. 10^6 particles
"$B" gen 1000 "$work/p.csv"
"$B" gen 1000 "$work/pn.csv" --novol
for f in p pn; do
  variant=$([ $f = p ] && echo volumes || echo delaunay)
  row=$("$B" gershgorin "$work/$f.csv" 0.002)
  IFS=, read -r _ n _ rd geo pl ge tot cpu lam dt rss <<<"$row"
  for ph in read:$rd geometry:$geo plan:$pl gershgorin:$ge; do
    echo "particles,$n,$variant,${ph%%:*},${ph#*:},,,$rss,default" >>"$tmp"
  done
  echo "particles,$n,$variant,total,$tot,$cpu,$dt,$rss,default" >>"$tmp"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$M" bound --particles "$work/$f.csv" \
    --support 0.002 -o "$work/bound.csv"
  read -r wall us ss kb <"$work/time"
  dtg=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i } NR == 2 { print $h["dt_gershgorin_s"] }' "$work/bound.csv")
  echo "particles,$n,$variant,mfstab_bound,$wall,$(awk -v a="$us" -v b="$ss" 'BEGIN { print a + b }'),$dtg,$(awk -v k="$kb" 'BEGIN { printf "%.1f", k / 1024 }'),default" >>"$tmp"
done

# 2. dt_certified against ARPACK
certify_rows() { # LABEL ENV...
  local label=$1
  shift
  for side in 100 316; do
    for v in "nodal 0.2 lumped" "gauss2 0 lumped" "nodal 0.2 consistent"; do
      set -- $v
      row=$(env "${envs[@]}" "$B" certify $side --quadrature "$1" --perturb "$2" --mass "$3")
      IFS=, read -r _ n mass q asm ars mv lam cs ls fs nf fnnz gf sig frac tr cr rss <<<"$row"
      var="$q-perturb$2-$mass"
      echo "certify,$n,$var,assembly,$asm,,,$rss,$label" >>"$tmp"
      echo "certify,$n,$var,arpack_lambda_max,$ars,,$lam,$rss,$label" >>"$tmp"
      echo "certify,$n,$var,lanczos_1e-4,$ls,,,$rss,$label" >>"$tmp"
      echo "certify,$n,$var,factorizations,$fs,,$nf,$rss,$label,$(awk -v a="$nf" -v b="$gf" 'BEGIN { print a * b }')" >>"$tmp"
      echo "certify,$n,$var,dt_certified,$cs,,$frac,$rss,$label" >>"$tmp"
      echo "certify,$n,$var,time_ratio,$tr,$cr,$fnnz,$rss,$label" >>"$tmp"
    done
  done
}
envs=(MFS_BENCH=1)
certify_rows default
if [ -n "${BLAS_DIR:-}" ]; then
  envs=(LD_LIBRARY_PATH="$BLAS_DIR")
  certify_rows "$BLAS_DIR"
fi
# limit_kind, limit_s, fraction (docs/benchmarks.md; the limits of notebooks-data/bench_bandwidth.csv)
/usr/bin/python3 "$(dirname "$0")/limits.py" "$tmp" --rule bench_check || true
mv "$tmp" "$OUT"
echo "wrote $OUT" >&2
