// The redeferred split of SHADING.md is exact: L_d + L_s from the sums equals the per-light sum.
#include <gtest/gtest.h>

#include <random>

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
            direct += shadeLight(s, l);
            accumulateIllumination(acc, s, l);
        }
        glm::dvec3 split = resolveMaterial(acc, s);
        for (int c = 0; c < 3; ++c)
            if (direct[c] > 1e-9) maxRel = std::max(maxRel, std::abs(direct[c] - split[c]) / direct[c]);
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
    EXPECT_NEAR(evaluateLight(spot, {0, 0, 0}).E.x, 1.0, 1e-12);       // on axis: full
    EXPECT_NEAR(evaluateLight(spot, {1, 0, 0}).E.x, 0.0, 1e-12);       // 45 degrees: outside
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
