#!/usr/bin/env bash
# Install what is missing, build, run every test; the last line counts them.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh || exit 1
bash scripts/build.sh || exit 1
meson test -C build --print-errorlogs --num-processes 2 > build/test-output.txt 2>&1
rc=$?
cat build/test-output.txt
pass=$(grep -cE '^ *[0-9]+/[0-9]+ .* OK ' build/test-output.txt || true)
fail=$(grep -cE '^ *[0-9]+/[0-9]+ .* (FAIL|TIMEOUT|ERROR) ' build/test-output.txt || true)
if [ "$rc" -ne 0 ] && [ "$fail" -eq 0 ]; then fail=1; fi
echo "mfstab: $pass passed, $fail failed"
exit $rc
