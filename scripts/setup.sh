#!/usr/bin/env bash
# Installs what vcpost needs from Debian 12 packages, in three layers, each
# with the ones before it:
#   demo  building vcpost and running it (scripts/demo.sh)
#   test  + the test suite and the benchmarks: GoogleTest, Google Benchmark,
#         LinuxCNC's rs274 and a browser the tests compare with (scripts/test.sh)
#   dev   + CI and development: clang-format, clang-tidy, libFuzzer, the
#         Debian package's tools (.ci/run, scripts/fuzz.sh, package-test.sh)
# Usage: scripts/setup.sh [demo|test|dev]   (default dev: everything)
# Idempotent: packages already present are skipped, so a second run is quick.
# Runs as root without prompts (sudo is used when not root and available).
set -euo pipefail
layer="${1:-dev}"

demo=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev
  libtomlplusplus-dev nlohmann-json3-dev libtbb-dev libspdlog-dev
  libocct-data-exchange-dev libocct-modeling-algorithms-dev
  libocct-modeling-data-dev libocct-foundation-dev
  # the report's charting library, inlined into its HTML page
  libjs-chart.js
)
test=(
  libgtest-dev libgmock-dev libbenchmark-dev
  # LinuxCNC's rs274, the interpreter the tests compare with; the browser
  # that runs the report's page; GNU time for bench/scale.sh
  linuxcnc-uspace chromium time
)
dev=(
  # fuzzing (scripts/fuzz.sh): clang with libFuzzer and its sanitizer runtimes
  clang-14 libclang-rt-14-dev
  # scripts/format-check.sh and .clang-tidy
  clang-format-14 clang-tidy-14
  # the Debian package (scripts/package-test.sh): CPack's dependency scan
  # (dpkg-shlibdeps, file), its check (lintian) and the man pages (man-db)
  dpkg-dev file lintian man-db
)

case "$layer" in
  demo) packages=("${demo[@]}") ;;
  test) packages=("${demo[@]}" "${test[@]}") ;;
  dev) packages=("${demo[@]}" "${test[@]}" "${dev[@]}") ;;
  *) echo "usage: scripts/setup.sh [demo|test|dev]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages of the $layer layer present"
  exit 0
fi

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "setup ($layer layer): installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
