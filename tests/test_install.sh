#!/usr/bin/env bash
# meson install into a temporary prefix; then the installed mfstab runs
# without LD_LIBRARY_PATH (its install rpath), the man page is there, and a C
# program (examples/tensile.c) and a C++ program (tests/install/hello.cpp)
# built with `pkg-config --cflags --libs mfstab` link and run.
# usage: bash tests/test_install.sh SOURCE-DIR
set -u
src=${1:?usage: bash tests/test_install.sh SOURCE-DIR}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
check() {
  local what=$1
  shift
  if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $what"; fi
}
p=$tmp/prefix
# only what is installed is built: the library, the program and its man page
if ! { meson setup "$tmp/b" "$src" --prefix="$p" --buildtype=release >"$tmp/log" 2>&1 &&
       ninja -C "$tmp/b" tools/mfstab tools/mfstab.1 >>"$tmp/log" 2>&1 &&
       meson install -C "$tmp/b" --no-rebuild >>"$tmp/log" 2>&1; }; then
  tail -20 "$tmp/log"
  echo "0 passed, 1 failed"
  exit 1
fi
v=$(env -u LD_LIBRARY_PATH "$p/bin/mfstab" --version 2>&1)
check "installed mfstab --version without LD_LIBRARY_PATH: '$v'" test "${v%% *}" = mfstab
check "installed mfstab: no man page" test -s "$p/share/man/man1/mfstab.1"
check "the man page does not list the options of run" grep -q -- '--set' "$p/share/man/man1/mfstab.1"
pc=$(dirname "$(find "$p" -name mfstab.pc | head -1)")
export PKG_CONFIG_PATH=$pc
flags=$(pkg-config --cflags --libs mfstab)
libdir=$(pkg-config --variable=libdir mfstab)
check "pkg-config --cflags --libs mfstab: '$flags'" test -n "$flags"
if cc -std=c11 -O2 "$src/examples/tensile.c" $flags -Wl,-rpath,"$libdir" -o "$tmp/tensile" 2>"$tmp/cc.txt"; then
  check "the C example against the installed library: $(tail -1 "$tmp/tensile.out" 2>/dev/null)" \
    sh -c "'$tmp/tensile' >'$tmp/tensile.out'"
else
  check "the C example does not build with pkg-config: $(head -3 "$tmp/cc.txt")" false
fi
if command -v c++ >/dev/null; then
  if c++ -O2 "$src/tests/install/hello.cpp" $flags -Wl,-rpath,"$libdir" -o "$tmp/hello" 2>"$tmp/cxx.txt"; then
    out=$("$tmp/hello")
    check "the C++ program against the installed library: '$out'" test $? -eq 0
  else
    check "the C++ program does not build with pkg-config: $(head -3 "$tmp/cxx.txt")" false
  fi
else
  echo "no C++ compiler: the C++ link test skipped"
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
