#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a multisampled G-buffer, edge pixels shaded per sample: fe_gbuffer.glsl)
// fe-variant: FE_MULTISAMPLED+FE_OCCLUSION (... with the occlusion target, multisampled too)
// Deferred image-based lighting, the fast path (prefiltered cube, split-sum table, SH irradiance).
#define FE_IBL_PREFILTERED
#include "fe_deferred_ibl_pass.glsl"
