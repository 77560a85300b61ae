#!/usr/bin/env bash
# End-to-end figures of the report (issue 6): page size and time for a
# program of N points from the sample generator, against the same job
# writing no report, and that post without the model (issue 39: the
# normals from the toolpath; CPU time beside wall time, which a loaded
# machine inflates). Usage (from the repository root, after building vcpost
# and vcpost-samplegen in BUILD):
#   bash bench/report.sh [BUILD=build/release] [POINTS=1000000]
set -euo pipefail
build=${1:-build/release}
points=${2:-1000000}
vcpost=$build/postproc/cli/vcpost
samplegen=$build/postproc/samplegen/vcpost-samplegen
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$samplegen" path wavy --points "$points" --gcode "$work/big.nc" >/dev/null
options=(--tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -q)
job=("$work/big.nc" --model samples/wavy.step "${options[@]}")

seconds() {  # wall seconds of a command
  local start end
  start=$(date +%s.%N)
  "$@"
  end=$(date +%s.%N)
  echo "$end - $start" | bc
}

cpu() {  # "wall s, CPU s (user + sys)" of a command, by GNU time
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@"
  awk '{ printf "%.2f s, CPU %.2f s", $1, $2 + $3 }' "$work/time"
}

echo "program: $points points, $(stat -c %s "$work/big.nc") bytes"
echo "post, no report:       $(cpu "$vcpost" post "${job[@]}" -o "$work/out.nc")"
echo "post, no model:        $(cpu "$vcpost" post "$work/big.nc" "${options[@]}" -o "$work/out.nc")"
echo "report -o .json:       $(seconds "$vcpost" report "${job[@]}" -o "$work/r.json") s"
echo "report -o .html:       $(seconds "$vcpost" report "${job[@]}" -o "$work/r.html") s, page $(stat -c %s "$work/r.html") bytes"
echo "report -o .csv:        $(seconds "$vcpost" report "${job[@]}" -o "$work/r.csv") s, csv $(stat -c %s "$work/r.csv") bytes"
if command -v chromium >/dev/null; then
  echo "chromium load+draw:    $(seconds chromium --headless --no-sandbox --disable-gpu --no-first-run \
      --disable-background-networking --disable-component-update --disable-sync \
      --user-data-dir="$work/profile" --dump-dom "file://$work/r.html" >"$work/dom.html" 2>/dev/null) s" \
      "(selfcheck: $(grep -o '<pre id="selfcheck">[^<]*' "$work/dom.html" | sed 's/.*>//'))"
fi
