#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred image-based lighting into the I-buffer, the fast path.
#define FE_IBL_PREFILTERED
#include "fe_illumination_ibl_pass.glsl"
