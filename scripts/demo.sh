#!/usr/bin/env bash
# Sets up, builds, and runs vcpost on the bundled samples: the working
# diameter at the paper's set-up, a sweep over the feed angle, and the batch
# of the paper's cases in samples/deff_cases.csv. Results go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
vcpost=build/release/postproc/cli/vcpost
mkdir -p out

echo "== The paper's set-up: D = 10 ball, ap 0.3, ae 0.5, tilt 25, azimuth 35, feed angle 90 =="
"$vcpost" deff --tool ball:10 --ap 0.3 --ae 0.5 --tilt 25 --azimuth 35 --feed-angle 90 \
  --side left --vc 120 --radius
echo
echo "== Sweep over the feed angle (the paper's Fig. 8 set-up, ap 1) =="
"$vcpost" deff --tool ball:10 --ap 1 --ae 0.5 --tilt 25 --azimuth 35 --side left \
  --sweep feed-angle=0:360:15 >out/sweep-feed-angle.csv
head -5 out/sweep-feed-angle.csv
echo "... $(($(wc -l <out/sweep-feed-angle.csv) - 1)) rows in out/sweep-feed-angle.csv"
echo
echo "== Batch: samples/deff_cases.csv =="
"$vcpost" deff --batch samples/deff_cases.csv >out/deff_cases.csv
echo "$(($(wc -l <out/deff_cases.csv) - 1)) cases written to out/deff_cases.csv"
