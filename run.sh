#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs an INI end to end
# (simulate -> localize -> report). Default: config/quickstart.ini.
set -euo pipefail
cd "$(dirname "$0")"
scripts/install-deps.sh
scripts/build.sh
ini="${1:-config/quickstart.ini}"
shift || true
exec build/apps/mrloc/mrloc run "$ini" "$@"
