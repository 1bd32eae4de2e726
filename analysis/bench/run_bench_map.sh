#!/usr/bin/env bash
# Build mfstab in release mode in $BUILD (default /tmp/build-bench) and run the map
# benchmark (issue 10): the 60 x 60 stretch map of the paper 000 material, cubic MLS,
# stress-tri, 8 directions x 64 wave numbers per grid point, for the Lagrangian and
# both Eulerian frames, the least of REPEATS runs (default 1; the machine is shared),
# into $OUTDIR/bench_map.csv (default notebooks-data); then the command itself (mfstab
# map, both frames at once) timed by /usr/bin/time into $OUTDIR/bench_map_command.csv.
# Extra arguments replace the grid sizes.  CORE=n pins the run to core n.
# bench_map_command.csv: command,grid,points,wall_s,user_s,s_per_point,peak_rss_mb,
# threads,gflop: threads the command's OpenMP team (OMP_NUM_THREADS, else the cores);
# gflop the minimal work of its grid, the one-thread bench_map row's gflop of each
# of its frames at the same grid (the same library calls and samples: 10^9 flops;
# analysis/bench/limits.py states it against dgemm's rate).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-/tmp/build-bench}
OUTDIR=${OUTDIR:-notebooks-data}
[ -f "$BUILD/build.ninja" ] || meson setup "$BUILD" --buildtype=release >/dev/null
meson compile -C "$BUILD" analysis/bench/bench_map tools/mfstab >/dev/null
mkdir -p "$OUTDIR"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(60)
pin=()
[ -z "${CORE:-}" ] || pin=(taskset -c "$CORE")
"${pin[@]}" "$BUILD/analysis/bench/bench_map" --repeat "${REPEATS:-1}" "${sizes[@]}" \
  -o "$OUTDIR/bench_map.csv"
echo "wrote $OUTDIR/bench_map.csv" >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
threads=${OMP_NUM_THREADS:-$(nproc)}
echo "command,grid,points,wall_s,user_s,s_per_point,peak_rss_mb,threads,gflop" >"$OUTDIR/bench_map_command.csv"
for n in "${sizes[@]}"; do
  for fr in lagrangian eulerian eulerian-consistent lagrangian,eulerian; do
    /usr/bin/time -f "%e %U %M" -o "$tmp/t" "${pin[@]}" "$BUILD/tools/mfstab" map --material paper000 \
      --stretch-range "0.3:2.0:$n" --kernel cubic --shape mls --dilation 2 --quadrature stress-tri \
      --frame "$fr" -o "$tmp/map.csv"
    read -r wall user rss <"$tmp/t"
    nf=$(awk -F, '{print NF}' <<<"$fr")
    g=$(awk -F, -v fr=",$fr," -v grid="${n}x$n" 'NR==1{for(i=1;i<=NF;i++)h[$i]=i;next}
      $h["threads"]==1 && $h["grid"]==grid && index(fr, "," $1 ",") {s+=$h["gflop"]; k++}
      END{if(k) printf "%.6g", s}' "$OUTDIR/bench_map.csv")
    awk -v c="mfstab map --frame $fr" -v n="$n" -v w="$wall" -v u="$user" -v r="$rss" -v f="$nf" \
      -v t="$threads" -v g="$g" \
      'BEGIN{printf "\"%s\",%dx%d,%d,%s,%s,%.6g,%.1f,%d,%s\n", c, n, n, n*n*f, w, u, u/(n*n*f), r/1024, t, g}' \
      >>"$OUTDIR/bench_map_command.csv"
  done
done
echo "wrote $OUTDIR/bench_map_command.csv" >&2
