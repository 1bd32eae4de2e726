#!/usr/bin/env bash
# Build the libFuzzer targets of tests/fuzz/ with clang, ASan and UBSan, and
# run each for SECONDS (default 600) from the seed corpus of tests/fuzz/corpus/.
# usage: bash scripts/fuzz.sh [SECONDS] [BUILD-DIR]
# One line per target: "fuzz NAME: N runs in S s, 0 crashes" (or the crash
# file); the last line counts the targets that passed; exit 1 on a finding,
# 77 when no clang is installed.
set -uo pipefail
cd "$(dirname "$0")/.."
secs=${1:-600}
bdir=${2:-build-fuzz}
cc=$(command -v clang-14 || command -v clang || true)
if [ -z "$cc" ]; then
  echo "fuzz: no clang on PATH; skipped"
  exit 77
fi
if [ ! -f "$bdir/build.ninja" ]; then
  CC=$cc meson setup "$bdir" -Dfuzz=true -Db_sanitize=address,undefined -Db_lundef=false \
    -Dbuildtype=debugoptimized >"$bdir.setup.log" 2>&1 || { cat "$bdir.setup.log"; exit 1; }
fi
ninja -C "$bdir" tests/fuzz/fuzz_scene tests/fuzz/fuzz_options tests/fuzz/fuzz_particles >"$bdir/fuzz-build.log" 2>&1 ||
  { cat "$bdir/fuzz-build.log"; exit 1; }
pass=0
fail=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1
for t in scene options particles; do
  work=$bdir/fuzz-$t
  mkdir -p "$work/corpus" "$work/artifacts"
  "$bdir/tests/fuzz/fuzz_$t" -max_total_time="$secs" -close_fd_mask=3 -rss_limit_mb=4096 \
    -timeout=20 -artifact_prefix="$work/artifacts/" "$work/corpus" "tests/fuzz/corpus/$t" \
    >"$work/log.txt" 2>&1
  rc=$?
  runs=$(sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\1 runs in \2 s/p' "$work/log.txt")
  found=$(ls "$work/artifacts" 2>/dev/null | head -1)
  if [ "$rc" -eq 0 ] && [ -z "$found" ]; then
    pass=$((pass + 1))
    echo "fuzz $t: ${runs:-? runs}, 0 crashes, 0 sanitizer reports"
  else
    fail=$((fail + 1))
    echo "fuzz $t: FAIL (exit $rc) ${found:+$work/artifacts/$found}"
    grep -m 5 -E "ERROR|SUMMARY|runtime error" "$work/log.txt"
  fi
done
echo "fuzz: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
