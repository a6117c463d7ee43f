// The shading model of ../shared/SHADING.md, the one contract every technique shares.
// Keep in step with renderer/shading/ShadingModel.h (the CPU double-precision reference).
#ifndef FE_SHADING_GLSL
#define FE_SHADING_GLSL

const float FE_PI = 3.14159265358979323846;
const float FE_MIN_ROUGHNESS = 0.045;

// Light types, as stored in GpuLight.directionType.w
const float FE_LIGHT_DIRECTIONAL = 0.0;
const float FE_LIGHT_POINT = 1.0;
const float FE_LIGHT_SPOT = 2.0;

// std430/std140-compatible light record (4 x vec4), written by renderer/shading/GpuLight.h.
struct GpuLight {
    vec4 positionRange;   // xyz world position, w range (0 = infinite)
    vec4 colorIntensity;  // rgb colour, w intensity (lux or candela)
    vec4 directionType;   // xyz direction the light points to (spot, directional), w type
    vec4 spotScaleOffset; // x = s, y = o of SHADING.md's spot falloff
};

struct SurfaceLight {
    vec3 wi;  // unit vector to the light
    vec3 E;   // irradiance at normal incidence
};

float feRangeWindow(float d, float range) {
    if (range <= 0.0) return 1.0;
    float q = d / range;
    float w = clamp(1.0 - q * q * q * q, 0.0, 1.0);
    return w * w;
}

SurfaceLight feEvaluateLight(GpuLight L, vec3 P) {
    SurfaceLight s;
    vec3 E = L.colorIntensity.rgb * L.colorIntensity.w;
    if (L.directionType.w == FE_LIGHT_DIRECTIONAL) {
        s.wi = -normalize(L.directionType.xyz);
        s.E = E;
        return s;
    }
    vec3 toLight = L.positionRange.xyz - P;
    float d2 = max(dot(toLight, toLight), 1e-12);
    float d = sqrt(d2);
    s.wi = toLight / d;
    E *= feRangeWindow(d, L.positionRange.w) / d2;
    if (L.directionType.w == FE_LIGHT_SPOT) {
        float cosTheta = dot(normalize(L.directionType.xyz), -s.wi);
        float t = clamp(cosTheta * L.spotScaleOffset.x + L.spotScaleOffset.y, 0.0, 1.0);
        E *= t * t;
    }
    s.E = E;
    return s;
}

struct SurfacePoint {
    vec3 P;          // world position
    vec3 n;          // unit shading normal
    vec3 wo;         // unit vector to the eye
    vec3 baseColor;  // linear
    float metallic;
    float roughness; // perceptual, clamped by feMakeSurface
};

float feClampRoughness(float r) { return clamp(r, FE_MIN_ROUGHNESS, 1.0); }

// Schlick's (1 - cos)^5 for cos in [-1, 1]: clamped (a rounding-negative base), and by two
// multiplications squared and one more rather than pow(), which CPU rasterizers evaluate as
// exp2(5 log2 x) once per light and pixel.
float feFresnelPower(float cosTheta) {
    const float x = clamp(1.0 - cosTheta, 0.0, 1.0), x2 = x * x;
    return x2 * x2 * x;
}

// Forward: the full per-light BRDF sum (SHADING.md "Per light").
vec3 feShadeLight(SurfacePoint s, SurfaceLight l) {
    float NoL = dot(s.n, l.wi);
    if (NoL <= 0.0) return vec3(0.0);
    float r = feClampRoughness(s.roughness);
    float a = r * r;
    float a2 = a * a;
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    float NoV = max(dot(s.n, s.wo), 1e-4);
    vec3 h = normalize(s.wo + l.wi);
    float NoH = dot(s.n, h);
    float P = feFresnelPower(dot(h, s.wo));
    vec3 F0 = mix(vec3(0.04), s.baseColor, s.metallic);
    vec3 F = F0 + (1.0 - F0) * P;
    float dd = NoH * NoH * (a2 - 1.0) + 1.0;
    float D = a2 / (FE_PI * dd * dd);
    float G = NoV / (NoV * (1.0 - k) + k) * NoL / (NoL * (1.0 - k) + k);
    vec3 f = (1.0 - F) * (1.0 - s.metallic) * s.baseColor / FE_PI + D * F * G / (4.0 * NoV * NoL);
    return f * l.E * NoL;
}

// Redeferred illumination: the light-only sums (SHADING.md "The redeferred split").
// The specular sums are stored pre-multiplied by alpha^2 / (4 pi): their raw peak near
// E / alpha^4 (~6e10 E at the roughness clamp) would overflow any 16-bit float, and even
// scaled they exceed half range for bright lights, so they live in 32-bit float targets.
struct IlluminationSums {
    vec3 Ldg;
    vec3 Lsg1;  // x alpha^2 / (4 pi)
    vec3 Lsg2;  // x alpha^2 / (4 pi)
};

void feAccumulateIllumination(inout IlluminationSums acc, vec3 n, vec3 wo, float roughness, SurfaceLight l) {
    float NoL = dot(n, l.wi);
    if (NoL <= 0.0) return;
    float r = feClampRoughness(roughness);
    float a = r * r;
    float a2 = a * a;
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    vec3 h = normalize(wo + l.wi);
    float NoH = dot(n, h);
    float P = feFresnelPower(dot(h, wo));
    float dd = NoH * NoH * (a2 - 1.0) + 1.0;
    // a2 / (4 pi R): dividing a2 by dd first keeps the intermediate in range at the clamp.
    float scaledInvR = (a2 / dd) / (dd * (NoL * (1.0 - k) + k) * 4.0 * FE_PI);
    vec3 EN = l.E * NoL;
    acc.Ldg += (1.0 - P) * EN;
    acc.Lsg1 += EN * scaledInvR;
    acc.Lsg2 += P * EN * scaledInvR;
}

// Redeferred material pass: L_d + L_s from the sums (emissive added by the caller).
vec3 feResolveMaterialNoV(IlluminationSums acc, float NoV, vec3 baseColor, float metallic, float roughness) {
    float r = feClampRoughness(roughness);
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    NoV = max(NoV, 1e-4);
    vec3 F0 = mix(vec3(0.04), baseColor, metallic);
    vec3 Ld = (1.0 - metallic) * (baseColor / FE_PI) * (1.0 - F0) * acc.Ldg;
    vec3 Ls = (F0 * acc.Lsg1 + (1.0 - F0) * acc.Lsg2) / (NoV * (1.0 - k) + k);
    return Ld + Ls;
}

vec3 feResolveMaterial(IlluminationSums acc, vec3 n, vec3 wo, vec3 baseColor, float metallic, float roughness) {
    return feResolveMaterialNoV(acc, dot(n, wo), baseColor, metallic, roughness);
}

vec3 feSrgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

#endif
