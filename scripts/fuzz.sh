#!/usr/bin/env bash
# Builds the libFuzzer targets (the "fuzz" preset: clang-14, ASan + UBSan)
# and runs each for DURATION seconds (default 60), one per core at a time,
# on the seed corpus that fuzz/collect_corpus.sh gathers from the tests'
# inputs. Fails on any finding: crash, sanitizer report, undocumented
# exception, an input slower than 5 s, above 2 GB or needing a stack above
# 1 MB; the input is left in build/fuzz/findings/<target>/ (save it under
# fuzz/regressions/<target>/ with a regression test).
# Prints the executions per target, and a finding's input in base64 (so a
# CI log alone reproduces it: base64 -d > crash; build/fuzz/fuzz/T crash).
# The mutation seed is fixed (FUZZ_SEED, default 1) so a run can be repeated
# exactly; FUZZ_SEED=0 lets libFuzzer pick one. Longer runs:
# docs/hardening.md.
# Usage: scripts/fuzz.sh [DURATION] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
duration="${1:-60}"
seed="${FUZZ_SEED:-1}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(gcode_fuzz cldata_fuzz profile_fuzz verify_fuzz stl_fuzz)

bash scripts/setup.sh dev  # the dev layer: clang-14 and libFuzzer
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$(nproc)"
build=build/fuzz
bash fuzz/collect_corpus.sh "$build"

export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# A 1 MB stack (the default is 8 MB): an input that recurses deep enough to
# need more (a value of thousands of nested signs) is a finding, as it would
# be in a thread with a small stack.
ulimit -s 1024
# One target per core at a time (each libFuzzer process runs on one).
run_target() {
  local t=$1 corpus="$build/corpus/$1" findings="$build/findings/$1" log="$build/logs/$1.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")"
  local status=0
  "$build/fuzz/$t" "$corpus" "$build/seeds/$t" -dict="fuzz/${t%_fuzz}.dict" \
    -max_total_time="$duration" -seed="$seed" -timeout=5 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$findings/" >"$log" 2>&1 || status=$?
  echo "$status" >"$log.status"
}
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  run_target "$t" &
done
wait
failed=()
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  log="$build/logs/$t.log"
  status=$(cat "$log.status")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  units=$(ls "$corpus" | wc -l)
  if [ "$status" -eq 0 ]; then
    echo "fuzz: $t ${runs:-?} executions in ${duration} s, corpus $units inputs, no finding"
  else
    echo "fuzz: $t FINDING (exit $status) after ${runs:-?} executions; log $log; inputs:"
    for f in "$findings"/*; do
      [ -f "$f" ] && echo "  $(basename "$f") base64: $(head -c 8192 "$f" | base64 -w0)"
    done
    grep -m1 -A25 -E '^==[0-9]+==ERROR|runtime error|uncaught exception|ALARM|out-of-memory|deadly signal' \
      "$log" || tail -30 "$log"
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]}"
  exit 1
fi
