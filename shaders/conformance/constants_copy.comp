#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Copies the 128 bytes of per-draw constants into a storage buffer (compute reads them too).
layout(local_size_x = 8) in;
FE_CONSTANTS(Values) { uvec4 v[8]; } values;
layout(binding = 0, std430) buffer Out { uvec4 outValues[8]; };
void main() { outValues[gl_LocalInvocationIndex] = values.v[gl_LocalInvocationIndex]; }
