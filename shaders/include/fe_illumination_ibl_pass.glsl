// The body of illumination_ibl*.frag.
#include "fe_ibl.glsl"
// Redeferred: the environment's light added into the I-buffer (feEnvironmentSums), one
// full-screen draw at the I-buffer's resolution, each texel for its representative pixel as the
// punctual illumination passes do. Alpha is left alone (the tiled pass keeps the upsampling
// filter's data there).
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
// The occlusion (GBuffer::gb3), or 1x1 white without one, at the representative pixel: it
// multiplies the environment's sums alone (the punctual ones are not occluded).
layout(binding = FE_SLOT_GBUFFER3) uniform sampler2D gb3;
// Per-source rates (redeferred --rates) may put the environment's diffuse and specular sums in
// I-buffers of different rates: FE_IBL_DIFFUSE_ONLY writes L_dg alone, FE_IBL_SPECULAR_ONLY
// L_sg1 and L_sg2 alone (the compiler drops the other half of the estimator).
#if defined(FE_IBL_DIFFUSE_ONLY)
layout(location = 0) out vec4 outLdg;
#elif defined(FE_IBL_SPECULAR_ONLY)
layout(location = 0) out vec4 outLsg1;
layout(location = 1) out vec4 outLsg2;
#else
layout(location = 0) out vec4 outLdg;
layout(location = 1) out vec4 outLsg1;
layout(location = 2) out vec4 outLsg2;
#endif
void main() {
    const int scale = int(frame.counts.y);
    const ivec2 p = min(ivec2(gl_FragCoord.xy) * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1);
    const float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) discard;
    const vec4 g1 = texelFetch(gb1, p, 0);
    const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
    const vec3 P = frame.cameraPosition.xyz + Pe;
    IlluminationSums acc = feEnvironmentSums(normalize(g1.xyz), feViewDirection(Pe), g1.a, frame.counts.z);
    const float occlusion = texture(gb3, (vec2(p) + 0.5) * frame.viewport.zw).r;
    acc.Ldg *= occlusion;
    acc.Lsg1 *= occlusion;
    acc.Lsg2 *= occlusion;
#ifndef FE_IBL_SPECULAR_ONLY
    outLdg = vec4(acc.Ldg, 0.0);
#endif
#ifndef FE_IBL_DIFFUSE_ONLY
    outLsg1 = vec4(acc.Lsg1, 0.0);
    outLsg2 = vec4(acc.Lsg2, 0.0);
#endif
}
