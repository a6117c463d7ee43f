#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_tile_culling.glsl"
// Tiled deferred lighting, one dispatch: a work group per 16x16 screen tile finds the tile's
// depth bounds, culls every light against the tile's slice of the view frustum (bounded by
// those depths), and each pixel then shades the tile's lights only, once, writing L_o.
// Culling: fe_tile_culling.glsl.
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
    const vec2 tile = vec2(gl_WorkGroupID.xy * 16u);
    feCullTile(depth, tile, min(tile + 16.0, frame.viewport.xy));
    if (!inside) return;
    const vec4 g2 = texelFetch(gb2, p, 0);
    vec3 radiance = g2.rgb;  // emissive, or the colour of an unlit surface
    if (depth < 1.0 && !feGBufferUnlit(g2.a)) {
        const vec4 g0 = texelFetch(gb0, p, 0);
        const vec4 g1 = texelFetch(gb1, p, 0);
        SurfacePoint s;
        s.P = feWorldFromDepth(vec2(p) + 0.5, depth);
        s.n = normalize(g1.xyz);
        s.wo = normalize(frame.cameraPosition.xyz - s.P);
        s.baseColor = g0.rgb;
        s.metallic = g0.a;
        s.roughness = g1.a;
        const uint count = feTileLightCount();
        for (uint k = 0u; k < count; ++k) radiance += feShadeLight(s, feEvaluateLight(lights[feTileLight(k)], s.P));
    }
    imageStore(outRadiance, p, vec4(radiance, 1.0));
}
