#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred image-based lighting, L_dg alone (per-source rates).
#define FE_IBL_DIFFUSE_ONLY
#include "fe_illumination_ibl_pass.glsl"
