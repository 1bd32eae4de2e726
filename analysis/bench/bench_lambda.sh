#!/usr/bin/env bash
# Benchmark (not a test; issue 14 item 4): lambda_max of 2D plane-strain models
# (bench_lambda.c: NX x NY nodes, cubic MLS, D = 2, stress-quad, lumped mass)
# by mfstab with 1 and 2 threads, by SciPy's eigsh on the same matrices (the
# same operator M^-1/2 K M^-1/2, start vector, ncv 20, which='LA', tol), and
# mfstab's certified step, REPS repetitions alternating; errors against a
# reference lambda_max (mfstab at tol 0, machine precision).
#
#   analysis/bench/bench_lambda.sh [BUILD_DIR] [SIDE...]
#     BUILD_DIR  meson build directory (default build) holding analysis/bench/bench_lambda
#     SIDE       square lattice sides (default 100 316: 10^4 and 10^5 nodes, 2 10^4 and
#                2 10^5 unknowns)
#   environment: REPS (default 5), TOL (default 1e-6), OUT (default
#   notebooks-data/bench_lambda.csv), CERTIFY (1: the certified step every
#   repetition, default 1), BEFORE (a second bench_lambda binary, e.g. of the
#   previous commit, run alternating with tool names mfstab-before (ARPACK) and
#   mfstab-lanczos-before (plain Lanczos)),
#   MFS_BENCH_GBS_1 / MFS_BENCH_GBS_2 (the bandwidth of 1 and 2 threads, GB/s;
#   default: analysis/bench/run.sh's notebooks-data/bench_bandwidth.csv if
#   present, else measured by each run), MFS_BENCH_GFLOPS (the certified
#   step's flop limit; default from bench_bandwidth.csv).
#
# CSV: bench_lambda.c's columns plus load_1min (of /proc/loadavg before the row);
# tool is mfstab (ARPACK, threads 1, 2), mfstab-lanczos (plain Lanczos,
# lib/analysis/mfs_lanczos.h, threads 1, 2: the solver of the step's questions;
# bytes_per_matvec = its own storage, 2 x 2 blocks), mfstab-certify, scipy (eigsh; op_s_per_matvec
# = its A @ x alone; bytes_per_matvec = CSR of A with int32 indices: 12 B per
# entry, 4 B per row pointer, x and y). The SciPy process runs with
# LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/openblas-serial: Debian's SciPy
# links libopenblas.so.0 (the pthread build by default), this makes it the
# serial OpenBLAS that mfstab's libblas.so.3 is (docs/parallel.md).
# OMP_WAIT_POLICY is passive unless set: what mfstab sets for itself (docs/parallel.md, Idle
# threads); with libgomp's default the 2-thread product lost up to 5 times on the loaded machine.
set -euo pipefail
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}

