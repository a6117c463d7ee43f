// Image-based lighting by importance sampling: renderer/shading/ShadingModel.h shadeEnvironment
// in single precision, the same sequence, basis and estimator (keep the two in step). The
// environment is read from its cube map's top level, so the GPU and the reference evaluate the
// same integrand (up to the cube's interpolation).
#ifndef FE_IBL_GLSL
#define FE_IBL_GLSL
#include "fe_scene.glsl"

// Sampled: the environment's cube; FE_IBL_PREFILTERED: its GGX-prefiltered cube
// (PrefilteredEnvironment), roughness r at level r x (FE_PREFILTER_LEVELS - 1).
layout(binding = FE_SLOT_ENVIRONMENT) uniform samplerCube environment;

float feRadicalInverse(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}

vec3 feEnvironment(vec3 d) { return textureLod(environment, d, 0.0).rgb; }
// Hammersley point i of n: ((i + 1/2) / n, radical inverse of i).
vec2 feHammersley(uint i, uint n) { return vec2((float(i) + 0.5) / float(n), feRadicalInverse(i)); }
// Duff et al. 2017: an orthonormal basis (t, b, n) from n alone.
void feBasis(vec3 n, out vec3 t, out vec3 b) {
    const float sg = n.z >= 0.0 ? 1.0 : -1.0, ba = -1.0 / (sg + n.z), bc = n.x * n.y * ba;
    t = vec3(1.0 + sg * n.x * n.x * ba, sg * bc, -sg * n.x);
    b = vec3(bc, sg + n.y * n.y * ba, -n.y);
}
// GGX half vector for the point u (theta_h from A, phi_h = 2 pi B) about n; cosH its n.h.
vec3 feGgxHalfVector(vec2 u, float a2, vec3 t, vec3 b, vec3 n, out float cosH) {
    const float phi = 2.0 * FE_PI * u.y;
    cosH = sqrt((1.0 - u.x) / (u.x * (a2 - 1.0) + 1.0));
    const float sinH = sqrt(max(1.0 - cosH * cosH, 0.0));
    return t * (sinH * cos(phi)) + b * (sinH * sin(phi)) + n * cosH;
}
// A cosine-weighted direction for the point u about n.
vec3 feCosineDirection(vec2 u, vec3 t, vec3 b, vec3 n) {
    const float phi = 2.0 * FE_PI * u.y, cosD = sqrt(1.0 - u.x), sinD = sqrt(u.x);
    return t * (sinD * cos(phi)) + b * (sinD * sin(phi)) + n * cosD;
}

#ifdef FE_IBL_PREFILTERED
// The usual fast path (Karis, "Real Shading in Unreal Engine 4", 2013: the split sum; Ramamoorthi
// and Hanrahan, "An Efficient Representation for Irradiance Environment Maps", 2001): the
// estimators below with the environment's radiance taken out of the sums, as prefiltered
// radiance (specular, assuming n = v = r while prefiltering) and SH irradiance (diffuse), times
// the rest of each sum tabulated per (NoV, roughness) on the CPU (render/SplitSumTable.h, baked
// into the renderer: shading::splitSumTerms). Its bias against the
// sampled estimator is measured (docs/BENCHMARKS.md).
#define FE_SLOT_IBL_SH 23
#define FE_SLOT_IBL_LUT 24
const float FE_PREFILTER_LEVELS = 6.0;  // PrefilteredEnvironment::kLevels
layout(binding = FE_SLOT_IBL_SH, std140) uniform IrradianceBlock {
    vec4 sh[9];  // L2 spherical harmonics of the radiance, in Ramamoorthi-Hanrahan order
} irradiance;
// Two tables, one above the other: rows [0, H) the separable model's, [H, 2H) glTF's
// (render/SplitSumTable.h). x: (1/n) sum g, y: (1/n) sum P g over GGX samples, g = NoL VoH / ((NoL (1-k) + k)
// n.h (NoV (1-k) + k)) (separable) or 4 V NoL VoH / n.h (glTF); z: (1/n) sum (1 - P) over
// cosine-weighted samples.
layout(binding = FE_SLOT_IBL_LUT) uniform sampler2D iblLut;

