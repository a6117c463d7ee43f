// The body of material*.frag, the redeferred material pass at full resolution: L_o = emissive
// + L_d + L_s from the I-buffer. One shader per path, chosen when the pipeline is made: on
// llvmpipe a path present but not taken measured as costly as running it (35 ms of a 53 ms pass
// at 1280x720), so no path is a run-time branch.
//   material.frag                 scale 1, w_o.n read from G-buffer 2 (consideration A)
//   material_rebuild_nov.frag     scale 1, w_o.n rebuilt from depth and the normal (FE_REBUILD_NOV)
//   material_upsample.frag        reduced rate (FE_UPSAMPLE): the sums upsampled with a
//                                 G-buffer-guided filter: the bilinear weights of the 4 nearest
//                                 I-buffer texels times depth, normal and roughness similarity
//                                 between this pixel and each texel's representative pixel;
//                                 w_o.n from G-buffer 2, as at scale 1
//   material_upsample_tiled.frag  the same, each texel's representative pixel data read from the
//                                 I-buffer's alpha channels (FE_REP_IN_IBUFFER; fe_scene.glsl)
//   material_upsample_split.frag  reduced rate, only L_dg upsampled (FE_SPLIT, --illum-split)
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D iLdg;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D iLsg1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D iLsg2;
layout(location = 0) out vec4 outRadiance;
#ifdef FE_UPSAMPLE
#include "fe_ibuffer_upsample.glsl"
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 g2 = texelFetch(gb2, p, 0);
    if (g2.a < 0.0) discard;  // nothing drawn here (G-buffer 2's clear value)
    if (feGBufferUnlit(g2.a)) { outRadiance = vec4(g2.rgb, 1.0); return; }
    vec4 g0 = texelFetch(gb0, p, 0);
    vec4 g1 = texelFetch(gb1, p, 0);
    IlluminationSums acc;
#if !defined(FE_UPSAMPLE) && !defined(FE_REBUILD_NOV)
    // Consideration A: w_o.n from the geometry pass; no depth, position or normal needed.
    acc.Ldg = texelFetch(iLdg, p, 0).rgb;
    acc.Lsg1 = texelFetch(iLsg1, p, 0).rgb;
    acc.Lsg2 = texelFetch(iLsg2, p, 0).rgb;
    outRadiance = vec4(g2.rgb + feResolveMaterialNoV(acc, g2.a, g0.rgb, g0.a, g1.a), 1.0);
#elif defined(FE_UPSAMPLE)
    // The filter needs this pixel's depth and normal; the resolve takes w_o.n from the geometry
    // pass (consideration A) as at scale 1: rebuilding the position and w_o here cost 2.5 of
    // the pass's 32 ms at 1280x720 on lavapipe, for the same image (docs/MEASUREMENT_LOG.md).
    acc = feUpsampleIBuffer(p, texelFetch(depthTexture, p, 0).r, normalize(g1.xyz), g1);
    outRadiance = vec4(g2.rgb + feResolveMaterialNoV(acc, g2.a, g0.rgb, g0.a, g1.a), 1.0);
#else
    float depth = texelFetch(depthTexture, p, 0).r;
    const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
    vec3 P = frame.cameraPosition.xyz + Pe;
    vec3 n = normalize(g1.xyz);
    vec3 wo = feViewDirection(Pe);
    acc.Ldg = texelFetch(iLdg, p, 0).rgb;
    acc.Lsg1 = texelFetch(iLsg1, p, 0).rgb;
    acc.Lsg2 = texelFetch(iLsg2, p, 0).rgb;
    outRadiance = vec4(g2.rgb + feResolveMaterial(acc, n, wo, g0.rgb, g0.a, g1.a), 1.0);
#endif
}
