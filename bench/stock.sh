#!/bin/sh
# End to end `vcpost post` with an in-process stock (issue 44): a 300 x 300
# mm level part, ROUGH points of a D20 flat end mill (31 passes along X, 10
# mm apart, 0.5 mm above the face) then FINISH points of a D10 ball (passes
# 0.3 mm apart on the face), the stock a block at --stock-cell 0.1 mm (9 M
# cells). Prints wall and CPU time and GNU time's max RSS of the post with
# the stock and of the same post without it. Usage:
#   bench/stock.sh [BUILD_DIR] [ROUGH] [FINISH]   (defaults: build/release, 1000000, 1000000)
set -eu
build=${1:-build/release}
rough=${2:-1000000}
finish=${3:-1000000}
vcpost=$build/postproc/cli/vcpost
[ -x "$vcpost" ] || { echo "stock.sh: $vcpost not built" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "stock.sh: needs GNU time (/usr/bin/time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

awk -v rough="$rough" -v finish="$finish" 'BEGIN {
  print "G21 G90 G17 G94"
  print "T1 M6"; print "S6000 M3"
  passes = 31; per = int(rough / passes)
  for (p = 0; p < passes; p++) {
    y = p * 10; printf "G0 X0 Y%.3f Z20\nG1 Z0.5 F3000\n", y
    for (i = 1; i <= per; i++) printf "G1 X%.4f\n", (p % 2 ? per - i : i) * 300 / per
    print "G0 Z20"
  }
  print "T2 M6"; print "S8000 M3"
  passes = 1000; per = int(finish / passes)
  for (p = 0; p < passes; p++) {
    y = p * 0.3; printf "G0 X0 Y%.3f Z20\nG1 Z0 F3000\n", y
    for (i = 1; i <= per; i++) printf "G1 X%.3f\n", i * 300 / per
    print "G0 Z20"
  }
  print "M5"; print "M30" }' > "$work/part.ngc"
cat > "$work/face.stl" <<'STL'
solid face
facet normal 0 0 1
outer loop
vertex -10 -10 0
vertex 310 -10 0
vertex 310 310 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex -10 -10 0
vertex 310 310 0
vertex -10 310 0
endloop
endfacet
endsolid face
STL

job="$work/part.ngc --model $work/face.stl --tool T1=flat:20 --tool T2=ball:10 --vc 200 --ap 0.3 --machine generic -q"
measure() {
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$@" > /dev/null 2> "$work/err" < /dev/null ||
    { cat "$work/err" >&2; exit 1; }
  awk '{ printf "wall %.2f s, CPU %.2f s, max RSS %.0f MB\n", $1, $2 + $3, $4 / 1024 }' "$work/time"
}
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "program: $(grep -c '^G1 X' "$work/part.ngc") cutting points ($rough roughing, $finish finishing), $(wc -c < "$work/part.ngc") bytes"
# shellcheck disable=SC2086
echo "with --stock-box 0,0,-10,300,300,3 --stock-cell 0.1: $(measure "$vcpost" post $job --stock-box 0,0,-10,300,300,3 --stock-cell 0.1 -o "$work/out.ngc")"
# shellcheck disable=SC2086
echo "without a stock:                                  $(measure "$vcpost" post $job -o "$work/plain.ngc")"
# shellcheck disable=SC2086
"$vcpost" post $job --stock-box 0,0,-10,300,300,3 --stock-cell 0.1 --summary-json "$work/s.json" -o "$work/out.ngc" 2>/dev/null
python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['stock']; print('stock: %d x %d cells, %.0f MB, built in %.2f s; ap from the stock at %d points, max %.3f mm' % (s['cells'][0], s['cells'][1], s['memory_bytes']/2**20, s['build_s'], s['points']['stock'], s['ap_max_mm']))" "$work/s.json" 2>/dev/null || true
