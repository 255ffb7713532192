#!/usr/bin/env bash
# Runs mrloc's libFuzzer targets (tests/fuzz) from the sanitized clang build (build-asan/).
#   scripts/fuzz.sh [SECONDS_PER_TARGET=600] [TARGET...]    targets: tests/fuzz/fuzz_<TARGET>.cpp
# Each target's header comment names its seeds (`// fuzz-seeds: <globs from the project's
# root>`), its largest input (`// fuzz-max-len: N`) and, if not 4096, its malloc limit
# (`// fuzz-malloc-limit-mb: N`): a new target needs no edit here.
# The corpus grows in build-asan/fuzz/corpus/<target>; a crash, a leak of a non-mrloc
# exception, a timeout or an out-of-memory is written to build-asan/fuzz/findings/ and makes
# this script fail. CI runs it briefly after the sanitized tests; see doc/hardening.md.
# MRLOC_FUZZ_FLAGS adds libFuzzer flags (CI: -detect_leaks=0).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in tests/fuzz/fuzz_*.cpp; do t="${f##*/fuzz_}"; targets+=("${t%.cpp}"); done
fi

# MRLOC_FUZZ_COVERAGE=OFF (CI): no libFuzzer coverage in mrloc's files (doc/hardening.md)
coverage="${MRLOC_FUZZ_COVERAGE:-ON}"
if [ ! -f build-asan/CMakeCache.txt ]; then
  CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DMRLOC_SANITIZE=ON \
    -DMRLOC_FUZZ_COVERAGE="$coverage" >/dev/null
elif ! grep -q "^MRLOC_FUZZ_COVERAGE:BOOL=$coverage\$" build-asan/CMakeCache.txt; then
  cmake -S . -B build-asan -DMRLOC_FUZZ_COVERAGE="$coverage" >/dev/null
fi
cmake --build build-asan -j "$(nproc)" --target "${targets[@]/#/fuzz_}" 2>&1 |
  { grep -v -E '^\[ *[0-9]+%\] (Building|Linking|Built)' || true; }

root="$PWD"
work="$root/build-asan/fuzz"
mkdir -p "$work/findings"
declared() {  # declared <target> <key> <default>: the value of `// <key>: ...` in its source
  local v
  v=$(sed -n "s|^// $2: *\([^ ]*\( [^(]*\)*\).*|\1|p" "$root/tests/fuzz/fuzz_$1.cpp" | head -1)
  echo "${v:-$3}"
}
seeds() {  # the seed files of a target, one per line
  local pattern
  for pattern in $(declared "$1" fuzz-seeds ""); do
    [ "${pattern#/}" = "$pattern" ] && pattern="$root/$pattern"
    compgen -G "$pattern" || true
  done
}
max_len() { declared "$1" fuzz-max-len 65536; }
# libFuzzer stops at any malloc above this (fuzz-malloc-limit-mb, 4096 unless declared).
malloc_limit() { declared "$1" fuzz-malloc-limit-mb 4096 | cut -d' ' -f1; }

# fuzz_one <target>: one target for `seconds`; its lines printed together when it ends; fails
# on a finding.
fuzz_one() {
  local t="$1" corpus="$work/corpus/$1" seed_dir="$work/seeds/$1" i=0 out
  mkdir -p "$corpus" "$seed_dir"
  while IFS= read -r f; do cp "$f" "$seed_dir/seed_$((i++))"; done < <(seeds "$t")
  out="fuzz_$t: ${seconds} s, $(ls "$seed_dir" | wc -l) seeds, corpus $(ls "$corpus" | wc -l)"
  # The INI target reads its paths (map = maps/...) from the project's root.
  if ! (cd "$root" && "$root/build-asan/tests/fuzz/fuzz_$t" "$corpus" "$seed_dir" \
          -max_total_time="$seconds" -max_len="$(max_len "$t")" -timeout=60 \
          -rss_limit_mb=4096 -malloc_limit_mb="$(malloc_limit "$t")" -print_final_stats=1 -close_fd_mask=1 \
          -artifact_prefix="$work/findings/${t}-" ${MRLOC_FUZZ_FLAGS:-} 2> "$work/$t.log"); then
    { echo "$out"; echo "fuzz_$t: FINDING (log: $work/$t.log, inputs: $work/findings/)"
      tail -40 "$work/$t.log"; } >&2
    return 1
  fi
  { echo "$out"
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb|^Done [0-9]+ runs' "$work/$t.log" || true
  } >&2
}

# Each target is one process on one core: as many run at once as there are cores, so CI's
# fuzzing takes its seconds per target divided by the cores.
status=0
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$(nproc)" ]; then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || status=1
  running=$((running - 1))
done
exit $status
