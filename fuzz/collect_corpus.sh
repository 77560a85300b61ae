#!/usr/bin/env bash
# Collects the seed corpus of each fuzz target from the tests' own inputs
# into BUILD_DIR/seeds/<target>/ (nothing is copied into the repository).
# Long programs are cut to their first 4 KB: the fuzzer mutates small
# inputs faster, and a prefix still has the header and typical blocks.
# The saved regression inputs (fuzz/regressions/<target>/) are seeds too.
# Usage: fuzz/collect_corpus.sh BUILD_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: collect_corpus.sh BUILD_DIR}/seeds"
shared="${VCPOST_SHARED_DATA_DIR:-$root/../shared/data}"
rm -rf "$out"
mkdir -p "$out"/{gcode_fuzz,cldata_fuzz,profile_fuzz}

# copy TARGET FILE...: each file under a name that keeps its origin.
copy() {
  local target="$1"
  shift
  local f
  for f in "$@"; do
    [ -f "$f" ] || continue
    local name="${f#"$root"/}"
    head -c 4096 "$f" >"$out/$target/${name//\//_}"
  done
}

shopt -s nullglob
copy gcode_fuzz "$root"/tests/postproc/bad/gcode/* "$root"/tests/postproc/gcode/programs/* \
  "$root"/samples/*.nc "$root"/fuzz/regressions/gcode_fuzz/*
copy cldata_fuzz "$root"/tests/postproc/bad/cldata/* "$root"/samples/*.cls \
  "$root"/fuzz/regressions/cldata_fuzz/*
copy profile_fuzz "$root"/machines/profiles/*.toml "$root"/tests/machines/bad/*.toml \
  "$root"/fuzz/regressions/profile_fuzz/*
# Real programs from public projects when the shared data folder is there.
if [ -d "$shared" ]; then
  copy gcode_fuzz "$shared"/gcode/*.ngc "$shared"/gcode/*.nc "$shared"/gcode/*.gcode \
    "$shared"/gcode/*.EIA
  copy cldata_fuzz "$shared"/cldata/*.apt "$shared"/cldata/*.cls "$shared"/cldata/*.clsf \
    "$shared"/cldata/*.ncl
fi
for t in gcode_fuzz cldata_fuzz profile_fuzz; do
  echo "seeds: $t $(ls "$out/$t" | wc -l) files"
done
