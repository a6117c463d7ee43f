// The G-buffer as the deferred passes read it (GBuffer.h), declared at its slots. With
// FE_MULTISAMPLED (--msaa N) the G-buffer and its depth hold N samples a pixel, and a pass shades
// each pixel in feGBufferShadings(p) shadings whose radiances it averages:
//  - one, where every sample holds the same surface (the same G-buffer texel and view depths
//    within 1 %): at the samples' mean depth, which for the centred standard sample patterns is
//    the depth at the pixel's centre, where a forward pass shades the pixel;
//  - one per sample at an edge (another surface, or the background, in some sample), each at
//    its sample's depth, so silhouettes resolve as a multisampled forward pass resolves them.
// One branch in the pass, not a stencil-split second pass: it keeps each technique one set of
// passes, and the edge test reads what the shading reads anyway.
// Without FE_MULTISAMPLED every pixel is one shading at its one depth, as before.
#ifdef FE_MULTISAMPLED
#define FE_GBUFFER_SAMPLER sampler2DMS
#else
#define FE_GBUFFER_SAMPLER sampler2D
#endif
layout(binding = FE_SLOT_GBUFFER0) uniform FE_GBUFFER_SAMPLER gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform FE_GBUFFER_SAMPLER gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform FE_GBUFFER_SAMPLER gb2;
layout(binding = FE_SLOT_DEPTH) uniform FE_GBUFFER_SAMPLER depthTexture;

// How many shadings pixel p takes: 1, or its sample count at an edge.
int feGBufferShadings(ivec2 p) {
#ifdef FE_MULTISAMPLED
    const int n = textureSamples(gb1);
    const vec4 a0 = texelFetch(gb0, p, 0), a1 = texelFetch(gb1, p, 0), a2 = texelFetch(gb2, p, 0);
    const float z0 = feViewDepth(texelFetch(depthTexture, p, 0).r);
    for (int i = 1; i < n; ++i) {
        // Within one triangle the G-buffer pass wrote one value to every sample it covers.
        if (texelFetch(gb0, p, i) != a0 || texelFetch(gb1, p, i) != a1 || texelFetch(gb2, p, i) != a2)
            return n;
        // The same material and normal in front of a parallel surface: its depth tells.
        if (abs(feViewDepth(texelFetch(depthTexture, p, i).r) - z0) > 0.01 * z0) return n;
    }
#endif
    return 1;
}

// The depth shading k of pixel p's `shadings` uses.
float feGBufferDepth(ivec2 p, int k, int shadings) {
#ifdef FE_MULTISAMPLED
    if (shadings == 1) {
        const int n = textureSamples(depthTexture);
        float sum = 0.0;
        for (int i = 0; i < n; ++i) sum += texelFetch(depthTexture, p, i).r;
        return sum / float(n);
    }
#endif
    return texelFetch(depthTexture, p, k).r;
}
