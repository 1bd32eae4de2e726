#!/usr/bin/env bash
# Configure (once) and build mfstab in ./build (release, -O2).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -f build/build.ninja ]; then
  meson setup --reconfigure build >/dev/null
else
  meson setup build --buildtype=release >/dev/null
fi
meson compile -C build >/dev/null
