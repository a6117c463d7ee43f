#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// Tiled deferred lighting with the tiles' light lists from the light-culling pass.
#define FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#include "fe_tiled_deferred_pass.glsl"
