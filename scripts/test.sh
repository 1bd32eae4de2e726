#!/usr/bin/env bash
# Install what is missing, build, run every test; the last line counts them.
#   1. the whole suite on the release build (./build)
#   2. the unit and CLI suites again under AddressSanitizer and UBSan
#      (./build-san, gcc; a leak, an overflow or undefined behaviour fails)
#   3. the fuzz targets of tests/fuzz/ for FUZZ_SECONDS (30) each where clang
#      is installed (./build-fuzz; scripts/fuzz.sh runs them for long)
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh || exit 1
bash scripts/build.sh || exit 1
pass=0
fail=0
count() { # count FILE: the OK and FAIL lines of a meson test log
  local p f
  p=$(grep -cE '^ *[0-9]+/[0-9]+ .* OK ' "$1" || true)
  f=$(grep -cE '^ *[0-9]+/[0-9]+ .* (FAIL|TIMEOUT|ERROR) ' "$1" || true)
  pass=$((pass + p))
  fail=$((fail + f))
  [ "$2" -ne 0 ] && [ "$f" -eq 0 ] && fail=$((fail + 1))
}

meson test -C build --print-errorlogs --num-processes 2 >build/test-output.txt 2>&1
rc=$?
cat build/test-output.txt
count build/test-output.txt $rc

echo "== the unit and CLI suites under ASan and UBSan (build-san)"
if { [ -f build-san/build.ninja ] ||
     meson setup build-san -Db_sanitize=address,undefined -Db_lundef=false \
       -Dbuildtype=debugoptimized >/dev/null; } && ninja -C build-san >/dev/null; then
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    meson test -C build-san --print-errorlogs --num-processes 2 --suite unit --suite cli \
    >build-san/test-output.txt 2>&1
  r=$?
  sed 's/^/  /' build-san/test-output.txt | grep -E '^ *[0-9]+/[0-9]+ |FAIL|ERROR' || true
  count build-san/test-output.txt $r
else
  echo "FAIL: the sanitizer build"
  fail=$((fail + 1))
fi

echo "== the fuzz targets, ${FUZZ_SECONDS:-30} s each (build-fuzz)"
bash scripts/fuzz.sh "${FUZZ_SECONDS:-30}" build-fuzz >build/fuzz-output.txt 2>&1
r=$?
cat build/fuzz-output.txt
if [ "$r" -eq 0 ]; then
  pass=$((pass + $(grep -c '^fuzz [a-z]*: .* 0 crashes' build/fuzz-output.txt)))
elif [ "$r" -ne 77 ]; then
  fail=$((fail + 1))
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
