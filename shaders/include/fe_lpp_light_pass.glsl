#include "fe_light_prepass.glsl"
#ifdef FE_SHADOWED
#include "fe_shadow.glsl"
#endif
// Light pre-pass, pass 2: one light per fragment of its volume, added into the light buffer;
// FE_SHADOWED: darkened by the light's shadow map (fe_shadow.glsl).
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D normalTexture;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(location = 0) flat in vec4 vLightWords[4];  // the volume's light (light_volume.vert)
layout(location = 0) out vec4 outLight;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0) discard;
    vec4 t = texelFetch(normalTexture, p, 0);
    vec3 n = feUnpackNormal(t);
    const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
    vec3 P = frame.cameraPosition.xyz + Pe;  // the eye ray at the stored depth
    vec3 wo = feViewDirection(Pe);
    IlluminationSums acc = IlluminationSums(vec3(0.0), vec3(0.0), vec3(0.0));
    SurfaceLight l = feEvaluateLightFromEye(GpuLight(vLightWords[0], vLightWords[1], vLightWords[2], vLightWords[3]), Pe);
#ifdef FE_SHADOWED
    l.E *= feShadowVisibility(P, n);
#endif
    feAccumulateIllumination(acc, n, wo, feUnpackRoughness(t), l);
    outLight = vec4(acc.Ldg, feLuminance(acc.Lsg1));
}
