// The default look of a user's model: a model without lights under the sky
// and a sun with shadows (assets::useDefaultSkyAndSun), backgrounds of every kind
// (RenderSettings::Background) on every backend, and the warnings a black or empty frame gets
// (render::frameWarnings).
#include <gtest/gtest.h>

#include <cmath>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "assets/GltfLoader.h"
#include "integration/FrameWarnings.h"
#include "integration/SceneRenderer.h"

using namespace fe;
using Kind = render::Background::Kind;

namespace {

// builtin:shadows as a user's model without lights: the loader's default rig in place of its own.
assets::Scene unlitShadowsScene() {
    assets::Scene scene = assets::makeBuiltinScene("shadows");
    scene.lights.clear();
    scene.showsShadows = false;
    assets::addDefaultLights(scene, *scene.camera);
    return scene;
}

struct Frame {
    gdi::Image linear, display;
};
Frame renderWith(gdi::Device& d, const assets::Scene& scene, render::RenderSettings s) {
    s.displayImage = true;
    render::SceneRenderer r(d, scene, s);
    r.renderFrame();
    return {r.readOutput(), r.readDisplay()};
}

float luminance(const std::array<float, 4>& t) {
    return 0.2126f * t[0] + 0.7152f * t[1] + 0.0722f * t[2];
}

}  // namespace

TEST(DefaultLook, ReplacesTheLightRigByTheSkyAndASunAboveTheViewersShoulder) {
    assets::Scene scene = unlitShadowsScene();
    ASSERT_TRUE(scene.hasDefaultLights);
    ASSERT_TRUE(assets::useDefaultSkyAndSun(scene));
    ASSERT_EQ(scene.lights.size(), 1u);
    const assets::Light& sun = scene.lights[0];
    EXPECT_EQ(sun.type, assets::LightType::Directional);
    EXPECT_FLOAT_EQ(sun.intensity, assets::kDefaultSunIlluminance);
    // From above, at least kDefaultSunMinElevation, and from behind the viewer: it lights what is seen.
    EXPECT_LE(sun.direction.y, -assets::kDefaultSunMinElevation + 1e-5f);
    EXPECT_GT(glm::dot(sun.direction, scene.camera->forward()), 0.0f);
    ASSERT_TRUE(scene.environment);
    EXPECT_EQ(scene.environment->kind, assets::Environment::Kind::Sky);
    EXPECT_EQ(scene.environment->sky.sunRadiance,
              glm::dvec3(0.0));  // the light is the sun: no disc
    EXPECT_NEAR(glm::dot(glm::vec3(scene.environment->sky.sunDirection), -sun.direction), 1.0f,
                1e-5f);
    EXPECT_TRUE(scene.showsShadows);

    // A scene with lights of its own keeps them, and gets no sky.
    assets::Scene lit = assets::makeBuiltinScene("shadows");
    const size_t lights = lit.lights.size();
    EXPECT_FALSE(assets::useDefaultSkyAndSun(lit));
    EXPECT_EQ(lit.lights.size(), lights);
    EXPECT_FALSE(lit.environment);
}

TEST(DefaultLook, LoadedFlatModelGetsIt) {
    assets::Scene scene = assets::loadGltf(std::string(FE_TEST_DATA) + "/flat_plane.gltf");
    EXPECT_TRUE(scene.hasDefaultLights);
    EXPECT_TRUE(assets::useDefaultSkyAndSun(scene));
    // The default camera sees the flat model from above: the sun lights its upper face.
    EXPECT_LT(scene.camera->forward().y, -0.2f);
}

TEST(FrameWarnings, NothingInViewNamesTheSide) {
    assets::Scene scene = assets::makeBuiltinScene("triangle");
    const glm::vec3 c = scene.bounds.center();
    const float r = glm::length(scene.bounds.size());
    using assets::Camera;
    const float fov = 0.8f;
    EXPECT_EQ(render::outOfView(scene,
                                Camera::lookAlong(c + glm::vec3(0, 0, 3 * r), {0, 0, -1}, {0, 1, 0},
                                                  fov, 0.01f, 100.0f),
                                1.5f),
              "");
    EXPECT_EQ(render::outOfView(scene,
                                Camera::lookAlong(c + glm::vec3(0, 0, 3 * r), {0, 0, 1}, {0, 1, 0},
                                                  fov, 0.01f, 100.0f),
                                1.5f),
              "behind the camera or nearer than znear");
    EXPECT_EQ(render::outOfView(scene,
                                Camera::lookAlong(c + glm::vec3(0, 0, 30 * r), {0, 0, -1},
                                                  {0, 1, 0}, fov, 0.01f, 2 * r),
                                1.5f),
              "beyond zfar");
    EXPECT_EQ(render::outOfView(scene,
                                Camera::lookAlong(c + glm::vec3(20 * r, 0, 3 * r), {0, 0, -1},
                                                  {0, 1, 0}, fov, 0.01f, 100.0f),
                                1.5f),
              "left of the view");
    EXPECT_EQ(render::outOfView(scene,
                                Camera::lookAlong(c + glm::vec3(0, 20 * r, 3 * r), {0, 0, -1},
                                                  {0, 1, 0}, fov, 0.01f, 100.0f),
                                1.5f),
              "below the view");
}

