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

// Specialization constants (render/ShaderFeatures.h): what the pipeline's scene holds, so that
// the driver's compiler drops the code of what it does not. CPU rasterizers run both sides of a
// branch under a lane mask, so a test of a uniform skips nothing; a constant removes the code.
// Unspecialized, everything is on. Lights: bit 0 directional, 1 point, 2 spot. BRDFs: bit 0
// glTF's, bit 1 the separable one (frame.shading.x picks when both are on).
layout(constant_id = 200) const uint FE_LIGHT_TYPES = 7u;
layout(constant_id = 201) const uint FE_BRDF_MODELS = 3u;

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
    float distance;  // to the light; 0 for a directional one
};

float feRangeWindow(float d, float range) {
    if (range <= 0.0) return 1.0;
    float q = d / range;
    float w = clamp(1.0 - q * q * q * q, 0.0, 1.0);
    return w * w;
}

// The light at P = origin + Pe. Camera-relative callers pass the eye-space offset Pe and the
// camera position: the light's position minus the camera's is exact in float where both are far
// from the origin and near each other, so the light vector keeps the offset's precision.
SurfaceLight feEvaluateLightAt(GpuLight L, vec3 Pe, vec3 origin) {
    SurfaceLight s;
    vec3 E = L.colorIntensity.rgb * L.colorIntensity.w;
    if ((FE_LIGHT_TYPES & 1u) != 0u && L.directionType.w == FE_LIGHT_DIRECTIONAL) {
        s.wi = -normalize(L.directionType.xyz);
        s.E = E;
        s.distance = 0.0;
        return s;
    }
    vec3 toLight = (L.positionRange.xyz - origin) - Pe;
    float d2 = max(dot(toLight, toLight), 1e-12);
    // The window from d^2 (q^4 = (d^2 / range^2)^2) and the direction by one reciprocal square
    // root: two divisions a light where the plain form takes five and a square root, which CPU
    // rasterizers pay for every light of every pixel.
    const float invD = inversesqrt(d2), range = L.positionRange.w;
    s.wi = toLight * invD;
    s.distance = d2 * invD;
    float window = 1.0;
    if (range > 0.0) {
        const float q2 = d2 / (range * range), w = clamp(1.0 - q2 * q2, 0.0, 1.0);
        window = w * w;
    }
    E *= window / d2;
    if ((FE_LIGHT_TYPES & 4u) != 0u && L.directionType.w == FE_LIGHT_SPOT) {
        float cosTheta = dot(normalize(L.directionType.xyz), -s.wi);
        float t = clamp(cosTheta * L.spotScaleOffset.x + L.spotScaleOffset.y, 0.0, 1.0);
        E *= t * t;
    }
    s.E = E;
    return s;
}
SurfaceLight feEvaluateLight(GpuLight L, vec3 P) { return feEvaluateLightAt(L, P, vec3(0.0)); }

struct SurfacePoint {
    vec3 P;          // world position
    vec3 Pe;         // eye space: P minus the camera position (camera-relative lighting)
    vec3 n;          // unit shading normal
    vec3 wo;         // unit vector to the eye
    vec3 baseColor;  // linear
    float metallic;
    float roughness; // perceptual, clamped by feMakeSurface
    // The dielectric's Fresnel (glTF model only): F0 and F90, 0.04 and 1 unless the material's
    // KHR_materials_ior / KHR_materials_specular say otherwise (a G-buffer holds the defaults).
    vec3 dielectricF0;
    float dielectricF90;
    // KHR_materials_clearcoat (glTF model only; 0 in a G-buffer): weight, perceptual roughness,
    // the layer's normal (the interpolated vertex normal) and its Fresnel F0 (F90 1).
    float clearcoat;
    float clearcoatRoughness;
    vec3 clearcoatNormal;
    float clearcoatF0;
    // KHR_materials_transmission and volume (glTF model, the transmission pass: FE_TRANSMISSION;
    // 0 elsewhere): the factor, the ray from P to where the light leaves the volume (0 thin-
    // walled), the index of refraction (0: infinite), the volume's transmittance along the ray.
    float transmission;
    vec3 transmissionRay;
    float ior;
    vec3 transmittance;
    // KHR_materials_sheen (glTF model, where the material is sampled: FE_MATERIAL_EXTENSIONS; 0
    // elsewhere): the sheen colour (0: none) and perceptual roughness.
    vec3 sheenColor;
    float sheenRoughness;
};

