#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred image-based lighting, the fast path (prefiltered cube, split-sum table, SH irradiance).
#define FE_IBL_PREFILTERED
#include "fe_deferred_ibl_pass.glsl"
