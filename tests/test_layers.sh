#!/usr/bin/env bash
# The stages of lib/ are folders (lib/meson.build: mfs_stages, in data-flow
# order); a file may include only headers of its own stage or of an earlier
# one.  Checks every #include "..." of lib/*/*.[ch], then checks itself: a
# copy of lib/ with one deliberate upward include must fail.
# usage: test_layers.sh LIB_DIR
set -u
LIB=${1:?usage: test_layers.sh LIB_DIR}

# check DIR: prints one line per upward or unknown include; exit 1 if any
check() {
  local dir=$1 bad=0 rank=0
  local stages
  stages=$(sed -n "s/^mfs_stages = \[\(.*\)\]/\1/p" "$dir/meson.build" | tr -d "' " | tr ',' ' ')
  [ -n "$stages" ] || { echo "no mfs_stages in $dir/meson.build"; return 1; }
  declare -A stage_of rank_of
  for s in $stages; do
    rank_of[$s]=$rank
    rank=$((rank + 1))
    for h in "$dir/$s"/*.h; do
      [ -e "$h" ] && stage_of[$(basename "$h")]=$s
    done
  done
  for s in $stages; do
    for f in "$dir/$s"/*.[ch]; do
      [ -e "$f" ] || continue
      while IFS= read -r inc; do
        local t=${stage_of[$inc]:-}
        if [ -z "$t" ]; then
          echo "$f: includes \"$inc\", which is not a header of any stage"
          bad=1
        elif [ "${rank_of[$t]}" -gt "${rank_of[$s]}" ]; then
          echo "$f ($s): includes $inc of the later stage $t"
          bad=1
        fi
      done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f")
    done
  done
  return $bad
}

pass=0
fail=0
if out=$(check "$LIB"); then
  pass=$((pass + 1))
else
  fail=$((fail + 1))
  echo "FAIL: upward includes in $LIB:"
  echo "$out"
fi
# self-test: an upward include (core -> time) must be caught
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp -r "$LIB" "$tmp/lib"
first=$(sed -n "s/^mfs_stages = \[\(.*\)\]/\1/p" "$tmp/lib/meson.build" | tr -d "' " | cut -d, -f1)
last_h=$(ls "$tmp/lib/time"/*.h | head -1)
victim=$(ls "$tmp/lib/$first"/*.h | head -1)
sed -i "0,/#include/s//#include \"$(basename "$last_h")\"\n#include/" "$victim"
if check "$tmp/lib" >"$tmp/out"; then
  fail=$((fail + 1))
  echo "FAIL: a deliberate include of $(basename "$last_h") in $(basename "$victim") was not caught"
else
  pass=$((pass + 1))
fi
# every allocation of the library and the tools goes through the library's
# allocator (lib/core/mfs_alloc.h): no bare malloc, calloc, realloc, strdup or
# free call outside mfs_alloc.c and the test allocator of tools/mfstab.c
bare=$(grep -rnE '(^|[^[:alnum:]_.>])(malloc|calloc|realloc|strdup|free)[[:space:]]*\(' \
         "$LIB" "$LIB/../tools" --include=*.c --include=*.h |
       grep -v -e '/mfs_alloc\.c:' -e '/tools/mfstab\.c:' | grep -vE '^[^:]+:[0-9]+:[[:space:]]*(/?\*|//)' |
       grep -vE '/\*.*(malloc|calloc|realloc|strdup|free)[[:space:]]*\(.*\*/' || true)
if [ -n "$bare" ]; then
  fail=$((fail + 1))
  echo "FAIL: allocations outside the library's allocator (use mfs_malloc ...):"
  echo "$bare"
else
  pass=$((pass + 1))
fi
echo "test_layers: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
