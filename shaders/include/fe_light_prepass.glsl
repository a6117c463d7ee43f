// The light pre-pass (Engel 2008, in ../shared/seeds/004): what its three passes share.
//
// Pass 1 stores the shading normal and roughness per pixel. Packed (the deck's layout): RGBA8,
// view-space normal x and y as unorm, z rebuilt as +-sqrt(1 - x^2 - y^2) with its sign in the
// alpha bit (normal maps and grazing angles do turn view-space normals away), roughness in b:
// 4 bytes per pixel, and position comes from the depth buffer and the eye ray. Unpacked
// (FE_LPP_UNPACKED, to measure what packing costs): RGBA16F world normal and roughness, 8.
//
// Pass 2 accumulates per light, into RGBA32F: rgb = L_dg (SHADING.md's redeferred diffuse sum,
// light colour and Fresnel (1 - P) included) and a = the monochrome specular: the luminance of
// L_sg1, pre-scaled by alpha^2 / (4 pi) like redeferred's, whose peak at the roughness clamp is
// ~2e4 x E, beyond half-float range for bright lights: hence 32-bit.
//
// Pass 3 rebuilds the specular colour from the monochrome term with the diffuse light's
// chromaticity (L_dg / lum(L_dg)), and Fresnel at n.v instead of per light at h.v: the two
// approximations of the technique, measured against exact shading in docs/BENCHMARKS.md.
#ifndef FE_LIGHT_PREPASS_GLSL
#define FE_LIGHT_PREPASS_GLSL
#include "fe_scene.glsl"

float feLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

vec4 fePackNormalRoughness(vec3 worldNormal, float roughness) {
#ifdef FE_LPP_UNPACKED
    return vec4(worldNormal, roughness);
#else
    vec3 v = mat3(frame.view) * worldNormal;
    return vec4(v.xy * 0.5 + 0.5, roughness, v.z < 0.0 ? 0.0 : 1.0);
#endif
}

float feUnpackRoughness(vec4 t) {
#ifdef FE_LPP_UNPACKED
    return t.w;
#else
    return t.z;
#endif
}

vec3 feUnpackNormal(vec4 t) {
#ifdef FE_LPP_UNPACKED
    return normalize(t.xyz);
#else
    vec2 xy = t.xy * 2.0 - 1.0;
    float z = sqrt(max(1.0 - dot(xy, xy), 0.0)) * (t.w < 0.5 ? -1.0 : 1.0);
    return normalize(transpose(mat3(frame.view)) * vec3(xy, z));  // view is rigid: inverse = transpose
#endif
}
#endif
