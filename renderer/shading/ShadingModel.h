// The shading models on the CPU, in double precision: the independent reference every GPU
// technique is tested against (and the source of truth when the GLSL in
// shaders/include/fe_shading.glsl is changed: the two must stay in step). Two BRDFs
// (docs/SHADING.md): glTF 2.0's (Appendix B), the default, and the separable one of
// ../shared/SHADING.md, whose factorisation the redeferred techniques need.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace fe::shading {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinRoughness = 0.045;

// x^5 by three products, for Schlick's Fresnel (std::pow was 5 % of an image-based-lighting
// reference's time; the two differ in the last bits only).
inline double pow5(double x) {
    const double x2 = x * x;
    return x2 * x2 * x;
}

enum class LightType { Directional, Point, Spot };

struct LightSample {
    glm::dvec3 wi{0.0};  // unit vector to the light
    glm::dvec3 E{0.0};   // irradiance at normal incidence
    double distance =
        std::numeric_limits<double>::infinity();  // to the light (directional: infinite)
};

struct PunctualLight {
    LightType type = LightType::Point;
    glm::dvec3 position{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};  // where the light points (spot, directional)
    glm::dvec3 color{1.0};
    double intensity = 1.0;  // lux (directional) or candela
    double range = 0.0;      // 0 = infinite
    double innerConeAngle = 0.0;
    double outerConeAngle = kPi / 4.0;

    // s and o of SHADING.md's spot falloff.
    double spotScale() const {
        return 1.0 / std::max(0.001, std::cos(innerConeAngle) - std::cos(outerConeAngle));
    }
    double spotOffset() const { return -std::cos(outerConeAngle) * spotScale(); }
};

inline double rangeWindow(double d, double range) {
    if (range <= 0.0) return 1.0;
    double q = d / range;
    double w = std::clamp(1.0 - q * q * q * q, 0.0, 1.0);
    return w * w;
}

inline LightSample evaluateLight(const PunctualLight& L, const glm::dvec3& P) {
    LightSample s;
    glm::dvec3 E = L.color * L.intensity;
    if (L.type == LightType::Directional) {
        s.wi = -glm::normalize(L.direction);
        s.E = E;
        return s;
    }
    glm::dvec3 toLight = L.position - P;
    double d2 = std::max(glm::dot(toLight, toLight), 1e-12);
    double d = std::sqrt(d2);
    s.wi = toLight / d;
    s.distance = d;
    E *= rangeWindow(d, L.range) / d2;
    if (L.type == LightType::Spot) {
        double cosTheta = glm::dot(glm::normalize(L.direction), -s.wi);
        double t = std::clamp(cosTheta * L.spotScale() + L.spotOffset(), 0.0, 1.0);
        E *= t * t;
    }
    s.E = E;
    return s;
}

struct SurfacePoint {
    glm::dvec3 P{0.0};
    glm::dvec3 n{0.0, 0.0, 1.0};
    glm::dvec3 wo{0.0, 0.0, 1.0};
    glm::dvec3 baseColor{1.0};
    double metallic = 0.0;
    double roughness = 1.0;  // perceptual; clamped here
    // The dielectric's Fresnel under the glTF model (KHR_materials_ior / specular: Material::
    // dielectricF0 and dielectricF90); the separable model keeps 0.04 and 1.
    glm::dvec3 dielectricF0{0.04};
    double dielectricF90 = 1.0;
    // KHR_materials_clearcoat (glTF model only): weight, perceptual roughness, the layer's normal
    // (the interpolated vertex normal, not the base's normal map) and its Fresnel F0 (F90 1).
    double clearcoat = 0.0;
    double clearcoatRoughness = 0.0;
    glm::dvec3 clearcoatNormal{0.0, 0.0, 1.0};
    double clearcoatF0 = 0.04;
    // KHR_materials_transmission and volume (glTF model only): the factor, the ray from P to
    // where the light leaves the volume (0 thin-walled; transmissionRay()), the index of
    // refraction, the volume's transmittance along that ray (volumeTransmittance()).
    double transmission = 0.0;
    glm::dvec3 transmissionRay{0.0};
    double ior = 1.5;
    glm::dvec3 transmittance{1.0};
    // KHR_materials_sheen (glTF model only): the sheen colour (0: none) and perceptual roughness.
    glm::dvec3 sheenColor{0.0};
    double sheenRoughness = 0.0;
};

