#!/usr/bin/env bash
# Sets up the test layer (scripts/setup.sh test: the demo's packages, the
# test frameworks, LinuxCNC's rs274, chromium), builds everything and runs
# the whole test suite (what CI runs first).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh test
ctest --preset release -j "$(nproc)"
