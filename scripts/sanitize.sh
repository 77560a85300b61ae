#!/usr/bin/env bash
# Builds the "asan" preset (GCC, AddressSanitizer + UndefinedBehaviorSanitizer,
# -O1 -g1: line tables, enough for the reports' file:line) and runs the test
# suite under it. Any sanitizer report fails its test: UBSan does not
# recover, ASan stops at the first error, leaks are errors (LeakSanitizer).
# Leaks inside third-party libraries we do not build are suppressed by name
# in scripts/lsan.supp (one comment per entry).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test  # the test layer: the suite under the sanitizers
cmake --preset asan >/dev/null
cmake --build --preset asan -j "$(nproc)"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# LinuxCncSim times a posted program on LinuxCNC's controller: its subject is
# the machine, not vcpost's memory, and it waits on LinuxCNC for a minute.
ctest --preset asan -j "$(nproc)" -E '^LinuxCncSim\.'

