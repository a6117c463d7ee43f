#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred image-based lighting (sampled: fe_deferred_ibl_pass.glsl).
#include "fe_deferred_ibl_pass.glsl"