// KHR_materials_sheen, as the Khronos Sample Viewer 1.1.0 evaluates it: the Charlie distribution
// and the visibility of Estevez and Kulla ("Production Friendly Microfacet Sheen BRDF", 2017),
// their fitted lambda, alpha = roughness^2 (roughness at least 1e-6).
inline double sheenAlpha(double roughness) {
    const double r = std::max(roughness, 1e-6);
    return r * r;
}
inline double charlieD(double roughness, double NoH) {
    const double invA = 1.0 / sheenAlpha(roughness), sin2 = std::max(1.0 - NoH * NoH, 0.0);
    return (2.0 + invA) * std::pow(sin2, 0.5 * invA) / (2.0 * kPi);
}
inline double sheenLambdaFit(double x, double a) {
    const double t = (1.0 - a) * (1.0 - a);
    const double p = 21.5473 + (25.3245 - 21.5473) * t, q = 3.82987 + (3.32435 - 3.82987) * t,
                 r = 0.19823 + (0.16801 - 0.19823) * t, u = -1.97760 + (-1.27393 + 1.97760) * t,
                 w = -4.32054 + (-4.85967 + 4.32054) * t;
    return p / (1.0 + q * std::pow(x, r)) + u * x + w;
}
inline double sheenLambda(double cosTheta, double a) {
    if (std::abs(cosTheta) < 0.5) return std::exp(sheenLambdaFit(cosTheta, a));
    return std::exp(2.0 * sheenLambdaFit(0.5, a) - sheenLambdaFit(1.0 - cosTheta, a));
}
inline double sheenVisibility(double NoL, double NoV, double roughness) {
    const double a = sheenAlpha(roughness);
    const double v = 1.0 / ((1.0 + sheenLambda(NoV, a) + sheenLambda(NoL, a)) * (4.0 * NoV * NoL));
    return std::isnan(v) ? 1.0 : std::clamp(v, 0.0, 1.0);
}

// The sheen's directional albedo E(cos, roughness) with colour 1, the integral of D V n.l over the
// hemisphere (midpoint rule, 48 x 48 directions), tabulated at kSheenTableSize^2 grid points
// (cos = i / (n - 1) along a row, roughness = j / (n - 1) down the rows) and read bilinearly: the
// base under the sheen keeps 1 - max(sheenColor) E (the Sample Viewer reads its own table). The
// GPU reads the same table (GpuScene uploads it). The integral is clamped to 1: near grazing the
// fitted visibility (clamped to 1 itself) lets the smoothest sheens' integral reach 2, which would
// weigh the base negatively.
constexpr int kSheenTableSize = 32;
inline double sheenAlbedoIntegral(double NoV, double roughness) {
    const int nTheta = 48, nPhi = 48;
    const glm::dvec3 v(std::sqrt(std::max(1.0 - NoV * NoV, 0.0)), 0.0, NoV);
    double sum = 0.0;
    for (int i = 0; i < nTheta; ++i) {
        const double theta = (i + 0.5) / nTheta * 0.5 * kPi, c = std::cos(theta),
                     sn = std::sin(theta);
        for (int k = 0; k < nPhi; ++k) {  // phi in [0, pi]: the integrand is even in phi
            const double phi = (k + 0.5) / nPhi * kPi;
            const glm::dvec3 l(sn * std::cos(phi), sn * std::sin(phi), c);
            const glm::dvec3 h = glm::normalize(v + l);
            sum += charlieD(roughness, h.z) * sheenVisibility(c, std::max(NoV, 1e-4), roughness) *
                   c * sn;
        }
    }
    return 2.0 * sum * (0.5 * kPi / nTheta) * (kPi / nPhi);
}
inline const std::vector<float>& sheenAlbedoTable() {
    static const std::vector<float> table = [] {
        std::vector<float> t(size_t(kSheenTableSize) * kSheenTableSize);
        for (int j = 0; j < kSheenTableSize; ++j)
            for (int i = 0; i < kSheenTableSize; ++i)
                t[size_t(j) * kSheenTableSize + i] =
                    float(std::min(sheenAlbedoIntegral(double(i) / (kSheenTableSize - 1),
                                                       double(j) / (kSheenTableSize - 1)),
                                   1.0));
        return t;
    }();
    return table;
}
inline double sheenAlbedo(double NoV, double roughness) {
    const std::vector<float>& t = sheenAlbedoTable();
    const double x = std::clamp(NoV, 0.0, 1.0) * (kSheenTableSize - 1),
                 y = std::clamp(roughness, 0.0, 1.0) * (kSheenTableSize - 1);
    const int x0 = std::min(int(x), kSheenTableSize - 2),
              y0 = std::min(int(y), kSheenTableSize - 2);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int i, int j) { return double(t[size_t(j) * kSheenTableSize + i]); };
    return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
           (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}
