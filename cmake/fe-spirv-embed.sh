#!/bin/sh
# fe_add_shaders' step after glslang for a graphics stage: the SPIR-V glslang wrote, optimized by
# spirv-opt's performance passes, embedded as a C array (the form glslangValidator --vn writes).
#   fe-spirv-embed.sh SPIRV_OPT TARGET_ENV IN.spv OUT.h NAME   (TARGET_ENV: vulkan1.2, opengl4.5)
# Why: lavapipe compiles the SPIR-V as given, and glslang's is unoptimized (every local in memory,
# every call a function): forward-plus at 1280x720 with 512 lights took 68 ms a frame on lavapipe
# from glslang's SPIR-V and 59.5-67 ms from spirv-opt's, the image byte for byte the same.
# Both encodings go through it, so that they stay made alike: the optimizer drops code whose
# result is unused, and with it the uses of resources only that code read, which the reflection
# of the bindings a shader uses (ShaderReflection.h) then leaves out; one encoding optimized and
# not the other reflected 12 and 15 bindings for forward_plus.frag, and so different errors on
# different backends. (Mesa's GL path optimizes its own input: no change measured there.)
# Bindings and specialization constants are kept in the module even where unused.
# Graphics stages only (FeShaders.cmake): optimizing the compute shaders gained nothing measurable
# (the light-culling pass) and broke one on lavapipe: tiled_deferred.comp's lights-in-storage
# variant shaded a sixth of the pixels wrong at 65,536 lights (Stability suite) once spirv-opt
# 2023.1's ssa-rewrite had run, with no undefined value in its output.
set -e
opt=$1 env=$2 in=$3 out=$4 name=$5
"$opt" -O --preserve-bindings --preserve-spec-constants --target-env="$env" "$in" -o "$in.opt"
{
  echo "#pragma once"
  echo "const uint32_t $name[] = {"
  # SPIR-V words in the machine's byte order, as the build machine runs the engine's tools.
  od -An -v -tx4 -w32 "$in.opt" | sed -e 's/^ *//' -e 's/ *$//' -e 's/\([0-9a-f]\{8\}\)/0x\1,/g'
  echo "};"
} > "$out.tmp"
mv "$out.tmp" "$out"
