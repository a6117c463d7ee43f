#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass pass 2, packed normals, a light with a shadow map.
#define FE_SHADOWED
#include "fe_lpp_light_pass.glsl"
