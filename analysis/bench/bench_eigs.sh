#!/usr/bin/env bash
# Benchmark (not a test): lambda_max of the 2D anti-plane model (N x N nodes
# on the unit square, cubic MLS, D = 2, gauss2, lumped mass) by mfstab
# (ARPACK mode 1 on M^-1/2 K M^-1/2), against SciPy's eigsh (the same ARPACK
# algorithm, same operator, same start vector, ncv and tol) on the matrices
# mfstab exports in Matrix Market format; and the streaming element bound
# (library call and the `mfstab bound` command, which must take <= 1 s at
# 10^6 nodes).
#
#   analysis/bench/bench_eigs.sh [BUILD_DIR] [SIDES...]
#     BUILD_DIR  meson build directory (default: build), holding
#                analysis/bench/bench_eigs and tools/mfstab
#     SIDES      lattice sides (default: 100 316 1000, i.e. 10^4, 10^5, 10^6 nodes)
#   environment: REPS (repetitions of the timed eigenvalue runs, the minimum is
#   kept; default 1), SCIPY_MAX_SIDE (largest side given to SciPy; default
#   1000), TMPDIR (where the Matrix Market files go), OUT (default
#   notebooks-data/bench_eigs.csv), NCV (default 20), TOL (default 1e-10),
#   BENCH_EIGS / MFSTAB (override the binaries).
#
# CSV: tool,phase,nodes,dofs,nnz_K,seconds,arpack_iterations,matvecs,
#      lambda_max,error,peak_rss_mb,ncv,tol,op_bytes
#   op_bytes: mfstab eigs: the bytes one product of its stored operator reads and
#   writes (mfs_eig_info.op_bytes, the limit's bytes); empty otherwise.
#   error: mfstab eigs: ||K v - lambda M v|| / (lambda ||M v||); scipy eigsh:
#   |lambda_scipy - lambda_mfstab| / lambda_mfstab; empty otherwise.
#   peak_rss_mb: peak resident memory of the process (mfstab: model assembly
#   included; scipy: loading included).
# Python: /usr/bin/python3 with Debian's python3-scipy (apt-get install -y python3-scipy).
set -euo pipefail

