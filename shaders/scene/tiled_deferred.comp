#version 450
#extension GL_GOOGLE_include_directive : require
// Tiled deferred lighting with the tiles' light lists from the light-culling pass.
#define FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#include "fe_tiled_deferred_pass.glsl"