inline double maxComponent(const glm::dvec3& c) { return std::max({c.r, c.g, c.b}); }
// A punctual light's sheen, sheenColor D V n.l E, and the weight of the base under it,
// min(1 - max(sheenColor) E(n.w_o), 1 - max(sheenColor) E(n.l)).
inline glm::dvec3 sheenLight(const SurfacePoint& s, const glm::dvec3& wi, double NoV,
                             const glm::dvec3& E, double& baseWeight) {
    const double NoL = std::clamp(glm::dot(s.n, wi), 0.0, 1.0), m = maxComponent(s.sheenColor);
    baseWeight = std::min(1.0 - m * sheenAlbedo(NoV, s.sheenRoughness),
                          1.0 - m * sheenAlbedo(NoL, s.sheenRoughness));
    if (NoL <= 0.0) return glm::dvec3(0.0);
    const double NoH = glm::dot(s.n, glm::normalize(s.wo + wi));
    return s.sheenColor * charlieD(s.sheenRoughness, NoH) *
           sheenVisibility(NoL, NoV, s.sheenRoughness) * NoL * E;
}

// KHR_materials_volume, as the Sample Viewer traces it: the refracted view ray (ior; infinite
// leaves it unbent) scaled by the thickness in mesh units times the mesh's axis scales.
inline glm::dvec3 transmissionRay(const glm::dvec3& n, const glm::dvec3& wo, double thickness,
                                  double ior, const glm::dvec3& meshScale) {
    if (thickness <= 0.0) return glm::dvec3(0.0);
    const glm::dvec3 refracted = std::isinf(ior) ? -wo : glm::refract(-wo, n, 1.0 / ior);
    const double len = glm::length(refracted);
    return (len > 0.0 ? refracted / len : -wo) * thickness * meshScale;
}
// Beer-Lambert: attenuationColor^(distance / attenuationDistance) (infinite distance: 1).
inline glm::dvec3 volumeTransmittance(const glm::dvec3& attenuationColor,
                                      double attenuationDistance, double distance) {
    if (std::isinf(attenuationDistance) || distance <= 0.0) return glm::dvec3(1.0);
    return glm::pow(attenuationColor, glm::dvec3(distance / attenuationDistance));
}
// Rough transmission's alpha: the surface's, scaled by clamp(2 ior - 2, 0, 1) (an index of 1
// bends nothing; the Sample Viewer's applyIorToRoughness), never below the clamp's alpha.
inline double transmissionAlpha(double alpha, double ior) {
    const double scale = std::isinf(ior) ? 1.0 : std::clamp(2.0 * ior - 2.0, 0.0, 1.0);
    return std::max(alpha * scale, kMinRoughness * kMinRoughness);
}

// The clearcoat's Fresnel seen from w_o along its normal: the base under it is weighed by
// 1 - clearcoat Fc (KHR_materials_clearcoat, as the Sample Viewer layers it).
inline double clearcoatViewFresnel(const SurfacePoint& s) {
    const double NoV = std::clamp(glm::dot(s.clearcoatNormal, s.wo), 0.0, 1.0);
    return s.clearcoatF0 + (1.0 - s.clearcoatF0) * pow5(1.0 - NoV);
}

inline double clampRoughness(double r) { return std::clamp(r, kMinRoughness, 1.0); }

