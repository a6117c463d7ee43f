#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_material.glsl"
// Forward: every light in one loop (SHADING.md per-light sum). Also the transparent pass.
layout(location = 0) in vec3 vWorld;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec2 vUv;
layout(location = 0) out vec4 outRadiance;
void main() {
    MaterialSample m = feSampleMaterial(vUv, vNormal, vTangent, gl_FrontFacing);
    if (feAlphaDiscard(m.alpha)) discard;
    vec3 L = m.emissive;
    if (m.unlit) {
        L = m.baseColor;
    } else {
        SurfacePoint s;
        s.P = vWorld;
        s.n = m.n;
        s.wo = normalize(frame.cameraPosition.xyz - vWorld);
        s.baseColor = m.baseColor;
        s.metallic = m.metallic;
        s.roughness = m.roughness;
        for (uint i = 0u; i < frame.counts.x; ++i) L += feShadeLight(s, feEvaluateLight(lights[i], vWorld));
    }
    // Alpha only matters for BLEND draws (source-over); opaque targets ignore it.
    outRadiance = vec4(L, object.params.w == 2.0 ? m.alpha : 1.0);
}
