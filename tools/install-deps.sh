#!/usr/bin/env bash
# Installs the Debian 12 packages the engine needs to build, render and test.
# Idempotent: skips apt entirely when everything is already installed.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools
  glslang-dev                  # GLSL compiled at run time (createShader from source)
  libosmesa6 libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri
  libglfw3-dev libx11-dev libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  libzstd-dev                  # capture files (fe capture, fe replay)
  libturbojpeg0-dev            # JPEG textures (stb_image's JPEG decoder is not safe on hostile files)
  googletest libgtest-dev libbenchmark-dev
  xvfb xauth
  python3-matplotlib chromium  # fe bench: its charts, and the browser test of its report
  libimgui-dev                 # the UI renderer (fe view)
  libcli11-dev libspdlog-dev   # the fe command line and its logging
  libspirv-cross-c-shared-dev  # shader reflection (bindings, inputs, outputs) checked against pipelines
  spirv-tools                  # SPIR-V validated before reflection (SPIRV-Cross trusts its input)
  clang libclang-rt-14-dev     # the fuzzers (libFuzzer); gcc's own sanitizer runtimes come with g++
  clang-format                 # the house style (.clang-format), checked in CI (tools/check-format.sh)
  librenderdoc librenderdoc-dev python3-renderdoc  # fe render --renderdoc-capture, and its test
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep "install ok installed" >/dev/null || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