// Gltf: glTF 2.0 Appendix B, as the Khronos Sample Viewer and Filament evaluate it: Lambert
// diffuse under the dielectric Fresnel (F0 = 0.04), GGX D, height-correlated Smith-GGX
// visibility, Schlick Fresnel mixed by metallic. Separable: ../shared/SHADING.md, the seeds'
// model (Schlick-GGX G with k = (r+1)^2/8, diffuse under the mixed Fresnel), whose light sums
// factor out of the material (the redeferred split below).
enum class Brdf { Gltf, Separable };

// glTF's V = G / (4 NoL NoV), height-correlated Smith-GGX (Heitz 2014, eq. 99).
inline double visibilityHeightCorrelated(double NoL, double NoV, double a2) {
    const double gv = NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2);
    const double gl = NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / (gv + gl);
}

// The clearcoat layer's light: Fc D V E n_c.l with its own normal and roughness (GGX, height-
// correlated V, Fc = F0c + (1 - F0c) P at the half vector), the Sample Viewer's clearcoat BRDF.
inline double clearcoatLight(const SurfacePoint& s, const glm::dvec3& wi) {
    const glm::dvec3& n = s.clearcoatNormal;
    const double NoL = glm::dot(n, wi);
    if (NoL <= 0.0) return 0.0;
    const double r = clampRoughness(s.clearcoatRoughness), a2 = r * r * r * r;
    const double NoV = std::max(glm::dot(n, s.wo), 1e-4);
    const glm::dvec3 h = glm::normalize(s.wo + wi);
    const double NoH = glm::dot(n, h), P = pow5(std::clamp(1.0 - glm::dot(h, s.wo), 0.0, 1.0));
    const double dd = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (kPi * dd * dd);
    return (s.clearcoatF0 + (1.0 - s.clearcoatF0) * P) * D *
           visibilityHeightCorrelated(NoL, NoV, a2) * NoL;
}

inline glm::dvec3 shadeBaseLight(const SurfacePoint& s, const LightSample& l, Brdf brdf);

// Per light: f x E x NoL; under the glTF model with a clearcoat, the base weighed by 1 - c Fc
// and the layer's light added.
inline glm::dvec3 shadeLight(const SurfacePoint& s, const LightSample& l, Brdf brdf = Brdf::Gltf) {
    if (brdf != Brdf::Gltf) return shadeBaseLight(s, l, brdf);
    glm::dvec3 base = shadeBaseLight(s, l, brdf);
    if (s.sheenColor != glm::dvec3(0.0)) {  // the sheen over the base (KHR_materials_sheen)
        double weight = 1.0;
        const glm::dvec3 sheen =
            sheenLight(s, l.wi, std::max(glm::dot(s.n, s.wo), 1e-4), l.E, weight);
        base = sheen + base * weight;
    }
    if (s.clearcoat <= 0.0) return base;
    return base * (1.0 - s.clearcoat * clearcoatViewFresnel(s)) +
           s.clearcoat * clearcoatLight(s, l.wi) * l.E;
}

// A punctual light through a transmissive surface (glTF model): the thin-walled BTDF of
// KHR_materials_transmission as the Sample Viewer evaluates it, (1 - F) baseColor D V with the
// light direction mirrored through the surface (seen from where it leaves the volume) and the
// transmission alpha, attenuated by the volume, under the diffuse lobe's (1 - F_d) and weighed
// by (1 - metallic) transmission; no n.l (docs/SHADING.md).
inline glm::dvec3 transmittedLight(const SurfacePoint& s, const LightSample& l) {
    if (s.transmission <= 0.0 || s.metallic >= 1.0) return glm::dvec3(0.0);
    const glm::dvec3 wi =
        std::isinf(l.distance) ? l.wi : glm::normalize(l.wi * l.distance - s.transmissionRay);
    const glm::dvec3 mirrored = wi - 2.0 * s.n * glm::dot(wi, s.n);
    const double r = clampRoughness(s.roughness), at = transmissionAlpha(r * r, s.ior),
                 a2 = at * at;
    const glm::dvec3 h = glm::normalize(mirrored + s.wo);
    const double NoH = std::clamp(glm::dot(s.n, h), 0.0, 1.0);
    const double NoL = std::clamp(glm::dot(s.n, mirrored), 0.0, 1.0),
                 NoV = std::max(glm::dot(s.n, s.wo), 1e-4);
    const double dd = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (kPi * dd * dd);
    auto power5 = [](double c) { return pow5(std::clamp(1.0 - c, 0.0, 1.0)); };
    const glm::dvec3 Ft =
        s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * power5(glm::dot(s.wo, h));
    // The reflection half vector's cosine with w_o, sqrt((1 + w_o.w_i) / 2): defined (0) where the
    // light is straight behind the surface, where normalize(w_o + w_i) is not.
    const double VoHr = std::sqrt(std::max(0.5 * (1.0 + glm::dot(s.wo, l.wi)), 0.0));
    const glm::dvec3 Fd = s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * power5(VoHr);
    const glm::dvec3 btdf = (1.0 - Ft) * s.baseColor * D * visibilityHeightCorrelated(NoL, NoV, a2);
    return (1.0 - s.metallic) * s.transmission * (1.0 - Fd) * btdf * s.transmittance * l.E;
}

