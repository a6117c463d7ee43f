// Builtin scenes (renderer/assets/BuiltinScenes.h): the exact contents other tests and
// benchmarks rely on.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <functional>
#include <set>
#include <tuple>

#include "TestSupport.h"
#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"

using namespace fe::assets;
using fe::assets::test::expectSceneInvariants;

namespace {
constexpr float kPi = 3.14159265358979323846f;
}

TEST(BuiltinLights, Has121UnitCubesOnTheSpecifiedGrid) {
    Scene s = makeBuiltinScene("lights");
    ASSERT_EQ(s.instances.size(), 121u);
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    EXPECT_EQ(s.meshes[0].primitives[0].vertices.size(), 24u);
    EXPECT_EQ(s.meshes[0].primitives[0].indices.size(), 36u);
    EXPECT_EQ(s.meshes[0].bounds.min, glm::vec3(-1.0f));
    EXPECT_EQ(s.meshes[0].bounds.max, glm::vec3(1.0f));

    std::set<std::pair<int, int>> centres;
    for (const auto& inst : s.instances) {
        EXPECT_EQ(inst.meshIndex, 0u);
        EXPECT_FALSE(inst.mirrored);
        EXPECT_EQ(glm::mat3(inst.world), glm::mat3(1.0f)) << "cubes are only translated";
        glm::vec3 c(inst.world[3]);
        EXPECT_EQ(c.z, 0.0f);
        EXPECT_EQ(c.x, std::round(c.x));
        EXPECT_EQ(c.y, std::round(c.y));
        centres.insert({int(c.x), int(c.y)});
    }
    std::set<std::pair<int, int>> expected;
    for (int x = -15; x <= 15; x += 3)
        for (int y = -15; y <= 15; y += 3) expected.insert({x, y});
    EXPECT_EQ(centres, expected);
    EXPECT_EQ(s.bounds.min, glm::vec3(-16, -16, -1));
    EXPECT_EQ(s.bounds.max, glm::vec3(16, 16, 1));
    expectSceneInvariants(s, "builtin:lights");
}

TEST(BuiltinLights, CameraIsExactlyAsSpecified) {
    Scene s = makeBuiltinScene("lights");
    ASSERT_TRUE(s.camera.has_value());
    const Camera& c = *s.camera;
    EXPECT_EQ(c.eye(), glm::vec3(0, 0, -15));
    EXPECT_NEAR(glm::distance(c.forward(), glm::vec3(0, 0, 1)), 0.0f, 1e-7f);
    EXPECT_NEAR(glm::distance(c.up(), glm::vec3(0, 1, 0)), 0.0f, 1e-7f);
    EXPECT_NEAR(c.yfov, kPi / 3.0f, 1e-6f);
    EXPECT_FLOAT_EQ(c.znear, 0.1f);
    EXPECT_FLOAT_EQ(c.zfar, 100.0f);
    EXPECT_FALSE(c.aspectRatio.has_value());
    EXPECT_FALSE(s.hasDefaultCamera);
    EXPECT_FALSE(s.hasDefaultLights);
}

TEST(BuiltinLights, LightCountDefaultsTo512AndFollowsTheOption) {
    EXPECT_EQ(makeBuiltinScene("lights").lights.size(), 512u);
    BuiltinOptions o;
    o.lights = 37;
    EXPECT_EQ(makeBuiltinScene("lights", o).lights.size(), 37u);
    o.lights = 0;
    Scene none = makeBuiltinScene("lights", o);
    EXPECT_TRUE(none.lights.empty());
    EXPECT_FALSE(none.hasDefaultLights) << "a builtin never gets the default rig";
}

TEST(BuiltinLights, LightsArePointLightsOfRange2InsideTheBoxForAnyFrame) {
    for (uint32_t frame : {0u, 1u, 299u, 1000u, 123457u, 4294967295u}) {
        BuiltinOptions o;
        o.frame = frame;
        Scene s = makeBuiltinScene("lights", o);
        for (const auto& l : s.lights) {
            ASSERT_EQ(l.type, LightType::Point);
            ASSERT_EQ(l.range, 2.0f);
            ASSERT_GT(l.intensity, 0.0f);
            ASSERT_TRUE(l.position.x >= -15.0f && l.position.x <= 15.0f) << frame;
            ASSERT_TRUE(l.position.y >= -15.0f && l.position.y <= 15.0f) << frame;
            ASSERT_TRUE(l.position.z >= -2.0f && l.position.z <= 2.0f) << frame;
            ASSERT_TRUE(l.color.r >= 0 && l.color.r <= 1 && l.color.g >= 0 && l.color.g <= 1 &&
                        l.color.b >= 0 && l.color.b <= 1);
            ASSERT_GT(l.color.r + l.color.g + l.color.b, 0.5f);
        }
    }
}

