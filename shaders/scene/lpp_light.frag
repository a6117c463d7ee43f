#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass pass 2, packed normals (the body: fe_lpp_light_pass.glsl).
#include "fe_lpp_light_pass.glsl"
