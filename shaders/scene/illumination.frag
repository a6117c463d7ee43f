#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred illumination, one light per volume fragment (fe_illumination_pass.glsl).
#include "fe_illumination_pass.glsl"
