#!/usr/bin/env bash
# Benchmark (not a test) of issue 15, into notebooks-data/bench_check.csv:
#  1. a 2D particle file of 10^6 particles (a 1000 x 1000 lattice of the unit
#     square perturbed by 20%, with its volumes): read, plan and dt_gershgorin,
#     phase by phase (bench_check gershgorin), and the whole command
#     'mfstab bound --particles FILE --support 0.002' (which also computes the
#     element bound and the Fourier estimate) with its wall time and peak memory
#     (/usr/bin/time), REPS times, the two alternating; the same file without
#     volumes (Qhull's triangulation gives them: 20-40 s) once, with DELAUNAY=1;
#  2. dt_certified against lambda_max by ARPACK on the same model at 10^4 and
#     10^5 particles (bench_check certify, both in one process), REPS times,
#     the order of the two alternating from one repetition to the next: the
#     perturbed lattice with nodal integration and the lattice with 2 x 2 Gauss
#     cells, lumped mass; and the perturbed lattice with consistent mass.
# BASE_BUILD=DIR (a build of an earlier commit) runs its bench_check and mfstab on the
# same files in the same repetitions, alternating with this build, labelled blas=base
# (its bench_check has no per-phase CPU and runs ARPACK first).
# One core: the library is single-threaded here, OMP_NUM_THREADS=1 keeps CHOLMOD and
# OpenBLAS on one thread.  THREADS2=1 (the default) runs the certification rows at
# 10^5 again with OMP_NUM_THREADS=2 OPENBLAS_NUM_THREADS=2 (both ARPACK and the
# certification, threads = 2).  BLAS_DIR=DIR runs the certification rows again with
# LD_LIBRARY_PATH=DIR, labelled blas=DIR.
#   analysis/bench/bench_check.sh [BUILD_DIR]      (default: build; REPS=5)
# CSV: job,particles,variant,phase,stat,seconds,cpu_seconds,value,peak_rss_mb,blas,load_1min,
#      gflop,threads
#   stat: rep1..repN (one repetition; load_1min: /proc/loadavg's first field before it) or
#   min, median, max over the repetitions (of seconds, cpu_seconds and value separately;
#   load_1min then the median of the repetitions').
#   seconds: wall clock; cpu_seconds: user + system CPU time;
#   value: particles total and mfstab_bound: dt_gershgorin (s); certify arpack_lambda_max:
#   lambda_max (1/s^2); factorizations: their count; dt_certified: dt_certified/dt_crit;
#   time_ratio: seconds = certify / arpack (wall), cpu_seconds the same in CPU time,
#   value the entries of the factor.  peak_rss_mb: the process's peak.
#   gflop: factorizations: the flops of all of them (10^9; CHOLMOD's count), the work
#   that analysis/bench/limits.py states against the dgemm rate.
#   certify phases: assembly, arpack_lambda_max, lanczos (the estimate, at bench_check's
#   --est-tol, mfstab bound --certify's 1e-3), factorizations (all that follows the
#   estimate), and within it order (the geometric nested dissection), analysis
#   (the symbolic analysis and the permuted pattern, value: supernodes) and numeric
#   (the numeric factorizations, forming sigma M - K included); dt_certified, time_ratio.
#   threads: OMP_NUM_THREADS of the row (ARPACK and the certification alike).
set -euo pipefail
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
BUILD=${1:-build}
REPS=${REPS:-5}
B=$BUILD/analysis/bench/bench_check
M=$BUILD/tools/mfstab
OUT=${OUT:-notebooks-data/bench_check.csv}
for b in "$B" "$M"; do
  [ -x "$b" ] || { echo "bench_check.sh: $b not found (build first)" >&2; exit 2; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_check.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$OUT")"
tmp="$work/raw.csv"
echo "job,particles,variant,phase,stat,seconds,cpu_seconds,value,peak_rss_mb,blas,load_1min,gflop,threads" >"$tmp"
load() { cut -d' ' -f1 /proc/loadavg; }

# 1. 10^6 particles
"$B" gen 1000 "$work/p.csv"
particles_rep() { # FILE VARIANT REP [BENCH MFSTAB LABEL]
  local f=$1 variant=$2 r=$3 b=${4:-$B} mf=${5:-$M} label=${6:-default} ld
  ld=$(load)
  row=$("$b" gershgorin "$f" 0.002)
  IFS=, read -r _ n _ rd geo pl ge tot cpu lam dt rss crd cgeo cpl cge <<<"$row"
  for ph in read:$rd:$crd geometry:$geo:$cgeo plan:$pl:$cpl gershgorin:$ge:$cge; do
    IFS=: read -r name s c <<<"$ph"
    echo "particles,$n,$variant,$name,rep$r,$s,$c,,$rss,$label,$ld" >>"$tmp"
  done
  echo "particles,$n,$variant,total,rep$r,$tot,$cpu,$dt,$rss,$label,$ld" >>"$tmp"
  ld=$(load)
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$mf" bound --particles "$f" \
    --support 0.002 -o "$work/bound.csv"
  read -r wall us ss kb <"$work/time"
  dtg=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i } NR == 2 { print $h["dt_gershgorin_s"] }' "$work/bound.csv")
  echo "particles,$n,$variant,mfstab_bound,rep$r,$wall,$(awk -v a="$us" -v b="$ss" 'BEGIN { print a + b }'),$dtg,$(awk -v k="$kb" 'BEGIN { printf "%.1f", k / 1024 }'),$label,$ld" >>"$tmp"
}
BB=${BASE_BUILD:+$BASE_BUILD/analysis/bench/bench_check}
BM=${BASE_BUILD:+$BASE_BUILD/tools/mfstab}
for r in $(seq 1 "$REPS"); do
  if [ -n "$BB" ] && [ $((r % 2)) = 0 ]; then particles_rep "$work/p.csv" volumes "$r" "$BB" "$BM" base; fi
  particles_rep "$work/p.csv" volumes "$r"
  if [ -n "$BB" ] && [ $((r % 2)) = 1 ]; then particles_rep "$work/p.csv" volumes "$r" "$BB" "$BM" base; fi
