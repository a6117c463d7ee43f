// The body of tiled_deferred*.comp. A work group per 16x16 screen tile; each pixel shades only
// its tile's lights, once, writing L_o. The tile's lights come from the light-culling pass
// (FE_TILE_LISTS, tiled_deferred.comp) or are culled by the work group itself against its
// depth bounds in shared memory (tiled_deferred_onepass.comp). Culling: fe_tile_culling.glsl.
// clustered_deferred.comp (FE_CLUSTER_LISTS) reads each pixel's cluster list instead
// (ClusterLightGrid, fe_clusters.glsl).
layout(local_size_x = 16, local_size_y = 16) in;
#include "fe_gbuffer.glsl"  // per sample at edges under FE_MULTISAMPLED
layout(binding = FE_SLOT_RADIANCE_OUT, rgba32f) uniform writeonly image2D outRadiance;

// L_o of one shading of pixel p (fe_gbuffer.glsl) at `depth`: its emission (or unlit colour)
// and its lights.
vec3 feShadeTiled(ivec2 p, int sampleIndex, float depth) {
    const vec4 g2 = texelFetch(gb2, p, sampleIndex);
    vec3 radiance = g2.rgb;  // emissive, or the colour of an unlit surface
    if (depth < 1.0 && !feGBufferUnlit(g2.a)) {
        const SurfacePoint s = feGBufferSurface(p, depth, texelFetch(gb0, p, sampleIndex),
                                                 texelFetch(gb1, p, sampleIndex));
        const SurfaceBrdf brdf = fePrepareBrdf(s);
#ifdef FE_CLUSTER_LISTS
        feUseClusterList(p, depth);
#ifdef FE_MULTISAMPLED
        const uint count = feClusterLightCount(frame.counts.x);  // whole lists: the bounds hold sample 0's depths
#else
        const uint count = feClusterBoundedLightCount(frame.counts.x);
#endif
        for (uint k = 0u; k < count; ++k) {
            const uint i = feClusterLight(k);
            // The shadowed lights, last in a run of the list, have passes of their own (a whole
            // list is two runs in light order).
#ifdef FE_MULTISAMPLED
            if (i >= frame.counts.x) continue;
#else
            if (i >= frame.counts.x) break;
#endif
            const GpuLight L = feLight(i);
#else
        const uint count = feTileLightCount();
        for (uint k = 0u; k < count; ++k) {
            const GpuLight L = feLight(feTileLight(k));
#endif
            // Most of a tile's lights miss most of its pixels: beyond its range a light adds
            // exactly 0 (the range window), so skip the shading.
            if (!feLightReaches(L, s.P)) continue;
            radiance += feShadeLight(brdf, feEvaluateLightFromEye(L, s.Pe));
        }
    }
    return radiance;
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const bool inside = all(lessThan(p, ivec2(frame.viewport.xy)));
    // The pixel's depth, or its samples' mean (fe_gbuffer.glsl); multisampled, the tile lists come
    // from the light-culling pass, whose bounds take in every sample.
    const float depth = inside ? feGBufferDepth(p, 0, 1) : 1.0;
#ifndef FE_CLUSTER_LISTS
    feFindTileLights(p, depth);  // every invocation: the shared-memory form has barriers
#endif
    if (!inside) return;
    const int shadings = feGBufferShadings(p);  // 1, or each sample of an edge
    vec3 radiance = vec3(0.0);
    for (int k = 0; k < shadings; ++k)
        radiance += feShadeTiled(p, k, shadings == 1 ? depth : texelFetch(depthTexture, p, k).r);
    imageStore(outRadiance, p, vec4(radiance / float(shadings), 1.0));
}