float feClampRoughness(float r) { return clamp(r, FE_MIN_ROUGHNESS, 1.0); }

// Schlick's (1 - cos)^5 for cos in [-1, 1]: clamped (a rounding-negative base), and by two
// multiplications squared and one more rather than pow(), which CPU rasterizers evaluate as
// exp2(5 log2 x) once per light and pixel.
float feFresnelPower(float cosTheta) {
    const float x = clamp(1.0 - cosTheta, 0.0, 1.0), x2 = x * x;
    return x2 * x2 * x;
}

// The roughness terms of the BRDF, prepared once per pixel by loops over lights (SurfaceBrdf below).
struct RoughnessTerms {
    float a2;  // alpha^2, alpha = clamped roughness^2
    float k;   // Schlick-GGX k
};

RoughnessTerms feRoughnessTerms(float roughness) {
    float r = feClampRoughness(roughness);
    float a = r * r;
    return RoughnessTerms(a * a, (r + 1.0) * (r + 1.0) / 8.0);
}

// The two shading models (RenderSettings::shadingModel, frame.shading.x; docs/SHADING.md):
// glTF 2.0's (Appendix B: height-correlated Smith-GGX visibility, the dielectric Fresnel on the
// diffuse lobe) and the seeds' separable one (../shared/SHADING.md: Schlick-GGX G, k = (r+1)^2/8),
// which the redeferred factorisation needs.
const uint FE_BRDF_GLTF = 0u;
const uint FE_BRDF_SEPARABLE = 1u;

// glTF's V = G / (4 NoL NoV), height-correlated Smith-GGX (Heitz 2014), for NoL, NoV > 0.
float feVisibilityHeightCorrelated(float NoL, float NoV, float a2) {
    const float gv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    const float gl = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / (gv + gl);
}

// The factors of the per-light BRDF sum that depend on the surface alone. Loops over lights
// (forward, tiled) prepare them once per pixel: CPU rasterizers' shader compilers do not move
// them out of the loop (on lavapipe that measured 5 % of the tiled lighting pass).
struct SurfaceBrdf {
    vec3 n;        // unit shading normal
    vec3 wo;       // unit vector to the eye
    vec3 F0;       // specular colour at normal incidence
    vec3 F90;      // ... and at grazing incidence (glTF: 1 unless KHR_materials_specular lowers it)
    vec3 dielectricF0;
    float dielectricF90;
    // The clearcoat layer (clearcoat 0: none): its normal, alpha^2, n_c.v, F0, and the weight of
    // the base under it, 1 - clearcoat Fc(n_c.v) (feClearcoatViewFresnel).
    float clearcoat;
    vec3 nc;
    float a2c;
    float NoVc;
    float clearcoatF0;
    float baseWeight;
    vec3 diffuse;  // (1 - metallic) baseColor / pi
    float a2;      // alpha^2, alpha = clamped roughness^2
    float k;       // Schlick-GGX k
    float NoV;
    float Gv;      // the view half of G (separable)
    bool gltf;     // FE_BRDF_GLTF, else FE_BRDF_SEPARABLE
    // The sheen layer (sheenMax 0: none): colour, roughness, max(colour) and the albedo at n.w_o.
    vec3 sheenColor;
    float sheenRoughness;
    float sheenMax;
    float sheenAlbedoV;
#ifdef FE_TRANSMISSION
    // (1 - metallic) transmission baseColor x the volume's transmittance; the transmission
    // alpha^2 (shading::transmissionAlpha); the ray to where the light leaves the volume.
    vec3 transmitted;
    float a2t;
    vec3 transmissionRay;
#endif
};

