#!/usr/bin/env bash
# Quick start, command 2: install, build, run the whole test suite (CTest) on every backend.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
