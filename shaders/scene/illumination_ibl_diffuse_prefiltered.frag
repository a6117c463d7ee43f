#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred image-based lighting by the fast path, L_dg alone.
#define FE_IBL_PREFILTERED
#define FE_IBL_DIFFUSE_ONLY
#include "fe_illumination_ibl_pass.glsl"
