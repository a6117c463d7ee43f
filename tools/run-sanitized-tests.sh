#!/usr/bin/env bash
# The test suite under AddressSanitizer (leak checking on) and UndefinedBehaviorSanitizer, in
# build-sanitize/ (all but the report and package labels, below). Any report fails the test that
# caused it. CI runs this after the suite.
# Suppressions are limited to the Mesa / Khronos driver modules; see tools/sanitizers/lsan.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFE_SANITIZE=address,undefined >/dev/null
cmake --build build-sanitize -j"$(nproc)"
here="$(pwd)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:detect_stack_use_after_return=0:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$here/tools/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$here/tools/sanitizers/ubsan.supp"
cd build-sanitize
# Every test but two labels whose work is not the engine's memory: report (the bench report in
# headless Chromium and matplotlib; the bench's own code runs in the cli_bench tests) and package
# (cmake --install and a consumer project built against it).
ctest --output-on-failure -j"$(nproc)" -LE "^(report|package)$" "$@"
