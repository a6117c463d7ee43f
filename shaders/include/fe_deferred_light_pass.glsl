// The body of deferred_light*.frag: one light per fragment of its volume, added into the
// radiance target; FE_SHADOWED: the light's shadow map (fe_shadow.glsl) darkens it.
#include "fe_scene.glsl"
#ifdef FE_SHADOWED
#include "fe_shadow.glsl"
#endif
#include "fe_gbuffer.glsl"
layout(location = 0) flat in vec4 vLightWords[4];  // the volume's light (light_volume.vert)
layout(location = 0) out vec4 outRadiance;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const int shadings = feGBufferShadings(p);  // 1, or each sample of an edge (fe_gbuffer.glsl)
    vec3 sum = vec3(0.0);
    bool lit = false;
    for (int k = 0; k < shadings; ++k) {
        const float depth = feGBufferDepth(p, k, shadings);
        if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, k).a)) continue;  // background or unlit
        const SurfacePoint s = feGBufferSurface(p, depth, texelFetch(gb0, p, k), texelFetch(gb1, p, k));
        SurfaceLight l = feEvaluateLightFromEye(GpuLight(vLightWords[0], vLightWords[1], vLightWords[2], vLightWords[3]), s.Pe);
#ifdef FE_SHADOWED
        l.E *= feShadowVisibility(s.P, s.n);
#endif
        sum += feShadeLight(s, l);
        lit = true;
    }
    if (!lit) discard;
    outRadiance = vec4(sum / float(shadings), 0.0);
}
