#!/usr/bin/env bash
# Configures (once) and builds mrloc in Release into build/, with one line per step.
#   scripts/build.sh            everything: the program, the tests (./test.sh)
#   scripts/build.sh mrloc      the program alone (./run.sh): GoogleTest is not needed
# MRLOC_WERROR=ON (CI) makes every warning in mrloc's own code an error.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=("$@")
tests=ON
[ ${#targets[@]} -gt 0 ] && tests=OFF
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMRLOC_TESTS=$tests \
    -DMRLOC_WERROR="${MRLOC_WERROR:-OFF}" >/dev/null
elif [ $tests = ON ] && grep -q '^MRLOC_TESTS:BOOL=OFF' build/CMakeCache.txt; then
  # built by ./run.sh without the tests: add them
  cmake -S . -B build -DMRLOC_TESTS=ON >/dev/null
fi
args=()
[ ${#targets[@]} -gt 0 ] && args=(--target "${targets[@]}")
# a line per step ("build  45%: modules/beacons ..."), not CMake's bookkeeping
cmake --build build -j "$(nproc)" "${args[@]}" 2>&1 |
  sed -u -E -e '/^\[ *[0-9]+%\] Built target/d' \
    -e 's#^\[ *([0-9]+)%\] Building CXX object ([^ ]*/)?CMakeFiles/([^ ]*)\.dir/(Unity/)?([^ ]*)\.o$#build \1%: \3 \5#' \
    -e 's#^\[ *([0-9]+)%\] Linking CXX (executable|static library) (.*)$#build \1%: linking \3#'
