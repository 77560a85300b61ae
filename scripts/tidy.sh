#!/usr/bin/env bash
# clang-tidy-14 with .clang-tidy's checks over every source file of the
# product (tests, benchmarks and fuzz drivers left out); fails on any
# warning, prints them all first.
# Usage, from anywhere, after a build configured in BUILD (scripts/test.sh
# configures build/release, with compile_commands.json):
#   bash scripts/tidy.sh [BUILD=build/release] [FILE.cpp ...]
# With files, only those (paths from the repository root).
# Files of one folder compiled with the same flags are checked TIDY_BATCH
# (default 8) at a time, as one translation unit that includes them: the checks then walk the
# standard and library headers they share once instead of once per file
# (most of a file's time). Only the unit's own files are reported. A unit
# that does not compile as one (two files defining the same internal name)
# is split until it does. TIDY_BATCH=1 checks each file alone.
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
batch=${TIDY_BATCH:-8}

# Inside the tree, so that .clang-tidy applies to the units.
[[ "$build" == /* ]] || build=$PWD/$build
work=$(mktemp -d "$build/tidy.XXXXXX")
trap 'rm -rf "$work"' EXIT
start=$SECONDS

# The units: a folder each with the files it checks (files), a source that
# includes them (unit.cpp) and its compile command (entry.json: the flags its
# files share).
printf '%s\n' "${files[@]/#/$PWD/}" | awk -v db="$db" -v work="$work" -v size="$batch" '
  BEGIN {
    while ((getline line < db) > 0) {
      if (line ~ /^  "directory": /) { dir = line; sub(/^  "directory": "/, "", dir); sub(/",$/, "", dir) }
      if (line ~ /^  "command": /) { cmd = line; sub(/^  "command": "/, "", cmd); sub(/",$/, "", cmd) }
      if (line ~ /^  "file": /) {
        f = line; sub(/^  "file": "/, "", f); sub(/"$/, "", f)
        flags = cmd; sub(/ -o [^ ]+ -c [^ ]+$/, "", flags); sub(/^[^ ]*ccache /, "", flags)
        flags_of[f] = flags; dir_of[f] = dir
      }
    }
  }
  {
    if (!($0 in flags_of)) { print "tidy.sh: " $0 " is not in " db > "/dev/stderr"; exit 3 }
    folder = $0; sub(/\/[^\/]*$/, "", folder)
    key = flags_of[$0] "\t" dir_of[$0] "\t" folder
    if (key != open_key || count >= size) {
      units++; open_key = key; count = 0
      unit = work "/u" units
      system("mkdir -p " unit)
      printf "{\"directory\": \"%s\", \"command\": \"%s -c %s/unit.cpp\", \"file\": \"%s/unit.cpp\"}\n",
        dir_of[$0], flags_of[$0], unit, unit > (unit "/entry.json")
    }
    count++
    print "#include \"" $0 "\"" > (unit "/unit.cpp")
    print $0 > (unit "/files")
  }'

# Checks a unit: its own files reported (header filter: those files; line
# filter: nothing of unit.cpp itself). A unit that does not compile as one
# (two of its files define the same internal name) is split in two, down to
# single files checked as they are.
check_unit() {
  local unit=$1 build=$2 own
  mapfile -t own < "$unit/files"
  if [[ ${#own[@]} -eq 1 ]]; then
    clang-tidy-14 -p "$build" --quiet "${own[0]}" > "$unit/log" 2>&1 || true
    return
  fi
  local filter names
  filter="^($(printf '%s|' "${own[@]}" | sed 's/[.+]/\\&/g; s/|$//'))\$"
  names=$(printf '{"name":"%s"},' "${own[@]}")
  printf '[%s]\n' "$(cat "$unit/entry.json")" > "$unit/compile_commands.json"
  clang-tidy-14 -p "$unit" --quiet --header-filter="$filter" --line-filter="[${names%,}]" \
    "$unit/unit.cpp" > "$unit/log" 2>&1 || true
  grep -qE ': error: ' "$unit/log" || return 0
  rm "$unit/log"
  local half=$(((${#own[@]} + 1) / 2)) part
  mkdir -p "$unit/a" "$unit/b"
  printf '%s\n' "${own[@]:0:half}" > "$unit/a/files"
  printf '%s\n' "${own[@]:half}" > "$unit/b/files"
  for part in "$unit/a" "$unit/b"; do
    sed 's/.*/#include "&"/' "$part/files" > "$part/unit.cpp"
    sed "s#$unit/unit.cpp#$part/unit.cpp#g" "$unit/entry.json" > "$part/entry.json"
    check_unit "$part" "$build"
  done
}
export -f check_unit
units=$(ls -d "$work"/u* | wc -l)
echo "tidy.sh: ${#files[@]} files in $units units, $(nproc) at a time"
ls -d "$work"/u* | xargs -P "$(nproc)" -I{} bash -c 'check_unit "$@"' _ {} "$build"

logs=$(find "$work" -name log | sort)
# shellcheck disable=SC2086 # one log path per word
warnings=$(cat $logs | grep -cE ': (warning|error): ' || true)
# shellcheck disable=SC2086
cat $logs | grep -vE '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$' |
  grep -vE '^Suppressed|^Use -header-filter|^$' || true
echo "tidy.sh: ${#files[@]} files in $((SECONDS - start)) s, $warnings warnings"
[[ "$warnings" -eq 0 ]]
