#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Per-source illumination rates (redeferred --rates): one reduced-rate I-buffer upsampled to full
// resolution with the material pass's G-buffer-guided filter and added into the full-rate
// I-buffer, which the material pass then resolves at scale 1. frame.counts.y and
// frame.illumViewport are this I-buffer's scale and size; each texel's representative pixel is
// read from the G-buffer (the I-buffers of several sources hold no filter data in alpha).
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D iLdg;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D iLsg1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D iLsg2;
layout(location = 0) out vec4 outLdg;
layout(location = 1) out vec4 outLsg1;
layout(location = 2) out vec4 outLsg2;
#include "fe_ibuffer_upsample.glsl"
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) discard;
    const vec4 g1 = texelFetch(gb1, p, 0);
    const IlluminationSums acc = feUpsampleIBuffer(p, depth, normalize(g1.xyz), g1);
    outLdg = vec4(acc.Ldg, 0.0);
    outLsg1 = vec4(acc.Lsg1, 0.0);
    outLsg2 = vec4(acc.Lsg2, 0.0);
}
