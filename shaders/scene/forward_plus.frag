#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a fragment outside its tile's depth bounds walks its cluster's list)
// Forward+ shading (forward-plus): fe_forward_pass.glsl over the pixel's tile light list.
#define FE_TILE_LISTS
#include "fe_forward_pass.glsl"