#ifdef FE_MATERIAL_EXTENSIONS
// KHR_materials_sheen (shading::charlieD, sheenVisibility, sheenAlbedo): the Charlie distribution
// and Estevez-Kulla visibility; the sheen's albedo from the table shading::sheenAlbedoTable makes
// (GpuScene uploads it, bound with every material's textures), read bilinearly between its grid
// points as the CPU reads it. Defined where the material is sampled (fe_material.glsl).
#define FE_SLOT_SHEEN_ALBEDO 44
const int FE_SHEEN_TABLE_SIZE = 32;
layout(binding = FE_SLOT_SHEEN_ALBEDO) uniform sampler2D feSheenAlbedoTable;
float feSheenAlbedo(float NoV, float roughness) {
    const vec2 p = clamp(vec2(NoV, roughness), 0.0, 1.0) * float(FE_SHEEN_TABLE_SIZE - 1);
    const ivec2 p0 = min(ivec2(p), ivec2(FE_SHEEN_TABLE_SIZE - 2));
    const vec2 f = p - vec2(p0);
    const float a = texelFetch(feSheenAlbedoTable, p0, 0).r, b = texelFetch(feSheenAlbedoTable, p0 + ivec2(1, 0), 0).r;
    const float c = texelFetch(feSheenAlbedoTable, p0 + ivec2(0, 1), 0).r, d = texelFetch(feSheenAlbedoTable, p0 + ivec2(1, 1), 0).r;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}
float feCharlieD(float roughness, float NoH) {
    const float r = max(roughness, 1e-6), invA = 1.0 / (r * r), sin2 = max(1.0 - NoH * NoH, 0.0);
    return (2.0 + invA) * pow(sin2, 0.5 * invA) / (2.0 * FE_PI);
}
float feSheenLambdaFit(float x, float a) {
    const float t = (1.0 - a) * (1.0 - a);
    const float p = mix(21.5473, 25.3245, t), q = mix(3.82987, 3.32435, t), r = mix(0.19823, 0.16801, t);
    const float u = mix(-1.97760, -1.27393, t), w = mix(-4.32054, -4.85967, t);
    return p / (1.0 + q * pow(x, r)) + u * x + w;
}
float feSheenLambda(float cosTheta, float a) {
    return abs(cosTheta) < 0.5 ? exp(feSheenLambdaFit(cosTheta, a))
                               : exp(2.0 * feSheenLambdaFit(0.5, a) - feSheenLambdaFit(1.0 - cosTheta, a));
}
float feSheenVisibility(float NoL, float NoV, float roughness) {
    const float r = max(roughness, 1e-6), a = r * r;
    return clamp(1.0 / ((1.0 + feSheenLambda(NoV, a) + feSheenLambda(NoL, a)) * (4.0 * NoV * NoL)), 0.0, 1.0);
}
#endif

// The clearcoat's Fresnel seen from w_o along its normal (shading::clearcoatViewFresnel).
float feClearcoatViewFresnel(SurfacePoint s) {
    return s.clearcoatF0 + (1.0 - s.clearcoatF0) * feFresnelPower(clamp(dot(s.clearcoatNormal, s.wo), 0.0, 1.0));
}

