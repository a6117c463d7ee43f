// The redeferred split of SHADING.md is exact: L_d + L_s from the sums equals the separable
// per-light sum; the glTF BRDF is glTF 2.0 Appendix B, checked against independent forms.
#include <gtest/gtest.h>

#include <random>

#include "render/SplitSumTable.h"
#include "shading/ShadingModel.h"

using namespace fe::shading;

TEST(ShadingModel, RedeferredSplitEqualsPerLightSum) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    double maxRel = 0;
    for (int i = 0; i < 20000; ++i) {
        SurfacePoint s;
        s.n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        s.wo = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        if (glm::dot(s.n, s.wo) < 0) s.wo = -s.wo;
        s.baseColor = {u01(rng), u01(rng), u01(rng)};
        s.metallic = u01(rng);
        s.roughness = (i % 10 == 0) ? 0.0 : u01(rng);  // also at the clamp
        glm::dvec3 direct(0.0);
        IlluminationSums acc;
        for (int j = 0; j < 4; ++j) {
            PunctualLight L;
            L.type = LightType(j % 3);
            L.position = {u(rng) * 3, u(rng) * 3, u(rng) * 3};
            L.direction = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
            L.range = j % 2 ? 5.0 : 0.0;
            L.intensity = 10;
            L.color = {1, 0.5, 0.25};
            LightSample l = evaluateLight(L, s.P);
            direct += shadeLight(s, l, Brdf::Separable);
            accumulateIllumination(acc, s, l);
        }
        glm::dvec3 split = resolveMaterial(acc, s);
        for (int c = 0; c < 3; ++c)
            if (direct[c] > 1e-9)
                maxRel = std::max(maxRel, std::abs(direct[c] - split[c]) / direct[c]);
    }
    EXPECT_LT(maxRel, 1e-9);
}

