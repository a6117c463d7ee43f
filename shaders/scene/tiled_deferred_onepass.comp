#version 450
#extension GL_GOOGLE_include_directive : require
// Tiled deferred lighting in one dispatch: each work group culls its tile's lights itself.
#include "fe_tile_culling.glsl"
#include "fe_tiled_deferred_pass.glsl"
