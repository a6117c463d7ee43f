// The body of illumination_ibl*.frag.
#include "fe_ibl.glsl"
// Redeferred: the environment's light added into the I-buffer (feEnvironmentSums), one
// full-screen draw at the I-buffer's resolution, each texel for its representative pixel as the
// punctual illumination passes do. Alpha is left alone (the tiled pass keeps the upsampling
// filter's data there).
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
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
    const IlluminationSums acc = feEnvironmentSums(normalize(g1.xyz), normalize(-Pe), g1.a, frame.counts.z);
#ifndef FE_IBL_SPECULAR_ONLY
    outLdg = vec4(acc.Ldg, 0.0);
#endif
#ifndef FE_IBL_DIFFUSE_ONLY
    outLsg1 = vec4(acc.Lsg1, 0.0);
    outLsg2 = vec4(acc.Lsg2, 0.0);
#endif
}