BUILD=${1:-build}
shift || true
SIDES=("$@")
[ ${#SIDES[@]} -eq 0 ] && SIDES=(100 316)
REPS=${REPS:-5}
TOL=${TOL:-1e-6}
CERTIFY=${CERTIFY:-1}
OUT=${OUT:-notebooks-data/bench_lambda.csv}
BL=${BENCH_LAMBDA:-$BUILD/analysis/bench/bench_lambda}
PY=/usr/bin/python3
SERIAL=/usr/lib/x86_64-linux-gnu/openblas-serial
[ -x "$BL" ] || { echo "bench_lambda.sh: $BL not found (build with meson first)" >&2; exit 2; }
$PY -c 'import scipy' 2>/dev/null || { echo "bench_lambda.sh: no SciPy for $PY" >&2; exit 2; }
bwcsv=notebooks-data/bench_bandwidth.csv
col() { # col THREADS COLUMN: from bench_bandwidth.csv (row kind=limit)
  [ -f "$bwcsv" ] || return 0
  awk -F, -v t="$1" -v c="$2" 'NR==1{for(i=1;i<=NF;i++)h[$i]=i;next}
    $h["kernel"]=="limit" && $h["threads"]==t {print $h[c]}' "$bwcsv"
}
GBS1=${MFS_BENCH_GBS_1:-$(col 1 gbs)}
GBS2=${MFS_BENCH_GBS_2:-$(col 2 gbs)}
export MFS_BENCH_GFLOPS=${MFS_BENCH_GFLOPS:-$(col 1 gflops)}
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_lambda.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$OUT")"
tmpout="$OUT.tmp.$$"
load() { cut -d' ' -f1 /proc/loadavg; }
hdr=$("$BL" 5 5 --header | head -1)
echo "$hdr,load_1min" > "$tmpout"
run_c() { # run_c BINARY TOOLNAME THREADS ARGS...: rows with the load appended
  local bin=$1 name=$2 t=$3 l gbs
  shift 3
  l=$(load)
  gbs=$GBS1
  [ "$t" = 2 ] && gbs=$GBS2
  MFS_BENCH_GBS=$gbs OMP_NUM_THREADS=$t "$bin" "$@" |
    sed -e "s/^mfstab,/$name,/" -e "s/^mfstab-lanczos,/$name,/" -e "s/\$/,$l/" >> "$tmpout"
}

for n in "${SIDES[@]}"; do
  echo "side $n: reference and export" >&2
  ref=$(OMP_NUM_THREADS=2 "$BL" "$n" "$n" --tol 0 | awk -F, '{print $13}')
  "$BL" "$n" "$n" --export "$work/m"
  # the matrices once in NumPy's format (Matrix Market parsing is slow)
  LD_LIBRARY_PATH=$SERIAL $PY - "$work/m" <<'EOF'
import sys
import numpy as np
import scipy.io
import scipy.sparse as sp
p = sys.argv[1]
K = scipy.io.mmread(p + "_K.mtx").tocsr()
M = scipy.io.mmread(p + "_M.mtx").tocsr()
s = 1.0 / np.sqrt(M.diagonal())
A = (sp.diags(s) @ K @ sp.diags(s)).tocsr()
A.sort_indices()
sp.save_npz(p + "_A.npz", A, compressed=False)
EOF
  rm -f "$work"/m_K.mtx "$work"/m_M.mtx
  for ((r = 1; r <= REPS; r++)); do
    for t in 1 2; do
      run_c "$BL" mfstab "$t" "$n" "$n" --tol "$TOL" --ref "$ref" --rep "$r"
      run_c "$BL" mfstab-lanczos "$t" "$n" "$n" --tol "$TOL" --ref "$ref" --rep "$r" --lanczos
      if [ -n "${BEFORE:-}" ]; then
        run_c "$BEFORE" mfstab-before "$t" "$n" "$n" --tol "$TOL" --ref "$ref" --rep "$r"
        run_c "$BEFORE" mfstab-lanczos-before "$t" "$n" "$n" --tol "$TOL" --ref "$ref" --rep "$r" \
          --lanczos
      fi
    done
    l=$(load)
    LD_LIBRARY_PATH=$SERIAL OMP_NUM_THREADS=1 $PY - "$work/m_A.npz" "$TOL" "$ref" "$r" "$n" "${GBS1:-0}" "$l" >> "$tmpout" <<'EOF'
import resource, sys, time
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, eigsh
path, tol, ref, rep, side, gbs, load = sys.argv[1:]
tol, ref, gbs = float(tol), float(ref), float(gbs)
A = sp.load_npz(path).tocsr()
n = A.shape[0]
# mfstab's start vector (splitmix64, lib/analysis/mfs_eigen.c)
g = np.uint64(0x9E3779B97F4A7C15)
with np.errstate(over="ignore"):
    z = g * (np.arange(n, dtype=np.uint64) + np.uint64(2))
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    z = z ^ (z >> np.uint64(31))
v0 = 2.0 * ((z >> np.uint64(11)).astype(np.float64) * 2.0**-53) - 1.0
cnt, top = [0], [0.0]
def mv(x):
    t = time.perf_counter()
    y = A @ x
    top[0] += time.perf_counter() - t
    cnt[0] += 1
    return y
op = LinearOperator(A.shape, matvec=mv, dtype=np.float64)
t = time.perf_counter()
w = eigsh(op, k=1, which="LA", tol=tol, ncv=20, v0=v0, return_eigenvectors=True)[0]
te = time.perf_counter() - t
lam, nmv = float(w[0]), cnt[0]
nnz = A.nnz
by = 12.0 * nnz + 4.0 * (n + 1) + 16.0 * n
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
if gbs > 0:
    lim = nmv * by / (gbs * 1e9)
    lims = f"{gbs:.2f},,{lim:.6g},{lim / te:.4f},{lim / top[0]:.4f}"
else:
    lims = ",,,,"
print(f"scipy,{rep},{int(side) ** 2},{n},{nnz},1,{tol:g},,{te:.4f},{nmv},{te / nmv:.6g},"
      f"{top[0] / nmv:.6g},{lam:.15g},{abs(lam - ref) / ref:.3g},,,bytes,{by:.0f},{lims},{peak:.1f},,,{load}")
EOF
    if [ "$CERTIFY" = 1 ]; then
      l=$(load)
      MFS_BENCH_GBS=$GBS1 OMP_NUM_THREADS=1 "$BL" "$n" "$n" --tol "$TOL" --ref "$ref" --rep "$r" \
        --certify | grep '^mfstab-certify,' | sed -e "s/\$/,$l/" >> "$tmpout"
    fi
    echo "side $n: repetition $r done" >&2
  done
  rm -f "$work"/m_A.npz
done
mv "$tmpout" "$OUT"
echo "wrote $OUT" >&2
