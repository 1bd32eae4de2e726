#!/usr/bin/env bash
# Build mfstab in release mode in $BUILD (default /tmp/build-bench) and run the map
# benchmark (issue 10): the 60 x 60 stretch map of the paper 000 material, cubic MLS,
# stress-tri, 8 directions x 64 wave numbers per grid point, for the Lagrangian and
# both Eulerian frames, the least of REPEATS runs (default 1; the machine is shared),
# into notebooks-data/bench_map.csv; then the command itself (mfstab map, both frames
# at once) timed by /usr/bin/time into notebooks-data/bench_map_command.csv.
# Extra arguments replace the grid sizes.  CORE=n pins the run to core n.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD:-/tmp/build-bench}
[ -f "$BUILD/build.ninja" ] || meson setup "$BUILD" --buildtype=release >/dev/null
meson compile -C "$BUILD" analysis/bench/bench_map tools/mfstab >/dev/null
mkdir -p notebooks-data
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(60)
pin=()
[ -z "${CORE:-}" ] || pin=(taskset -c "$CORE")
"${pin[@]}" "$BUILD/analysis/bench/bench_map" --repeat "${REPEATS:-1}" "${sizes[@]}" \
  -o notebooks-data/bench_map.csv
echo "wrote notebooks-data/bench_map.csv" >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "command,grid,points,wall_s,user_s,s_per_point,peak_rss_mb" >notebooks-data/bench_map_command.csv
for n in "${sizes[@]}"; do
  for fr in lagrangian eulerian eulerian-consistent lagrangian,eulerian; do
    /usr/bin/time -f "%e %U %M" -o "$tmp/t" "${pin[@]}" "$BUILD/tools/mfstab" map --material paper000 \
      --stretch-range "0.3:2.0:$n" --kernel cubic --shape mls --dilation 2 --quadrature stress-tri \
      --frame "$fr" -o "$tmp/map.csv"
    read -r wall user rss <"$tmp/t"
    nf=$(awk -F, '{print NF}' <<<"$fr")
    awk -v c="mfstab map --frame $fr" -v n="$n" -v w="$wall" -v u="$user" -v r="$rss" -v f="$nf" \
      'BEGIN{printf "\"%s\",%dx%d,%d,%s,%s,%.6g,%.1f\n", c, n, n, n*n*f, w, u, u/(n*n*f), r/1024}' \
      >>notebooks-data/bench_map_command.csv
  done
done
echo "wrote notebooks-data/bench_map_command.csv" >&2
