#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_CLUSTER_LISTS (the cluster grid's lists, else the tile lists)
// fe-variant: FE_EVERY_LIGHT (the loop walks every unshadowed light: no list)
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// fe-variant: FE_CLUSTER_LISTS+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_EVERY_LIGHT+FE_LIGHTS_IN_STORAGE
// Light-list statistics (SceneRenderer::lightListStatistics): per pixel, how many lights the
// technique's shading loop walks there, at the (resolved) depth the tile lists were culled for:
// the length of its tile list (all lights where the list overflowed), or of its cluster's list up
// to the unshadowed lights, or every unshadowed light. (Under MSAA a Forward+ fragment at an edge
// may walk its cluster's list instead; this pass does not see it.) Next to it, how many of those
// lights reach the surface (their range window is non-zero there): what an exact culling walks
// at least, whatever its lists; its top bit set where the loop misses one of them (culling that
// is not exact: a light dropped). All ones in both where no surface was drawn.
// It walks every light at every pixel, so it reads them from the uniform block where they fit
// (fe_scene.glsl: 7x faster on llvmpipe), and it is never part of a timed frame (measureLightLists).
#define FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#ifdef FE_CLUSTER_LISTS
#include "fe_clusters.glsl"
#endif
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_RADIANCE_OUT, r32ui) uniform writeonly uimage2D evaluated;
layout(binding = FE_SLOT_TILE_LIGHTS_OUT, r32ui) uniform writeonly uimage2D reaching;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    const float depth = texelFetch(depthTexture, p, 0).r;
    uint n = 0xffffffffu, reach = 0xffffffffu;
    if (depth < 1.0) {
        const vec3 P = feWorldFromDepth(vec2(p) + 0.5, depth);
        uint walkedReaching = 0u;
#if defined(FE_CLUSTER_LISTS)
        feUseClusterList(p, depth);
        const uint count = feClusterBoundedLightCount(frame.counts.x);
        n = 0u;
        for (uint k = 0u; k < count && feClusterLight(k) < frame.counts.x; ++k, ++n)
            if (feLightReaches(feLight(feClusterLight(k)), P)) ++walkedReaching;
#elif defined(FE_EVERY_LIGHT)
        n = frame.counts.x;
        walkedReaching = 0xffffffffu;  // every light walked: none missed
#else
        feUseTileList(p);  // the depth read here is the one its tile was culled for: the list holds
        n = feTileLightCount();
        for (uint k = 0u; k < n; ++k)
            if (feLightReaches(feLight(feTileLight(k)), P)) ++walkedReaching;
#endif
        reach = 0u;
        for (uint i = 0u; i < frame.counts.x; ++i)
            if (feLightReaches(feLight(i), P)) ++reach;
        if (walkedReaching < reach) reach |= 0x80000000u;
    }
    imageStore(evaluated, p, uvec4(n));
    imageStore(reaching, p, uvec4(reach));
}