// E(n) = integral of L cos over the hemisphere about n, from the radiance's SH (R&H eq. 13).
vec3 feShIrradiance(vec3 n) {
    const float c1 = 0.429043, c2 = 0.511664, c3 = 0.743125, c4 = 0.886227, c5 = 0.247708;
    const vec4 L00 = irradiance.sh[0], L1m1 = irradiance.sh[1], L10 = irradiance.sh[2], L11 = irradiance.sh[3];
    const vec4 L2m2 = irradiance.sh[4], L2m1 = irradiance.sh[5], L20 = irradiance.sh[6], L21 = irradiance.sh[7], L22 = irradiance.sh[8];
    const vec3 E = c1 * L22.rgb * (n.x * n.x - n.y * n.y) + c3 * L20.rgb * n.z * n.z + c4 * L00.rgb - c5 * L20.rgb +
                   2.0 * c1 * (L2m2.rgb * n.x * n.y + L21.rgb * n.x * n.z + L2m1.rgb * n.y * n.z) +
                   2.0 * c2 * (L11.rgb * n.x + L1m1.rgb * n.y + L10.rgb * n.z);
    return max(E, vec3(0.0));
}
struct FePrefiltered {
    vec3 radiance;  // prefiltered along the mirror direction
    vec3 E;         // irradiance about n
    vec3 lut;
    float NoV;
};
FePrefiltered fePrefiltered(vec3 n, vec3 wo, float roughness, bool gltf) {
    FePrefiltered p;
    const float r = feClampRoughness(roughness);
    p.NoV = max(dot(n, wo), 1e-4);
    p.radiance = textureLod(environment, reflect(-wo, n), r * (FE_PREFILTER_LEVELS - 1.0)).rgb;
    p.E = feShIrradiance(n);
    // Within the model's half, clamped to its outer texel centres so the filter never mixes halves.
    const float h = float(textureSize(iblLut, 0).y) * 0.5;
    const float row = clamp(r * h, 0.5, h - 0.5) + (gltf ? h : 0.0);
    p.lut = texture(iblLut, vec2(p.NoV, row / (2.0 * h))).xyz;
    return p;
}
IlluminationSums feEnvironmentSums(vec3 n, vec3 wo, float roughness, uint count) {
    const FePrefiltered p = fePrefiltered(n, wo, roughness, false);
    const float r = feClampRoughness(roughness), kp = (r + 1.0) * (r + 1.0) / 8.0;
    const float toPunctual = p.NoV * (1.0 - kp) + kp;  // the material pass divides by it
    return IlluminationSums(p.E * p.lut.z, p.radiance * (p.lut.x * toPunctual), p.radiance * (p.lut.y * toPunctual));
}
#else

// Redeferred: the environment's light as I-buffer sums (SHADING.md "The redeferred split", the
// seed's estimators): L_dg = (pi / n) sum (1 - P) L over cosine-weighted directions, and the
// specular sums over GGX half vectors stored as the punctual ones are (x alpha^2 / (4 pi)), then
// times (NoV (1 - k_p) + k_p) / (NoV (1 - k) + k), so that the material pass's common resolve,
// which divides by the punctual k_p's term, yields the environment's own k = alpha^2 / 2.
IlluminationSums feEnvironmentSums(vec3 n, vec3 wo, float roughness, uint count) {
    const float r = feClampRoughness(roughness), a = r * r, a2 = a * a, k = a2 / 2.0;
    const float kp = (r + 1.0) * (r + 1.0) / 8.0;
    const float NoV = max(dot(n, wo), 1e-4);
    vec3 t, b;
    feBasis(n, t, b);
    IlluminationSums acc = IlluminationSums(vec3(0.0), vec3(0.0), vec3(0.0));
    for (uint i = 0u; i < count; ++i) {
        const vec2 u = feHammersley(i, count);
        float cosH;
        const vec3 h = feGgxHalfVector(u, a2, t, b, n, cosH);
        const float VoH = dot(wo, h);
        const vec3 wi = 2.0 * VoH * h - wo;
        const float NoL = dot(n, wi);
        if (NoL > 0.0 && VoH > 0.0) {
            const float P = feFresnelPower(VoH);
            const vec3 term = feEnvironment(wi) * (NoL * VoH / ((NoL * (1.0 - k) + k) * cosH));
            acc.Lsg1 += term;
            acc.Lsg2 += P * term;
        }
        const vec3 wd = feCosineDirection(u, t, b, n);
        const float Pd = feFresnelPower(dot(normalize(wo + wd), wo));
        acc.Ldg += (1.0 - Pd) * feEnvironment(wd);
    }
    const float toPunctual = (NoV * (1.0 - kp) + kp) / (NoV * (1.0 - k) + k) / float(count);
    acc.Ldg *= FE_PI / float(count);
    acc.Lsg1 *= toPunctual;
    acc.Lsg2 *= toPunctual;
    return acc;
}
#endif  // FE_IBL_PREFILTERED

