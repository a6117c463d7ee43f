#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred image-based lighting into the I-buffer (sampled: fe_illumination_ibl_pass.glsl).
#include "fe_illumination_ibl_pass.glsl"