TEST(FrameWarnings, ABlackFrameSaysWhy) {
    assets::Scene scene = assets::makeBuiltinScene("triangle");
    render::RenderSettings s{.width = 4, .height = 4};
    auto image = [](std::array<float, 4> texel) {
        return gdi::Image::fromTexels(4, 4, gdi::Format::RGBA8,
                                      std::vector<std::array<float, 4>>(16, texel));
    };
    const gdi::Image black = image({0, 0, 0, 1}), lit = image({0.2f, 0.1f, 0.0f, 1.0f}),
                     clear = image({0, 0, 0, 0});
    EXPECT_TRUE(render::frameWarnings(scene, *scene.camera, s, lit).empty());
    EXPECT_TRUE(render::frameWarnings(scene, *scene.camera, s, clear).empty())
        << "a transparent background is not black";
    scene.lights.clear();
    for (assets::Material& m : scene.materials) m.emissiveFactor = glm::vec3(0.0f), m.unlit = false;
    auto only = [&] {
        const std::vector<std::string> w = render::frameWarnings(scene, *scene.camera, s, black);
        return w.size() == 1 ? w[0] : "(" + std::to_string(w.size()) + " warnings)";
    };
    EXPECT_NE(only().find("the image is black: the scene has no lights"), std::string::npos)
        << only();
    assets::Light off;
    off.intensity = 0.0f;
    scene.lights.push_back(off);
    EXPECT_NE(only().find("zero intensity"), std::string::npos) << only();
    scene.lights[0].intensity = 1.0f;
    EXPECT_NE(only().find("no light reaches a visible surface"), std::string::npos) << only();
}

