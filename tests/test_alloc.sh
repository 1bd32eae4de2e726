#!/usr/bin/env bash
# Allocation-failure test (issue 12): every allocation that a command makes
# through the library's allocator (lib/core/mfs_alloc.h; the program's own and
# CHOLMOD's and UMFPACK's included) fails in turn, MFSTAB_ALLOC_FAIL=k for
# k = 1 .. K (K counted by MFSTAB_ALLOC_COUNT on a good run).  Each must end
# in exit 1 with one line on stderr that says "out of memory", nothing on
# standard output, and no file at all in the output directory (the -o file,
# the --write-modes files, a temporary file); or, where the code has a way
# around the failure (CHOLMOD keeps a block whose shrinking realloc fails, and
# tries another ordering when AMD's memory fails), in exit 0 with the output
# of the good run: the same files and standard output, every field equal or,
# for numbers, equal to 1e-9 of the largest magnitude in its column (another
# ordering rounds differently, and a value that is zero but for round-off
# differs in every digit).
# Not hooked, so not tested here: Qhull's own allocations (the Delaunay
# triangulation of a particle file without a volume column: libqhull_r
# allocates through the C library; the library checks its exit code, and its
# memory errors are MFS_ENOMEM), GSL's inside gsl_rng_alloc and the
# Gauss-Legendre tables, stdio's buffers, and what ARPACK and LAPACK keep on
# the stack.
# Under ASan (the sanitizer build of scripts/test.sh) also without a leak or
# any other report: a report is one more line on stderr, a leak exit 23.
# To see where allocation k is made: MFSTAB_ALLOC_FAIL=k MFSTAB_ALLOC_ABORT=1
# under gdb.
# usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir [PATTERN]
# (PATTERN: only the command lines that contain it)
set -u
M=${1:?usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir [PATTERN]}
S=${2:?usage: bash tests/test_alloc.sh /path/to/mfstab scenes-dir [PATTERN]}
ONLY=${3:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }
shopt -s nullglob

# Particle files: the 3 x 3 lattice 0..2 without volumes (its dual volumes
# from Qhull's Delaunay triangulation) and with them.
printf 'x,y\n' >"$tmp/p9.csv"
printf 'x,y,volume\n' >"$tmp/p9v.csv"
for y in 0 1 2; do
  for x in 0 1 2; do
    echo "$x,$y" >>"$tmp/p9.csv"
    echo "$x,$y,1" >>"$tmp/p9v.csv"
  done
done

# same_file A B: the same fields (split at commas and blanks), numbers equal
# to 1e-9 of the largest magnitude in their column of A; a backward error (a
# column whose name says backward) is round-off itself: to 1e-12
same_file() {
  awk -F'[, ]' 'function num(s) { return s ~ /^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$/ }
    NR == FNR { a[FNR] = $0; n = FNR
      if (FNR == 1) for (i = 1; i <= NF; i++) if ($i ~ /backward/) mx[i] = 1e-3
      for (i = 1; i <= NF; i++) if (num($i)) { v = $i < 0 ? -$i : $i; if (v > mx[i]) mx[i] = v }
      next }
    { if (!(FNR in a)) exit 1; k = split(a[FNR], x, /[, ]/); if (k != NF) exit 1
      for (i = 1; i <= NF; i++) if (x[i] != $i) {
        if (!num(x[i]) || !num($i)) exit 1
        d = x[i] - $i; if (d < 0) d = -d
        if (d > 1e-9 * mx[i]) exit 1 } m2 = FNR }
    END { exit !(m2 == n) }' "$1" "$2"
}

