// A particle's fragment: a round soft-edged disc, tested by hand against the scene depth (the
// depth texture is sampled, not attached) and faded out over the emitter's softness where it
// nears the surface behind it (soft particles), so it never cuts a hard line into the ground.
#include "fe_scene.glsl"
#include "fe_particles.glsl"
layout(binding = FE_SLOT_DEPTH) uniform sampler2D sceneDepth;
layout(location = 0) in vec4 vColor;
layout(location = 1) in vec2 vCorner;
layout(location = 2) in vec3 vWorld;
layout(location = 3) in float vSoftness;
layout(location = 0) out vec4 outColor;
void main() {
    float r2 = dot(vCorner, vCorner);
    if (r2 >= 1.0) discard;
    float shape = (1.0 - r2) * (1.0 - r2);
    float depth = texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r;
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 h = frame.invViewProj * vec4(ndc, depth, 1.0);
    float fade = 1.0;
    if (abs(h.w) > 1e-9) {  // where nothing was drawn the scene point is at infinity: no fade
        float sceneDistance = distance(h.xyz / h.w, frame.cameraPosition.xyz);
        float particleDistance = distance(vWorld, frame.cameraPosition.xyz);
        if (particleDistance >= sceneDistance) discard;
        fade = vSoftness > 0.0 ? clamp((sceneDistance - particleDistance) / vSoftness, 0.0, 1.0) : 1.0;
    }
#if FE_PARTICLES_ALPHA
    outColor = vec4(vColor.rgb, vColor.a * shape * fade);
#else
    outColor = vec4(vColor.rgb * shape * fade, 0.0);
#endif
}