TEST(ShadingModel, RangeWindowAndSpotFalloff) {
    EXPECT_DOUBLE_EQ(rangeWindow(0.0, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(rangeWindow(2.0, 2.0), 0.0);
    EXPECT_DOUBLE_EQ(rangeWindow(5.0, 0.0), 1.0);
    PunctualLight spot;
    spot.type = LightType::Spot;
    spot.position = {0, 0, 1};
    spot.direction = {0, 0, -1};
    spot.innerConeAngle = 0.2;
    spot.outerConeAngle = 0.4;
    EXPECT_NEAR(evaluateLight(spot, {0, 0, 0}).E.x, 1.0, 1e-12);  // on axis: full
    EXPECT_NEAR(evaluateLight(spot, {1, 0, 0}).E.x, 0.0, 1e-12);  // 45 degrees: outside
    EXPECT_NEAR(glm::length(evaluateLight(spot, {0, 0, 0}).wi - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(ShadingModel, LambertianWhiteUnderOneLux) {
    SurfacePoint s;  // n = wo = +z, white dielectric, rough
    PunctualLight L;
    L.type = LightType::Directional;
    L.direction = {0, 0, -1};
    glm::dvec3 Lo = shadeLight(s, evaluateLight(L, s.P));
    // (1 - F) c / pi + specular at normal incidence, F = 0.04
    EXPECT_GT(Lo.x, 0.96 / kPi);
    EXPECT_LT(Lo.x, 1.0);
}

namespace {
// The glTF specular lobe written from Heitz (2014) directly: G2 = 1 / (1 + Lambda(v) + Lambda(l)),
// Lambda(x) = (-1 + sqrt(1 + alpha^2 tan^2 theta_x)) / 2, f_s = F D G2 / (4 NoL NoV); and the
// diffuse lobe of Appendix B's fresnel_mix(0.04, ...): (1 - m) c / pi (1 - F_dielectric).
glm::dvec3 gltfBrdfFromHeitz(const SurfacePoint& s, const glm::dvec3& wi) {
    const double r = clampRoughness(s.roughness), a2 = r * r * r * r;
    const double NoL = glm::dot(s.n, wi), NoV = glm::dot(s.n, s.wo);
    const glm::dvec3 h = glm::normalize(wi + s.wo);
    const double NoH = glm::dot(s.n, h), VoH = glm::dot(s.wo, h);
    auto lambda = [&](double c) {
        return (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))) / 2.0;
    };
    const double G2 = 1.0 / (1.0 + lambda(NoV) + lambda(NoL));
    const double D = a2 / (kPi * std::pow(NoH * NoH * (a2 - 1.0) + 1.0, 2.0));
    const double P = std::pow(1.0 - VoH, 5.0);
    const glm::dvec3 Fmetal = s.baseColor + (1.0 - s.baseColor) * P;
    const double Fdielectric = 0.04 + 0.96 * P;
    const glm::dvec3 dielectric =
        s.baseColor / kPi * (1.0 - Fdielectric) + Fdielectric * D * G2 / (4.0 * NoL * NoV);
    const glm::dvec3 metal = Fmetal * D * G2 / (4.0 * NoL * NoV);
    return glm::mix(dielectric, metal, s.metallic);
}
}  // namespace

TEST(ShadingModel, GltfBrdfIsAppendixB) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    double maxRel = 0, meanSeparableRatio = 0;
    int n = 0;
    for (int i = 0; i < 20000; ++i) {
        SurfacePoint s;
        s.n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        s.wo = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        if (glm::dot(s.n, s.wo) < 0.05) continue;
        s.baseColor = {u01(rng), u01(rng), u01(rng)};
        s.metallic = u01(rng);
        s.roughness = (i % 10 == 0) ? 0.0 : u01(rng);
        LightSample l;
        l.wi = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        l.E = {1.0, 2.0, 0.5};
        const double NoL = glm::dot(s.n, l.wi);
        if (NoL < 0.05) continue;
        const glm::dvec3 want = gltfBrdfFromHeitz(s, l.wi) * l.E * NoL;
        const glm::dvec3 got = shadeLight(s, l, Brdf::Gltf);
        for (int c = 0; c < 3; ++c) maxRel = std::max(maxRel, std::abs(got[c] - want[c]) / want[c]);
        meanSeparableRatio += shadeLight(s, l, Brdf::Separable).y / got.y;
        ++n;
    }
    EXPECT_LT(maxRel, 1e-9);
    // The two models are not the same function (the test would pass if Gltf fell back to Separable).
    EXPECT_GT(std::abs(meanSeparableRatio / n - 1.0), 0.01) << meanSeparableRatio / n;
}

// At alpha = 1 the height-correlated visibility is 1 / (2 (NoL + NoV)): a closed form.
TEST(ShadingModel, HeightCorrelatedVisibilityAtFullRoughness) {
    for (double NoL : {0.1, 0.5, 1.0})
        for (double NoV : {0.2, 0.7, 1.0})
            EXPECT_NEAR(visibilityHeightCorrelated(NoL, NoV, 1.0), 0.5 / (NoL + NoV), 1e-15);
}

namespace {
// KHR_materials_specular's and KHR_materials_clearcoat's formulas as their texts arrange them,
// written apart from ShadingModel.h: dielectric_brdf = mix(diffuse, specular_brdf, F_d) per
// channel with F_d = F0 + (F90 - F0) P; metal_brdf = specular_brdf (c + (1 - c) P); material =
// mix(dielectric, metal, m); then the coat: material (1 - w Fc(n_c.v)) + w Fc(v.h) D_c G2_c /
// (4 n_c.l n_c.v), each lobe times its own n.l (Heitz's G2 as above).
glm::dvec3 coatedFromTheExtensions(const SurfacePoint& s, const LightSample& l) {
    const glm::dvec3 h = glm::normalize(l.wi + s.wo);
    const double VoH = glm::dot(s.wo, h), P = std::pow(1.0 - VoH, 5.0);
    auto ggx = [&](const glm::dvec3& n, double roughness) {  // D G2 / (4 n.l n.v), and n.l
        const double r = clampRoughness(roughness), a2 = r * r * r * r;
        const double NoL = glm::dot(n, l.wi), NoV = glm::dot(n, s.wo), NoH = glm::dot(n, h);
        auto lambda = [&](double c) {
            return (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))) / 2.0;
        };
        const double D = a2 / (kPi * std::pow(NoH * NoH * (a2 - 1.0) + 1.0, 2.0));
        return std::pair{D / (1.0 + lambda(NoV) + lambda(NoL)) / (4.0 * NoL * NoV), NoL};
    };
    const auto [spec, NoL] = ggx(s.n, s.roughness);
    const glm::dvec3 Fd = s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * P;
    const glm::dvec3 dielectric = glm::mix(s.baseColor / kPi, glm::dvec3(spec), Fd);
    const glm::dvec3 metal = spec * (s.baseColor + (1.0 - s.baseColor) * P);
    const glm::dvec3 base = glm::mix(dielectric, metal, s.metallic) * l.E * NoL;
    const auto [coat, NoLc] = ggx(s.clearcoatNormal, s.clearcoatRoughness);
    const double fresnelView =
        s.clearcoatF0 +
        (1.0 - s.clearcoatF0) * std::pow(1.0 - glm::dot(s.clearcoatNormal, s.wo), 5.0);
    const double fresnelHalf = s.clearcoatF0 + (1.0 - s.clearcoatF0) * P;
    return base * (1.0 - s.clearcoat * fresnelView) + s.clearcoat * fresnelHalf * coat * l.E * NoLc;
}
}  // namespace

