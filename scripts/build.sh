#!/usr/bin/env bash
# Configures (once) and builds mrloc in Release into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
# the progress lines filtered out; the build's own status decides (pipefail: grep's never does)
cmake --build build -j "$(nproc)" 2>&1 | { grep -v -E '^\[ *[0-9]+%\] (Building|Linking|Built)' || true; }
