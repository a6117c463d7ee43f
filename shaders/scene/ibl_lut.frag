#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_ibl.glsl"
// PrefilteredEnvironment's tables: for w_o at NoV = u and roughness v (texel centres), what the
// sampled estimators (fe_ibl.glsl) weigh the environment's radiance by, with the same sequence:
// x = (1/n) sum g and y = (1/n) sum P g over GGX half vectors, g = NoL VoH / ((NoL (1-k) + k)
// n.h (NoV (1-k) + k)) in rows [0, H) (the separable model), g = 4 V NoL VoH / n.h with glTF's
// height-correlated V in rows [H, 2H); z = (1/n) sum (1 - P) over cosine-weighted directions.
layout(binding = FE_SLOT_OBJECT, std140) uniform LutBlock {
    vec4 size;      // x width (NoV), y height (roughness) of each of the two tables
    uvec4 samples;  // x count
} lut;
layout(location = 0) out vec4 outTerms;
void main() {
    const float NoV = max(gl_FragCoord.x / lut.size.x, 1e-4);
    const bool gltf = gl_FragCoord.y >= lut.size.y;
    const float r = feClampRoughness((gltf ? gl_FragCoord.y - lut.size.y : gl_FragCoord.y) / lut.size.y);
    const float a = r * r, a2 = a * a, k = a2 / 2.0;
    const vec3 n = vec3(0.0, 0.0, 1.0), wo = vec3(sqrt(max(1.0 - NoV * NoV, 0.0)), 0.0, NoV);
    const vec3 t = vec3(1.0, 0.0, 0.0), b = vec3(0.0, 1.0, 0.0);
    const uint count = lut.samples.x;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < count; ++i) {
        const vec2 u = feHammersley(i, count);
        float cosH;
        const vec3 h = feGgxHalfVector(u, a2, t, b, n, cosH);
        const float VoH = dot(wo, h);
        const vec3 wi = 2.0 * VoH * h - wo;
        const float NoL = wi.z;
        if (NoL > 0.0 && VoH > 0.0) {
            const float P = feFresnelPower(VoH);
            const float g = gltf ? 4.0 * feVisibilityHeightCorrelated(NoL, NoV, a2) * NoL * VoH / cosH
                                 : NoL * VoH / ((NoL * (1.0 - k) + k) * cosH * (NoV * (1.0 - k) + k));
            sum.x += g;
            sum.y += P * g;
        }
        const vec3 wd = feCosineDirection(u, t, b, n);
        sum.z += 1.0 - feFresnelPower(dot(normalize(wo + wd), wo));
    }
    outTerms = vec4(sum / float(count), 1.0);
}
