#!/usr/bin/env bash
# MPI (docs/parallel.md): `mpirun -np N mfstab eigs|bound` against one process.
#   1. tests/test_peigs (the library: products through the halo exchange, the
#      bounds bit for bit, PARPACK against ARPACK, every status) on 1 and 2 ranks
#   2. mfstab eigs on 1 and 2 ranks against mfstab without mpirun: lambda_max
#      and what derives from it to 1e-10, every other column identical (the
#      bounds and masses bit for bit), apart from the Lanczos counts
#   3. mfstab bound on 1 and 2 ranks: the CSV identical byte for byte
#   4. what is not distributed: one line, exit 2, no output file; -o written
#      once, by rank 0, no temporary file left
#   5. allocation failures on 2 ranks (a sample): exit 1, one line, no file
# Skipped (exit 77) with a message where mpirun is missing or mfstab was
# built without MPI (then the library's stubs and the refusal of a launch on
# 2 ranks are still checked).
# usage: test_mpi.sh MFSTAB TEST_PEIGS HAVE_MPI(0|1)
set -u
M=${1:?usage: test_mpi.sh MFSTAB TEST_PEIGS HAVE_MPI}
TP=${2:?}
HAVE=${3:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$(cd "$(dirname "$0")/.." && pwd)
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

if [ "$HAVE" != 1 ]; then
  if "$TP" >"$tmp/tp.txt" 2>&1; then ok; else bad "test_peigs without MPI: $(tail -3 "$tmp/tp.txt")"; fi
  OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 "$M" eigs >"$tmp/o.csv" 2>"$tmp/e.txt"
  rc=$?
  if [ $rc -eq 2 ] && [ "$(wc -l <"$tmp/e.txt")" -eq 1 ] && grep -q 'built without MPI' "$tmp/e.txt" &&
     [ ! -s "$tmp/o.csv" ]; then ok; else bad "a launch on 2 ranks without MPI: rc $rc, $(cat "$tmp/e.txt")"; fi
  echo "test_mpi: $pass passed, $fail failed"
  [ $fail -eq 0 ] || exit 1
  echo "SKIP: mfstab was built without MPI (install libopenmpi-dev libparpack2-dev openmpi-bin and reconfigure)"
  exit 77
fi
if ! command -v mpirun >/dev/null 2>&1; then
  echo "SKIP: mpirun is missing (Debian: apt-get install openmpi-bin)"
  exit 77
fi
MR=(mpirun -q --oversubscribe)
[ "$(id -u)" -eq 0 ] && MR+=(--allow-run-as-root)

# 1. the library
for np in 1 2; do
  if "${MR[@]}" -np $np "$TP" >"$tmp/tp$np.txt" 2>&1; then
    ok
  else
    bad "test_peigs on $np rank(s):"
    grep -E 'FAIL|passed' "$tmp/tp$np.txt" | head -20
  fi
done

# compare A B: the eigs CSVs of one process (A) and of some ranks (B).
# Columns from lambda_max to 1e-10 relative; the Lanczos counts and the
# residual may differ; every other column identical.
compare_eigs() {
  /usr/bin/python3 - "$1" "$2" <<'EOF'
import csv, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
if len(a) != 1 or len(b) != 1 or list(a[0]) != list(b[0]):
    print("rows or columns differ"); sys.exit(1)
near = {"lambda_max_per_s2", "omega_max_rad_s", "dt_crit_s", "bound_ratio", "gershgorin_ratio"}
free = {"arpack_iterations", "arpack_matvecs", "arpack_residual"}
bad = []
for k in a[0]:
    x, y = a[0][k], b[0][k]
    if k in free:
        continue
    if k in near and (x or y):
        if not x or not y or abs(float(x) - float(y)) > 1e-10 * abs(float(x)):
            bad.append("%s %s vs %s" % (k, x, y))
    elif k not in near and x != y:
        bad.append("%s %s vs %s" % (k, x, y))
if b[0]["arpack_residual"] and float(b[0]["arpack_residual"]) > 1e-8:
    bad.append("arpack_residual %s" % b[0]["arpack_residual"])
if bad:
    print("; ".join(bad)); sys.exit(1)
EOF
}

# 2 and 3. the commands on models of every kind (the last: lumped masses <= 0, tests/test_cli.sh's)
printf 'x,volume\n2.8980211416829427,1\n3.5831232851661508,1\n3.758693438343573,1\n3.7813888591844877,0.001\n7.014895649611761,1\n7.053251366963367,1\n7.227225216560104,1\n7.960414989720876,0.001\n8.358171972261282,0.001\n9.305400074553292,0.001\n' >"$tmp/negmass.csv"
models=(
  "--nodes 61 --dilation 2.3 --quadrature gauss2"
  "--nodes 53 --fixed ends --kernel quartic --dilation 1.7"
  "--dim 2 --nodes 23,17 --quadrature stress-quad --physics plane-strain --poisson 0.3 --fixed boundary"
  "--dim 2 --nodes 16,14 --periodic --quadrature stress-tri --dilation 2.1"
  "--dim 2 --nodes 18,16 --perturb 0.2 --seed 7 --quadrature gauss2 --dilation 2.4"
  "--particles $root/analysis/particles/plate.csv --support 0.013 --fix clamp --young 2e9 --poisson 0.3 --density 1200 --physics plane-strain"
  "--particles $tmp/negmass.csv --support 3"
)
k=0
for args in "${models[@]}"; do
  k=$((k + 1))
  # shellcheck disable=SC2086
  "$M" eigs $args -o "$tmp/e0.csv" 2>"$tmp/ee0.txt" || bad "model $k: eigs in one process: $(cat "$tmp/ee0.txt")"
  # shellcheck disable=SC2086
  "$M" bound $args -o "$tmp/b0.csv" 2>"$tmp/eb0.txt" || bad "model $k: bound in one process: $(cat "$tmp/eb0.txt")"
  for np in 1 2; do
    # shellcheck disable=SC2086
    if ! "${MR[@]}" -np $np "$M" eigs $args -o "$tmp/e$np.csv" 2>"$tmp/err.txt"; then
      bad "model $k ($args): eigs on $np rank(s) failed: $(head -3 "$tmp/err.txt")"
    elif ! cmp -s "$tmp/ee0.txt" "$tmp/err.txt"; then
      bad "model $k ($args): eigs on $np rank(s) says '$(head -c 300 "$tmp/err.txt")', one process '$(head -c 300 "$tmp/ee0.txt")'"
    elif out=$(compare_eigs "$tmp/e0.csv" "$tmp/e$np.csv"); then
      ok
    else
      bad "model $k ($args): eigs on $np rank(s) against one process: $out"
    fi
    # shellcheck disable=SC2086
    if ! "${MR[@]}" -np $np "$M" bound $args -o "$tmp/b$np.csv" 2>"$tmp/err.txt"; then
      bad "model $k ($args): bound on $np rank(s) failed: $(head -3 "$tmp/err.txt")"
    elif cmp -s "$tmp/b0.csv" "$tmp/b$np.csv" && cmp -s "$tmp/eb0.txt" "$tmp/err.txt"; then
      ok
    else
      bad "model $k ($args): bound on $np rank(s) differs from one process:"
      diff <(tr , '\n' <"$tmp/b0.csv") <(tr , '\n' <"$tmp/b$np.csv") | head -8
    fi
  done
done

# 4. what is not distributed, and the output
refuse() { # refuse WHAT ARGS...: exit 2, one line naming WHAT, no output
  local what=$1
  shift
  rm -f "$tmp/r.csv"
  "${MR[@]}" -np 2 "$M" "$@" -o "$tmp/r.csv" >"$tmp/out.txt" 2>"$tmp/err.txt"
  local rc=$?
  if [ $rc -eq 2 ] && [ "$(wc -l <"$tmp/err.txt")" -eq 1 ] && grep -q -- "$what" "$tmp/err.txt" &&
     [ ! -e "$tmp/r.csv" ] && [ ! -s "$tmp/out.txt" ]; then
    ok
  else
    bad "mpirun -np 2 mfstab $*: rc $rc (want 2), stderr: $(head -3 "$tmp/err.txt")"
  fi
}
refuse "--zero-modes" eigs --zero-modes
refuse "--certify" eigs --certify
refuse "--certify" bound --certify
refuse "--mass consistent" eigs --mass consistent
refuse "--seeds" eigs --dim 2 --perturb 0.1 --seeds 3
refuse "only eigs and bound" stencil
refuse "--bogus" eigs --bogus
refuse "fewer ranks" eigs --nodes 3 --fixed ends
refuse "--dilation 0.6" eigs --dilation 0.6 --quadrature gauss2
# with one rank, what needs one process runs there
if "${MR[@]}" -np 1 "$M" eigs --zero-modes -o "$tmp/z1.csv" 2>"$tmp/err.txt" &&
   "$M" eigs --zero-modes -o "$tmp/z0.csv" && cmp -s "$tmp/z0.csv" "$tmp/z1.csv"; then
  ok
else
  bad "mpirun -np 1 mfstab eigs --zero-modes differs from one process: $(head -2 "$tmp/err.txt")"
fi
# standard output: one CSV, from rank 0; a file: no temporary left
"${MR[@]}" -np 2 "$M" eigs --nodes 41 >"$tmp/so.csv" 2>"$tmp/err.txt"
if [ "$(wc -l <"$tmp/so.csv")" -eq 2 ] && [ ! -s "$tmp/err.txt" ]; then ok; else
  bad "mpirun -np 2 mfstab eigs to stdout: $(wc -l <"$tmp/so.csv") lines (want 2), stderr $(head -2 "$tmp/err.txt")"; fi
mkdir "$tmp/d"
"${MR[@]}" -np 2 "$M" bound --nodes 41 -o "$tmp/d/b.csv" 2>"$tmp/err.txt"
if [ "$(ls -A "$tmp/d")" = b.csv ] && [ "$(wc -l <"$tmp/d/b.csv")" -eq 2 ]; then ok; else
  bad "mpirun -np 2 mfstab bound -o: the directory holds '$(ls -A "$tmp/d" | tr '\n' ' ')'"; fi
# 5. allocation failures on 2 ranks (tests/test_alloc.sh's rule, every allocation of a sample
# of about 8 spread over the run): exit 1, one line saying "out of memory", no file, no hang
sweep() {
  local what="mpirun -np 2 mfstab $*" K k rc n badk=0
  rm -rf "$tmp/af" "$tmp/count"
  mkdir "$tmp/af"
  "${MR[@]}" -np 2 -x MFSTAB_ALLOC_COUNT="$tmp/count" "$M" "$@" -o "$tmp/af/good.csv" 2>/dev/null
  K=$(cat "$tmp/count" 2>/dev/null || echo 0)
  rm -f "$tmp/af/good.csv"
  [ "$K" -gt 0 ] || { bad "$what: no allocation count"; return; }
  for ((k = 1; k <= K; k += (K + 7) / 8)); do
    timeout 60 "${MR[@]}" -np 2 -x MFSTAB_ALLOC_FAIL=$k "$M" "$@" -o "$tmp/af/o.csv" \
      >"$tmp/af.out" 2>"$tmp/af.err"
    rc=$?
    n=$(wc -l <"$tmp/af.err")
    if [ $rc -ne 1 ] || [ "$n" -ne 1 ] || ! grep -q "out of memory" "$tmp/af.err" ||
       [ -n "$(ls -A "$tmp/af")" ] || [ -s "$tmp/af.out" ]; then
      badk=$((badk + 1))
      [ $badk -le 3 ] && bad "$what: allocation $k of $K failing: exit $rc, $n lines: $(head -c 200 "$tmp/af.err" | tr '\n' '|') files: $(ls -A "$tmp/af" | tr '\n' ' ')"
      rm -f "$tmp/af/"*
    fi
  done
  [ $badk -eq 0 ] && ok
}
sweep eigs --dim 2 --nodes 12,10
sweep bound --dim 2 --nodes 12,10 --perturb 0.1

echo "test_mpi: $pass passed, $fail failed"
[ $fail -eq 0 ]
