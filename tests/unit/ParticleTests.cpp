// The VFX renderer (render/VfxRenderer.h): builtin:particles drawn by every technique on every
// backend with the backends agreeing and validation silent; the simulated particle counts (the
// indirect draws' instance counts) equal the CPU's count of living particles; the alpha list is
// drawn back to front; particles change the image where they are and fade into the ground
// (soft particles); bad emitters are refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "integration/SceneRenderer.h"
#include "render/VfxRenderer.h"

using namespace fe;

namespace {
constexpr uint32_t kW = 96, kH = 72;

gdi::Image frameOf(gdi::Device& d, const assets::Scene& scene, const std::string& technique,
                   render::VfxRenderer::Counts* counts = nullptr,
                   std::vector<float>* distances = nullptr, double* time = nullptr) {
    render::RenderSettings s{.technique = technique, .width = kW, .height = kH};
    s.displayImage = true;
    render::SceneRenderer r(d, scene, s);
    if (time && r.vfx()) *time = r.vfx()->time();
    r.renderFrame();
    if (counts && r.vfx()) *counts = r.vfx()->lastCounts();
    if (distances && r.vfx()) *distances = r.vfx()->lastAlphaDistances();
    return r.readDisplay();
}
}  // namespace

TEST(Particles, EveryTechniqueOnEveryBackendAgrees) {
    const assets::Scene scene = assets::makeBuiltinScene("particles");
    std::map<std::string, std::vector<std::pair<std::string, gdi::Image>>> images;
    for (const std::string& b : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(b, true);
        if (!p.available) continue;
        for (const render::TechniqueInfo& t : render::techniques())
            images[t.name].push_back({b, frameOf(*p.device, scene, t.name)});
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
    }
    for (const auto& [technique, byBackend] : images) {
        ASSERT_FALSE(byBackend.empty());
        for (size_t i = 1; i < byBackend.size(); ++i) {
            const gdi::ImageDiff d =
                gdi::compareImages(byBackend[0].second, byBackend[i].second, 5.0 / 255.0);
            EXPECT_LE(d.fractionOver(), 0.002)
                << technique << ": " << byBackend[0].first << " vs " << byBackend[i].first << ": "
                << d.pixelsOverTolerance << " pixels over 5/255, max " << d.maxAbsError;
        }
    }
}

class Particles : public fe::testing::BackendTest {
protected:
    Particles() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

TEST_P(Particles, SimulatedCountsMatchTheCpuAndAlphaIsSortedBackToFront) {
    const assets::Scene scene = assets::makeBuiltinScene("particles");
    render::VfxRenderer::Counts counts;
    std::vector<float> distances;
    double time = 0;
    frameOf(*device, scene, "forward", &counts, &distances, &time);
    const render::VfxRenderer::Counts expected = render::VfxRenderer::aliveAt(scene.emitters, time);
    ASSERT_GT(expected.additive, 50u);
    ASSERT_GT(expected.alpha, 50u);
    // The shader evaluates births in single precision: a slot exactly at a birth or death may differ.
    EXPECT_NEAR(double(counts.additive), double(expected.additive), 2.0);
    EXPECT_NEAR(double(counts.alpha), double(expected.alpha), 2.0);
    ASSERT_EQ(distances.size(), counts.alpha);
    EXPECT_TRUE(std::is_sorted(distances.rbegin(), distances.rend()))
        << "the alpha list is not farthest first";
    EXPECT_GT(distances.front(), distances.back());
}

// The largest difference of two images' bytes.
static int largestByteDifference(const gdi::Image& a, const gdi::Image& b) {
    int largest = a.data.size() == b.data.size() ? 0 : 255;
    for (size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
        largest = std::max(largest, std::abs(int(a.data[i]) - int(b.data[i])));
    return largest;
}

// RenderSettings::asyncCompute: the particles' reset, simulation and sort run on the compute
// queue beside the scene's passes (and, under MSAA, the unbounded light assignment of
// clustered-deferred), the frame cut into submissions with the waits between them; the image
// is the one the single list draws, bit for bit. Marking nothing async fails the first checks.
// On a GPU the frame is not the same to the bit (an H200, 2026-11-30, both APIs): particles
// join their draw lists, and lights their tiles' lists, through atomics in an order that varies
// with the GPU's scheduling (on Vulkan between two single-list frames too; on GL, one queue,
// with how the frame is cut into submissions), and the float sums follow the order. There the
// async frame may differ from the single list's by 2/255 per channel; a software rasterizer
// must draw it to the bit.
TEST_P(Particles, AsyncComputeDrawsTheSameFrame) {
    const assets::Scene scene = assets::makeBuiltinScene("particles");
    for (const uint32_t msaa : {1u, 4u}) {
        if (msaa > 1 && !(device->info().limits.colorSampleCounts & 4)) continue;
        gdi::Image images[2];
        for (const bool async : {false, true}) {
            render::RenderSettings s{
                .technique = "clustered-deferred", .width = kW, .height = kH, .msaa = msaa};
            s.asyncCompute = async;
            render::SceneRenderer r(*device, scene, s);
            std::vector<std::string> beside;
            for (const graph::PassInfo& p : r.graph().passes())
                if (!p.culled && p.forkBefore >= 0) beside.push_back(p.name);
            using V = std::vector<std::string>;
            const V expected = !async ? V{}
                               : msaa == 1
                                   ? V{"particles reset", "particles simulate", "particles sort"}
                                   : V{"light-assignment", "particles reset", "particles simulate",
                                       "particles sort"};
            EXPECT_EQ(beside, expected) << msaa << " samples";
            r.renderFrame();
            images[async] = r.readOutput();
        }
        EXPECT_LE(largestByteDifference(images[0], images[1]),
                  device->info().softwareRasterizer ? 0 : 2)
            << msaa << " samples";
    }
    EXPECT_EQ(device->validationErrorCount(), 0u);
}

// With the emitters removed the frame changes only where the particles were (the fire and the
// smoke column: a few percent of the frame, not most of it).
TEST_P(Particles, ParticlesDrawOnlyWhereTheyAre) {
    const assets::Scene scene = assets::makeBuiltinScene("particles");
    const gdi::Image with = frameOf(*device, scene, "deferred");
    assets::Scene none = scene;
    none.emitters.clear();
    const gdi::Image without = frameOf(*device, none, "deferred");
    size_t changed = 0;
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            float d = 0;
            for (int c = 0; c < 3; ++c) d += std::abs(with.texel(x, y)[c] - without.texel(x, y)[c]);
            changed += d > 0.02f;
        }
    EXPECT_GT(changed, kW * kH / 50) << "particles barely visible";
    EXPECT_LT(changed, kW * kH / 3) << "particles changed most of the frame";
}

// Soft particles: large, dim additive particles lying on the ground fade out where they meet it,
// so with softness 0 (a hard cut where they enter the ground) those pixels are brighter.
TEST_P(Particles, SoftParticlesFadeIntoTheGround) {
    assets::Scene scene = assets::makeBuiltinScene("particles");
    assets::ParticleEmitter mist;
    mist.name = "mist";
    mist.position = {0.0f, 0.05f, 0.8f};
    mist.velocity = {0.0f, 0.02f, 0.0f};
    mist.gravity = {0.0f, 0.0f, 0.0f};
    mist.spread = 1.5f;
    mist.rate = 10.0f, mist.lifetime = 2.0f;
    mist.sizeStart = mist.sizeEnd = 0.5f;
    mist.colorStart = mist.colorEnd = {0.12f, 0.12f, 0.12f, 1.0f};
    mist.softness = 0.5f;
    scene.emitters = {mist};
    const gdi::Image soft = frameOf(*device, scene, "forward");
    scene.emitters[0].softness = 0.0f;
    const gdi::Image hard = frameOf(*device, scene, "forward");
    size_t brighter = 0, darker = 0;
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            float h = 0;
            for (int c = 0; c < 3; ++c) h += hard.texel(x, y)[c] - soft.texel(x, y)[c];
            brighter += h > 0.02f;
            darker += h < -0.02f;
        }
    EXPECT_GT(brighter, 15u)
        << "soft particles did not fade where they meet the ground";  // measured 25 on every backend
    EXPECT_EQ(darker, 0u) << "fading can only take light away";
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Particles);

