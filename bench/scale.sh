#!/usr/bin/env bash
# End-to-end scale figures (issue 7): `vcpost post` and `vcpost report` on
# sample-generator programs of 100 k, 1 M and 10 M points over three models
# of the same wavy mould surface (wavy.step: one B-spline face; patches.step:
# the same surface in 10 x 10 faces; wavy.stl: about 100 k triangles), and
# in the same run LinuxCNC's rs274 on the same G-code and a naive
# OpenCASCADE projection (bench/naive_projection) on a sample of points.
# Usage, from the repository root after building vcpost, vcpost-samplegen
# and naive_projection in BUILD:
#   bash bench/scale.sh [BUILD=build/release] [SIZE ...]   (default sizes: 100000 1000000 10000000)
# (VCPOST=..., SAMPLEGEN=..., NAIVE=... in the environment take those
# executables from elsewhere than BUILD. TOOL=bull:10:2 (any tool of
# `vcpost post --tool`: ball:D, bull:D:rc, flat:D) generates the programs
# for that tool, `vcpost-samplegen path --tool`, and posts them with it,
# instead of ball:10, the wavy part's own ball; a bull-nose or flat program
# takes longer to generate: its drop-cutter searches the tool's rim.)
#
# Every figure is one run measured with GNU time: wall seconds, CPU
# seconds (user + sys) and peak RSS. Points/s = program points / post wall
# seconds, parse, contact, working diameter, plan and write included. "x
# rs274" = rs274 wall / post wall on the same program (rs274 only
# interprets it). The naive projection's points/s is per query on the STEP
# models (one figure per model, sampled from the first size's program; it
# does not depend on the program's length); "x naive" = post points/s /
# naive points/s. A second table gives the same rates per CPU second: on a
# shared, loaded machine (the load average is printed) wall time grows with
# the others' work and CPU time much less. The model load time is that of
# a whole `vcpost post` on a 20-point program (an upper bound: process start
# and the tiny job included). At the end the issue's targets are checked
# (ok / MISSED) on programs of 1 M points and more; below that the fixed
# start (the model load above) weighs, and the rates are printed with and
# without it. The script exits 1 when a run failed, not when a target is
# missed.
set -euo pipefail

build=${1:-build/release}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(100000 1000000 10000000)

# VCPOST, SAMPLEGEN, NAIVE override the executables taken from BUILD.
vcpost=${VCPOST:-$build/postproc/cli/vcpost}
samplegen=${SAMPLEGEN:-$build/postproc/samplegen/vcpost-samplegen}
naive=${NAIVE:-$build/bench/naive_projection}
for exe in "$vcpost" "$samplegen" "$naive"; do
  [ -x "$exe" ] || {
    echo "scale.sh: $exe is not built (cmake --build $build --target vcpost vcpost-samplegen naive_projection)" >&2
    exit 2
  }
done
[ -x /usr/bin/time ] || { echo "scale.sh: needs GNU time (/usr/bin/time; scripts/setup.sh installs it)" >&2; exit 2; }
for size in "${sizes[@]}"; do
  [[ $size =~ ^[0-9]+$ && $size -ge 10 ]] || { echo "scale.sh: size '$size': a number of points >= 10 expected" >&2; exit 2; }
done
rs274=$(command -v rs274 || true)