inline glm::dvec3 shadeBaseLight(const SurfacePoint& s, const LightSample& l, Brdf brdf) {
    double NoL = glm::dot(s.n, l.wi);
    const glm::dvec3 transmitted = brdf == Brdf::Gltf ? transmittedLight(s, l) : glm::dvec3(0.0);
    if (NoL <= 0.0) return transmitted;
    double r = clampRoughness(s.roughness);
    double a = r * r, a2 = a * a;
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    double NoV = std::max(glm::dot(s.n, s.wo), 1e-4);
    glm::dvec3 h = glm::normalize(s.wo + l.wi);
    double NoH = glm::dot(s.n, h);
    double P = pow5(std::clamp(1.0 - glm::dot(h, s.wo), 0.0, 1.0));
    glm::dvec3 F0 = glm::mix(glm::dvec3(0.04), s.baseColor, s.metallic);
    glm::dvec3 F = F0 + (1.0 - F0) * P;
    double dd = NoH * NoH * (a2 - 1.0) + 1.0;
    double D = a2 / (kPi * dd * dd);
    if (brdf == Brdf::Gltf) {
        const glm::dvec3 Fd = s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * P;
        const glm::dvec3 Fm = glm::mix(s.dielectricF0, s.baseColor, s.metallic) +
                              (glm::mix(glm::dvec3(s.dielectricF90), glm::dvec3(1.0), s.metallic) -
                               glm::mix(s.dielectricF0, s.baseColor, s.metallic)) *
                                  P;
        const glm::dvec3 diffuse =
            (1.0 - s.metallic) * (1.0 - s.transmission) * s.baseColor / kPi * (1.0 - Fd);
        return (diffuse + D * Fm * visibilityHeightCorrelated(NoL, NoV, a2)) * l.E * NoL +
               transmitted;
    }
    double G = NoV / (NoV * (1.0 - k) + k) * NoL / (NoL * (1.0 - k) + k);
    glm::dvec3 f =
        (1.0 - F) * (1.0 - s.metallic) * s.baseColor / kPi + D * F * G / (4.0 * NoV * NoL);
    return f * l.E * NoL;
}

// SHADING.md "The redeferred split", unscaled (the double reference can hold E / alpha^4).
struct IlluminationSums {
    glm::dvec3 Ldg{0.0}, Lsg1{0.0}, Lsg2{0.0};
};

inline void accumulateIllumination(IlluminationSums& acc, const SurfacePoint& s,
                                   const LightSample& l) {
    double NoL = glm::dot(s.n, l.wi);
    if (NoL <= 0.0) return;
    double r = clampRoughness(s.roughness);
    double a = r * r, a2 = a * a;
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    glm::dvec3 h = glm::normalize(s.wo + l.wi);
    double NoH = glm::dot(s.n, h);
    double P = pow5(std::clamp(1.0 - glm::dot(h, s.wo), 0.0, 1.0));
    double dd = NoH * NoH * (a2 - 1.0) + 1.0;
    double R = dd * dd * (NoL * (1.0 - k) + k);
    acc.Ldg += (1.0 - P) * l.E * NoL;
    acc.Lsg1 += l.E * NoL / R;
    acc.Lsg2 += P * l.E * NoL / R;
}