SurfaceBrdf fePrepareBrdf(SurfacePoint s, uint model) {
    SurfaceBrdf b;
    b.gltf = FE_BRDF_MODELS == 1u || (FE_BRDF_MODELS != 2u && model == FE_BRDF_GLTF);
    b.n = s.n;
    b.wo = s.wo;
    const RoughnessTerms t = feRoughnessTerms(s.roughness);
    b.a2 = t.a2;
    b.k = t.k;
    b.NoV = max(dot(s.n, s.wo), 1e-4);
    b.Gv = b.NoV / (b.NoV * (1.0 - b.k) + b.k);
    b.dielectricF0 = b.gltf ? s.dielectricF0 : vec3(0.04);
    b.dielectricF90 = b.gltf ? s.dielectricF90 : 1.0;
    b.F0 = mix(b.dielectricF0, s.baseColor, s.metallic);
    b.F90 = mix(vec3(b.dielectricF90), vec3(1.0), s.metallic);
    b.diffuse = (1.0 - s.metallic) * s.baseColor / FE_PI;
#ifdef FE_TRANSMISSION
    // Transmission replaces that much of the diffuse lobe (glTF model only).
    const float transmission = b.gltf ? s.transmission : 0.0;
    b.diffuse *= 1.0 - transmission;
    b.transmitted = (1.0 - s.metallic) * transmission * s.baseColor * s.transmittance;
    const float iorScale = s.ior == 0.0 ? 1.0 : clamp(2.0 * s.ior - 2.0, 0.0, 1.0);
    const float at = max(sqrt(t.a2) * iorScale, FE_MIN_ROUGHNESS * FE_MIN_ROUGHNESS);
    b.a2t = at * at;
    b.transmissionRay = s.transmissionRay;
#endif
#ifdef FE_LAYERED
    b.clearcoat = b.gltf ? s.clearcoat : 0.0;
#else
    b.clearcoat = 0.0;  // the scene has no layered material (GpuScene::hasLayeredMaterials)
#endif
    b.nc = s.clearcoatNormal;
    const float rc = feClampRoughness(s.clearcoatRoughness);
    b.a2c = rc * rc * rc * rc;
    b.NoVc = max(dot(s.clearcoatNormal, s.wo), 1e-4);
    b.clearcoatF0 = s.clearcoatF0;
    b.baseWeight = 1.0 - b.clearcoat * feClearcoatViewFresnel(s);
    b.sheenColor = s.sheenColor;
    b.sheenRoughness = s.sheenRoughness;
    b.sheenMax = 0.0;
    b.sheenAlbedoV = 0.0;
#if defined(FE_MATERIAL_EXTENSIONS) && defined(FE_LAYERED)
    b.sheenMax = b.gltf ? max(s.sheenColor.r, max(s.sheenColor.g, s.sheenColor.b)) : 0.0;
    if (b.sheenMax > 0.0) b.sheenAlbedoV = feSheenAlbedo(b.NoV, b.sheenRoughness);
#endif
    return b;
}

vec3 feShadeBaseLight(SurfaceBrdf b, SurfaceLight l);

// Forward: the full per-light BRDF sum (SHADING.md "Per light"); with a clearcoat (glTF model)
// the base weighed by 1 - c Fc(n_c.v) and the layer's Fc D V E n_c.l added (shading::shadeLight).
vec3 feShadeLight(SurfaceBrdf b, SurfaceLight l) {
    vec3 L = feShadeBaseLight(b, l);
    // The layers exist in the FE_LAYERED variants only: on CPU rasterizers a branch around code
    // in this loop costs what the code costs (GpuScene::hasLayeredMaterials).
#if defined(FE_MATERIAL_EXTENSIONS) && defined(FE_LAYERED)
    // The sheen over the base (shading::sheenLight): sheenColor D V n.l E added, the base weighed
    // by min(1 - max(sheenColor) E(n.w_o), 1 - max(sheenColor) E(n.l)).
    if (b.sheenMax > 0.0) {
        const float NoL = clamp(dot(b.n, l.wi), 0.0, 1.0);
        const float weight = min(1.0 - b.sheenMax * b.sheenAlbedoV, 1.0 - b.sheenMax * feSheenAlbedo(NoL, b.sheenRoughness));
        vec3 sheen = vec3(0.0);
        if (NoL > 0.0) {
            const float NoH = dot(b.n, normalize(b.wo + l.wi));
            sheen = b.sheenColor * (feCharlieD(b.sheenRoughness, NoH) * feSheenVisibility(NoL, b.NoV, b.sheenRoughness) * NoL) * l.E;
        }
        L = sheen + L * weight;
    }
#endif
#ifdef FE_LAYERED
    if (b.clearcoat <= 0.0) return L;
    L *= b.baseWeight;
    const float NoLc = dot(b.nc, l.wi);
    if (NoLc > 0.0) {
        const vec3 h = normalize(b.wo + l.wi);
        const float NoHc = dot(b.nc, h), P = feFresnelPower(dot(h, b.wo));
        const float dd = NoHc * NoHc * (b.a2c - 1.0) + 1.0, D = b.a2c / (FE_PI * dd * dd);
        const float Fc = b.clearcoatF0 + (1.0 - b.clearcoatF0) * P;
        L += b.clearcoat * Fc * D * feVisibilityHeightCorrelated(NoLc, b.NoVc, b.a2c) * NoLc * l.E;
    }
#endif
    return L;
}

