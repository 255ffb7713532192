#!/usr/bin/env bash
# The main job: installs what the program needs and builds it alone (the tests are
# ./test.sh's); then, with no argument, the tour: each of the five methods on a short scenario
# of its own (config/tour.txt) simulated, localized and reported into out/tour/<method>/, and
# out/tour/index.html with every headline beside the paper's figure. With an INI (and mrloc
# run's options): that one scenario end to end. Each step says when it starts and how long it
# took.
set -euo pipefail
cd "$(dirname "$0")"
step=$SECONDS
echo "run.sh: Debian packages (scripts/install-deps.sh tour)" >&2
scripts/install-deps.sh tour
echo "run.sh: packages ready in $((SECONDS - step)) s; building mrloc (scripts/build.sh mrloc)" >&2
step=$SECONDS
scripts/build.sh mrloc
echo "run.sh: mrloc built in $((SECONDS - step)) s" >&2
mrloc=build/apps/mrloc/mrloc
if [ $# -gt 0 ]; then
  ini="$1"
  shift
  exec "$mrloc" run "$ini" "$@"
fi
start=$SECONDS
while read -r name ini; do
  case "$name" in '' | '#'*) continue ;; esac
  echo "tour: $name ($ini)" >&2
  # the run's last line is its headline
  "$mrloc" run "$ini" --out "out/tour/$name" --quiet | tail -n 1
done < config/tour.txt
"$mrloc" index out/tour --title "mrloc's tour: five methods, five papers" >/dev/null
echo "tour: five methods in $((SECONDS - start)) s; the index: out/tour/index.html"
