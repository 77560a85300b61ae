#!/usr/bin/env bash
# clang-tidy-14 with .clang-tidy's checks over every source file of the
# product (tests, benchmarks and fuzz drivers left out); fails on any
# warning, prints them all first.
# Usage, from anywhere, after a build configured in BUILD (scripts/test.sh
# configures build/release, with compile_commands.json):
#   bash scripts/tidy.sh [BUILD=build/release] [FILE.cpp ...]
# With files, only those (paths from the repository root).
set -euo pipefail
cd "$(dirname "$0")/.."
build=build/release
if [[ $# -gt 0 && "$1" != *.cpp ]]; then
  build=$1
  shift
fi
db="$build/compile_commands.json"
if [[ ! -f "$db" ]]; then
  echo "tidy.sh: $db is missing: configure the build first (bash scripts/test.sh does)" >&2
  exit 2
fi
if [[ $# -gt 0 ]]; then
  files=("$@")
else
  # Sources the build compiles: the compile database, minus tests, benchmarks
  # and fuzz drivers (their own rules: gtest macros, Google Benchmark loops).
  mapfile -t files < <(git ls-files '*.cpp' | grep -vE '^(tests|bench|fuzz)/' |
    while read -r f; do grep -qF "\"$PWD/$f\"" "$db" && echo "$f"; done)
fi

logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
start=$SECONDS
echo "tidy.sh: ${#files[@]} files, $(nproc) at a time"
# One log per file, so parallel runs do not interleave their messages.
printf '%s\n' "${files[@]}" | xargs -P "$(nproc)" -I{} sh -c \
  'clang-tidy-14 -p "$1" --quiet "$2" > "$3/$(echo "$2" | tr / _).log" 2>&1 || true' \
  _ "$build" {} "$logs"

warnings=$(cat "$logs"/*.log | grep -cE ': (warning|error): ' || true)
cat "$logs"/*.log | grep -vE '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$' |
  grep -vE '^Suppressed|^Use -header-filter|^$' || true
echo "tidy.sh: ${#files[@]} files in $((SECONDS - start)) s, $warnings warnings"
[[ "$warnings" -eq 0 ]]
