#version 450
#extension GL_GOOGLE_include_directive : require
// The display pass tone-mapped by the ACES fit (fe_display_pass.glsl).
#define FE_TONEMAP 1
#include "fe_display_pass.glsl"
