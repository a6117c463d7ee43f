#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass pass 2, packed normals, a point light with a shadow cube.
#define FE_SHADOWED
#define FE_SHADOW_CUBE
#include "fe_lpp_light_pass.glsl"
