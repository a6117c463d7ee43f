// The body of deferred_ibl*.frag.
#include "fe_ibl.glsl"
// Deferred image-based lighting: the environment's light for each G-buffer pixel, added to L_o
// (fe_ibl.glsl, frame.counts.z samples per term); per sample at edges under FE_MULTISAMPLED
// (fe_gbuffer.glsl).
#include "fe_gbuffer.glsl"
// The occlusion (GBuffer::gb3): at one sample the target or 1x1 white, sampled at the pixel's
// centre; multisampled, the target's sample (FE_OCCLUSION) or none.
#ifndef FE_MULTISAMPLED
layout(binding = FE_SLOT_GBUFFER3) uniform sampler2D gb3;
float feOcclusionAt(ivec2 p, int k) { return texture(gb3, (vec2(p) + 0.5) * frame.viewport.zw).r; }
#elif defined(FE_OCCLUSION)
layout(binding = FE_SLOT_GBUFFER3) uniform sampler2DMS gb3;
float feOcclusionAt(ivec2 p, int k) { return texelFetch(gb3, p, k).r; }
#else
float feOcclusionAt(ivec2 p, int k) { return 1.0; }
#endif
layout(location = 0) out vec4 outRadiance;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const int shadings = feGBufferShadings(p);
    vec3 sum = vec3(0.0);
    bool lit = false;
    for (int k = 0; k < shadings; ++k) {
        const float depth = feGBufferDepth(p, k, shadings);
        if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, k).a)) continue;
        const SurfacePoint s = feGBufferSurface(p, depth, texelFetch(gb0, p, k), texelFetch(gb1, p, k));
        sum += feOcclusionAt(p, k) * feShadeEnvironment(s, frame.counts.z);
        lit = true;
    }
    if (!lit) discard;
    outRadiance = vec4(sum / float(shadings), 0.0);
}
