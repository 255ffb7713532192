#!/usr/bin/env bash
# The README's picture of the tour's index (doc/images/tour-index.png), taken by headless
# Chromium from the current tour (./run.sh's out/tour/index.html, made first when missing),
# so that the README never shows figures from an older build. Installs Debian's chromium
# when it is missing (a maintainer's tool: neither the program nor the tests need it).
#   scripts/screenshots.sh [WIDTHxHEIGHT=1280x760]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-1280x760}"
case "$size" in [0-9]*x[0-9]*) ;; *) echo "screenshots: give WIDTHxHEIGHT, not '$size'" >&2; exit 2 ;; esac
if ! command -v chromium >/dev/null; then
  echo "screenshots: installing Debian's chromium (headless screenshots)" >&2
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends chromium
fi
[ -f out/tour/index.html ] || ./run.sh
shot="$(mktemp -d)"
trap 'rm -rf "$shot"' EXIT
# --no-sandbox: Chromium refuses to run as root with its sandbox (CI machines, containers)
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size="${size/x/,}" \
  --screenshot="$shot/index.png" "file://$PWD/out/tour/index.html" 2>/dev/null
[ -s "$shot/index.png" ] || { echo "screenshots: Chromium wrote no picture" >&2; exit 1; }
mv "$shot/index.png" doc/images/tour-index.png
echo "doc/images/tour-index.png ($size, from out/tour/index.html of $(git rev-parse --short HEAD 2>/dev/null || echo 'this tree'))"
