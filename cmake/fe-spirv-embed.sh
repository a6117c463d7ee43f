#!/bin/sh
# fe_add_shaders' Vulkan step: the SPIR-V glslang wrote, optimized by spirv-opt's performance
# passes, embedded as a C array (the form glslangValidator --vn writes).
#   fe-spirv-embed.sh SPIRV_OPT IN.spv OUT.h NAME
# Why: lavapipe compiles the SPIR-V as given, and glslang's is unoptimized (every local in memory,
# every call a function): forward-plus at 1280x720 with 512 lights took 68 ms a frame on lavapipe
# from glslang's SPIR-V and 59.5-67 ms from spirv-opt's, the image byte for byte the same;
# Mesa's GL path optimizes its own input, so the GL encoding is left as glslang wrote it (no
# change measured there). Bindings and specialization constants are kept even where unused, so
# that both encodings reflect the same interface (the same errors on every backend).
# Graphics stages only (FeShaders.cmake): optimizing the compute shaders gained nothing measurable
# (the light-culling pass) and broke one on lavapipe: tiled_deferred.comp's lights-in-storage
# variant shaded a sixth of the pixels wrong at 65,536 lights (Stability suite) once spirv-opt
# 2023.1's ssa-rewrite had run, with no undefined value in its output.
set -e
opt=$1 in=$2 out=$3 name=$4
"$opt" -O --preserve-bindings --preserve-spec-constants --target-env=vulkan1.2 "$in" -o "$in.opt"
{
  echo "#pragma once"
  echo "const uint32_t $name[] = {"
  # SPIR-V words in the machine's byte order, as the build machine runs the engine's tools.
  od -An -v -tx4 -w32 "$in.opt" | sed -e 's/^ *//' -e 's/ *$//' -e 's/\([0-9a-f]\{8\}\)/0x\1,/g'
  echo "};"
} > "$out.tmp"
mv "$out.tmp" "$out"
