// The shading model of ../shared/SHADING.md on the CPU, in double precision: the independent
// reference every GPU technique is tested against (and the source of truth when the GLSL in
// shaders/include/fe_shading.glsl is changed: the two must stay in step).
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace fe::shading {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinRoughness = 0.045;

enum class LightType { Directional, Point, Spot };

struct LightSample {
    glm::dvec3 wi{0.0};  // unit vector to the light
    glm::dvec3 E{0.0};   // irradiance at normal incidence
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
    double spotScale() const { return 1.0 / std::max(0.001, std::cos(innerConeAngle) - std::cos(outerConeAngle)); }
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
};

inline double clampRoughness(double r) { return std::clamp(r, kMinRoughness, 1.0); }

// SHADING.md "Per light": f x E x NoL.
inline glm::dvec3 shadeLight(const SurfacePoint& s, const LightSample& l) {
    double NoL = glm::dot(s.n, l.wi);
    if (NoL <= 0.0) return glm::dvec3(0.0);
    double r = clampRoughness(s.roughness);
    double a = r * r, a2 = a * a;
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    double NoV = std::max(glm::dot(s.n, s.wo), 1e-4);
    glm::dvec3 h = glm::normalize(s.wo + l.wi);
    double NoH = glm::dot(s.n, h);
    double P = std::pow(std::clamp(1.0 - glm::dot(h, s.wo), 0.0, 1.0), 5.0);
    glm::dvec3 F0 = glm::mix(glm::dvec3(0.04), s.baseColor, s.metallic);
    glm::dvec3 F = F0 + (1.0 - F0) * P;
    double dd = NoH * NoH * (a2 - 1.0) + 1.0;
    double D = a2 / (kPi * dd * dd);
    double G = NoV / (NoV * (1.0 - k) + k) * NoL / (NoL * (1.0 - k) + k);
    glm::dvec3 f = (1.0 - F) * (1.0 - s.metallic) * s.baseColor / kPi + D * F * G / (4.0 * NoV * NoL);
    return f * l.E * NoL;
}

// SHADING.md "The redeferred split", unscaled (the double reference can hold E / alpha^4).
struct IlluminationSums {
    glm::dvec3 Ldg{0.0}, Lsg1{0.0}, Lsg2{0.0};
};

inline void accumulateIllumination(IlluminationSums& acc, const SurfacePoint& s, const LightSample& l) {
    double NoL = glm::dot(s.n, l.wi);
    if (NoL <= 0.0) return;
    double r = clampRoughness(s.roughness);
    double a = r * r, a2 = a * a;
    double k = (r + 1.0) * (r + 1.0) / 8.0;
    glm::dvec3 h = glm::normalize(s.wo + l.wi);
    double NoH = glm::dot(s.n, h);
    double P = std::pow(std::clamp(1.0 - glm::dot(h, s.wo), 0.0, 1.0), 5.0);
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
    glm::dvec3 Ls = a2 / (4.0 * kPi * (NoV * (1.0 - k) + k)) * (F0 * acc.Lsg1 + (1.0 - F0) * acc.Lsg2);
    return Ld + Ls;
}

}  // namespace fe::shading