inline glm::dvec3 resolveMaterial(const IlluminationSums& acc, const SurfacePoint& s) {
    double r = clampRoughness(s.roughness);
    double a = r * r, a2 = a * a;
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    double NoV = std::max(glm::dot(s.n, s.wo), 1e-4);
    glm::dvec3 F0 = glm::mix(glm::dvec3(0.04), s.baseColor, s.metallic);
    glm::dvec3 Ld = (1.0 - s.metallic) * (s.baseColor / kPi) * (1.0 - F0) * acc.Ldg;
    glm::dvec3 Ls =
        a2 / (4.0 * kPi * (NoV * (1.0 - k) + k)) * (F0 * acc.Lsg1 + (1.0 - F0) * acc.Lsg2);
    return Ld + Ls;
}

// --- Image-based lighting (SHADING.md "Image-based lighting"; the seed's "Specular importance
// sampling"). Keep in step with shaders/include/fe_ibl.glsl: the same sequence, basis and
// estimator, so that the GPU and this reference at the same sample count differ only by
// precision and the cube map's interpolation.

// Van der Corput radical inverse in base 2 of a 32-bit index.
inline double radicalInverse(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10;
}
// Hammersley point i of n: (A, B) = ((i + 1/2) / n, radical inverse of i).
inline glm::dvec2 hammersley(uint32_t i, uint32_t n) { return {(i + 0.5) / n, radicalInverse(i)}; }

