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
mkdir -p "$out"/{gcode_fuzz,cldata_fuzz,profile_fuzz,verify_fuzz,stl_fuzz}

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
# verify_fuzz: programs alone (checked against themselves patched in S) and
# each sample with a copy of itself, input and output joined by the separator line
# of fuzz/verify_driver.h.
copy verify_fuzz "$root"/samples/*.nc "$root"/tests/postproc/gcode/programs/* \
  "$root"/fuzz/regressions/verify_fuzz/*
for original in "$root"/samples/*.nc "$root"/samples/*.cls; do
  [ -f "$original" ] || continue
  { head -c 2048 "$original"; printf '\n%%%%vcpost-output%%%%\n'; head -c 2048 "$original"; } \
    >"$out/verify_fuzz/pair_$(basename "$original")"
done
# stl_fuzz: small STL files (binary and ASCII) whole: a cut binary STL is
# only ever a size error.
for f in $(find "$root"/tests "$root"/samples "$root"/fuzz/regressions/stl_fuzz -name '*.stl' 2>/dev/null) \
  "$shared"/stl/*.stl "$shared"/*/*.stl; do
  [ -f "$f" ] || continue
  [ "$(stat -c %s "$f")" -le 65536 ] || continue
  name="${f#"$root"/}"
  cp "$f" "$out/stl_fuzz/${name//\//_}"
done
# Real programs from public projects when the shared data folder is there.
if [ -d "$shared" ]; then
  copy gcode_fuzz "$shared"/gcode/*.ngc "$shared"/gcode/*.nc "$shared"/gcode/*.gcode \
    "$shared"/gcode/*.EIA
  copy cldata_fuzz "$shared"/cldata/*.apt "$shared"/cldata/*.cls "$shared"/cldata/*.clsf \
    "$shared"/cldata/*.ncl
fi
for t in gcode_fuzz cldata_fuzz profile_fuzz verify_fuzz stl_fuzz; do
  echo "seeds: $t $(ls "$out/$t" | wc -l) files"
done