work=$(mktemp -d "${TMPDIR:-/tmp}/vcpost_scale.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM
failed=0

# run NAME CMD...: runs CMD under GNU time; sets t_wall (s), t_cpu (s),
# t_rss (MB) and t_ok (0/1); stdout and stderr go to $work/NAME.log, whose
# tail is shown when the command fails.
run() {
  local name=$1
  shift
  local rc=0 user sys
  /usr/bin/time -f '%e %M %U %S' -o "$work/$name.time" "$@" > "$work/$name.log" 2>&1 < /dev/null || rc=$?
  read -r t_wall t_rss_kb user sys < <(tail -n 1 "$work/$name.time")
  t_cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
  t_rss=$(awk -v k="$t_rss_kb" 'BEGIN { printf "%.0f", k / 1024 }')
  if [ "$rc" -eq 0 ]; then
    t_ok=1
  else
    t_ok=0
    failed=1
    echo "scale.sh: $name failed (exit $rc after $t_wall s, CPU $t_cpu s, peak RSS $t_rss MB): $*" >&2
    tail -n 5 "$work/$name.log" | sed 's/^/    /' >&2
  fi
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), $(awk '/MemTotal/ { printf "%.1f GB", $2 / 1048576 }' /proc/meminfo)"
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "tool: ${TOOL:-ball:10} (programs generated and posted for it)"
echo "vcpost: $vcpost (repository at $(git -C "$(dirname "$0")/.." rev-parse --short HEAD 2>/dev/null || echo '?'))"
# How it was built: the figures depend on it.
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt" 2>/dev/null; }
echo "build: $(cache_value CMAKE_BUILD_TYPE) $(cache_value CMAKE_CXX_FLAGS), $(cache_value CMAKE_CXX_COMPILER | xargs -r basename)"

# gen LOG ARGS...: the sample generator, its messages in $work/LOG.log
# (shown, and the script stopped, when it fails).
gen() {
  local log=$work/$1.log
  shift
  "$samplegen" "$@" 2> "$log" || { echo "scale.sh: vcpost-samplegen $* failed:" >&2; cat "$log" >&2; exit 2; }
}
gen step step wavy "$work/wavy.step"
gen step step patches "$work/patches.step"
gen stl stl wavy "$work/wavy.stl" --triangles 100000
echo "models: wavy.step 1 face, patches.step 100 faces, wavy.stl $(grep -o '[0-9]* triangles' "$work/stl.log")"
models=(wavy.step patches.step wavy.stl)
tool=${TOOL:-ball:10}
job=(--tool "$tool" --vc 120 --ap 0.3 --machine mazak-3axis -q)

# STEP load: a whole post of a program of about 10 points, 1 mm apart in a
# 3 x 3 mm window: spread over the whole mould, 10 points are 20-25 mm
# apart and their straight moves cut into the surface and lift off it (a
# bull-nose post refuses that as a program that does not match the model).
gen gen path wavy --tool "$tool" --points 10 --window 50,30,53,33 --gcode "$work/tiny.nc"
declare -A load load_cpu
for model in wavy.step patches.step wavy.stl; do
  run "load_$model" "$vcpost" post "$work/tiny.nc" --model "$work/$model" "${job[@]}" -o "$work/tiny.out.nc"
  load[$model]=$([ "$t_ok" = 1 ] && echo "$t_wall" || echo fail)
  load_cpu[$model]=$t_cpu
done
echo "model load (vcpost post of a 20-point program): wavy.step ${load[wavy.step]} s" \
  "(CPU ${load_cpu[wavy.step]} s), patches.step ${load[patches.step]} s (CPU ${load_cpu[patches.step]} s)," \
  "wavy.stl ${load[wavy.stl]} s (CPU ${load_cpu[wavy.stl]} s)"

declare -A naive_rate naive_cpu_rate
rows=() cpu_rows=()
for size in "${sizes[@]}"; do
  if [ "$size" -ge 5000000 ]; then
    free_kb=$(df -Pk "$work" | awk 'NR == 2 { print $4 }')
    if [ "$free_kb" -lt $((3 * 1024 * 1024)) ]; then
      echo "skipping $size points: $((free_kb / 1024)) MB free in $work, 3 GB needed" >&2
      continue
    fi
  fi
  program=$work/p$size.nc
  gen gen path wavy --tool "$tool" --points "$size" --gcode "$program"
  points=$(grep -o '[0-9]* points' "$work/gen.log" | cut -d' ' -f1)
  lines=$(wc -l < "$program")
  echo "program: $points points, $lines lines, $(($(stat -c %s "$program") / 1048576)) MB (load average $(cut -d' ' -f1 /proc/loadavg))"

  r_wall=- r_rate=- r_cpu=-
  if [ -n "$rs274" ]; then
    run "rs274_$size" "$rs274" -g "$program"
    if [ "$t_ok" = 1 ] && grep -q PROGRAM_END "$work/rs274_$size.log"; then
      r_wall=$t_wall r_cpu=$t_cpu
      r_rate=$(awk -v n="$lines" -v w="$t_wall" 'BEGIN { printf "%.0f", (w > 0 ? n / w : 0) }')
    else
      echo "scale.sh: rs274 did not reach PROGRAM_END on $program" >&2
      grep -m3 -i error "$work/rs274_$size.log" | sed 's/^/    /' >&2 || true
    fi
    rm -f "$work/rs274_$size.log"  # its transcript is as large as the program
  fi

  for model in "${models[@]}"; do
    if [[ $model == *.step && -z ${naive_rate[$model]+x} ]]; then
      run "naive_$model" "$naive" "$work/$model" "$program" --sample 2000 --ball-radius 5 --max-seconds 30
      field() { awk -v f="$1" '/^naive_projection:/ { for (i = 1; i < NF; ++i) if ($i == f) print $(i + 1) }' "$work/naive_$model.log"; }
      naive_rate[$model]=$(field points_per_s)
      naive_cpu_rate[$model]=$(field points_per_cpu_s)
      [ "$t_ok" = 1 ] && [ -n "${naive_rate[$model]}" ] || naive_rate[$model]=-
      [ "$t_ok" = 1 ] && [ -n "${naive_cpu_rate[$model]}" ] || naive_cpu_rate[$model]=-
      echo "naive projection on $model: $(sed -n 's/^naive_projection: //p' "$work/naive_$model.log")"
    fi
    run "post_${model}_$size" "$vcpost" post "$program" --model "$work/$model" "${job[@]}" -o "$work/out.nc"
    p_ok=$t_ok p_wall=$t_wall p_rss=$t_rss p_cpu=$t_cpu
    rm -f "$work/out.nc"
    outputs=(-o "$work/r.json")
    [ "$size" -eq 1000000 ] && outputs+=(-o "$work/r.html")
    run "report_${model}_$size" "$vcpost" report "$program" --model "$work/$model" "${job[@]}" "${outputs[@]}"
    q_ok=$t_ok q_wall=$t_wall q_rss=$t_rss
    [ -f "$work/r.html" ] && html=" html $(($(stat -c %s "$work/r.html") / 1024)) KB" || html=
    rm -f "$work/r.json" "$work/r.html"
    rows+=("$(awk -v m="$model" -v n="$points" -v pok="$p_ok" -v pw="$p_wall" -v pr="$p_rss" \
      -v qok="$q_ok" -v qw="$q_wall" -v qr="$q_rss" -v rw="$r_wall" -v rr="$r_rate" \
      -v nv="${naive_rate[$model]:--}" -v html="$html" 'BEGIN {
        rate = (pok && pw > 0) ? n / pw : 0
        post = pok ? sprintf("%8.2f %10.0f %7d", pw, rate, pr) : sprintf("%8s %10s %7s", "FAIL", "-", "-")
        rep = qok ? sprintf("%8.2f %7d", qw, qr) : sprintf("%8s %7s", "FAIL", "-")
        vs = (rw != "-" && pok && pw > 0) ? sprintf("%6.2f", rw / pw) : sprintf("%6s", "-")
        xn = (nv != "-" && rate > 0) ? sprintf("%8.0f", rate / nv) : sprintf("%8s", "-")
        printf "%-13s %9d %s %s %8s %9s %s %10s %s%s", m, n, post, rep, rw, rr, vs, nv, xn, html }')")
    cpu_rows+=("$(awk -v m="$model" -v n="$points" -v pok="$p_ok" -v pc="$p_cpu" -v rc="$r_cpu" \
      -v nv="${naive_cpu_rate[$model]:--}" 'BEGIN {
        rate = (pok && pc > 0) ? n / pc : 0
        post = pok ? sprintf("%8.2f %10.0f", pc, rate) : sprintf("%8s %10s", "FAIL", "-")
        vs = (rc != "-" && rate > 0) ? sprintf("%8.2f", rc / pc) : sprintf("%8s", "-")
        xn = (nv != "-" && rate > 0) ? sprintf("%8.0f", rate / nv) : sprintf("%8s", "-")
        printf "%-13s %9d %s %8s %s %10s %s", m, n, post, rc, vs, nv, xn }')")
    if [ "$p_ok" = 1 ]; then
      echo "$model $points $p_wall $p_rss" >> "$work/post.txt"
    fi
  done
  rm -f "$program"
done

echo
printf "%-13s %9s %8s %10s %7s %8s %7s %8s %9s %6s %10s %8s\n" model points "post s" "post pt/s" "post MB" \
  "report s" "rep MB" "rs274 s" "rs274 l/s" "x rs274" "naive pt/s" "x naive"
for row in "${rows[@]}"; do echo "$row"; done
echo
echo "per CPU second (user + sys):"
printf "%-13s %9s %8s %10s %8s %8s %10s %8s\n" model points "post cpu" "post pt/s" "rs274" "x rs274" \
  "naive pt/s" "x naive"
for row in "${cpu_rows[@]}"; do echo "$row"; done
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"

# The issue's targets, from the rows measured.
echo
echo "targets (issue 7):"
check() {  # check TEXT OK
  printf "  %-62s %s\n" "$1" "$([ "$2" = 1 ] && echo ok || echo MISSED)"
}
if [ -f "$work/post.txt" ]; then
  while read -r model points wall rss; do
    rate=$(awk -v n="$points" -v w="$wall" 'BEGIN { printf "%.0f", (w > 0 ? n / w : 0) }')
    case $model in
      wavy.step) need=1000000 ;;
      patches.step) need=300000 ;;
      *) need=1000000 ;;
    esac
    if [ "$points" -ge 1000000 ]; then
      check "post $model $points points: $rate points/s >= $need" "$([ "$rate" -ge "$need" ] && echo 1 || echo 0)"
    else
      # A small program's run is mostly the fixed start (process, model
      # load): the rates are shown with and without it, not checked.
      net=$(awk -v n="$points" -v w="$wall" -v l="${load[$model]}" \
        'BEGIN { printf "%s", (l != "fail" && w > l ? sprintf("%.0f", n / (w - l)) : "-") }')
      printf "  %-62s %s\n" "post $model $points points: $rate points/s, $net after the start" \
        "(not checked: start ${load[$model]} s)"
    fi
    if [ "$points" -ge 5000000 ]; then
      check "post $model $points points: peak RSS $rss MB < 500" "$([ "$rss" -lt 500 ] && echo 1 || echo 0)"
    fi
  done < "$work/post.txt"
fi
if [ "${load[patches.step]}" != fail ]; then
  check "STEP load of the 100-face model: ${load[patches.step]} s < 2" \
    "$(awk -v t="${load[patches.step]}" 'BEGIN { print (t < 2 ? 1 : 0) }')"
fi
exit "$failed"
