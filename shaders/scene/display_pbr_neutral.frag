#version 450
#extension GL_GOOGLE_include_directive : require
// The display pass tone-mapped by Khronos PBR Neutral (fe_display_pass.glsl).
#define FE_TONEMAP 2
#include "fe_display_pass.glsl"
