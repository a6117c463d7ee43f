#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred illumination of a point light with a shadow cube.
#define FE_SHADOWED
#define FE_SHADOW_CUBE
#include "fe_illumination_pass.glsl"