TEST(BuiltinLights, LightsSpreadOverTheWholeBoxWithVariedColours) {
    auto lights = lightsSceneLights(512, 0);
    int quadrant[4] = {0, 0, 0, 0}, front = 0;
    std::set<std::tuple<float, float, float>> colours;
    for (const auto& l : lights) {
        quadrant[(l.position.x < 0 ? 0 : 1) + (l.position.y < 0 ? 0 : 2)]++;
        front += l.position.z < 0.0f;
        colours.insert({l.color.r, l.color.g, l.color.b});
    }
    for (int q : quadrant) EXPECT_GT(q, 90) << "expected about 128 per quadrant";
    EXPECT_GT(front, 200);
    EXPECT_LT(front, 312);
    EXPECT_GT(colours.size(), 400u);
}

TEST(BuiltinLights, DeterministicPerFrameAndMovingBetweenFrames) {
    auto a = lightsSceneLights(512, 42);
    auto b = lightsSceneLights(512, 42);
    auto c = lightsSceneLights(512, 43);
    auto d = lightsSceneLights(512, 342);
    ASSERT_EQ(a.size(), 512u);
    float maxStep = 0.0f, minStep = 1e9f, far = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].position, b[i].position);
        EXPECT_EQ(a[i].color, b[i].color);
        EXPECT_EQ(a[i].color, c[i].color) << "colours do not animate";
        float step = glm::distance(a[i].position, c[i].position);
        maxStep = std::max(maxStep, step);
        minStep = std::min(minStep, step);
        far = std::max(far, glm::distance(a[i].position, d[i].position));
        EXPECT_EQ(a[i].position.z, c[i].position.z);
    }
    EXPECT_GT(minStep, 0.0f) << "every light moves every frame";
    EXPECT_LT(maxStep, 0.05f) << "slow orbit: at most 2*pi*1.5/600 per frame";
    EXPECT_GT(far, 1.0f) << "300 frames later the lights have clearly moved";
    // The scene and the standalone function agree, so renderers can animate without reloading.
    BuiltinOptions o;
    o.frame = 42;
    Scene s = makeBuiltinScene("lights", o);
    for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(s.lights[i].position, a[i].position);
    // A prefix of the lights does not depend on how many there are.
    auto few = lightsSceneLights(10, 42);
    for (size_t i = 0; i < few.size(); ++i) EXPECT_EQ(few[i].position, a[i].position);
}

// The documented exposure claim: the lit faces facing the camera average about 0.3 linear
// radiance (Lambert part of SHADING.md with base colour 0.8), so the image is neither black nor
// blown out at exposure 1.
TEST(BuiltinLights, FrontFacesAreWellExposed) {
    Scene s = makeBuiltinScene("lights");
    const Material& m = s.materials[0];
    double sum = 0.0;
    int samples = 0, bright = 0;
    for (const auto& inst : s.instances) {
        glm::vec3 c(inst.world[3]);
        if (std::abs(c.y) > 9.0f) continue;  // roughly the visible rows
        for (int i = 0; i < 6; ++i) {
            for (int j = 0; j < 6; ++j) {
                glm::vec3 p(c.x - 1 + (i + 0.5f) / 3.0f, c.y - 1 + (j + 0.5f) / 3.0f, -1.0f);
                glm::vec3 n(0, 0, -1);
                double L = 0.0;
                for (const auto& l : s.lights) {
                    glm::vec3 d = l.position - p;
                    float dist = glm::length(d);
                    float NoL = glm::dot(n, d / dist);
                    if (NoL <= 0.0f || dist >= l.range) continue;
                    float q = dist / l.range;
                    float w = std::pow(std::clamp(1.0f - q * q * q * q, 0.0f, 1.0f), 2.0f);
                    float E = l.intensity * w / (dist * dist);
                    float lum = 0.2126f * l.color.r + 0.7152f * l.color.g + 0.0722f * l.color.b;
                    L += m.baseColorFactor.g / kPi * E * NoL * lum;
                }
                sum += L;
                bright += L > 0.8;
                ++samples;
            }
        }
    }
    double mean = sum / samples;
    EXPECT_GT(mean, 0.15);
    EXPECT_LT(mean, 0.6);
    EXPECT_LT(double(bright) / samples, 0.25);
}

TEST(BuiltinSpheres, RoughnessAcrossMetallicDownWithColouredBase) {
    Scene s = makeBuiltinScene("spheres");
    ASSERT_EQ(s.instances.size(), 49u);
    ASSERT_EQ(s.meshes.size(), 49u);
    for (const auto& inst : s.instances) {
        const Material& m = s.materials[s.meshes[inst.meshIndex].primitives[0].material];
        glm::vec3 p(inst.world[3]);
        // Column x = -3..3 -> roughness 0..1, row y = 3..-3 -> metallic 0..1.
        EXPECT_NEAR(m.roughness, (p.x + 3.0f) / 6.0f, 1e-6f);
        EXPECT_NEAR(m.metallic, (3.0f - p.y) / 6.0f, 1e-6f);
        EXPECT_EQ(p.z, 0.0f);
        EXPECT_GT(m.baseColorFactor.r - m.baseColorFactor.b, 0.3f) << "not grey";
    }
    EXPECT_GE(s.lights.size(), 2u);
    expectSceneInvariants(s, "builtin:spheres");
}

