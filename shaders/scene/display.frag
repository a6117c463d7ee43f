#version 450
#extension GL_GOOGLE_include_directive : require
// The display pass tone-mapped by clamp (fe_display_pass.glsl).
#define FE_TONEMAP 0
#include "fe_display_pass.glsl"