// The dielectric's F0/F90 and the clearcoat as shadeLight evaluates them equal the extensions'
// arrangement (relative 1e-9), over random surfaces, lights, ior, specular and coats; and each
// input changes the result (the test would pass if shadeLight ignored them otherwise).
TEST(ShadingModel, DielectricAndClearcoatAreTheExtensionsFormulas) {
    std::mt19937 rng(47);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    double maxRel = 0, coatEffect = 0, dielectricEffect = 0;
    int n = 0;
    for (int i = 0; i < 20000; ++i) {
        SurfacePoint s;
        s.n = glm::normalize(glm::dvec3(u(rng), u(rng), 1.0));
        s.clearcoatNormal = glm::normalize(glm::dvec3(u(rng) * 0.3, u(rng) * 0.3, 1.0));
        s.wo = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        LightSample l;
        l.wi = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        l.E = {1.0, 2.0, 0.5};
        if (glm::dot(s.n, s.wo) < 0.05 || glm::dot(s.n, l.wi) < 0.05 ||
            glm::dot(s.clearcoatNormal, s.wo) < 0.05 || glm::dot(s.clearcoatNormal, l.wi) < 0.05)
            continue;
        s.baseColor = {u01(rng), u01(rng), u01(rng)};
        s.metallic = u01(rng);
        s.roughness = 0.05 + 0.95 * u01(rng);
        const double ior = 1.0 + 2.0 * u01(rng), f = (ior - 1.0) / (ior + 1.0), specular = u01(rng);
        s.dielectricF0 =
            glm::min(f * f * glm::dvec3(u01(rng) * 2.0, u01(rng), 1.0), glm::dvec3(1.0)) * specular;
        s.dielectricF90 = specular;
        s.clearcoat = u01(rng);
        s.clearcoatRoughness = 0.05 + 0.95 * u01(rng);
        s.clearcoatF0 = f * f;
        const glm::dvec3 want = coatedFromTheExtensions(s, l), got = shadeLight(s, l, Brdf::Gltf);
        for (int c = 0; c < 3; ++c) maxRel = std::max(maxRel, std::abs(got[c] - want[c]) / want[c]);
        SurfacePoint uncoated = s, plain = s;
        uncoated.clearcoat = 0.0;
        plain.dielectricF0 = glm::dvec3(0.04), plain.dielectricF90 = 1.0;
        coatEffect += std::abs(shadeLight(uncoated, l).y / got.y - 1.0);
        dielectricEffect += std::abs(shadeLight(plain, l).y / got.y - 1.0);
        ++n;
    }
    ASSERT_GT(n, 1000);
    EXPECT_LT(maxRel, 1e-9);
    EXPECT_GT(coatEffect / n, 0.01);
    EXPECT_GT(dielectricEffect / n, 0.01);
}

