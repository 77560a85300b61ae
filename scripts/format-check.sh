#!/usr/bin/env bash
# Checks that every C++ file of the repository is formatted as .clang-format
# says (clang-format-14, Debian 12's). Lists the files that differ and fails.
# With --advisory it only reports and exits 0 (how .ci/run calls it until
# the tree has been formatted once; then drop --advisory there).
# To format a file: clang-format-14 -i FILE. Usage:
#   scripts/format-check.sh [--advisory] [FILE...]
set -euo pipefail
cd "$(dirname "$0")/.."
advisory=0
if [ "${1:-}" = "--advisory" ]; then
  advisory=1
  shift
fi
format=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$format" ]; then
  echo "format-check: clang-format-14 is missing (bash scripts/setup.sh installs it)" >&2
  exit 2
fi
if [ $# -gt 0 ]; then
  files=("$@")
else
  # (not tests/golden/: its .h files are Klartext programs, not C++)
  mapfile -t files < <(git ls-files '*.cpp' '*.h' ':!tests/golden/')
fi
bad=0
for f in "${files[@]}"; do
  if ! "$format" --style=file --dry-run -Werror "$f" >/dev/null 2>&1; then
    echo "format-check: $f differs from .clang-format"
    bad=$((bad + 1))
  fi
done
echo "format-check: $bad of ${#files[@]} files differ"
if [ "$bad" -gt 0 ] && [ "$advisory" -eq 0 ]; then
  exit 1
fi
exit 0