done
if [ "${DELAUNAY:-0}" = 1 ]; then
  "$B" gen 1000 "$work/pn.csv" --novol
  particles_rep "$work/pn.csv" delaunay 1
fi

# 2. dt_certified against ARPACK, alternating which runs first
certify_one() { # BENCH LABEL SIDE REP QUAD PERTURB MASS [--certify-first]
  local b=$1 label=$2 side=$3 r=$4 ld row var st
  ld=$(load)
  row=$(env "${envs[@]}" "$b" certify "$side" --quadrature "$5" --perturb "$6" --mass "$7" ${8:-})
  IFS=, read -r _ n mass q asm ars mv lam cs ls fs nf fnnz gf sig frac tr cr rss acpu ccpu cf \
    os as ns nsup _ <<<"$row"
  var="$q-perturb$6-$7"
  st="rep$r"
  local th=${threads:-1}
  echo "certify,$n,$var,assembly,$st,$asm,,,$rss,$label,$ld,,$th" >>"$tmp"
  echo "certify,$n,$var,arpack_lambda_max,$st,$ars,${acpu:-},$lam,$rss,$label,$ld,,$th" >>"$tmp"
  echo "certify,$n,$var,lanczos,$st,$ls,,,$rss,$label,$ld,,$th" >>"$tmp"
  echo "certify,$n,$var,factorizations,$st,$fs,,$nf,$rss,$label,$ld,$(awk -v a="$nf" -v b="$gf" 'BEGIN { print a * b }'),$th" >>"$tmp"
  if [ -n "${ns:-}" ]; then
    echo "certify,$n,$var,order,$st,$os,,,$rss,$label,$ld,,$th" >>"$tmp"
    echo "certify,$n,$var,analysis,$st,$as,,$nsup,$rss,$label,$ld,,$th" >>"$tmp"
    echo "certify,$n,$var,numeric,$st,$ns,,$nf,$rss,$label,$ld,$(awk -v a="$nf" -v b="$gf" 'BEGIN { print a * b }'),$th" >>"$tmp"
  fi
  echo "certify,$n,$var,dt_certified,$st,$cs,${ccpu:-},$frac,$rss,$label,$ld,,$th" >>"$tmp"
  echo "certify,$n,$var,time_ratio,$st,$tr,$cr,$fnnz,$rss,$label,$ld,,$th" >>"$tmp"
}
certify_rows() { # LABEL [SIDES]
  local label=$1
  for side in ${2:-100 316}; do
    for r in $(seq 1 "$REPS"); do
      first=$([ $((r % 2)) = 0 ] && echo --certify-first || true)
      for v in "nodal 0.2 lumped" "gauss2 0 lumped" "nodal 0.2 consistent"; do
        set -- $v
        if [ -n "$BB" ] && [ "$side" = 316 ] && [ $((r % 2)) = 0 ]; then
          certify_one "$BB" base $side $r $1 $2 $3
        fi
        certify_one "$B" "$label" $side $r $1 $2 $3 $first
        if [ -n "$BB" ] && [ "$side" = 316 ] && [ $((r % 2)) = 1 ]; then
          certify_one "$BB" base $side $r $1 $2 $3
        fi
      done
    done
  done
}
envs=(MFS_BENCH=1)
threads=1
certify_rows default
if [ "${THREADS2:-1}" = 1 ]; then
  envs=(MFS_BENCH=1 OMP_NUM_THREADS=2 OPENBLAS_NUM_THREADS=2)
  threads=2
  BB0=$BB
  BB=
  certify_rows default 316
  BB=$BB0
  envs=(MFS_BENCH=1)
  threads=1
