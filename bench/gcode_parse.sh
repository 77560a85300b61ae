#!/bin/sh
# Parse + interpret speed and memory of `vcpost moves` against LinuxCNC's
# rs274 on the same plain 3-axis G1 program, in the same run. Usage:
#   bench/gcode_parse.sh [BUILD_DIR] [LINES]     (defaults: build/release, 2000000)
#
# Speed: lines per second of CPU time (user + sys, from wait4 via GNU time),
# which a shared machine's load does not change much; wall time is printed
# beside it with the load average. Memory: the maximum resident size of
# `vcpost moves --count` on LINES/10 and LINES lines; the script fails when
# the longer program needs more than 4 MB more (streaming: it must not grow
# with the program's length).
set -eu
build=${1:-build/release}
lines=${2:-2000000}
vcpost=$build/postproc/cli/vcpost
[ -x "$vcpost" ] || { echo "gcode_parse.sh: $vcpost not built" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "gcode_parse.sh: needs GNU time (/usr/bin/time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The program: LINES moves of 0.1 mm, 1000 per row, with a wavy Z.
generate() {
  awk -v n="$1" 'BEGIN {
    print "G21 G90 G17"; print "S12000 M3"; print "G0 X0 Y0 Z5"; print "G1 Z0 F1500"
    for (i = 0; i < n; i++) printf "G1 X%.3f Y%.3f Z%.3f\n", (i % 1000) * 0.1, int(i / 1000) * 0.25, -0.001 * (i % 97)
    print "M30" }' > "$2"
}
generate "$lines" "$work/plain.ngc"
generate $((lines / 10)) "$work/short.ngc"
total=$((lines + 5))

# Prints "wall cpu maxrss_kb" of one run; the command's output is discarded.
measure() {
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$@" > /dev/null 2>&1 < /dev/null || true
  awk '{ printf "%s %.3f %s\n", $1, $2 + $3, $4 }' "$work/time"
}

echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "program: $total lines, $(wc -c < "$work/plain.ngc") bytes, plain 3-axis G1"
# shellcheck disable=SC2046
set -- $(measure "$vcpost" moves --count "$work/plain.ngc")
v_wall=$1 v_cpu=$2 v_rss=$3
awk -v n="$total" -v w="$v_wall" -v c="$v_cpu" -v m="$v_rss" 'BEGIN {
  printf "vcpost moves --count: CPU %.3f s = %.2f M lines/s CPU; wall %.3f s = %.2f M lines/s; max RSS %.1f MB\n",
         c, n / c / 1e6, w, n / w / 1e6, m / 1024 }'

if command -v rs274 > /dev/null; then
  # shellcheck disable=SC2046
  set -- $(measure rs274 -g "$work/plain.ngc")
  r_wall=$1 r_cpu=$2
  awk -v n="$total" -v w="$r_wall" -v c="$r_cpu" -v vc="$v_cpu" -v vw="$v_wall" 'BEGIN {
    printf "rs274 -g:             CPU %.3f s = %.2f M lines/s CPU; wall %.3f s = %.2f M lines/s\n",
           c, n / c / 1e6, w, n / w / 1e6
    printf "ratio vcpost/rs274: %.1f (CPU), %.1f (wall)\n", c / vc, w / vw }'
  # rs274 must have read the whole file, not stopped at an error.
  rs274 -g "$work/short.ngc" < /dev/null 2>&1 | grep "PROGRAM_END" >/dev/null ||
    echo "warning: rs274 did not reach PROGRAM_END on the short program"
else
  echo "rs274 not installed (linuxcnc-uspace): no comparison"
fi

# shellcheck disable=SC2046
set -- $(measure "$vcpost" moves --count "$work/short.ngc")
s_rss=$3
awk -v a="$s_rss" -v b="$v_rss" -v n="$lines" 'BEGIN {
  d = (b - a) / 1024
  printf "memory: max RSS %.1f MB at %d lines, %.1f MB at %d lines: +%.1f MB (bound 4 MB) %s\n",
         a / 1024, n / 10, b / 1024, n, d, d <= 4 ? "ok" : "FAILED"
  exit d <= 4 ? 0 : 1 }'
