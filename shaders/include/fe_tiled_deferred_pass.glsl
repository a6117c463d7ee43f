// The body of tiled_deferred*.comp. A work group per 16x16 screen tile; each pixel shades only
// its tile's lights, once, writing L_o. The tile's lights come from the light-culling pass
// (FE_TILE_LISTS, tiled_deferred.comp) or are culled by the work group itself against its
// depth bounds in shared memory (tiled_deferred_onepass.comp). Culling: fe_tile_culling.glsl.
// clustered_deferred.comp (FE_CLUSTER_LISTS) reads each pixel's cluster list instead
// (ClusterLightGrid, fe_clusters.glsl).
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_RADIANCE_OUT, rgba32f) uniform writeonly image2D outRadiance;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const bool inside = all(lessThan(p, ivec2(frame.viewport.xy)));
    const float depth = inside ? texelFetch(depthTexture, p, 0).r : 1.0;
#ifndef FE_CLUSTER_LISTS
    feFindTileLights(p, depth);  // every invocation: the shared-memory form has barriers
#endif
    if (!inside) return;
    const vec4 g2 = texelFetch(gb2, p, 0);
    vec3 radiance = g2.rgb;  // emissive, or the colour of an unlit surface
    if (depth < 1.0 && !feGBufferUnlit(g2.a)) {
        const vec4 g0 = texelFetch(gb0, p, 0);
        const vec4 g1 = texelFetch(gb1, p, 0);
        const SurfacePoint s = feGBufferSurface(p, depth, g0, g1);
        const SurfaceBrdf brdf = fePrepareBrdf(s);
#ifdef FE_CLUSTER_LISTS
        feUseClusterList(p, depth);
        const uint count = feClusterBoundedLightCount(frame.counts.x);
        for (uint k = 0u; k < count; ++k) {
            const uint i = feClusterLight(k);
            if (i >= frame.counts.x) break;  // the shadowed lights, last in the list, have passes of their own
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
    imageStore(outRadiance, p, vec4(radiance, 1.0));
}
