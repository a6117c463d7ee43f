// The body of tiled_illumination*.comp (one file per tile size in I-buffer texels).
// Redeferred illumination as one compute pass: a work group per tile of 16x16 full-resolution
// pixels, FE_TILE_TEXELS^2 I-buffer texels at 1/scale of the resolution, culls the lights
// (fe_tile_culling.glsl), and each I-buffer texel accumulates the sums of its representative
// G-buffer pixel (the centre of its block, as illumination.frag) over its tile's lights,
// storing them with no blending. Tiles stay 16 pixels wide at every scale: measured with tiles
// of 16x16 texels, the pass cost the same at scales 1, 2 and 4 (88-92 ms on lavapipe), the
// larger tiles' longer light lists eating what the fewer texels saved.
layout(local_size_x = FE_TILE_TEXELS, local_size_y = FE_TILE_TEXELS) in;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0, rgba32f) uniform writeonly image2D outLdg;
layout(binding = FE_SLOT_IBUFFER1, rgba32f) uniform writeonly image2D outLsg1;
layout(binding = FE_SLOT_IBUFFER2, rgba32f) uniform writeonly image2D outLsg2;

void main() {
    const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    const int scale = int(frame.counts.y);
#ifdef FE_ILLUM_SPLIT
    // Split I-buffer: one invocation per pixel, storing its specular sums at full resolution and
    // its L_dg only if it is the representative pixel of its I-buffer texel.
    const bool inside = all(lessThan(q, ivec2(frame.viewport.xy)));
    const ivec2 p = q;
#else
    const bool inside = all(lessThan(q, ivec2(frame.illumViewport.xy)));
    const ivec2 p = min(q * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1);
#endif
    const bool lit = inside && !feGBufferUnlit(texelFetch(gb2, p, 0).a);
    const float depth = lit ? texelFetch(depthTexture, p, 0).r : 1.0;
    feFindTileLights(p, depth);
    if (!inside) return;
    IlluminationSums acc = IlluminationSums(vec3(0.0), vec3(0.0), vec3(0.0));
    vec4 g1 = vec4(0.0, 0.0, 1.0, 0.0);
    if (depth < 1.0) {
        g1 = texelFetch(gb1, p, 0);
        const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
        const vec3 P = frame.cameraPosition.xyz + Pe;
        const vec3 n = normalize(g1.xyz);
        const vec3 wo = feViewDirection(Pe);
        const RoughnessTerms terms = feRoughnessTerms(g1.a);
        const uint count = feTileLightCount();
        for (uint k = 0u; k < count; ++k) {
            const GpuLight L = feLight(feTileLight(k));
            // Many of a tile's lights miss this texel's point: beyond its range a light adds
            // exactly 0 (range window), skip it.
            if (!feLightReaches(L, P)) continue;
            feAccumulateIllumination(acc, n, wo, terms, feEvaluateLightFromEye(L, Pe));
        }
    }
    // The representative pixel's data for the upsampling filter (fe_scene.glsl).
    const float viewDepth = depth < 1.0 ? feViewDepth(depth) : 0.0;
#ifdef FE_ILLUM_SPLIT
    const ivec2 qi = q / scale;
    if (all(equal(p, min(qi * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1))))
        imageStore(outLdg, qi, vec4(acc.Ldg, viewDepth));
    imageStore(outLsg1, q, vec4(acc.Lsg1, 0.0));
    imageStore(outLsg2, q, vec4(acc.Lsg2, 0.0));
#else
    const vec2 oct = feOctEncode(normalize(g1.xyz));
    imageStore(outLdg, q, vec4(acc.Ldg, viewDepth));
    imageStore(outLsg1, q, vec4(acc.Lsg1, oct.x));
    imageStore(outLsg2, q, vec4(acc.Lsg2, fePackOctYRoughness(oct.y, g1.a)));
#endif
}
