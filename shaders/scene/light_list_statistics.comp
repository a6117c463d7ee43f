#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_CLUSTER_LISTS (the cluster grid's lists, else the tile lists)
// Light-list statistics (SceneRenderer::lightListStatistics): per pixel, how many lights the
// technique's shading loop walks there: the length of its tile list (all lights where the list
// overflowed or the surface lies outside the depth bounds it was culled for), or of its cluster's
// list up to the unshadowed lights. All ones where no surface was drawn.
#define FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#ifdef FE_CLUSTER_LISTS
#include "fe_clusters.glsl"
#endif
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_RADIANCE_OUT, r32ui) uniform writeonly uimage2D evaluated;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    const float depth = texelFetch(depthTexture, p, 0).r;
    uint n = 0xffffffffu;
    if (depth < 1.0) {
#ifdef FE_CLUSTER_LISTS
        feUseClusterList(p, depth);
        const uint count = feClusterLightCount(frame.counts.x);
        n = 0u;
        for (uint k = 0u; k < count && feClusterLight(k) < frame.counts.x; ++k) ++n;
#else
        feUseTileListAt(p, depth);
        n = feTileLightCount();
#endif
    }
    imageStore(evaluated, p, uvec4(n));
}
