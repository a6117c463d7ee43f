#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_cube.glsl"
#include "fe_ibl.glsl"
// PrefilteredEnvironment: one face of one level of the GGX-prefiltered cube. Each texel averages
// the environment over GGX samples about its direction (n = v = r), weighted by NoL, each read
// from the environment's mip whose texel matches the sample's share of the solid angle
// (Krivanek and Colbert, "Real-time Shading with Filtered Importance Sampling", 2008), so 64
// samples give a smooth result.
layout(binding = FE_SLOT_OBJECT, std140) uniform PrefilterBlock {
    vec4 params;  // x face, y face size in texels, z roughness, w solid angle of a source texel (level 0)
    uvec4 samples;  // x count
} prefilter;
layout(location = 0) out vec4 outRadiance;
void main() {
    const vec3 n = feCubeFaceDirection(int(prefilter.params.x), gl_FragCoord.xy / prefilter.params.y);
    const float r = max(prefilter.params.z, FE_MIN_ROUGHNESS), a = r * r, a2 = a * a;
    vec3 t, b;
    feBasis(n, t, b);
    const uint count = prefilter.samples.x;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < count; ++i) {
        float cosH;
        const vec3 h = feGgxHalfVector(feHammersley(i, count), a2, t, b, n, cosH);
        const vec3 l = 2.0 * cosH * h - n;
        const float NoL = dot(n, l);
        if (NoL <= 0.0) continue;
        // pdf of l with v = n: D n.h / (4 v.h) = D / 4.
        const float dd = cosH * cosH * (a2 - 1.0) + 1.0;
        const float pdf = a2 / (FE_PI * dd * dd) / 4.0;
        const float lod = max(0.5 * log2(1.0 / (float(count) * pdf * prefilter.params.w)) + 1.0, 0.0);
        sum += textureLod(environment, l, lod).rgb * NoL;
        weight += NoL;
    }
    outRadiance = vec4(sum / max(weight, 1e-6), 1.0);
}
