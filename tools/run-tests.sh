#!/usr/bin/env bash
# Quick start, command 2: install, build, run the whole test suite (CTest) on every backend.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
cd build
# --timeout: a test that hangs fails after 10 minutes (the slowest takes about 2 on 2 cores)
# instead of holding the run.
ctest --output-on-failure --timeout 600 -j"$(nproc)" "$@"
