#!/usr/bin/env bash
# Packs what a lent NVIDIA machine needs to run the built engine, its tests and its benchmarks
# (docs/BENCHMARKS.md, "On NVIDIA"): stripped binaries at their build/ paths (the tests name
# them by absolute path), the Debian 12 libraries the image lacks, and the Khronos validation
# layer. Writes .gpubundle/bundle.tar.gz (git-ignored; the device tool carries it).
#   tools/gpu/make-bundle.sh        (after a build in build/)
set -euo pipefail
cd "$(dirname "$0")/../.."
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
binaries=(tools/fe tests/fe_unit_tests tests/fe_execution_tests tests/fe_stability_tests tests/fe_tool_tests
          bench/fe_bench_execution bench/fe_bench_abstraction)
for b in "${binaries[@]}"; do
  mkdir -p "$stage/build/$(dirname "$b")"
  strip -o "$stage/build/$b" "build/$b"
done
# Every shared library they load except the C runtime and the GL/Vulkan loaders, which come
# from the driver's side (.gl/, README of the device tool).
mkdir -p "$stage/gpu-libs/layers"
for b in "${binaries[@]}"; do ldd "build/$b"; done | awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -v -E '/(libc|libm|libgcc_s|libstdc\+\+|libvulkan|ld-linux)[.-]' | while read -r lib; do cp -L "$lib" "$stage/gpu-libs/"; done
cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$stage/gpu-libs/"
cp /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json "$stage/gpu-libs/layers/"
mkdir -p .gpubundle
tar -C "$stage" -czf .gpubundle/bundle.tar.gz build gpu-libs
ls -la .gpubundle/bundle.tar.gz
