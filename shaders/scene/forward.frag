#version 450
#extension GL_GOOGLE_include_directive : require
// Forward shading (fe_forward_pass.glsl).
#include "fe_forward_pass.glsl"
