#!/usr/bin/env bash
# Measures the run transaction (doc/hardening.md): runs an INI into a folder, then re-runs it
# into the finished folder N times, each interrupted at a random moment by SIGINT, SIGTERM or
# SIGKILL, and checks after each that the finished run's files are byte-identical.
#   scripts/interrupt-rerun.sh <ini> [N=20] [seed=1]
set -euo pipefail
cd "$(dirname "$0")/.."
ini="$1"; n="${2:-20}"; RANDOM="${3:-1}"
mrloc="build/apps/mrloc/mrloc"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
out="$work/run"
"$mrloc" run "$ini" -q --out "$out" >/dev/null
full=$( { /usr/bin/time -f %e "$mrloc" run "$ini" -q --out "$work/timing" >/dev/null; } 2>&1 | tail -1)
( cd "$out" && find . -type f -print0 | sort -z | xargs -0 sha256sum ) > "$work/before"
same=0; signals=(INT TERM KILL)
for ((i = 1; i <= n; i++)); do
  sig=${signals[$((RANDOM % 3))]}
  delay=$(awk -v r="$RANDOM" -v f="$full" 'BEGIN { printf "%.2f", f * r / 32768 }')
  "$mrloc" run "$ini" -q --out "$out" >/dev/null 2>&1 & pid=$!
  sleep "$delay"; kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null && rc=0 || rc=$?
  ( cd "$out" && find . -type f -print0 | sort -z | xargs -0 sha256sum ) > "$work/after"
  if [ "$rc" -eq 0 ]; then
    verdict="finished before the signal"
    ( cd "$out" && find . -type f -print0 | sort -z | xargs -0 sha256sum ) > "$work/before"
    same=$((same + 1))
  elif cmp -s "$work/before" "$work/after"; then
    verdict="previous run intact"; same=$((same + 1))
  else
    verdict="PREVIOUS RUN CHANGED"; diff "$work/before" "$work/after" | head -5
  fi
  left=$(find "$work" -maxdepth 1 -name '.run.staging.*' | wc -l)
  echo "$i: SIG$sig after ${delay} s of ${full} s: exit $rc, $verdict, staging folders left: $left"
done
echo "intact or finished: $same of $n"
[ "$same" -eq "$n" ]
