#!/usr/bin/env bash
# Installs everything vcpost needs to build and test, from Debian 12 packages.
# Idempotent: packages already present are skipped, so a second run is quick.
# Runs as root without prompts (sudo is used when not root and available).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev
  libtomlplusplus-dev nlohmann-json3-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libocct-data-exchange-dev libocct-modeling-algorithms-dev
  libocct-modeling-data-dev libocct-foundation-dev
  linuxcnc-uspace time
  # the report's charting library (inlined into its HTML) and the browser that tests the page
  libjs-chart.js chromium
  # fuzzing (scripts/fuzz.sh): clang with libFuzzer and its sanitizer runtimes
  clang-14 libclang-rt-14-dev
  # scripts/format-check.sh and .clang-tidy
  clang-format-14 clang-tidy-14
  # the Debian package (scripts/package-test.sh): CPack's dependency scan
  # (dpkg-shlibdeps, file), its check (lintian) and the man pages (man-db)
  dpkg-dev file lintian man-db
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