// KHR_materials_sheen: the Charlie distribution is normalised (the integral of D n.h over the
// hemisphere of half vectors is 1), and the albedo table holds the sheen's directional albedo: at
// its grid points the integral of D V n.l at 4x the resolution along each angle (within 1 % or
// 1e-3 from roughness 0.25; 10 % at 1/31, whose lobe the table's 48 angles barely resolve;
// clamped to 1, which the smoothest sheens' integral passes at grazing angles), within
// [0, 1], and read bilinearly between the points.
TEST(ShadingModel, SheenDistributionAndAlbedoTable) {
    for (double r : {0.3, 0.6, 1.0}) {
        double sum = 0.0;
        const int n = 4096;
        for (int i = 0; i < n; ++i) {
            const double theta = (i + 0.5) / n * 0.5 * kPi;
            sum += charlieD(r, std::cos(theta)) * std::cos(theta) * std::sin(theta);
        }
        EXPECT_NEAR(sum * 2.0 * kPi * (0.5 * kPi / n), 1.0, 1e-3) << "roughness " << r;
    }
    auto albedo = [](double NoV, double r) {
        const int nTheta = 192, nPhi = 192;
        const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
        double sum = 0.0;
        for (int i = 0; i < nTheta; ++i) {
            const double theta = (i + 0.5) / nTheta * 0.5 * kPi, c = std::cos(theta),
                         s = std::sin(theta);
            for (int k = 0; k < nPhi; ++k) {
                const double phi = (k + 0.5) / nPhi * 2.0 * kPi;
                const glm::dvec3 l(s * std::cos(phi), s * std::sin(phi), c);
                sum += charlieD(r, glm::normalize(v + l).z) *
                       sheenVisibility(c, std::max(NoV, 1e-4), r) * c * s;
            }
        }
        return sum * (0.5 * kPi / nTheta) * (2.0 * kPi / nPhi);
    };
    const std::vector<float>& table = sheenAlbedoTable();
    ASSERT_EQ(table.size(), size_t(kSheenTableSize * kSheenTableSize));
    for (float e : table) EXPECT_TRUE(e >= 0.0f && e <= 1.0f) << e;
    for (int j : {1, 8, 16, 31})
        for (int i : {0, 4, 16, 31}) {
            const double mu = double(i) / (kSheenTableSize - 1),
                         r = double(j) / (kSheenTableSize - 1);
            const double want = std::min(albedo(mu, r), 1.0),
                         got = table[size_t(j) * kSheenTableSize + i];
            EXPECT_NEAR(got, want, std::max((j < 8 ? 0.1 : 0.01) * want, 1e-3))
                << "cos " << mu << ", roughness " << r;
            EXPECT_NEAR(sheenAlbedo(mu, r), got, 1e-7);
        }
    const double mid = sheenAlbedo(0.5 / (kSheenTableSize - 1), 0.5);
    const double a = sheenAlbedo(0.0, 0.5), b = sheenAlbedo(1.0 / (kSheenTableSize - 1), 0.5);
    EXPECT_NEAR(mid, 0.5 * (a + b), 1e-7);
    EXPECT_GT(sheenAlbedo(1.0, 0.5), 0.0);
}

// The split-sum table compiled into the renderer (render/SplitSumTable.h) is the shading model's:
// equal to computeSplitSumTable() (else it must be baked again), and what shadeEnvironment's
// estimator weighs a constant environment by, at each texel centre: a metal of F0 c reflects
// c x + (1 - c) y; a white dielectric 0.04 x + 0.96 y + 0.96 z (the diffuse lobe under
// 1 - F_d = 0.96 (1 - P)), under each BRDF.
TEST(ShadingModel, SplitSumTableIsTheEstimatorsWeights) {
    const std::span<const float> baked = fe::render::bakedSplitSumTable();
    const std::vector<float> computed = fe::render::computeSplitSumTable();
    constexpr uint32_t S = fe::render::kSplitSumSize;
    ASSERT_EQ(baked.size(), size_t(S) * 2 * S * 4);
    ASSERT_EQ(computed.size(), baked.size());
    for (size_t i = 0; i < baked.size(); ++i)
        ASSERT_NEAR(baked[i], computed[i], 1e-6 * std::max(1.0f, std::abs(computed[i])))
            << "texel " << i / 4 << ": bake it again (build/tools/fe_bake_split_sum > "
            << "renderer/render/SplitSumTableData.cpp)";
    const auto white = [](const glm::dvec3&) { return glm::dvec3(1.0); };
    for (uint32_t y = 0; y < 2 * S; y += 5)
        for (uint32_t x = 0; x < S; x += 3) {
            const bool gltf = y >= S;
            const float* t = &baked[(size_t(y) * S + x) * 4];
            SurfacePoint s;
            const double NoV = (x + 0.5) / S;
            s.wo = {std::sqrt(1.0 - NoV * NoV), 0.0, NoV};
            s.roughness = ((gltf ? y - S : y) + 0.5) / S;
            const Brdf brdf = gltf ? Brdf::Gltf : Brdf::Separable;
            s.metallic = 1.0;
            s.baseColor = glm::dvec3(0.3);
            EXPECT_NEAR(shadeEnvironment(s, white, fe::render::kSplitSumSamples, brdf).x,
                        0.3 * t[0] + 0.7 * t[1], 2e-6)
                << "metal at texel " << x << ", " << y;
            s.metallic = 0.0;
            s.baseColor = glm::dvec3(1.0);
            EXPECT_NEAR(shadeEnvironment(s, white, fe::render::kSplitSumSamples, brdf).x,
                        0.04 * t[0] + 0.96 * t[1] + 0.96 * t[2], 2e-6)
                << "dielectric at texel " << x << ", " << y;
        }
}
