#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// Redeferred tiled illumination with the split I-buffer (--illum-split): one invocation per pixel
// of a 16x16-pixel tile; specular sums at full resolution, L_dg at 1/scale.
#define FE_TILE_TEXELS 16
#define FE_TILE_INVOCATIONS 256u
#define FE_ILLUM_SPLIT
#define FE_TILE_LISTS  // lists from the light-culling pass
#include "fe_tile_culling.glsl"
#include "fe_tiled_illumination_pass.glsl"
