#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass pass 2 with the unpacked RGBA16F normal target, to measure what packing costs.
#define FE_LPP_UNPACKED 1
#include "fe_lpp_light_pass.glsl"