// An orthonormal basis (t, b, n) from n alone (Duff et al., "Building an Orthonormal Basis,
// Revisited", JCGT 2017), the same on the GPU.
inline void basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
    const double s = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (s + n.z), c = n.x * n.y * a;
    t = {1.0 + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

// L_o from the environment by importance sampling: n GGX half vectors for the specular term
// (theta_h = acos(sqrt((1 - A) / (A (alpha^2 - 1) + 1))), phi_h = 2 pi B, w_i the reflection
// of w_o about h; the estimator (1/n) sum F L_i NoL (w_o.h) / ((NoL (1-k) + k)(n.h)(NoV (1-k)
// + k)), which is the seed's F0 L_sg1 + (1 - F0) L_sg2 form) and n cosine-weighted directions
// for the diffuse term ((1/n) sum (1 - F)(1 - m) c L_i). k = alpha^2 / 2 (SHADING.md, IBL).
// Brdf::Gltf: the same samples weighed by glTF's BRDF (docs/SHADING.md): specular F L 4 V NoL
// (w_o.h) / (n.h) with V the height-correlated visibility, diffuse (1 - m) c (1 - F_d) L with the
// dielectric's F_d = 0.04 + 0.96 P (Appendix B's mix of the dielectric and metal lobes).
// The reflection w_i of w_o about the GGX half vector of Hammersley point u (theta_h from A,
// phi_h = 2 pi B) about n with basis (t, b), with its n.l, w_o.h and n.h: each specular sample.
struct GgxSample {
    glm::dvec3 wi;
    double NoL, VoH, NoH;
};
inline GgxSample ggxSample(const glm::dvec2& u, double a2, const glm::dvec3& t, const glm::dvec3& b,
                           const glm::dvec3& n, const glm::dvec3& wo) {
    const double phi = 2.0 * kPi * u.y;
    const double cosH = std::sqrt((1.0 - u.x) / (u.x * (a2 - 1.0) + 1.0)),
                 sinH = std::sqrt(1.0 - cosH * cosH);
    const glm::dvec3 h = t * (sinH * std::cos(phi)) + b * (sinH * std::sin(phi)) + n * cosH;
    const double VoH = glm::dot(wo, h);
    const glm::dvec3 wi = 2.0 * VoH * h - wo;
    return {wi, glm::dot(n, wi), VoH, cosH};
}

// A GGX sample's specular weight without F and L: 4 V NoL (w_o.h) / (n.h) under glTF's BRDF (V
// height-correlated), NoL (w_o.h) / ((NoL (1-k) + k)(n.h)(NoV (1-k) + k)) under the separable one.
inline double ggxSampleWeight(double NoL, double VoH, double NoH, double NoV, double a2, double k,
                              Brdf brdf) {
    return brdf == Brdf::Gltf ? 4.0 * visibilityHeightCorrelated(NoL, NoV, a2) * NoL * VoH / NoH
                              : NoL * VoH / ((NoL * (1.0 - k) + k) * NoH * (NoV * (1.0 - k) + k));
}
// The cosine-weighted direction of Hammersley point u about n with basis (t, b): each diffuse
// sample (its n.w_d is sqrt(1 - A)).
inline glm::dvec3 cosineSample(const glm::dvec2& u, const glm::dvec3& t, const glm::dvec3& b,
                               const glm::dvec3& n) {
    const double phi = 2.0 * kPi * u.y, cosD = std::sqrt(1.0 - u.x), sinD = std::sqrt(u.x);
    return t * (sinD * std::cos(phi)) + b * (sinD * std::sin(phi)) + n * cosD;
}

template <class Environment>
glm::dvec3 shadeEnvironment(const SurfacePoint& s, const Environment& environment, uint32_t n,
                            Brdf brdf = Brdf::Gltf) {
    const double r = clampRoughness(s.roughness), a = r * r, a2 = a * a, k = a2 / 2.0;
    const double NoV = std::max(glm::dot(s.n, s.wo), 1e-4);
    const bool gltf = brdf == Brdf::Gltf;
    const glm::dvec3 dF0 = gltf ? s.dielectricF0 : glm::dvec3(0.04),
                     dF90(gltf ? s.dielectricF90 : 1.0);
    const glm::dvec3 F0 = glm::mix(dF0, s.baseColor, s.metallic),
                     F90 = glm::mix(dF90, glm::dvec3(1.0), s.metallic);
    glm::dvec3 t, b;
    basis(s.n, t, b);
    glm::dvec3 specular(0.0), diffuse(0.0), sheen(0.0);
    const bool sheenLayer = gltf && s.sheenColor != glm::dvec3(0.0);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::dvec2 u = hammersley(i, n);
        // Specular: a GGX half vector.
        const auto [wi, NoL, VoH, cosH] = ggxSample(u, a2, t, b, s.n, s.wo);
        if (NoL > 0.0 && VoH > 0.0) {
            const double P = pow5(std::clamp(1.0 - VoH, 0.0, 1.0));
            specular += (F0 + (F90 - F0) * P) * environment(wi) *
                        ggxSampleWeight(NoL, VoH, cosH, NoV, a2, k, brdf);
        }
        // Diffuse: a cosine-weighted direction.
        const glm::dvec3 wd = cosineSample(u, t, b, s.n);
        const double cosD = std::sqrt(1.0 - u.x);  // n.w_d
        const glm::dvec3 hd = glm::normalize(s.wo + wd);
        const double Pd = pow5(std::clamp(1.0 - glm::dot(hd, s.wo), 0.0, 1.0));
        diffuse +=
            (gltf ? 1.0 - dF0 - (dF90 - dF0) * Pd : (1.0 - F0) * (1.0 - Pd)) * environment(wd);
        // The sheen by the same cosine-weighted directions: pi D V L (the pdf is n.l / pi).
        if (sheenLayer)
            sheen += kPi * charlieD(s.sheenRoughness, glm::dot(s.n, hd)) *
                     sheenVisibility(cosD, NoV, s.sheenRoughness) * environment(wd);
    }
    // Transmission replaces that much of the diffuse lobe (the light from behind: transmittedScene()).
    const double transmission = gltf ? s.transmission : 0.0;
    glm::dvec3 base =
        ((1.0 - s.metallic) * (1.0 - transmission) * s.baseColor * diffuse + specular) / double(n);
    if (sheenLayer)  // the sheen over the base, which keeps 1 - max(sheenColor) E(n.w_o)
        base = s.sheenColor * sheen / double(n) +
               base * (1.0 - maxComponent(s.sheenColor) * sheenAlbedo(NoV, s.sheenRoughness));
    if (!gltf || s.clearcoat <= 0.0) return base;
    // The clearcoat layer: GGX samples about its normal at its roughness, Fresnel F0c .. 1.
    const double rc = clampRoughness(s.clearcoatRoughness), a2c = rc * rc * rc * rc;
    const double NoVc = std::max(glm::dot(s.clearcoatNormal, s.wo), 1e-4);
    basis(s.clearcoatNormal, t, b);
    glm::dvec3 layer(0.0);
    for (uint32_t i = 0; i < n; ++i) {
        const auto [wi, NoL, VoH, cosH] =
            ggxSample(hammersley(i, n), a2c, t, b, s.clearcoatNormal, s.wo);
        if (NoL > 0.0 && VoH > 0.0) {
            const double P = pow5(std::clamp(1.0 - VoH, 0.0, 1.0));
            layer += (s.clearcoatF0 + (1.0 - s.clearcoatF0) * P) * environment(wi) *
                     (4.0 * visibilityHeightCorrelated(NoL, NoVc, a2c) * NoL * VoH / cosH);
        }
    }
    return base * (1.0 - s.clearcoat * clearcoatViewFresnel(s)) + s.clearcoat * layer / double(n);
}