TEST(ParticleEmitters, BadEmittersAreRefused) {
    auto vulkan = gdi::probeBackend("gl-osmesa", true);
    if (!vulkan.available) GTEST_SKIP() << vulkan.reason;
    assets::Scene scene = assets::makeBuiltinScene("particles");
    scene.emitters[0].rate = NAN;
    EXPECT_EQ(fe::testing::errorOf([&] { frameOf(*vulkan.device, scene, "forward"); }),
              "particle emitter 'fire': a value is not finite (NaN or infinity)");
    scene = assets::makeBuiltinScene("particles");
    scene.emitters[1].rate = 1000.0f;  // 3000 smoke particles alive at once
    EXPECT_EQ(
        fe::testing::errorOf([&] { frameOf(*vulkan.device, scene, "forward"); }),
        "alpha-blended particles: 3000 alive at once (rate x lifetime) exceed the 1024 one work group sorts");
    scene = assets::makeBuiltinScene("particles");
    scene.emitters[0].lifetime = 0.0f;
    EXPECT_NE(fe::testing::errorOf([&] {
                  frameOf(*vulkan.device, scene, "forward");
              }).find("rate and lifetime must be positive"),
              std::string::npos);
}

// A glTF node's extras attach an emitter at the node's world position (docs/PARTICLES.md); a
// malformed one is an error naming the node and the key.
TEST(ParticleEmitters, GltfNodeExtrasAttachAnEmitter) {
    const assets::Scene scene = assets::loadScene(std::string(FE_TEST_DATA) + "/emitter.gltf");
    ASSERT_EQ(scene.emitters.size(), 1u);
    const assets::ParticleEmitter& e = scene.emitters[0];
    EXPECT_EQ(e.name, "flame");
    EXPECT_EQ(e.position, glm::vec3(1.0f, 2.5f, 3.0f));  // the parent's translation plus its own
    EXPECT_EQ(e.rate, 40.0f);
    EXPECT_EQ(e.lifetime, 0.5f);
    EXPECT_EQ(e.velocity, glm::vec3(0.0f, 2.0f, 0.0f));
    EXPECT_EQ(e.sizeStart, 0.2f);
    EXPECT_EQ(e.sizeEnd, 0.05f);
    EXPECT_EQ(e.colorEnd, glm::vec4(1.0f, 0.2f, 0.0f, 0.0f));
    EXPECT_EQ(e.blend, assets::ParticleEmitter::Blend::Additive);
    EXPECT_EQ(e.softness, 0.1f);
    EXPECT_EQ(e.spread, assets::ParticleEmitter{}.spread);  // not given: the default
}
