#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred illumination of a light with a shadow map.
#define FE_SHADOWED
#include "fe_illumination_pass.glsl"
