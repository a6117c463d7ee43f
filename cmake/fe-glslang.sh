#!/bin/sh
# fe_add_shaders' compile step: glslangValidator ARGS..., and when it fails on a built-in that
# only one API has, the portable name to use instead (fe_common.glsl), after glslang's message.
#   fe-glslang.sh GLSLANG_VALIDATOR ARGS...
out=$("$@" 2>&1)
status=$?
[ -n "$out" ] && printf '%s\n' "$out"
if [ $status -ne 0 ]; then
  case "$out" in
    *gl_VertexIndex* | *gl_VertexID*)
      echo "fe: gl_VertexIndex is Vulkan's name and gl_VertexID GL's: write FE_VERTEX_ID (#include \"fe_common.glsl\"), which names the right one on each API and counts from firstVertex on both" ;;
  esac
  case "$out" in
    *gl_InstanceIndex* | *gl_InstanceID*)
      echo "fe: gl_InstanceIndex is Vulkan's name and gl_InstanceID GL's: write FE_INSTANCE_ID (#include \"fe_common.glsl\"), which counts from firstInstance on both" ;;
  esac
fi
exit $status
