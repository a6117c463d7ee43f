#!/usr/bin/env bash
# Quick start, command 2: install, build, run the whole test suite (CTest) on every backend.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
cd build
# --timeout: a test that hangs fails after 10 minutes (the slowest takes about 2 on 2 cores)
# instead of holding the run. One test more than the cores: a test waiting (on an X server, a
# child process, Chromium) leaves its core to the others (2 cores: 323 s at -j3, 351 s at -j2).
ctest --output-on-failure --timeout 600 -j"$(($(nproc) + 1))" "$@"