fi
if [ -n "${BLAS_DIR:-}" ]; then
  envs=(LD_LIBRARY_PATH="$BLAS_DIR")
  BB=
  certify_rows "$BLAS_DIR"
fi

# the repetitions, then min / median / max of each column over them
/usr/bin/python3 - "$tmp" "$OUT.tmp.$$" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["job", "particles", "variant", "phase", "stat", "seconds", "cpu_seconds", "value",
        "peak_rss_mb", "blas", "load_1min", "gflop", "threads"]
groups = {}
for r in rows:
    groups.setdefault((r["job"], r["particles"], r["variant"], r["phase"], r["blas"],
                       r.get("threads") or ""), []).append(r)
with open(sys.argv[2], "w", newline="") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(cols)
    for key, g in groups.items():
        for r in g:
            w.writerow([r.get(c) or "" for c in cols])
        if len(g) < 2:
            continue
        def col(c):
            v = [float(r[c]) for r in g if r.get(c)]
            return v
        for stat, fn in (("min", min), ("median", statistics.median), ("max", max)):
            out = dict(zip(["job", "particles", "variant", "phase"], key[:4]))
            out["stat"], out["blas"], out["threads"] = stat, key[4], key[5]
            for c in ("seconds", "cpu_seconds", "value", "peak_rss_mb", "gflop"):
                v = col(c)
                out[c] = "%.10g" % fn(v) if v else ""
            out["load_1min"] = "%.2f" % statistics.median(col("load_1min"))
            w.writerow([out[c] for c in cols])
EOF
# limit_kind, limit_s, fraction (docs/benchmarks.md; the limits of notebooks-data/bench_bandwidth.csv)
/usr/bin/python3 "$(dirname "$0")/limits.py" "$OUT.tmp.$$" --rule bench_check || true
mv "$OUT.tmp.$$" "$OUT"
echo "wrote $OUT" >&2