// What shadeEnvironment's estimators weigh the environment's radiance by when it is taken out of
// their sums (the split sum of the prefiltered fast path, fe_ibl.glsl), for w_o at NoV about
// n = z and roughness r, by the same n samples: x = (1/n) sum g and y = (1/n) sum P g over the
// GGX half vectors, g the specular weight of `brdf` without F and L; z = (1/n) sum (1 - P) over
// the cosine-weighted directions (the diffuse lobe's Fresnel).
inline glm::dvec3 splitSumTerms(double NoV, double roughness, Brdf brdf, uint32_t n) {
    const double r = clampRoughness(roughness), a = r * r, a2 = a * a, k = a2 / 2.0;
    const glm::dvec3 normal(0.0, 0.0, 1.0), t(1.0, 0.0, 0.0), b(0.0, 1.0, 0.0);
    const glm::dvec3 wo(std::sqrt(std::max(1.0 - NoV * NoV, 0.0)), 0.0, NoV);
    glm::dvec3 sum(0.0);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::dvec2 u = hammersley(i, n);
        const auto [wi, NoL, VoH, cosH] = ggxSample(u, a2, t, b, normal, wo);
        if (NoL > 0.0 && VoH > 0.0) {
            const double P = pow5(std::clamp(1.0 - VoH, 0.0, 1.0));
            const double g = ggxSampleWeight(NoL, VoH, cosH, NoV, a2, k, brdf);
            sum.x += g;
            sum.y += P * g;
        }
        const glm::dvec3 wd = cosineSample(u, t, b, normal);
        sum.z += 1.0 - pow5(std::clamp(1.0 - glm::dot(glm::normalize(wo + wd), wo), 0.0, 1.0));
    }
    return sum / double(n);
}

// The weight of the opaque scene's radiance seen through a transmissive surface (glTF model):
// (1 - metallic) transmission baseColor (1 - F(n.w_o)) times the volume's transmittance, the
// light the dielectric does not reflect at the viewing angle (docs/SHADING.md: the Sample Viewer
// weighs it by its split-sum tables instead, and shows it only under image-based light).
inline glm::dvec3 transmittedSceneWeight(const SurfacePoint& s) {
    if (s.transmission <= 0.0) return glm::dvec3(0.0);
    const double NoV = std::clamp(glm::dot(s.n, s.wo), 0.0, 1.0);
    const glm::dvec3 F = s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * pow5(1.0 - NoV);
    return (1.0 - s.metallic) * s.transmission * s.baseColor * (1.0 - F) * s.transmittance;
}
// The mip level of the opaque scene's copy that rough transmission reads: log2 of the copy's
// larger side times the perceptual roughness scaled by clamp(2 ior - 2, 0, 1) (the Sample
// Viewer's, which filters the copy by its mip chain).
inline double transmissionLod(double perceptualRoughness, double ior, uint32_t width,
                              uint32_t height) {
    const double scale = std::isinf(ior) ? 1.0 : std::clamp(2.0 * ior - 2.0, 0.0, 1.0);
    return std::log2(double(std::max(width, height))) * std::clamp(perceptualRoughness, 0.0, 1.0) *
           scale;
}

}  // namespace fe::shading
