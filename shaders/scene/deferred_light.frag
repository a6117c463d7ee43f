#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a multisampled G-buffer, edge pixels shaded per sample: fe_gbuffer.glsl)
// Deferred lighting, one light per volume fragment (fe_deferred_light_pass.glsl).
#include "fe_deferred_light_pass.glsl"
