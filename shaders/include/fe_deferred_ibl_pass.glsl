// The body of deferred_ibl*.frag.
#include "fe_ibl.glsl"
// Deferred image-based lighting: the environment's light for each G-buffer pixel, added to L_o
// (fe_ibl.glsl, frame.counts.z samples per term).
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
// The occlusion (GBuffer::gb3), or 1x1 white without one: sampled at the pixel's centre.
layout(binding = FE_SLOT_GBUFFER3) uniform sampler2D gb3;
layout(location = 0) out vec4 outRadiance;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) discard;
    const vec4 g0 = texelFetch(gb0, p, 0), g1 = texelFetch(gb1, p, 0);
    const SurfacePoint s = feGBufferSurface(p, depth, g0, g1);
    const float occlusion = texture(gb3, (vec2(p) + 0.5) * frame.viewport.zw).r;
    outRadiance = vec4(occlusion * feShadeEnvironment(s, frame.counts.z), 0.0);
}
