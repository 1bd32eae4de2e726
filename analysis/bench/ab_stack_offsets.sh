#!/usr/bin/env bash
# Two builds of libmfstab side by side (bench_dispersion_ab) at eight starting
# addresses of the stack (not a test; docs/benchmarks.md, round 9).  Address
# randomization off (setarch -R), and the environment 0, 16, ..., 112 bytes
# longer, so that the stack starts 16 bytes further on each time: a time that
# depends on the row is an alignment effect of the code, not the machine's.
#
#   analysis/bench/ab_stack_offsets.sh LIB_A LIB_B [OUT] [REPEAT]
#     LIB_A, LIB_B  the two libmfstab.so (e.g. a worktree's build of an older commit)
#     OUT           CSV (default $TMPDIR/ab_stack_offsets.csv)
#     REPEAT        passes of each library per row (default 500)
#   BUILD (default build): where analysis/bench/bench_dispersion_ab is.
#
# CSV: stack_pad_bytes, then bench_dispersion_ab's columns (phase, points,
# repeats, seconds_a, seconds_b, ns_per_point_a, ns_per_point_b, ratio = B / A,
# identical, peak_rss_mb, load1).
set -euo pipefail
A=${1:?usage: ab_stack_offsets.sh LIB_A LIB_B [OUT] [REPEAT]}
B=${2:?usage: ab_stack_offsets.sh LIB_A LIB_B [OUT] [REPEAT]}
OUT=${3:-${TMPDIR:-/tmp}/ab_stack_offsets.csv}
REPEAT=${4:-500}
AB=${BUILD:-build}/analysis/bench/bench_dispersion_ab
[ -x "$AB" ] || { echo "ab_stack_offsets.sh: $AB not found (meson compile first)" >&2; exit 2; }
command -v setarch > /dev/null || { echo "ab_stack_offsets.sh: no setarch (util-linux)" >&2; exit 2; }
tmp=$(mktemp "${TMPDIR:-/tmp}/ab_stack.XXXXXX")
trap 'rm -f "$tmp" "$tmp.row"' EXIT
first=1
for pad in 0 16 32 48 64 80 96 112; do
  fill=$(printf '%*s' "$pad" '' | tr ' ' x)
  setarch "$(uname -m)" -R env MFS_STACK_PAD="$fill" "$AB" "$A" "$B" --repeat "$REPEAT" -o "$tmp.row"
  if [ "$first" = 1 ]; then
    echo "stack_pad_bytes,$(head -1 "$tmp.row")" > "$tmp"
    first=0
  fi
  tail -n +2 "$tmp.row" | sed "s/^/$pad,/" >> "$tmp"
done
mkdir -p "$(dirname "$OUT")"
mv "$tmp" "$OUT"
echo "ab_stack_offsets.sh: wrote $OUT" >&2
