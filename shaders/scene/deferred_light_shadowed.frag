#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a multisampled G-buffer, edge pixels shaded per sample: fe_gbuffer.glsl)
// Deferred lighting of a light with a shadow map: a cascade array or a spot map.
#define FE_SHADOWED
#include "fe_deferred_light_pass.glsl"
