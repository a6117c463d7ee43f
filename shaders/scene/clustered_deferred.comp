#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// Clustered deferred lighting: each pixel shades the lights of its cluster (ClusterLightGrid).
#define FE_TILE_LISTS  // the list passes' helpers and uniform lights (fe_tile_culling.glsl)
#define FE_CLUSTER_LISTS
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
#include "fe_tiled_deferred_pass.glsl"
