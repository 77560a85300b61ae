#!/usr/bin/env bash
# Sets up, builds, and runs vcpost on the bundled samples: the constant-vc
# post of finishing programs (G-code and APT CL) against their STEP models
# for a Mazak-like 3-axis machine with an HTML report of each, and the
# working-diameter model at the paper's set-up. Results go to out/.
# Installs the demo layer only (scripts/setup.sh demo): no test tools.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh demo >/dev/null
vcpost=build/release/postproc/cli/vcpost
mkdir -p out

# No --tool: the programs name their tool, the G-code in a Fusion 360
# comment "(T1 D=10. CR=5. - ball end mill)", the CL in CUTTER/.
post() {  # program model vc ap output
  echo "== vcpost post $1 --model $2 --vc $3 --ap $4 --machine mazak-3axis"
  "$vcpost" post "$1" --model "$2" --vc "$3" --ap "$4" --machine mazak-3axis \
    -o "out/$5" --summary-json "out/${5%.*}.summary.json" --report "out/${5%.*}.html"
  echo "   wrote out/$5, out/${5%.*}.summary.json and the report out/${5%.*}.html"
}
post samples/wavy_raster_a0_ae2.nc samples/wavy.step 120 0.3 wavy_raster.ccs.nc
post samples/cylinder_r100_ae0.5_a45.cls samples/cylinder.step 150 0.2 cylinder_a45.ccs.nc
post samples/dome_iso_rings.nc samples/dome.step 120 0.3 dome_rings.ccs.nc
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