# same_output: the files of $tmp/out and the standard output are those of the good run
same_output() {
  local f g
  local -a now=("$tmp/out/"*) was=("$tmp/good/"*)
  [ "${#now[@]}" -eq "${#was[@]}" ] || return 1
  for g in "${was[@]}"; do
    f=$tmp/out/${g##*/}
    [ -f "$f" ] && same_file "$g" "$f" || return 1
  done
  same_file "$tmp/good.stdout" "$tmp/stdout" || { [ ! -s "$tmp/good.stdout" ] && [ ! -s "$tmp/stdout" ]; }
}

# every_allocation ARGS...: the loop over k for one command line; OUT/ in an
# argument is the output directory (where -o writes too)
every_allocation() {
  local what="mfstab $*" o=$tmp/out/res.csv a
  [[ $what == *"$ONLY"* ]] || return 0
  local -a args=()
  for a in "$@"; do args+=("${a//OUT\//$tmp/out/}"); done
  rm -rf "$tmp/out" "$tmp/good"
  mkdir -p "$tmp/out"
  rm -f "$tmp/count"
  if ! MFSTAB_ALLOC_COUNT=$tmp/count "$M" "${args[@]}" -o "$o" >"$tmp/good.stdout" 2>"$tmp/good.err"; then
    ko "$what: the good run failed: $(head -c 200 "$tmp/good.err")"
    return
  fi
  # what a normal run prints on stderr (mfstab run: the step line of its header);
  # a failure after it may follow it
  local -a glines=()
  mapfile -t glines <"$tmp/good.err"
  local ng=${#glines[@]}
  local K bad=0 k rc recovered=0 n
  K=$(cat "$tmp/count")
  mv "$tmp/out" "$tmp/good"
  mkdir "$tmp/out"
  for ((k = 1; k <= K; k++)); do
    MFSTAB_ALLOC_FAIL=$k "$M" "${args[@]}" -o "$o" >"$tmp/stdout" 2>"$tmp/err"
    rc=$?
    local -a left=("$tmp/out/"*) lines=()
    mapfile -t lines <"$tmp/err"
    n=${#lines[@]}
    local head_ok=1 i
    if [ "$n" -eq $((ng + 1)) ]; then
      for ((i = 0; i < ng; i++)); do [ "${lines[i]}" == "${glines[i]}" ] || head_ok=0; done
    fi
    if [ "$rc" -eq 1 ] && { [ "$n" -eq 1 ] || { [ "$n" -eq $((ng + 1)) ] && [ "$head_ok" -eq 1 ]; }; } &&
       [[ ${lines[n - 1]} == *"out of memory"* ]] &&
       [ "${#left[@]}" -eq 0 ] && [ ! -s "$tmp/stdout" ]; then
      continue
    fi
    if [ "$rc" -eq 0 ] && cmp -s "$tmp/err" "$tmp/good.err" && same_output; then
      recovered=$((recovered + 1)) # a way around it, and the same result
    else
      [ "$bad" -lt 3 ] && echo "FAIL: $what: allocation $k of $K failing: exit $rc, $n lines: $(head -c 300 "$tmp/err" | tr '\n' '|')$([ "${#left[@]}" -gt 0 ] && echo " (${#left[@]} files left: ${left[*]##*/})")$([ -s "$tmp/stdout" ] && echo ' (standard output)')"
      bad=$((bad + 1))
    fi
    rm -rf "$tmp/out"
    mkdir "$tmp/out"
  done
  if [ "$bad" -eq 0 ]; then
    pass=$((pass + 1))
    echo "ok: $what: each of its $K allocations failing ends in exit 1, out of memory ($recovered recovered with the same output)"
  else
    ko "$what: $bad of its $K allocations failing mishandled"
  fi
}

every_allocation stencil
every_allocation stencil --dim 2 --quadrature stress-tri
every_allocation dispersion --points 11
every_allocation dispersion --dim 2 --quadrature gauss2 --points 5 --classify
every_allocation dispersion --dim 2 --physics plane-strain --stress 0.2 --stress-yy -0.1 --points 5
every_allocation dispersion --dim 2 --physics plane-strain --material neo-hookean --stretch 1.1 --points 5
every_allocation map --material neo-hookean --stretch-range 0.8:1.2:3
every_allocation eigs --nodes 20 --zero-modes
every_allocation eigs --dim 2 --nodes 6,6 --zero-modes --physics plane-strain
every_allocation eigs --dim 2 --nodes 4,4 --perturb 0.1 --seed 3
every_allocation eigs --nodes 12 --certify
every_allocation eigs --nodes 12 --write-modes OUT/m
every_allocation eigs --particles "$tmp/p9v.csv" --support 1.6 --zero-modes
every_allocation bound --nodes 20
every_allocation bound --dim 2 --nodes 5,5 --perturb 0.1 --seed 3
every_allocation bound --particles "$tmp/p9.csv" --support 1.6
every_allocation check --particles "$tmp/p9.csv" --support 1.6
every_allocation static --nodes 5,3 --method cd1,sph,efg
every_allocation static --problem plate-hole --nodes 3 --method mls --refine 2
every_allocation static --nodes 5,3 --method jb --patch
every_allocation run "$S/gaussian-pulse.ini" --set model.nodes=30
every_allocation run "$S/gaussian-pulse.ini" --set model.nodes=30 --step-rule gershgorin
every_allocation run "$S/gaussian-pulse.ini" --set model.nodes=30 --step-rule certified
every_allocation run "$S/plate-pulse-2d.ini" --set model.nodes=8 --set model.nodes_y=6 --set time.end=1e-5
every_allocation run "$S/tsph-elastic-bar.ini" --set model.nodes=30
every_allocation run "$S/plate-tensile-2d.ini" --set model.nodes=8 --set model.nodes_y=8 \
  --set model.length=0.008 --set model.length_y=0.008 --set initial.mode_x=4 \
  --set initial.pulse_center=0.004 --set initial.pulse_center_y=0.004 --set time.end=1.6e-7

echo "test_alloc: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