TEST(BuiltinSpheres, CameraFramesEverySphere) {
    for (uint32_t n : {2u, 5u, 7u, 16u}) {
        BuiltinOptions o;
        o.sphereGrid = n;
        Scene s = makeBuiltinScene("spheres", o);
        ASSERT_EQ(s.instances.size(), size_t(n) * n);
        ASSERT_TRUE(s.camera);
        glm::mat4 proj = glm::perspective(s.camera->yfov, 1.0f, s.camera->znear, s.camera->zfar);
        glm::mat4 vp = proj * s.camera->viewFromWorld();
        for (const auto& inst : s.instances) {
            AABB b = s.meshes[inst.meshIndex].bounds.transformed(inst.world);
            for (int i = 0; i < 8; ++i) {
                glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                 (i & 4) ? b.max.z : b.min.z);
                glm::vec4 clip = vp * glm::vec4(corner, 1.0f);
                ASSERT_GT(clip.w, 0.0f);
                EXPECT_LE(std::abs(clip.x / clip.w), 1.0f) << n;
                EXPECT_LE(std::abs(clip.y / clip.w), 1.0f) << n;
            }
        }
    }
}

TEST(BuiltinPlane, AnalyticSetup) {
    Scene s = makeBuiltinScene("plane");
    ASSERT_EQ(s.instances.size(), 1u);
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::Point);
    EXPECT_EQ(l.position, glm::vec3(0, 0, 1));
    EXPECT_EQ(l.intensity, 1.0f);
    EXPECT_EQ(l.range, 0.0f);
    const Primitive& p = s.meshes[0].primitives[0];
    for (const auto& v : p.vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.camera->eye(), glm::vec3(0, 0, 3));
    EXPECT_EQ(s.materials[0].baseColorFactor, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    expectSceneInvariants(s, "builtin:plane");
    expectSceneInvariants(makeBuiltinScene("triangle"), "builtin:triangle");
}

TEST(BuiltinScenes, UnknownNameListsTheValidOnes) {
    try {
        makeBuiltinScene("spherez");
        FAIL() << "expected AssetError";
    } catch (const AssetError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("spherez"), std::string::npos) << msg;
        for (const auto& n : builtinSceneNames()) EXPECT_NE(msg.find(n), std::string::npos) << msg;
    }
}

TEST(BuiltinScenes, LoadSceneDispatchesOnThePrefix) {
    BuiltinOptions o;
    o.lights = 3;
    Scene s = loadScene("builtin:lights", {}, o);
    EXPECT_EQ(s.name, "lights");
    EXPECT_EQ(s.lights.size(), 3u);
    EXPECT_THROW(loadScene("builtin:"), AssetError);
    EXPECT_THROW(loadScene(""), AssetError);
    EXPECT_THROW(loadScene("/nonexistent/dir/scene.gltf"), AssetError);
}

// A material built in code is held to what the loader enforces on a file: the extensions' factors
// finite and in range (an infinite ior and attenuation distance are meaningful), each refusal
// naming the material and the factor; and the defaults pass.
TEST(SceneChecks, MaterialExtensionFactorsAreCheckedLikeTheLoaders) {
    const fe::assets::Scene ok = fe::assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    EXPECT_NO_THROW(fe::assets::checkFinite(ok));
    auto refusal = [&](const std::function<void(fe::assets::Material&)>& change) {
        fe::assets::Scene s = ok;
        change(s.materials[0]);
        try {
            fe::assets::checkFinite(s);
        } catch (const fe::assets::AssetError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    using M = fe::assets::Material;
    EXPECT_NE(refusal([](M& m) { m.transmission = 1.5f; }).find("transmission must lie in [0, 1]"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) { m.sheenColor.g = NAN; }).find("is not finite"), std::string::npos);
    EXPECT_NE(
        refusal([](M& m) { m.sheenRoughness = -0.5f; }).find("sheenRoughness must lie in [0, 1]"),
        std::string::npos);
    EXPECT_NE(refusal([](M& m) { m.ior = 0.5f; }).find("ior must be at least 1"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) {
                  m.attenuationDistance = 0.0f;
              }).find("attenuationDistance must be positive"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) { m.thickness = -1.0f; }).find("thickness must not be negative"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) { m.clearcoat = 2.0f; }).find("clearcoat must lie in [0, 1]"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) {
                  m.specularTexture.transform.scale.x = INFINITY;
              }).find("a texture transform"),
              std::string::npos);
    EXPECT_NE(refusal([](M& m) { m.transmission = 1.5f; }).find(ok.materials[0].name),
              std::string::npos);
    EXPECT_EQ(refusal([](M& m) { m.ior = INFINITY; }), "(accepted)");
}
