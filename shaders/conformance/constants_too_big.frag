#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// A constants block of 144 bytes, over the device's 128: pipelines using it are refused.
FE_CONSTANTS(TooBig) { vec4 v[9]; } big;
layout(location = 0) out vec4 outColor;
void main() { outColor = big.v[8]; }
