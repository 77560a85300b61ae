#!/usr/bin/env bash
# Installs the dependencies (scripts/setup.sh) and builds the release preset.
# VCPOST_WERROR=ON in the environment makes warnings errors (CI does).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release -DVCPOST_WERROR="${VCPOST_WERROR:-OFF}" >/dev/null
cmake --build --preset release -j "$(nproc)"
