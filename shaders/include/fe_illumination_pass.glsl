#include "fe_scene.glsl"
#ifdef FE_SHADOWED
#include "fe_shadow.glsl"
#endif
// The body of illumination*.frag, the redeferred illumination pass: light-only sums into the
// I-buffer, possibly at 1/scale of the resolution. Each I-buffer texel shades the G-buffer texel
// at the centre of its block (the material pass's upsampling filter uses the same representative
// texels). FE_SHADOWED: darkened by the light's shadow map (fe_shadow.glsl).
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(location = 0) flat in vec4 vLightWords[4];  // the volume's light (light_volume.vert)
layout(location = 0) out vec4 outLdg;
layout(location = 1) out vec4 outLsg1;
layout(location = 2) out vec4 outLsg2;
void main() {
    int scale = int(frame.counts.y);
    ivec2 p = min(ivec2(gl_FragCoord.xy) * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1);
    float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) discard;
    vec4 g1 = texelFetch(gb1, p, 0);
    const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
    vec3 P = frame.cameraPosition.xyz + Pe;
    vec3 n = normalize(g1.xyz);
    vec3 wo = feViewDirection(Pe);
    IlluminationSums acc;
    acc.Ldg = vec3(0.0);
    acc.Lsg1 = vec3(0.0);
    acc.Lsg2 = vec3(0.0);
    SurfaceLight l = feEvaluateLightFromEye(GpuLight(vLightWords[0], vLightWords[1], vLightWords[2], vLightWords[3]), Pe);
#ifdef FE_SHADOWED
    l.E *= feShadowVisibility(P, n);  // at the representative pixel, like the rest of the sums
#endif
    feAccumulateIllumination(acc, n, wo, g1.a, l);
    outLdg = vec4(acc.Ldg, 0.0);
    outLsg1 = vec4(acc.Lsg1, 0.0);
    outLsg2 = vec4(acc.Lsg2, 0.0);
}
