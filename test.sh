#!/usr/bin/env bash
# Installs what is missing (the tests' packages too), builds everything, and runs every test
# (CI calls this, with MRLOC_WERROR=ON).
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)" "$@"
