#!/usr/bin/env bash
# Quick start, command 1: install, build, render the default scene on the best available backend.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p out
./build/tools/fe render --out out/default.png "$@"
echo "wrote out/default.png"
