#!/usr/bin/env bash
# Finite models and the solvers in parallel (issue 14): the same file, byte for
# byte, with OMP_NUM_THREADS=1, 2 and 3.  The assembly computes every row (and
# the plan's table every point) on one thread in the serial order, the element
# bound and the Gershgorin pass combine their per-row values in the serial
# order with the serial ties; lambda_max's product runs on the threads by a
# fixed number of row blocks (lib/analysis/mfs_eigen.c, sym_csr: the same
# sums for any thread count; plain Lanczos, lib/analysis/mfs_lanczos.c, the same
# way), ARPACK's iteration and the solvers' force loops
# are serial, so lambda_max (eigs), the bounds (bound), the check
# report and the time-domain runs come out the same bits: no column needs the
# 1e-12 tolerance.  Files and, for check, its report on stdout.  Skipped (77)
# without OpenMP.
# usage: bash tests/test_threads_models.sh /path/to/mfstab /path/to/source
set -u
M=${1:?usage: bash tests/test_threads_models.sh /path/to/mfstab /path/to/source}
S=${2:?usage: bash tests/test_threads_models.sh /path/to/mfstab /path/to/source}
if ! ldd "$M" 2>/dev/null | grep -q 'libgomp'; then
  echo "SKIP: $M is built without OpenMP (libgomp)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
same() { # same NAME ARGS...: the output file and stdout with 1, 2 and 3 threads
  local name=$1 n
  shift
  for n in 1 2 3; do
    if ! (cd "$S" && OMP_NUM_THREADS=$n "$M" "$@" -o "$tmp/$name.$n.csv" >"$tmp/$name.$n.out" \
      2>"$tmp/err"); then
      fail=$((fail + 1))
      echo "FAIL: $name with $n threads: exit $? $(head -c 200 "$tmp/err")"
      return
    fi
  done
  local rows
  rows=$(($(grep -vc '^#' "$tmp/$name.1.csv") - 1))
  for n in 2 3; do
    local f
    for f in csv out; do
      if ! cmp -s "$tmp/$name.1.$f" "$tmp/$name.$n.$f"; then
        fail=$((fail + 1))
        echo "FAIL: $name: $f with $n threads differs from 1: $(cmp "$tmp/$name.1.$f" "$tmp/$name.$n.$f" | head -1)"
        diff "$tmp/$name.1.$f" "$tmp/$name.$n.$f" | head -4 | cut -c1-300
        return
      fi
    done
  done
  if [ "$rows" -lt 1 ]; then
    fail=$((fail + 1))
    echo "FAIL: $name: no rows"
    return
  fi
  pass=$((pass + 1))
  echo "ok: $name: $rows rows, the same bytes with 1, 2 and 3 threads"
}
# lambda_max (ARPACK), the element bound, Gershgorin, the zero modes (CHOLMOD)
same eigs-1d eigs --nodes 41 --length 1 --quadrature gauss2 --dilation 2
same eigs-2d-seeds eigs --dim 2 --nodes 21,21 --perturb 0.3 --seeds 3 --zero-modes
same eigs-plane-strain eigs --dim 2 --nodes 25,25 --physics plane-strain --quadrature stress-quad \
  --dilation 2.5
# a model whose lambda_max product runs on the threads (2.6e6 stored entries of the upper
# triangle, above lib/analysis/mfs_eigen.c's SYM_PARALLEL_MIN = 2^21)
same eigs-parallel-product eigs --dim 2 --nodes 190,190 --physics plane-strain \
  --quadrature stress-quad
# bound --certify: its estimate by plain Lanczos (lib/analysis/mfs_lanczos.c) on the same model,
# the product and the vector passes on the threads (the same 8 row blocks), then the factorization
same bound-certify-parallel bound --dim 2 --nodes 190,190 --physics plane-strain \
  --quadrature stress-quad --certify
# the bounds alone (streamed)
same bound-2d bound --dim 2 --nodes 61,61 --physics plane-strain
same bound-tri bound --dim 2 --nodes 41,41 --quadrature stress-tri --perturb 0.2
# the report on the user's particles
same check-plate check --particles analysis/particles/plate.csv --fix clamp \
  --smoothing-length 0.0065 --convention sphinxsys --physics plane-strain --young 2e9 \
  --poisson 0.3 --density 1200
# the time-domain solvers (their step from the model's stable step)
same run-rod run analysis/scenes/rod-tensile.ini --set discretization.frame=lagrangian \
  --set time.end=1e-5
same run-plate run analysis/scenes/plate-tensile-2d.ini --set time.end=8e-7
echo "test_threads_models: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
