#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// fe-variant: FE_MULTISAMPLED (--msaa: a multisampled G-buffer, edge pixels shaded per sample: fe_gbuffer.glsl)
// fe-variant: FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE
// Tiled deferred lighting with the tiles' light lists from the light-culling pass.
#define FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#include "fe_tiled_deferred_pass.glsl"
