#!/usr/bin/env bash
# The installed package used from outside the tree: `cmake --install` into a fresh prefix, the
# examples configured on their own against it (find_package(fe) 0.1: fe::gdi, fe::renderer,
# fe_add_shaders), built and run headless on every backend with validation on; then the
# turntable compiled again with nothing but pkg-config's flags, and the installed fe run.
#   package_consumer.sh BUILD_DIR SOURCE_DIR WORK_DIR [SANITIZERS]
# SANITIZERS: the build's FE_SANITIZE; its libraries need the consumer linked with them too.
set -euo pipefail
build=$1 src=$2 work=$3 sanitize=${4:-}
flags="" linkflags=""
if [ -n "$sanitize" ]; then
  # As the build does (cmake/FeSanitize.cmake): driver modules kept loaded, so leak reports
  # can be attributed and the driver suppressions match, and the same runtime defaults.
  flags="-fsanitize=$sanitize"
  linkflags="$flags $work/KeepModulesLoaded.o $work/SanitizerDefaults.o -Wl,--export-dynamic-symbol=dlclose"
fi
rm -rf "$work"
mkdir -p "$work"
if [ -n "$sanitize" ]; then
  for f in KeepModulesLoaded SanitizerDefaults; do cc -O2 -c "$src/tools/sanitizers/$f.c" -o "$work/$f.o"; done
fi
step() {  # runs a step quietly, showing its log when it fails
  local log=$1
  shift
  "$@" >"$log" 2>&1 || { cat "$log"; echo "package consumer: failed: $*"; exit 1; }
}
step "$work/install.log" cmake --install "$build" --prefix "$work/prefix"
step "$work/configure.log" cmake -S "$src/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$linkflags"
step "$work/build.log" cmake --build "$work/examples" -j2
for b in vulkan gl-egl gl-osmesa; do
  (cd "$work" && FE_BACKEND=$b "$work/examples/fe_example_quickstart" | grep -qF "drew a triangle on $b") ||
    { echo "package consumer: README's quick start did not draw on $b"; exit 1; }
  "$work/examples/fe_example_triangle" --backend "$b" --validation --out "$work/triangle_$b.png"
  "$work/examples/fe_example_turntable" --backend "$b" --validation --frames 2 --size 96x72 --out "$work/turntable_$b.png"
  "$work/examples/fe_example_turntable" builtin:crowd --backend "$b" --validation --frames 2 --size 96x72 \
    --out "$work/crowd_$b.png" >"$work/crowd_$b.txt"
  grep -qF "animation 'sway' played" "$work/crowd_$b.txt" || { echo "package consumer: the turntable did not play the crowd's animation"; exit 1; }
  "$work/examples/fe_example_threads" --backend "$b" --validation >"$work/threads_$b.txt"
  "$work/examples/fe_example_ported" --backend "$b" --validation >"$work/ported_$b.txt"
  "$work/examples/fe_example_materials" --backend "$b" --validation >"$work/materials_$b.txt"
  # HLSL built by the installed fe-hlsl, a geometry shader, tessellation (its first line names the backend).
  "$work/examples/fe_example_stages" --backend "$b" --validation --out "$work/stages_$b.png" | tail -n +2 >"$work/stages_$b.txt"
  grep -qF "every stage seen" "$work/stages_$b.txt" || { echo "package consumer: the stages example missed a stage on $b"; exit 1; }
  for want in "mistake 1: graphics pipeline 'triangles': tessellation shaders draw patches" \
              "mistake 2: pipeline 'no geometry': geometryShader is not a geometry shader" \
              "mistake 3: beginRenderPass: this list is for the copy queue" \
              "mistake 4: render pass: colour attachment 0 texture lacks RenderTarget usage"; do
    grep -qF "$want" "$work/stages_$b.txt" || { echo "package consumer: the stages example lacks '$want' on $b"; exit 1; }
  done
done
# Lists recorded on two threads and mistakes made on purpose: the same words on every backend.
for b in gl-egl gl-osmesa; do
  diff "$work/threads_vulkan.txt" "$work/threads_$b.txt" || { echo "package consumer: vulkan and $b disagree"; exit 1; }
  diff "$work/ported_vulkan.txt" "$work/ported_$b.txt" || { echo "package consumer: vulkan and $b disagree (ported)"; exit 1; }
  diff "$work/materials_vulkan.txt" "$work/materials_$b.txt" || { echo "package consumer: vulkan and $b disagree (materials)"; exit 1; }
  diff "$work/stages_vulkan.txt" "$work/stages_$b.txt" || { echo "package consumer: vulkan and $b disagree (stages)"; exit 1; }
  python3 "$src/tests/check_png.py" "$work/stages_$b.png" --like "$work/stages_vulkan.png" 0.01 >/dev/null ||
    { echo "package consumer: the stages images of vulkan and $b differ"; exit 1; }
done
cat "$work/threads_vulkan.txt" "$work/ported_vulkan.txt" "$work/materials_vulkan.txt"
# What the materials example must see: vertex colours at the top corners, the texture's black
# half at the bottom (second uv set, quarter-turn transform), two BRDFs, the default look, a pane
# of glass passing 1 - F0 of what is behind it, and the mistakes refused.
for want in "top left blue, top right green, bottom dark" "BRDFs differ: yes" \
            "default look: yes, 1 light(s), the sky lights it, corner transparent, quad opaque, 0 warning(s)" \
            "mistake 1: technique redeferred shades with the separable BRDF only" "mistake 2: scene refused: " \
            "mistake 3: an environment background needs an environment" \
            "the glass passes 96 % of the light behind it" "transmission must lie in [0, 1]" ; do
  grep -qF "$want" "$work/materials_vulkan.txt" || { echo "package consumer: materials example lacks '$want'"; exit 1; }
done
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"
# shellcheck disable=SC2046 # pkg-config's flags are words
c++ -O1 $flags -o "$work/turntable_pkgconfig" "$src/examples/turntable/main.cpp" $(pkg-config --cflags --libs fe) $linkflags
"$work/turntable_pkgconfig" --backend gl-osmesa --frames 1 --size 64x48 --out "$work/turntable_pkgconfig.png"
# (into a file, not a pipe: head closing the pipe early would fail fe with SIGPIPE under pipefail)
"$work/prefix/bin/fe" info --backend vulkan >"$work/info.txt"
head -2 "$work/info.txt"
echo "package consumer: built and ran against $work/prefix (fe $(pkg-config --modversion fe))"
