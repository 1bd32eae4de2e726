#!/usr/bin/env bash
# Benchmark (not a test): the same benchmarks of two builds, side by side in
# one run, alternating (the machine is shared: a run of one and a run of the
# other, R times), and the ratio new/old of each timed quantity as min,
# median and max over the repetitions.
#   analysis/bench/compare_builds.sh OLD_BUILD NEW_BUILD [R [BENCHMARKS]]
#   (R default 5; BENCHMARKS a quoted list of solver assembly dispersion eigs, default all)
# Rows (CSV on stdout): benchmark,quantity,old_min_s,new_min_s,ratio_min,ratio_median,ratio_max
#   solver       bench_solver 100000 200: the step-loop seconds of each (frame, dilation)
#   assembly     bench_assembly 500: the seconds of each phase of the table pipeline, the
#                total and K_and_M (K and the lumped mass: assembly_K + assembly_lumped_M,
#                or pattern + fill, or the one-sweep assembly)
#   dispersion   bench_dispersion: seconds of each (family, phase)
#   eigs         bench_eigs 316: the model setup, bound and eigenvalue seconds
# Also prints the load average before and after.  The sizes can be changed with
# SOLVER_ARGS (default "100000 200"), ASSEMBLY_ARGS ("500"), EIGS_ARGS ("316").
set -u
OLD=${1:?usage: compare_builds.sh OLD_BUILD NEW_BUILD [R]}
NEW=${2:?}
R=${3:-5}
BENCHES=${4:-solver assembly dispersion eigs}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}" >&2
# run NAME BUILD I: the CSV of one benchmark into $tmp/NAME.BUILDTAG.I
run() {
  local name=$1 b=$2 tag=$3 i=$4 bin=$2/analysis/bench
  case $name in
  solver) "$bin/bench_solver" ${SOLVER_ARGS:-100000 200} | awk -F, 'NR>1{print $3"_D"$4","$6}' ;;
  assembly) # the table pipeline (the only one of the old benchmark; a newer one also has
            # modes model and solver, run alone with --mode table, so that the table's
            # phases do not start from the heap the model mode left): its phases, and
            # K_and_M = the old assembly_K + assembly_lumped_M against the newer pattern +
            # fill or assembly, with the particle -> points transpose where it is a phase
            # of its own (the old assembly_K built it)
            local margs=""
            "$bin/bench_assembly" --mode table 20 2>/dev/null | head -1 | grep -q mode && margs="--mode table"
            "$bin/bench_assembly" $margs ${ASSEMBLY_ARGS:-500} | awk -F, 'NR==1{for(k=1;k<=NF;k++)h[$k]=k; next}
            ("mode" in h) && $h["mode"] != "table" {next}
            {print $h["phase"]","$h["seconds"]}
            $h["phase"] ~ /^(assembly_K|assembly_lumped_M|pattern|fill|assembly|transpose)$/ {km += $h["seconds"]}
            END{print "K_and_M,"km}' ;;
  dispersion) "$bin/bench_dispersion" 2>/dev/null | awk -F, 'NR==1{for(k=1;k<=NF;k++)h[$k]=k
            t = ("seconds_median" in h) ? h["seconds_median"] : h["seconds"]; next}
            {print $h["family"]"_"$h["phase"]","$t}' ;;
  eigs) "$bin/bench_eigs" ${EIGS_ARGS:-316} | awk -F, '{print "setup,"$5; print "bound,"$6; print "eig,"$7}' ;;
  esac >"$tmp/$name.$tag.$i"
}
for name in $BENCHES; do
  for i in $(seq "$R"); do
    run "$name" "$OLD" old "$i"
    run "$name" "$NEW" new "$i"
  done
done
echo "benchmark,quantity,old_min_s,new_min_s,ratio_min,ratio_median,ratio_max"
for name in $BENCHES; do
  /usr/bin/python3 - "$tmp" "$name" "$R" <<'PY'
import sys, statistics
tmp, name, R = sys.argv[1], sys.argv[2], int(sys.argv[3])
def load(tag, i):
    d = {}
    for line in open(f"{tmp}/{name}.{tag}.{i}"):
        k, v = line.strip().rsplit(",", 1)
        try:
            d[k] = float(v)
        except ValueError:
            pass
    return d
old = [load("old", i) for i in range(1, R + 1)]
new = [load("new", i) for i in range(1, R + 1)]
for k in old[0]:
    o = [r[k] for r in old if k in r and r[k] > 0]
    n = [r[k] for r in new if k in r and r[k] > 0]
    if len(o) != R or len(n) != R:
        continue
    ratios = [b / a for a, b in zip(o, n)]
    print(f"{name},{k},{min(o):.4g},{min(n):.4g},{min(ratios):.3f},{statistics.median(ratios):.3f},{max(ratios):.3f}")
PY
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
