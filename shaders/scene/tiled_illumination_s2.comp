#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// Redeferred tiled illumination at illum-scale 2: 8x8 I-buffer texels per 16x16-pixel tile.
#define FE_TILE_TEXELS 8
#define FE_TILE_INVOCATIONS 64u
#define FE_TILE_LISTS  // lists from the light-culling pass
#include "fe_tile_culling.glsl"
#include "fe_tiled_illumination_pass.glsl"
