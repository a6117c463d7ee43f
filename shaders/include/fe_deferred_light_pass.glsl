// The body of deferred_light*.frag: one light per fragment of its volume, added into the
// radiance target; FE_SHADOWED: the light's shadow map (fe_shadow.glsl) darkens it.
#include "fe_scene.glsl"
#ifdef FE_SHADOWED
#include "fe_shadow.glsl"
#endif
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(location = 0) flat in uint vLightIndex;
layout(location = 0) out vec4 outRadiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) discard;  // background or unlit
    vec4 g0 = texelFetch(gb0, p, 0);
    vec4 g1 = texelFetch(gb1, p, 0);
    const SurfacePoint s = feGBufferSurface(p, depth, g0, g1);
    SurfaceLight l = feEvaluateLightFromEye(feLight(vLightIndex), s.Pe);
#ifdef FE_SHADOWED
    l.E *= feShadowVisibility(s.P, s.n);
#endif
    outRadiance = vec4(feShadeLight(s, l), 0.0);
}
