// The scene shaders' specialization (render/ShaderFeatures.h): the light types a scene holds,
// the BRDF a frame shades with and what each material samples are constants of the pipelines,
// whose code for the rest the driver drops. What the bits say, and on every backend that a
// renderer whose lights change type (updateLights) shades the new types as a renderer made for
// them does: its pipelines must follow the lights, not keep the first frame's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "integration/SceneRenderer.h"
#include "render/ShaderFeatures.h"

using namespace fe;
using render::ShaderFeatures;

namespace {

assets::Light light(assets::LightType type) {
    assets::Light l;
    l.type = type;
    return l;
}

// The largest difference of any channel between two RGBA32F images, relative to the brighter.
double largestRelativeDifference(const gdi::Image& a, const gdi::Image& b) {
    double m = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double p = a.texel(x, y)[c], q = b.texel(x, y)[c];
                m = std::max(m, std::abs(p - q) / std::max({std::abs(p), std::abs(q), 1e-3}));
            }
    return m;
}

}  // namespace

TEST(ShaderFeatures, SayWhatTheLightsHold) {
    using T = assets::LightType;
    EXPECT_EQ(ShaderFeatures::lightTypesOf({}), 0u);
    EXPECT_EQ(ShaderFeatures::lightTypesOf({light(T::Point), light(T::Point)}),
              ShaderFeatures::kPoint);
    EXPECT_EQ(ShaderFeatures::lightTypesOf({light(T::Directional), light(T::Spot)}),
              ShaderFeatures::kDirectional | ShaderFeatures::kSpot);
    EXPECT_EQ(ShaderFeatures::brdfOf(shading::Brdf::Gltf), ShaderFeatures::kGltf);
    EXPECT_EQ(ShaderFeatures::brdfOf(shading::Brdf::Separable), ShaderFeatures::kSeparable);
}

TEST(ShaderFeatures, SayWhatAMaterialSamples) {
    const assets::TextureRef texture{.index = 0};
    EXPECT_EQ(ShaderFeatures::materialOf(assets::Material{}), 0u);
    const auto with = [&](auto set) {
        assets::Material m;
        set(m);
        return ShaderFeatures::materialOf(m);
    };
    EXPECT_EQ(with([&](auto& m) { m.baseColorTexture = texture; }), ShaderFeatures::kBaseTextures);
    EXPECT_EQ(with([&](auto& m) { m.metallicRoughnessTexture = texture; }),
              ShaderFeatures::kBaseTextures);
    EXPECT_EQ(with([&](auto& m) { m.emissiveTexture = texture; }), ShaderFeatures::kBaseTextures);
    EXPECT_EQ(with([&](auto& m) { m.occlusionTexture = texture; }), ShaderFeatures::kBaseTextures);
    EXPECT_EQ(with([&](auto& m) { m.normalTexture = texture; }), ShaderFeatures::kNormalMap);
    EXPECT_EQ(with([&](auto& m) { m.specularColorTexture = texture; }),
              ShaderFeatures::kSpecularTextures);
    EXPECT_EQ(with([&](auto& m) { m.clearcoatRoughnessTexture = texture; }),
              ShaderFeatures::kClearcoatTextures);
    EXPECT_EQ(with([&](auto& m) { m.clearcoatNormalTexture = texture; }),
              ShaderFeatures::kClearcoatNormalMap);
    EXPECT_EQ(with([&](auto& m) { m.sheenColor = glm::vec3(0.5f); }), ShaderFeatures::kSheen);
    EXPECT_EQ(with([&](auto& m) { m.alphaMode = assets::AlphaMode::Mask; }),
              ShaderFeatures::kAlphaMask);
    EXPECT_EQ(with([&](auto& m) { m.alphaMode = assets::AlphaMode::Blend; }), 0u);
}

namespace {
class SpecializedShaders : public fe::testing::BackendTest {
protected:
    SpecializedShaders() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};
}  // namespace

// The spheres lit by three point lights, then (updateLights) by two directional lights and a
// spot: the renderer made for the points shades the new lights as one made for them does, on
// the forward passes and the compute light loops alike.
TEST_P(SpecializedShaders, LightsThatChangeTypeAreShadedAsTheirType) {
    const assets::Scene mixed = assets::makeBuiltinScene("spheres", {.sphereGrid = 3});
    ASSERT_EQ(mixed.lights.size(), 3u);
    assets::Scene points = mixed;
    for (assets::Light& l : points.lights) {
        l.type = assets::LightType::Point;
        l.position = glm::vec3(0.0f, 0.0f, 3.0f) - 2.0f * l.direction;
        l.range = 0.0f;
    }
    std::vector<assets::Light> lights = mixed.lights;
    for (assets::Light& l : lights)
        if (l.type == assets::LightType::Point) {
            l.type = assets::LightType::Spot;
            l.direction = glm::normalize(glm::vec3(0.0f) - l.position);
            l.innerConeAngle = 0.05f;
            l.outerConeAngle = 0.15f;
        }
    assets::Scene spots = mixed;
    spots.lights = lights;
    for (const char* technique :
         {"forward", "forward-plus", "deferred-tiled", "clustered-deferred", "visibility-buffer"}) {
        if (std::string(technique) != "forward" && !device->info().features.computeShaders)
            continue;
        const render::RenderSettings s{.technique = technique, .width = 64, .height = 48};
        render::SceneRenderer changing(*device, points, s);
        changing.renderFrame();
        const gdi::Image lit = changing.readOutput();
        changing.updateLights(lights);
        changing.renderFrame();
        render::SceneRenderer made(*device, spots, s);
        made.renderFrame();
        EXPECT_LE(largestRelativeDifference(changing.readOutput(), made.readOutput()), 1e-4)
            << technique;
        EXPECT_GE(largestRelativeDifference(lit, made.readOutput()), 0.5)
            << technique << ": the lights' change hardly changes the image";
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(SpecializedShaders);