BUILD=${1:-build}
shift || true
SIDES=("$@")
[ ${#SIDES[@]} -eq 0 ] && SIDES=(100 316 1000)
REPS=${REPS:-1}
SCIPY_MAX_SIDE=${SCIPY_MAX_SIDE:-1000}
NCV=${NCV:-20}
TOL=${TOL:-1e-10}
OUT=${OUT:-notebooks-data/bench_eigs.csv}
BENCH_EIGS=${BENCH_EIGS:-$BUILD/analysis/bench/bench_eigs}
MFSTAB=${MFSTAB:-$BUILD/tools/mfstab}
PY=/usr/bin/python3
for b in "$BENCH_EIGS" "$MFSTAB"; do
  [ -x "$b" ] || { echo "bench_eigs.sh: $b not found (build with meson first)" >&2; exit 2; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/bench_eigs.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$OUT")"
tmpout="$OUT.tmp.$$"
echo "tool,phase,nodes,dofs,nnz_K,seconds,arpack_iterations,matvecs,lambda_max,error,peak_rss_mb,ncv,tol,op_bytes" > "$tmpout"

have_scipy=1
$PY -c 'import scipy' 2>/dev/null || { have_scipy=0; echo "bench_eigs.sh: no SciPy for $PY; skipping it" >&2; }

for n in "${SIDES[@]}"; do
  nodes=$((n * n))
  # mfstab: REPS runs, keep the fastest eigenvalue time
  best=""
  for ((r = 0; r < REPS; r++)); do
    row=$("$BENCH_EIGS" "$n" --ncv "$NCV" --tol "$TOL")
    if [ -z "$best" ] || awk -F, -v a="$row" -v b="$best" 'BEGIN{split(a,x,",");split(b,y,",");exit !(x[7]<y[7])}'; then
      best=$row
    fi
  done
  IFS=, read -r _ _ dofs nnz setup bound_s eig_s iters mv lam bound resid peak opb <<< "$best"
  echo "mfstab,setup,$nodes,$dofs,$nnz,$setup,,,,,$peak,,," >> "$tmpout"
  echo "mfstab,eigs,$nodes,$dofs,$nnz,$eig_s,$iters,$mv,$lam,$resid,$peak,$NCV,$TOL,$opb" >> "$tmpout"
  echo "mfstab,bound-library,$nodes,$dofs,$nnz,$bound_s,,,$bound,,,,," >> "$tmpout"
  # the command, wall clock and peak memory of the whole process
  t=$( { /usr/bin/time -f "%e %M" "$MFSTAB" bound --dim 2 --nodes "$n,$n" --kernel cubic \
         --shape mls --dilation 2 --quadrature gauss2 -o "$work/bound.csv" ; } 2>&1 | tail -1 )
  echo "mfstab,bound-command,$nodes,$dofs,$nnz,${t% *},,,,,$(awk -v k="${t#* }" 'BEGIN{printf "%.1f", k/1024}'),,," >> "$tmpout"
  echo "side $n: mfstab eigs ${eig_s} s ($iters iterations, $mv products), bound ${bound_s} s, command ${t% *} s" >&2

  if [ "$have_scipy" = 1 ] && [ "$n" -le "$SCIPY_MAX_SIDE" ]; then
    "$BENCH_EIGS" "$n" --ncv "$NCV" --tol "$TOL" --export "$work/m" > /dev/null
    $PY - "$work/m" "$TOL" "$NCV" "$lam" "$nodes" "$nnz" "$REPS" >> "$tmpout" <<'EOF'
import resource, sys, time
import numpy as np
import scipy.io
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, eigsh

prefix, tol, ncv, lam_ref, nodes, nnz, reps = sys.argv[1:]
tol, ncv, lam_ref, reps = float(tol), int(ncv), float(lam_ref), int(reps)
t = time.perf_counter()
K = scipy.io.mmread(prefix + "_K.mtx").tocsr()
M = scipy.io.mmread(prefix + "_M.mtx").tocsr()
t_load = time.perf_counter() - t
n = K.shape[0]
s = 1.0 / np.sqrt(M.diagonal())
S = sp.diags(s)
A = (S @ K @ S).tocsr()  # the operator mfstab uses
A.sort_indices()
# mfstab's start vector (splitmix64, lib/mfs_eigen.c), so both runs are the same iteration
g = np.uint64(0x9E3779B97F4A7C15)
with np.errstate(over="ignore"):
    z = g * (np.arange(n, dtype=np.uint64) + np.uint64(2))
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    z = z ^ (z >> np.uint64(31))
v0 = 2.0 * ((z >> np.uint64(11)).astype(np.float64) * 2.0**-53) - 1.0
best = None
for _ in range(reps):
    cnt = [0]
    def mv(x):
        cnt[0] += 1
        return A @ x
    op = LinearOperator(A.shape, matvec=mv, dtype=np.float64)
    t = time.perf_counter()
    w = eigsh(op, k=1, which="LA", tol=tol, ncv=ncv, v0=v0, return_eigenvectors=False)
    te = time.perf_counter() - t
    if best is None or te < best[0]:
        best = (te, cnt[0], w[0])
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
te, nmv, lam = best
print(f"scipy,load,{nodes},{n},{nnz},{t_load:.4f},,,,,{peak:.1f},,,")
print(f"scipy,eigsh,{nodes},{n},{nnz},{te:.4f},,{nmv},{lam:.12g},{abs(lam - lam_ref) / lam_ref:.3g},{peak:.1f},{ncv},{tol:g},")
print(f"side: scipy eigsh {te:.3f} s ({nmv} products), load {t_load:.1f} s", file=sys.stderr)
EOF
    rm -f "$work"/m_K.mtx "$work"/m_M.mtx
  fi
done
# limit_kind, limit_s, fraction (docs/benchmarks.md; the limits of notebooks-data/bench_bandwidth.csv)
/usr/bin/python3 "$(dirname "$0")/limits.py" "$tmpout" --rule bench_eigs || true
mv "$tmpout" "$OUT"
echo "wrote $OUT" >&2
