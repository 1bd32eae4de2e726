#!/usr/bin/env bash
# The dispersion sweeps and the map in parallel (issue 14): the same file, byte
# for byte, with OMP_NUM_THREADS=1, 2 and 3 (every point is computed on its own,
# the classification's extremes are combined in a fixed order).  Curves (1D,
# several stresses and dilations; 2D plane strain on the star cell, the LAPACK
# path), --classify (onset bisections), map (one plan for every state; a plan per
# state of an Eulerian kernel under a stretch).  Skipped (77) without OpenMP.
# usage: bash tests/test_threads_dispersion.sh /path/to/mfstab
set -u
M=${1:?usage: bash tests/test_threads_dispersion.sh /path/to/mfstab}
if ! ldd "$M" 2>/dev/null | grep -q 'libgomp'; then
  echo "SKIP: $M is built without OpenMP (libgomp)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
same() { # same NAME ARGS...: the output with 1, 2 and 3 threads
  local name=$1 n
  shift
  for n in 1 2 3; do
    if ! OMP_NUM_THREADS=$n "$M" "$@" -o "$tmp/$name.$n.csv" 2>"$tmp/err"; then
      fail=$((fail + 1))
      echo "FAIL: $name with $n threads: exit $? $(head -c 200 "$tmp/err")"
      return
    fi
  done
  local rows
  rows=$(($(wc -l <"$tmp/$name.1.csv") - 1))
  for n in 2 3; do
    if ! cmp -s "$tmp/$name.1.csv" "$tmp/$name.$n.csv"; then
      fail=$((fail + 1))
      echo "FAIL: $name: $n threads differ from 1: $(cmp "$tmp/$name.1.csv" "$tmp/$name.$n.csv" | head -1)"
      return
    fi
  done
  if [ "$rows" -lt 1 ]; then
    fail=$((fail + 1))
    echo "FAIL: $name: no rows"
    return
  fi
  pass=$((pass + 1))
  echo "ok: $name: $rows rows, the same bytes with 1, 2 and 3 threads"
}
same curves-1d dispersion --dim 1 --frame eulerian --quadrature stress --dilation 1.5,2.5 \
  --stress -0.3,0,0.4 --points 2001
same curves-star-plane dispersion --dim 2 --physics plane-strain --quadrature stress-star \
  --theta 0,15,30,45 --points 301
same classify-1d dispersion --dim 1 --kernel cubic --dilation 1.5,3 --frame eulerian \
  --stress -0.5,0,0.5 --classify --points 301
same classify-2d dispersion --dim 2 --quadrature nodal --dilation 2,2.5 --theta 0,20,45 \
  --classify --points 201
same map-stretch map --material paper000 --stretch-range 0.6:1.4:6 --quadrature stress-tri \
  --frame lagrangian,eulerian,eulerian-consistent
same map-stress map --stress-range -1:0.6:5 --stress-xy 0.2 --frame lagrangian,eulerian
echo "test_threads_dispersion: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