// L_o from the environment under glTF's BRDF (shading::shadeEnvironment with Brdf::Gltf): specular
// F L 4 V NoL (w_o.h) / (n.h), diffuse (1 - m) c 0.96 (1 - P) L, over the same samples; on the
// fast path the same weights tabulated (the table's glTF half) against prefiltered radiance.
vec3 feClearcoatEnvironment(SurfacePoint s, uint count);
vec3 feShadeEnvironmentBase(SurfacePoint s, uint count);

vec3 feShadeEnvironmentGltf(SurfacePoint s, uint count) {
    const vec3 base = feShadeEnvironmentBase(s, count);
#ifdef FE_LAYERED  // the clearcoat in the layered variants alone (fe_shading.glsl says why)
    if (s.clearcoat <= 0.0) return base;
    return base * (1.0 - s.clearcoat * feClearcoatViewFresnel(s)) + s.clearcoat * feClearcoatEnvironment(s, count);
#else
    return base;
#endif
}

// The clearcoat layer's image-based light: the specular estimator about its normal, at its
// roughness, Fresnel F0c .. 1 (shading::shadeEnvironment).
vec3 feClearcoatEnvironment(SurfacePoint s, uint count) {
    const float f0 = s.clearcoatF0;
#ifdef FE_IBL_PREFILTERED
    const FePrefiltered p = fePrefiltered(s.clearcoatNormal, s.wo, s.clearcoatRoughness, true);
    return p.radiance * (f0 * p.lut.x + (1.0 - f0) * p.lut.y);
#else
    const float r = feClampRoughness(s.clearcoatRoughness), a2 = r * r * r * r;
    const vec3 n = s.clearcoatNormal;
    const float NoV = max(dot(n, s.wo), 1e-4);
    vec3 t, b;
    feBasis(n, t, b);
    vec3 layer = vec3(0.0);
    for (uint i = 0u; i < count; ++i) {
        const vec2 u = feHammersley(i, count);
        float cosH;
        const vec3 h = feGgxHalfVector(u, a2, t, b, n, cosH);
        const float VoH = dot(s.wo, h);
        const vec3 wi = 2.0 * VoH * h - s.wo;
        const float NoL = dot(n, wi);
        if (NoL > 0.0 && VoH > 0.0)
            layer += (f0 + (1.0 - f0) * feFresnelPower(VoH)) * feEnvironment(wi) *
                     (4.0 * feVisibilityHeightCorrelated(NoL, NoV, a2) * NoL * VoH / cosH);
    }
    return layer / float(count);
#endif
}

