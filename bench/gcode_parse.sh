#!/bin/sh
# Parse + interpret speed of vcpost against LinuxCNC's rs274 on the same
# plain 3-axis G1 program, in the same run. Usage:
#   bench/gcode_parse.sh [BUILD_DIR] [LINES]     (defaults: build/release, 2000000)
set -eu
build=${1:-build/release}
lines=${2:-2000000}
vcpost=$build/postproc/cli/vcpost
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
file=$work/plain.ngc
awk -v n="$lines" 'BEGIN {
  print "G21 G90 G17"; print "S12000 M3"; print "G0 X0 Y0 Z5"; print "G1 Z0 F1500"
  for (i = 0; i < n; i++) printf "G1 X%.3f Y%.3f Z%.3f\n", (i % 1000) * 0.1, int(i / 1000) * 0.25, -0.001 * (i % 97)
  print "M30" }' > "$file"
total=$((lines + 5))
now() { date +%s.%N; }
t0=$(now); "$vcpost" moves --count "$file" > "$work/v.txt"; t1=$(now)
if command -v rs274 > /dev/null; then
  rs274 -g "$file" < /dev/null > /dev/null 2>&1; t2=$(now)
else
  t2=""
fi
awk -v n="$total" -v t0="$t0" -v t1="$t1" -v t2="$t2" 'BEGIN {
  v = n / (t1 - t0); printf "vcpost moves --count: %d lines in %.3f s = %.2f M lines/s\n", n, t1 - t0, v / 1e6
  if (t2 != "") { r = n / (t2 - t1); printf "rs274 -g:             %d lines in %.3f s = %.2f M lines/s\n", n, t2 - t1, r / 1e6
                  printf "ratio vcpost/rs274: %.1f\n", v / r } else print "rs274 not installed" }'
