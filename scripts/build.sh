#!/usr/bin/env bash
# Installs a layer of the dependencies (scripts/setup.sh) and builds the
# release preset into build/release/.
# Usage: scripts/build.sh [demo|test]   (default test)
#   demo  the demo layer; the command, the library and the man pages only
#   test  the test layer; everything, the tests and benchmarks included
# VCPOST_WERROR=ON in the environment makes warnings errors (CI does).
set -euo pipefail
cd "$(dirname "$0")/.."
layer="${1:-test}"
case "$layer" in
  demo) with_tests=OFF ;;
  test) with_tests=ON ;;
  *) echo "usage: scripts/build.sh [demo|test]" >&2; exit 2 ;;
esac
bash scripts/setup.sh "$layer"
cmake --preset release -DVCPOST_BUILD_TESTS="$with_tests" -DVCPOST_BUILD_BENCH="$with_tests" \
  -DVCPOST_WERROR="${VCPOST_WERROR:-OFF}" >/dev/null
cmake --build --preset release -j "$(nproc)"