// The base material (under any clearcoat) lit by the environment.
vec3 feShadeEnvironmentBase(SurfacePoint s, uint count) {
    // The dielectric's Fresnel F0 + (F90 - F0) P (KHR_materials_ior / specular; 0.04 and 1 by default).
    const vec3 dF0 = s.dielectricF0, dF90 = vec3(s.dielectricF90);
    const vec3 F0 = mix(dF0, s.baseColor, s.metallic), F90 = mix(dF90, vec3(1.0), s.metallic);
#ifdef FE_TRANSMISSION
    const vec3 diffuseColor = (1.0 - s.metallic) * (1.0 - s.transmission) * s.baseColor;  // the rest is transmitted
#else
    const vec3 diffuseColor = (1.0 - s.metallic) * s.baseColor;
#endif
#ifdef FE_IBL_PREFILTERED
    const FePrefiltered p = fePrefiltered(s.n, s.wo, s.roughness, true);
    // (1/n) sum (1 - F_d) = (1 - dF0) - (dF90 - dF0)(1 - z), z the table's (1/n) sum (1 - P).
    const vec3 diffuseWeight = (1.0 - dF0) - (dF90 - dF0) * (1.0 - p.lut.z);
    const vec3 base = diffuseColor / FE_PI * p.E * diffuseWeight + p.radiance * (F0 * p.lut.x + (F90 - F0) * p.lut.y);
#if defined(FE_MATERIAL_EXTENSIONS) && defined(FE_LAYERED)
    // The sheen's broad lobe by the irradiance, sheenColor E(n.w_o) E_irr / pi (the Sample Viewer
    // prefilters a cube by the Charlie lobe instead; docs/SHADING.md), over the base.
    if (s.sheenColor != vec3(0.0)) {
        const float albedo = feSheenAlbedo(max(dot(s.n, s.wo), 1e-4), s.sheenRoughness);
        const float sheenMax = max(s.sheenColor.r, max(s.sheenColor.g, s.sheenColor.b));
        return s.sheenColor * albedo * p.E / FE_PI + base * (1.0 - sheenMax * albedo);
    }
#endif
    return base;
#else
    const float r = feClampRoughness(s.roughness), a = r * r, a2 = a * a;
    const float NoV = max(dot(s.n, s.wo), 1e-4);
    vec3 t, b;
    feBasis(s.n, t, b);
    vec3 specular = vec3(0.0), diffuse = vec3(0.0), sheen = vec3(0.0);
    const bool sheenLayer = s.sheenColor != vec3(0.0);
    for (uint i = 0u; i < count; ++i) {
        const vec2 u = feHammersley(i, count);
        float cosH;
        const vec3 h = feGgxHalfVector(u, a2, t, b, s.n, cosH);
        const float VoH = dot(s.wo, h);
        const vec3 wi = 2.0 * VoH * h - s.wo;
        const float NoL = dot(s.n, wi);
        if (NoL > 0.0 && VoH > 0.0) {
            const float P = feFresnelPower(VoH);
            specular += (F0 + (F90 - F0) * P) * feEnvironment(wi) * (4.0 * feVisibilityHeightCorrelated(NoL, NoV, a2) * NoL * VoH / cosH);
        }
        const vec3 wd = feCosineDirection(u, t, b, s.n);
        const vec3 hd = normalize(s.wo + wd);
        const float Pd = feFresnelPower(dot(hd, s.wo));
        const vec3 Ld = feEnvironment(wd);
        diffuse += (1.0 - dF0 - (dF90 - dF0) * Pd) * Ld;
#if defined(FE_MATERIAL_EXTENSIONS) && defined(FE_LAYERED)
        // The sheen by the same directions: pi D V L (shading::shadeEnvironment).
        if (sheenLayer)
            sheen += (FE_PI * feCharlieD(s.sheenRoughness, dot(s.n, hd)) * feSheenVisibility(dot(s.n, wd), NoV, s.sheenRoughness)) * Ld;
#endif
    }
    const vec3 base = (diffuseColor * diffuse + specular) / float(count);
#if defined(FE_MATERIAL_EXTENSIONS) && defined(FE_LAYERED)
    if (sheenLayer) {
        const float sheenMax = max(s.sheenColor.r, max(s.sheenColor.g, s.sheenColor.b));
        return s.sheenColor * sheen / float(count) + base * (1.0 - sheenMax * feSheenAlbedo(NoV, s.sheenRoughness));
    }
#endif
    return base;
#endif
}

// L_o from the environment (shading::shadeEnvironment) under the frame's BRDF. Separable: the
// sums resolved as the redeferred material pass resolves them, L_d = (1 - m)(c / pi)(1 - F0) L_dg
// and L_s = (F0 L_sg1 + (1 - F0) L_sg2) / (NoV (1 - k_p) + k_p), which with the sums' rescaling
// is the estimator's own form.
vec3 feShadeEnvironment(SurfacePoint s, uint n) {
    if (frame.shading.x == FE_BRDF_GLTF) return feShadeEnvironmentGltf(s, n);
    return feResolveMaterialNoV(feEnvironmentSums(s.n, s.wo, s.roughness, n), dot(s.n, s.wo), s.baseColor, s.metallic,
                                s.roughness);
}
#endif
