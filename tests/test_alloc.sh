#!/usr/bin/env bash
# Allocation-failure test (issue 12): every allocation that a command makes
# through the library's allocator (lib/core/mfs_alloc.h; the program's own and
# CHOLMOD's included) fails in turn, MFSTAB_ALLOC_FAIL=k for k = 1 .. K (K
# counted by MFSTAB_ALLOC_COUNT on a good run).  Each must end in exit 1 with
# one line on stderr that says "out of memory", no output file and no
# temporary file; or, where the code has a way around the failure (CHOLMOD
# keeps a block whose shrinking realloc fails, and tries another ordering when
# AMD's memory fails), in exit 0 with the output of the good run (every field
# equal, numbers to 1e-9 relative: another ordering rounds differently).
# Under ASan (the sanitizer build of scripts/test.sh) also without a leak.
# To see where allocation k is made: MFSTAB_ALLOC_FAIL=k MFSTAB_ALLOC_ABORT=1
# under gdb.
# usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir
set -u
M=${1:?usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir}
S=${2:?usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }
# same_csv A B: the same fields, numbers equal to 1e-9 relative
same_csv() {
  awk -F, 'NR == FNR { a[FNR] = $0; n = FNR; next }
    { if (!(FNR in a)) exit 1; k = split(a[FNR], x, ","); if (k != NF) exit 1
      for (i = 1; i <= NF; i++) if (x[i] != $i) {
        if (x[i] !~ /^[-+0-9.eE]+$/ || $i !~ /^[-+0-9.eE]+$/) exit 1
        d = x[i] - $i; m = (x[i] < 0 ? -x[i] : x[i]); if (d < 0) d = -d
        if (d > 1e-9 * m) exit 1 } m2 = FNR }
    END { exit !(m2 == n) }' "$1" "$2"
}

# every_allocation ARGS...: the loop over k for one command line
every_allocation() {
  local what="mfstab $*" o=$tmp/out/res.csv
  mkdir -p "$tmp/out"
  rm -f "$tmp/count"
  if ! MFSTAB_ALLOC_COUNT=$tmp/count "$M" "$@" -o "$o" >/dev/null 2>"$tmp/err"; then
    ko "$what: the good run failed: $(head -c 200 "$tmp/err")"
    return
  fi
  local K bad=0 k rc recovered=0
  K=$(cat "$tmp/count")
  mv "$o" "$tmp/good.csv"
  for ((k = 1; k <= K; k++)); do
    MFSTAB_ALLOC_FAIL=$k "$M" "$@" -o "$o" >"$tmp/stdout" 2>"$tmp/err"
    rc=$?
    local n
    n=$(wc -l <"$tmp/err" | tr -d ' ')
    if [ "$rc" -eq 0 ] && [ ! -s "$tmp/err" ] && same_csv "$tmp/good.csv" "$o"; then
      recovered=$((recovered + 1)) # a way around it, and the same result
      rm -f "$o"
      continue
    fi
    if [ "$rc" -ne 1 ] || [ "$n" -ne 1 ] || ! grep -q "out of memory" "$tmp/err" ||
       [ -e "$o" ] || [ -s "$tmp/stdout" ] || compgen -G "$tmp/out/*.tmp*" >/dev/null; then
      [ "$bad" -lt 3 ] && ko "$what: allocation $k of $K failing: exit $rc, $n lines: $(head -c 300 "$tmp/err" | tr '\n' '|')$([ -e "$o" ] && echo ' (an output file)')"
      bad=$((bad + 1))
      rm -f "$o" "$tmp/out/"*.tmp*
    fi
  done
  if [ "$bad" -eq 0 ]; then
    pass=$((pass + 1))
    echo "ok: $what: each of its $K allocations failing ends in exit 1, out of memory ($recovered recovered with the same output)"
  else
    echo "     ($bad of $K failed)"
  fi
}

every_allocation stencil
every_allocation stencil --dim 2 --quadrature stress-tri
every_allocation dispersion --points 11
every_allocation dispersion --dim 2 --quadrature gauss2 --points 5 --classify
every_allocation eigs --nodes 20 --zero-modes
every_allocation eigs --dim 2 --nodes 6,6 --zero-modes --physics plane-strain
every_allocation bound --nodes 20
every_allocation run "$S/gaussian-pulse.ini" --set model.nodes=30
every_allocation run "$S/plate-pulse-2d.ini" --set model.nodes=8 --set model.nodes_y=6 --set time.end=1e-5
every_allocation run "$S/tsph-elastic-bar.ini" --set model.nodes=30

echo "test_alloc: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
