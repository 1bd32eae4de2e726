#!/usr/bin/env bash
# Benchmark (not a test): instructions executed by the same benchmarks of two
# builds (valgrind --tool=callgrind, one thread), the machine-load-free
# companion of compare_builds.sh (this machine has no hardware counters for
# perf).  Sizes are small: callgrind runs about 50 times slower.
#   analysis/bench/compare_instructions.sh OLD_BUILD NEW_BUILD
# Rows (CSV on stdout): benchmark,args,old_instructions,new_instructions,ratio
#   ratio = new / old, the whole process (start-up included).  Only benchmarks
#   whose programs do the same work in both builds are listed: bench_assembly's
#   modes and phases changed (compare them by phase with compare_builds.sh).
set -u
OLD=${1:?usage: compare_instructions.sh OLD_BUILD NEW_BUILD}
NEW=${2:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1 MFSTAB_NO_REEXEC=1
# ir BUILD BENCH ARGS...: the instruction count of one run
ir() {
  local b=$1 name=$2
  shift 2
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$b/analysis/bench/$name" "$@" \
    >/dev/null 2>"$tmp/cg.err" || { echo "NA"; return; }
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.err" | tail -1
}
echo "benchmark,args,old_instructions,new_instructions,ratio"
while read -r name args; do
  # shellcheck disable=SC2086
  o=$(ir "$OLD" "$name" $args)
  # shellcheck disable=SC2086
  n=$(ir "$NEW" "$name" $args)
  r=$(awk -v o="$o" -v n="$n" 'BEGIN{ if (o > 0 && n > 0) printf "%.4f", n / o; else print "" }')
  echo "$name,$args,$o,$n,$r"
done <<'LIST'
bench_solver 3000 40
bench_eigs 60
bench_dispersion
LIST
