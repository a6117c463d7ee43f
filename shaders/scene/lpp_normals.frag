#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass pass 1, packed normals (the body: fe_lpp_normals_pass.glsl).
#include "fe_lpp_normals_pass.glsl"
