#!/usr/bin/env bash
# Regression test of the rebuilt middle layer (issue 9): every output of
# tests/golden/generate.sh equals the reference copies in tests/golden/data/
# (made from main before the change) to 1e-12 relative (compare.py).
# usage: test_golden.sh MFSTAB SOURCE_ROOT
set -u
M=${1:?usage: test_golden.sh MFSTAB SOURCE_ROOT}
R=${2:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! bash "$R/tests/golden/generate.sh" "$M" "$R/analysis/scenes" "$tmp/new" >"$tmp/log" 2>&1; then
  cat "$tmp/log"
  echo "test_golden: 0 passed, 1 failed (generate.sh failed)"
  exit 1
fi
/usr/bin/python3 "$R/tests/golden/compare.py" "$R/tests/golden/data" "$tmp/new" 1e-12
