#!/usr/bin/env bash
# Benchmark (not a test): lambda_max (ARPACK, analysis/bench/bench_eigs: the 2D
# anti-plane model, cubic MLS, D = 2, gauss2, lumped mass on an N x N lattice)
# with each BLAS/LAPACK that Debian installs side by side: the reference
# (libblas3, liblapack3) and OpenBLAS's serial, pthread and openmp builds
# (libopenblas0-serial, -pthread, -openmp).  The same binary; the library is
# chosen at load time by LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/openblas-VARIANT
# (what `update-alternatives` does for the whole system, docs/parallel.md).
# The runs of the variants alternate (run 1 of each, then run 2, ...), so that
# a change of the machine's load falls on all of them alike.
#
#   analysis/bench/bench_blas.sh [BUILD_DIR] [SIDE]   (default build, 250)
#   environment: REPS (default 5), OUT (default notebooks-data/bench_blas.csv),
#   OMP_NUM_THREADS (passed on; the pthread/openmp OpenBLAS use it too)
#
# CSV, one row per run: blas,run,nodes,dofs,nnz_K,eig_s,matvecs,lambda_max,
#   load_1min (the machine's load average when the run started), then one row
#   per variant with run = min, median, max of eig_s and ratio_to_reference
#   (the reference's statistic / the variant's: > 1 is faster), lambda_max the
#   largest relative difference from the reference's.
set -euo pipefail
BUILD=${1:-build}
SIDE=${2:-250}
REPS=${REPS:-5}
OUT=${OUT:-notebooks-data/bench_blas.csv}
B="$BUILD/analysis/bench/bench_eigs"
[ -x "$B" ] || { echo "bench_blas: $B not built" >&2; exit 2; }
LIB=/usr/lib/x86_64-linux-gnu
variants=(reference)
for v in serial pthread openmp; do
  [ -e "$LIB/openblas-$v/libblas.so.3" ] && variants+=("openblas-$v")
done
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
echo "blas,run,nodes,dofs,nnz_K,eig_s,matvecs,lambda_max,load_1min,ratio_to_reference" >"$tmp"
for r in $(seq 1 "$REPS"); do
  for v in "${variants[@]}"; do
    L=""
    [ "$v" = reference ] || L="$LIB/$v"
    load=$(cut -d' ' -f1 /proc/loadavg)
    # bench_eigs: tool,nodes,dofs,nnz_K,setup_s,bound_s,eig_s,iterations,matvecs,lambda_max,...
    LD_LIBRARY_PATH="$L" "$B" "$SIDE" |
      awk -F, -v v="$v" -v r="$r" -v load="$load" \
        '{ print v "," r "," $2 "," $3 "," $4 "," $7 "," $9 "," $10 "," load "," }' >>"$tmp"
  done
done
/usr/bin/python3 - "$tmp" "$OUT" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
by = {}
for r in rows:
    by.setdefault(r["blas"], []).append(r)
ref = by["reference"]
lref = float(ref[0]["lambda_max"])
stat = {}
for v, rs in by.items():
    t = sorted(float(r["eig_s"]) for r in rs)
    stat[v] = {"min": t[0], "median": statistics.median(t), "max": t[-1]}
out = list(rows)
for v, rs in by.items():
    dl = max(abs(float(r["lambda_max"]) - lref) / lref for r in rs)
    loads = [float(r["load_1min"]) for r in rs]
    for k in ("min", "median", "max"):
        out.append({**rs[0], "run": k, "eig_s": "%.4f" % stat[v][k], "lambda_max": "%.3g" % dl,
                    "load_1min": "%.2f" % statistics.median(loads),
                    "ratio_to_reference": "%.3f" % (stat["reference"][k] / stat[v][k])})
with open(sys.argv[2], "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader()
    w.writerows(out)
for v in by:
    print("%-17s eig_s min %.3f median %.3f max %.3f  reference/this (median) %.2f" %
          (v, stat[v]["min"], stat[v]["median"], stat[v]["max"],
           stat["reference"]["median"] / stat[v]["median"]))
PY
# limit_kind, limit_s, fraction (docs/benchmarks.md; the limits of notebooks-data/bench_bandwidth.csv)
/usr/bin/python3 "$(dirname "$0")/limits.py" "$OUT" --rule bench_blas || true
