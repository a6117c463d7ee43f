#!/usr/bin/env bash
# Quick start, command 1: install, build, render the default scene on the best available backend.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p out
# The default scene: metals, shadows (a cascaded sun, a spot, a point light's cube) and a sky that
# also lights the scene (image-based lighting).
./build/tools/fe render builtin:shadows --environment builtin:sky --ibl-samples 256 --shadows on --out out/default.png "$@"
echo "wrote out/default.png"
