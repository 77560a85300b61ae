#!/usr/bin/env bash
# Sets up, builds, and runs vcpost on the bundled samples: the constant-vc
# post of finishing programs (G-code and APT CL) against their STEP models
# for a Mazak-like 3-axis machine with an HTML report of each, and the
# working-diameter model at the paper's set-up. Results go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
vcpost=build/release/postproc/cli/vcpost
mkdir -p out

post() {  # program model tool vc ap output
  echo "== vcpost post $1 --model $2 --tool $3 --vc $4 --ap $5 --machine mazak-3axis"
  "$vcpost" post "$1" --model "$2" --tool "$3" --vc "$4" --ap "$5" --machine mazak-3axis \
    -o "out/$6" --summary-json "out/${6%.*}.summary.json" --report "out/${6%.*}.html"
  echo "   wrote out/$6, out/${6%.*}.summary.json and the report out/${6%.*}.html"
}
post samples/wavy_raster_a0_ae2.nc samples/wavy.step ball:10 120 0.3 wavy_raster.ccs.nc
post samples/cylinder_r100_ae0.5_a45.cls samples/cylinder.step ball:12 150 0.2 cylinder_a45.ccs.nc
post samples/dome_iso_rings.nc samples/dome.step ball:10 120 0.3 dome_rings.ccs.nc
echo
echo "== What changed in the wavy program (first S words):"
diff samples/wavy_raster_a0_ae2.nc out/wavy_raster.ccs.nc | grep '^>' | head -5 || true
echo
echo "== Working diameter at the paper's set-up (D 10 ball, ap 0.3, ae 0.5, tilt 25, azimuth 35, feed angle 90)"
"$vcpost" deff --tool ball:10 --ap 0.3 --ae 0.5 --tilt 25 --azimuth 35 --feed-angle 90 \
  --side left --vc 120 | grep -E 'D_max|D_min|D_mean|spindle'
"$vcpost" deff --tool ball:10 --ap 1 --ae 0.5 --tilt 25 --azimuth 35 --side left \
  --sweep feed-angle=0:360:15 >out/sweep-feed-angle.csv
echo "   sweep over the feed angle: out/sweep-feed-angle.csv"