class Backgrounds : public fe::testing::BackendTest {
protected:
    Backgrounds() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

// Transparent: alpha 0 where nothing was drawn, 1 on opaque surfaces (their colour as with the
// environment behind them), in between on a blended one; kept through FXAA and TAA.
TEST_P(Backgrounds, TransparentIsAlphaZeroWhereNothingIsDrawn) {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.materials[0].alphaMode = assets::AlphaMode::Blend;
    scene.materials[0].baseColorFactor.a = 0.5f;
    render::RenderSettings s{.technique = "forward", .width = 64, .height = 48};
    s.iblPrefiltered = true;
    const Frame environment = renderWith(*device, scene, s);
    for (render::AntiAliasing aa :
         {render::AntiAliasing::None, render::AntiAliasing::Fxaa, render::AntiAliasing::Taa}) {
        s.antiAliasing = aa;
        s.background.kind = Kind::Transparent;
        const Frame f = renderWith(*device, scene, s);
        size_t clear = 0, opaque = 0, partial = 0, sameColour = 0;
        for (uint32_t y = 0; y < f.display.height; ++y)
            for (uint32_t x = 0; x < f.display.width; ++x) {
                const auto t = f.display.texel(x, y);
                if (t[3] == 0.0f)
                    ++clear;
                else if (t[3] == 1.0f) {
                    ++opaque;
                    const auto e = environment.display.texel(x, y);
                    sameColour += std::abs(t[0] - e[0]) <= 1.5f / 255 &&
                                  std::abs(t[1] - e[1]) <= 1.5f / 255 &&
                                  std::abs(t[2] - e[2]) <= 1.5f / 255;
                } else if (std::abs(t[3] - 0.5f) < 0.02f)
                    ++partial;
            }
        const size_t n = size_t(f.display.width) * f.display.height;
        EXPECT_EQ(f.display.texel(0, 0)[3], 0.0f) << int(aa);
        EXPECT_GT(clear, n / 5) << int(aa);
        EXPECT_GT(opaque, n / 5) << int(aa);
        EXPECT_GT(partial, n / 50)
            << int(aa) << ": the blended sphere over nothing keeps its alpha";
        if (aa == render::AntiAliasing::None) {
            EXPECT_GT(double(sameColour), 0.95 * double(opaque));
        }
    }
    // Every technique: what each leaves in L_o's alpha differs (forward writes 1, the G-buffer
    // and compute ones do not), so the coverage must come from the background pass itself.
    s.antiAliasing = render::AntiAliasing::None;
    for (const render::TechniqueInfo& t : render::techniques()) {
        if (std::string(t.name).find("tiled") != std::string::npos &&
            !device->info().features.computeShaders)
            continue;
        s.technique = t.name;
        const gdi::Image d = renderWith(*device, scene, s).display;
        size_t clear = 0, opaque = 0;
        for (uint32_t y = 0; y < d.height; ++y)
            for (uint32_t x = 0; x < d.width; ++x)
                clear += d.texel(x, y)[3] == 0.0f, opaque += d.texel(x, y)[3] == 1.0f;
        const size_t n = size_t(d.width) * d.height;
        EXPECT_GT(clear, n / 5) << t.name;
        EXPECT_GT(opaque, n / 5) << t.name;
    }
}

// A colour: exactly that sRGB value where nothing is drawn, under every tone mapper and FXAA.
TEST_P(Backgrounds, ColourIsExactUnderEveryTonemapper) {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    render::RenderSettings s{.technique = "forward", .width = 64, .height = 48};
    s.background = {.kind = Kind::Color, .color = glm::vec3(0x33, 0x66, 0x99) / 255.0f};
    for (shading::Tonemap t :
         {shading::Tonemap::Clamp, shading::Tonemap::Aces, shading::Tonemap::PbrNeutral})
        for (render::AntiAliasing aa : {render::AntiAliasing::None, render::AntiAliasing::Fxaa}) {
            s.tonemap = t;
            s.antiAliasing = aa;
            const gdi::Image d = renderWith(*device, scene, s).display;
            // RGBA8_SRGB reads back as stored: the sRGB-encoded bytes.
            const auto corner = d.texel(0, 0);
            EXPECT_NEAR(corner[0] * 255.0f, 0x33, 0.01f) << shading::tonemapName(t);
            EXPECT_NEAR(corner[1] * 255.0f, 0x66, 0.01f);
            EXPECT_NEAR(corner[2] * 255.0f, 0x99, 0.01f);
            EXPECT_EQ(corner[3], 1.0f);
            const auto centre = d.texel(d.width / 4, d.height / 4);  // a sphere of the 2x2 grid
            EXPECT_GT(std::abs(centre[0] * 255.0f - 0x33) + std::abs(centre[2] * 255.0f - 0x99),
                      10.0f);
        }
}

TEST_P(Backgrounds, EnvironmentWithoutOneIsRefused) {
    const assets::Scene scene = assets::makeBuiltinScene("triangle");
    render::RenderSettings s{.technique = "forward", .width = 16, .height = 16};
    s.background.kind = Kind::Environment;
    EXPECT_EQ(
        fe::testing::errorOf([&] { render::SceneRenderer r(*device, scene, s); }),
        "an environment background needs an environment (--environment FILE.hdr|builtin:sky)");
    s.background = {.kind = Kind::Color, .color = glm::vec3(1.5f, 0, 0)};
    EXPECT_EQ(fe::testing::errorOf([&] { render::SceneRenderer r(*device, scene, s); }),
              "the background colour's channels must lie in [0, 1] (sRGB-encoded)");
}

// The default look: the sky shows above the model, the sun's shadow darkens the ground, and
// nothing is black.
TEST_P(Backgrounds, DefaultLookShowsSkyAndSunShadows) {
    assets::Scene scene = unlitShadowsScene();
    ASSERT_TRUE(assets::useDefaultSkyAndSun(scene));
    render::RenderSettings s{.technique = "forward", .width = 96, .height = 64};
    s.iblPrefiltered = true;
    s.tonemap = shading::Tonemap::PbrNeutral;
    const Frame unshadowed = renderWith(*device, scene, s);
    s.shadows.enabled = true;
    s.shadows.mapSize = 512;
    const Frame shadowed = renderWith(*device, scene, s);
    const auto sky = shadowed.display.texel(shadowed.display.width / 2, 0);
    EXPECT_GT(sky[2], sky[0]) << "blue sky at the top";
    EXPECT_GT(luminance(sky), 0.5f);
    size_t darker = 0, black = 0;
    for (uint32_t y = 0; y < shadowed.display.height; ++y)
        for (uint32_t x = 0; x < shadowed.display.width; ++x) {
            const float a = luminance(unshadowed.display.texel(x, y)),
                        b = luminance(shadowed.display.texel(x, y));
            darker += b < a - 0.08f;
            black += b < 1.0f / 255;
        }
    const size_t n = size_t(shadowed.display.width) * shadowed.display.height;
    EXPECT_GT(darker, n / 100) << "the sun casts shadows (1.8 % of pixels measured)";
    EXPECT_LT(black, n / 100);
    EXPECT_TRUE(render::frameWarnings(scene, *scene.camera, s, shadowed.display).empty());
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Backgrounds);