#ifdef FE_TRANSMISSION
// A punctual light through a transmissive surface (shading::transmittedLight): (1 - F_t) D V
// with the light mirrored through the surface, seen from where it leaves the volume, under the
// diffuse lobe's (1 - F_d); no n.l.
vec3 feTransmittedLight(SurfaceBrdf b, SurfaceLight l) {
    const vec3 wi = l.distance > 0.0 ? normalize(l.wi * l.distance - b.transmissionRay) : l.wi;
    const vec3 mirrored = wi - 2.0 * b.n * dot(wi, b.n);
    const vec3 h = normalize(mirrored + b.wo);
    const float NoH = clamp(dot(b.n, h), 0.0, 1.0), NoL = clamp(dot(b.n, mirrored), 0.0, 1.0);
    const float dd = NoH * NoH * (b.a2t - 1.0) + 1.0, D = b.a2t / (FE_PI * dd * dd);
    const vec3 Ft = b.dielectricF0 + (b.dielectricF90 - b.dielectricF0) * feFresnelPower(dot(b.wo, h));
    // cos of the reflection half vector with w_o, defined where the light is straight behind.
    const float VoHr = sqrt(max(0.5 * (1.0 + dot(b.wo, l.wi)), 0.0));
    const vec3 Fd = b.dielectricF0 + (b.dielectricF90 - b.dielectricF0) * feFresnelPower(VoHr);
    return (1.0 - Fd) * (1.0 - Ft) * b.transmitted * (D * feVisibilityHeightCorrelated(NoL, b.NoV, b.a2t)) * l.E;
}
#endif

vec3 feShadeBaseLight(SurfaceBrdf b, SurfaceLight l) {
    float NoL = dot(b.n, l.wi);
#ifdef FE_TRANSMISSION
    const vec3 transmitted = b.gltf ? feTransmittedLight(b, l) : vec3(0.0);
    if (NoL <= 0.0) return transmitted;
#else
    const vec3 transmitted = vec3(0.0);
    if (NoL <= 0.0) return vec3(0.0);
#endif
    vec3 h = normalize(b.wo + l.wi);
    float NoH = dot(b.n, h);
    float P = feFresnelPower(dot(h, b.wo));
    vec3 F = b.F0 + (b.F90 - b.F0) * P;
    float dd = NoH * NoH * (b.a2 - 1.0) + 1.0;
    float D = b.a2 / (FE_PI * dd * dd);
    if (b.gltf) {
        // mix(dielectric, metal, metallic): the diffuse lobe under the dielectric's Fresnel
        // (F0 0.04, F90 1 by default), the specular under F = mix(F_dielectric, F_metal, metallic)
        // = F0 + (F90 - F0) P.
        const vec3 Fd = b.dielectricF0 + (b.dielectricF90 - b.dielectricF0) * P;
        const vec3 f = (1.0 - Fd) * b.diffuse + D * F * feVisibilityHeightCorrelated(NoL, b.NoV, b.a2);
        return f * l.E * NoL + transmitted;
    }
    float G = b.Gv * NoL / (NoL * (1.0 - b.k) + b.k);
    vec3 f = (1.0 - F) * b.diffuse + D * F * G / (4.0 * b.NoV * NoL);
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

void feAccumulateIllumination(inout IlluminationSums acc, vec3 n, vec3 wo, RoughnessTerms t, SurfaceLight l) {
    float NoL = dot(n, l.wi);
    if (NoL <= 0.0) return;
    const float a2 = t.a2, k = t.k;
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

void feAccumulateIllumination(inout IlluminationSums acc, vec3 n, vec3 wo, float roughness, SurfaceLight l) {
    feAccumulateIllumination(acc, n, wo, feRoughnessTerms(roughness), l);
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
