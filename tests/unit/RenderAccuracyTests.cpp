// Accuracy of the lighting techniques on every backend: forward against the CPU double-precision
// reference (renderer/reference), deferred and redeferred (I-buffer at full rate) against
// forward, and the measured error of redeferred at half and quarter illumination rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "assets/BuiltinScenes.h"
#include "assets/Geometry.h"
#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/ShaderRegistry.h"
#include "reference/CpuReference.h"
#include "reference/ImageMetrics.h"
#include "integration/FrameWarnings.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"
#include "render/ClusterLightGrid.h"
#include "render/GpuScene.h"
#include "render/LightVolumes.h"
#include "render/TileLightCulling.h"

using namespace fe;

namespace {
constexpr uint32_t kW = 96, kH = 72;

// The separable BRDF for forward images the redeferred and light pre-pass techniques are
// compared with (render::resolveBrdf): the comparisons measure the technique, not the BRDF.
constexpr render::ShadingModel kSeparable = render::ShadingModel::Separable;
gdi::Image renderImage(gdi::Device& d, const assets::Scene& scene, const std::string& t,
                       uint32_t scale = 1, bool split = false, bool precomputedNoV = true,
                       render::ShadingModel model = render::ShadingModel::Auto) {
    render::RenderSettings s{.technique = t,
                             .width = kW,
                             .height = kH,
                             .illumScale = scale,
                             .illumSplit = split,
                             .precomputedNoV = precomputedNoV};
    s.shadingModel = model;
    render::SceneRenderer r(d, scene, s);
    r.renderFrame();
    return r.readOutput();
}

// Relative error per channel, floored at 1e-3 of the image's mean so dark pixels don't dominate.
struct Stats {
    double fractionOver = 0, maxRel = 0;
};
Stats compare(const gdi::Image& a, const gdi::Image& b, double tol, double floor,
              const std::function<bool(uint32_t, uint32_t)>& skip = {}) {
    uint32_t over = 0, n = 0;
    Stats s;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            if (skip && skip(x, y)) continue;
            ++n;
            auto ta = a.texel(x, y), tb = b.texel(x, y);
            bool bad = false;
            for (int c = 0; c < 3; ++c) {
                double rel = std::abs(ta[c] - tb[c]) /
                             std::max({std::abs(double(ta[c])), std::abs(double(tb[c])), floor});
                if (!std::isfinite(ta[c])) rel = INFINITY;
                s.maxRel = std::max(s.maxRel, rel);
                bad = bad || rel > tol;
            }
            over += bad;
        }
    s.fractionOver = n ? double(over) / n : 1.0;
    return s;
}

class RenderAccuracy : public fe::testing::BackendTest {
protected:
    RenderAccuracy() : BackendTest(true) {}
    void SetUp() override {
        BackendTest::SetUp();
        scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 5});
    }
    assets::Scene scene;
};
}  // namespace

TEST_P(RenderAccuracy, ForwardMatchesCpuReference) {
    gdi::Image gpu = renderImage(*device, scene, "forward");
    render::ReferenceImage ref = render::renderReference(scene, *scene.camera, kW, kH);
    std::vector<std::array<float, 4>> texels;
    for (auto& v : ref.radiance) texels.push_back({float(v.x), float(v.y), float(v.z), 1});
    gdi::Image cpu = gdi::Image::fromTexels(kW, kH, gdi::Format::RGBA32F, texels);
    // Float32 shading vs double: 1% relative (0.01 absolute floor) on all pixels not on a
    // silhouette, where rasterization coverage and ray casting may see different surfaces.
    Stats s =
        compare(gpu, cpu, 0.01, 0.01, [&](uint32_t x, uint32_t y) { return ref.nearEdge(x, y); });
    RecordProperty("max_rel", std::to_string(s.maxRel));
    EXPECT_LE(s.fractionOver, 0.001) << "max relative error " << s.maxRel;
}

TEST_P(RenderAccuracy, DeferredMatchesForward) {
    gdi::Image f = renderImage(*device, scene, "forward");
    for (const char* t : {"deferred", "deferred-tiled"}) {
        gdi::Image d = renderImage(*device, scene, t);
        // G-buffer rounding: base colour in 8-bit sRGB (<0.4% relative above 0.05), normals and
        // roughness in half floats (specular highlights of smooth spheres move by a fraction of a
        // pixel): 2% relative on 99% of pixels.
        Stats s = compare(d, f, 0.02, 0.01);
        EXPECT_LE(s.fractionOver, 0.01) << t << " max relative error " << s.maxRel;
    }
}

// Tile culling drops no light: 128 ranged point lights over cubes, the tiled compute pass
// against light volumes on the same G-buffer: the same sums up to float ordering.
TEST_P(RenderAccuracy, TiledCullingDropsNoLight) {
    assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 128});
    auto render = [&](const char* t, bool cullingPass = true) {
        render::SceneRenderer r(
            *device, lights,
            {.technique = t, .width = 96, .height = 64, .tileCullingPass = cullingPass});
        r.renderFrame();
        return r.readOutput();
    };
    gdi::Image volumes = render("deferred");
    for (bool cullingPass : {true, false}) {
        Stats s = compare(render("deferred-tiled", cullingPass), volumes, 1e-4, 1e-3);
        EXPECT_EQ(s.fractionOver, 0.0)
            << (cullingPass ? "culling pass" : "one pass") << " max relative error " << s.maxRel;
    }
    // The tiled illumination pass fills the I-buffer with the same sums as the volumes (which
    // round L_dg to half float after every light's blend, where the compute pass rounds once).
    Stats r = compare(render("redeferred-tiled"), render("redeferred"), 1e-2, 1e-3);
    EXPECT_EQ(r.fractionOver, 0.0) << "redeferred-tiled max relative error " << r.maxRel;
}

// The clustered techniques read the light cluster grid (32x32-pixel tiles x 32 depth slices): a
// culled light adds exactly 0, and lists keep index order, so clustered-forward equals forward
// and clustered-deferred equals deferred-tiled bit for bit, with 256 ranged lights (and with
// 4x MSAA for the forward one). And the grid culls: a cluster holds a small part of the lights.
TEST_P(RenderAccuracy, ClusteredTechniquesCullExactly) {
    const assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 256});
    auto render = [&](const char* t, uint32_t msaa = 1) {
        render::SceneRenderer r(*device, lights,
                                {.technique = t, .width = 96, .height = 64, .msaa = msaa});
        r.renderFrame();
        gdi::Image image = r.readOutput();
        if (r.clusters()) {
            const render::ClusterLightGrid::Statistics st = r.clusters()->statistics();
            constexpr uint32_t tile = render::ClusterLightGrid::kTilePixels;
            EXPECT_EQ(st.clusters, (96 + tile - 1) / tile * ((64 + tile - 1) / tile) *
                                       render::ClusterLightGrid::kSlices)
                << t;
            EXPECT_LE(st.entries, r.clusters()->listCapacity()) << t;
            EXPECT_EQ(st.overflowed, 0u) << t;
            EXPECT_GT(st.nonEmpty, 0u) << t;
            EXPECT_LT(st.meanLights, 256.0 / 4) << t << ": the clusters hardly cull";
        }
        return image;
    };
    Stats f = compare(render("clustered-forward"), render("forward"), 1e-6, 1e-6);
    EXPECT_EQ(f.fractionOver, 0.0) << "clustered-forward max relative error " << f.maxRel;
    Stats d = compare(render("clustered-deferred"), render("deferred-tiled"), 1e-6, 1e-6);
    EXPECT_EQ(d.fractionOver, 0.0) << "clustered-deferred max relative error " << d.maxRel;
    // The visibility buffer shades the same lists with full-precision normals and positions
    // rebuilt from the triangle (the G-buffer rounds normals to half floats): as forward, up to
    // the rasterizer's interpolation against the ray's barycentrics. lavapipe and llvmpipe agree
    // to 3e-4; on an H200 27 % of pixels differed by over 1e-3 (at most 3.2 %, in the narrow
    // highlights), so the bound is the G-buffer techniques' 2 % (deferred against forward).
    const gdi::Image visibility = render("visibility-buffer"),
                     forward = render("clustered-forward");
    Stats v = compare(visibility, forward, 0.02, 0.01);
    EXPECT_EQ(v.fractionOver, 0.0) << "visibility-buffer max relative error " << v.maxRel;
    if (device->info().softwareRasterizer) {
        Stats close = compare(visibility, forward, 1e-3, 1e-3);
        EXPECT_EQ(close.fractionOver, 0.0)
            << "visibility-buffer max relative error " << close.maxRel;
    }
    if (device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4) {
        Stats m = compare(render("clustered-forward", 4), render("forward", 4), 1e-6, 1e-6);
        EXPECT_EQ(m.fractionOver, 0.0)
            << "clustered-forward at 4 samples, max relative error " << m.maxRel;
    }
}

// builtin:atrium (a deep arcade with translucent banners, 64 ranged lights through its depth):
// the many-light techniques against the CPU reference (which composites the blended banners far
// to near) at the exact techniques' tolerance: PSNR >= 45 dB, at most 0.1 % of pixels beyond 5/255.
TEST_P(RenderAccuracy, ManyLightTechniquesMatchTheReferenceInTheAtrium) {
    const assets::Scene atrium = assets::makeBuiltinScene("atrium", {.lights = 64});
    constexpr uint32_t W = 128, H = 72;
    const render::ReferenceImage ref = render::renderReference(atrium, *atrium.camera, W, H);
    const render::DisplayImage expected = render::toDisplay(W, H, ref.radiance);
    for (const char* t : {"forward", "forward-plus", "clustered-forward", "clustered-deferred",
                          "deferred-tiled", "visibility-buffer"}) {
        render::SceneRenderer r(*device, atrium, {.technique = t, .width = W, .height = H});
        r.renderFrame();
        const gdi::Image out = r.readOutput();
        std::vector<glm::dvec3> linear;
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x) {
                const auto v = out.texel(x, y);
                linear.emplace_back(v[0], v[1], v[2]);
            }
        const render::ImageMetrics m =
            render::compareImages(render::toDisplay(W, H, linear), expected);
        RecordProperty(std::string("psnr_") + t, std::to_string(m.psnr));
        EXPECT_GE(m.psnr, 45.0) << t;
        EXPECT_LE(m.percentOver5, 0.1) << t;
    }
}

// The light-list statistics: what each technique's shading loop walks per pixel. Every light for
// forward; far fewer for the culled techniques' lists, the tiles (8x8 pixels, depth-bounded)
// and the clusters (32x32 pixels, 32 slices) each within the lights; volumes are not measured.
// Next to it the lights that reach each pixel, the same for every technique and never more than
// a list walks; and no pixel's list misses a light that reaches it.
TEST_P(RenderAccuracy, LightListStatisticsCountWhatTheLoopsWalk) {
    const assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 256});
    auto statistics = [&](const char* t, uint32_t msaa = 1) {
        render::SceneRenderer r(
            *device, lights,
            {.technique = t, .width = 96, .height = 64, .msaa = msaa, .lightListStatistics = true});
        r.renderFrame();
        return r.lightListStatistics();
    };
    const render::LightListStatistics every = statistics("forward");
    EXPECT_EQ(every.lists, "every light");
    EXPECT_EQ(every.mean, 256.0);
    EXPECT_EQ(every.max, 256u);
    EXPECT_GT(every.reaching,
              1.0);  // 256 lights of range 2 among 121 cubes: a few reach each surface
    EXPECT_LT(every.reaching, 256.0 / 8);
    EXPECT_EQ(every.pixelsMissingALight, 0u);
    if (device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4) {
        // Multisampled techniques count on the resolved depth: the same surfaces, the same lights.
        for (const char* t : {"forward-zprepass", "forward-plus", "clustered-forward"}) {
            const render::LightListStatistics m = statistics(t, 4);
            EXPECT_TRUE(m.measured) << t;
            EXPECT_NEAR(m.reaching, every.reaching, 0.05 * every.reaching) << t << " at 4 samples";
            EXPECT_EQ(m.pixelsMissingALight, 0u) << t << " at 4 samples";
        }
    }
    for (const char* t : {"forward-plus", "deferred-tiled", "clustered-forward",
                          "clustered-deferred", "visibility-buffer"}) {
        const render::LightListStatistics l = statistics(t);
        EXPECT_TRUE(l.measured) << t;
        const bool clustered =
            std::string(t).starts_with("clustered") || std::string(t) == "visibility-buffer";
        EXPECT_EQ(l.lists, clustered ? "cluster lists" : "tile lists") << t;
        EXPECT_EQ(l.pixels, every.pixels) << t;  // the same surfaces
        EXPECT_GT(l.mean, 0.0) << t;
        EXPECT_LT(l.mean, 256.0 / 4)
            << t << ": the lists hardly cull";  // 32-pixel clusters: 3x2 columns here
        EXPECT_LE(double(l.p95), double(l.max)) << t;
        EXPECT_LE(l.max, 256u) << t;
        EXPECT_NEAR(l.reaching, every.reaching, 1e-3 * every.reaching) << t;
        EXPECT_GE(l.mean, l.reaching) << t;
        EXPECT_EQ(l.pixelsMissingALight, 0u)
            << t << ": a list misses a light that reaches its pixel";
    }
    // The two tiled techniques share the culling pass: the same lists.
    EXPECT_EQ(statistics("forward-plus").mean, statistics("deferred-tiled").mean);
    EXPECT_FALSE(statistics("deferred").measured);
}

// The deep scene the clusters are for: builtin:atrium, 512 lights spread through 40 m of depth,
// at 480x270. Every list walks at most 2.5x the lights that reach each pixel (what any exact
// culling walks at least). Measured: clusters 2.33x with 32 slices after the near split
// (ClusterLightGrid::kNearSplit), 2.66x with 24 slices from the near plane (as before it);
// the depth-bounded 8x8 tiles 2.17x.
TEST_P(RenderAccuracy, ListsWalkFewMoreLightsThanReachInADeepScene) {
    const assets::Scene atrium = assets::makeBuiltinScene("atrium", {.lights = 512});
    for (const char* t : {"clustered-deferred", "deferred-tiled"}) {
        render::SceneRenderer r(
            *device, atrium,
            {.technique = t, .width = 480, .height = 270, .lightListStatistics = true});
        r.renderFrame();
        const render::LightListStatistics l = r.lightListStatistics();
        ASSERT_TRUE(l.measured) << t;
        EXPECT_EQ(l.pixelsMissingALight, 0u) << t;
        EXPECT_GT(l.reaching, 1.0) << t;
        RecordProperty(std::string("walked_per_reaching_") + t,
                       std::to_string(l.mean / l.reaching));
        EXPECT_LE(l.mean, 2.5 * l.reaching) << t;
    }
}

// The cluster lists bounded by the opaque depth (ClusterLightGrid::declareBounded): an opaque
// pixel walks only the lights that reach the depths its cluster's surfaces hold. In the deep
// atrium (translucent banners: the lists keep the rest of the slice's lights after the bounded
// part, for blended fragments) the same image as the whole lists, fewer lights walked, none
// missed. builtin:lights has no blended surface: the lists keep only the bounded parts.
// Measured at 320x180 with 256 lights (lavapipe): 5.71 lights walked a pixel bounded against
// 6.26 whole, the same for the three techniques (one grid). It fails if the bounds are not taken
// (as many lights walked), or are too tight (a light missed, a different image).
TEST_P(RenderAccuracy, ClusterDepthBoundsShortenTheOpaqueListsExactly) {
    const assets::Scene atrium = assets::makeBuiltinScene("atrium", {.lights = 256});
    const assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 256});
    for (const char* t : {"clustered-deferred", "clustered-forward", "visibility-buffer"}) {
        auto render = [&](const assets::Scene& scene, bool bounds) {
            render::SceneRenderer r(*device, scene,
                                    {.technique = t,
                                     .width = 320,
                                     .height = 180,
                                     .clusterDepthBounds = bounds,
                                     .lightListStatistics = true});
            bool boundsPass = false;
            for (const auto& p : r.graph().passes())
                boundsPass = boundsPass || p.name == "cluster-bounds";
            EXPECT_EQ(boundsPass, bounds) << t;
            r.renderFrame();
            return std::tuple(r.readOutput(), r.lightListStatistics(), r.clusters()->statistics());
        };
        const auto [whole, wholeWalked, wholeGrid] = render(atrium, false);
        const auto [bounded, boundedWalked, boundedGrid] = render(atrium, true);
        EXPECT_FALSE(wholeGrid.bounded) << t;
        EXPECT_TRUE(boundedGrid.bounded) << t;
        EXPECT_EQ(boundedWalked.pixelsMissingALight, 0u) << t;
        EXPECT_EQ(boundedWalked.reaching, wholeWalked.reaching) << t;
        EXPECT_LT(boundedWalked.mean, 0.95 * wholeWalked.mean)
            << t << ": the bounds shorten nothing";
        EXPECT_LT(boundedGrid.meanBoundedLights, boundedGrid.meanLights) << t;
        EXPECT_EQ(boundedGrid.entries, wholeGrid.entries)
            << t << ": the banners walk the whole lists";
        RecordProperty(std::string("walked_bounded_") + t, std::to_string(boundedWalked.mean));
        RecordProperty(std::string("walked_whole_") + t, std::to_string(wholeWalked.mean));
        // Opaque pixels add the same lights in the same order; a banner's fragments add its
        // cluster's in another order (the bounded part first): float rounding only.
        Stats a = compare(bounded, whole, 1e-5, 1e-5);
        EXPECT_EQ(a.fractionOver, 0.0) << t << " in the atrium: max relative error " << a.maxRel;

        const auto [wholeLights, wholeLightsWalked, wholeLightsGrid] = render(lights, false);
        const auto [boundedLights, boundedLightsWalked, boundedLightsGrid] = render(lights, true);
        EXPECT_EQ(boundedLightsWalked.pixelsMissingALight, 0u) << t;
        EXPECT_EQ(boundedLightsGrid.meanBoundedLights, boundedLightsGrid.meanLights)
            << t << ": only the bounded parts";
        EXPECT_LT(boundedLightsGrid.entries, wholeLightsGrid.entries) << t;
        Stats l = compare(boundedLights, wholeLights, 1e-6, 1e-6);
        EXPECT_EQ(l.fractionOver, 0.0)
            << t << " in builtin:lights: max relative error " << l.maxRel;
    }
}

// Every technique's translucent pass reads the cluster grid (made for it when the technique has
// none): the same image as lighting blended surfaces with every light, shadowed lights included.
TEST_P(RenderAccuracy, TranslucentPassReadsTheClusterGrid) {
    for (const char* name : {"lights", "shadows"}) {
        assets::Scene scene1 = assets::makeBuiltinScene(name, {.lights = 96});
        for (size_t i = 0; i < scene1.materials.size(); i += 2) {
            scene1.materials[i].alphaMode = assets::AlphaMode::Blend;
            scene1.materials[i].baseColorFactor.a = 0.5f;
        }
        for (const char* t :
             {"deferred", "forward-plus", "clustered-deferred", "visibility-buffer"}) {
            auto render = [&](bool clusters) {
                render::SceneRenderer r(*device, scene1,
                                        {.technique = t,
                                         .width = 96,
                                         .height = 64,
                                         .translucentClusters = clusters,
                                         .shadows = {.enabled = std::string(name) == "shadows"}});
                bool assigns = false;
                for (const auto& p : r.graph().passes())
                    assigns = assigns || p.name == "light-assignment";
                EXPECT_EQ(assigns, clusters || std::string(t) == "clustered-deferred" ||
                                       std::string(t) == "visibility-buffer")
                    << name << " " << t;
                r.renderFrame();
                return r.readOutput();
            };
            Stats s = compare(render(true), render(false), 1e-6, 1e-6);
            EXPECT_EQ(s.fractionOver, 0.0)
                << name << " " << t << ": max relative error " << s.maxRel;
        }
    }
}

// The clusters' lists share an index array of ClusterLightGrid::kMeanListCapacity entries per
// cluster; a cluster that finds no room left shades every light and is counted. 300 weak lights
// reaching every pixel ask for 300 per cluster: the later clusters overflow, and the image still
// equals forward's. The lists then grow: framesInFlight frames later none overflows, and the
// image is the same.
TEST_P(RenderAccuracy, ClusterListOverflowIsCountedAndShadesEveryLight) {
    assets::Scene scene1 = assets::makeBuiltinScene("lights", {.lights = 300});
    for (auto& l : scene1.lights) {
        l.position = {0.0f, 3.0f, 0.0f};
        l.range = 100.0f;
        l.intensity = 0.05f;
    }
    render::SceneRenderer r(*device, scene1,
                            {.technique = "clustered-forward", .width = 48, .height = 32});
    r.renderFrame();
    const gdi::Image clustered = r.readOutput();
    const render::ClusterLightGrid::Statistics st = r.clusters()->statistics();
    EXPECT_GT(st.overflowed, 0u);
    EXPECT_GT(st.entries, r.clusters()->listCapacity());
    render::SceneRenderer f(*device, scene1, {.technique = "forward", .width = 48, .height = 32});
    f.renderFrame();
    const gdi::Image forward = f.readOutput();
    Stats s = compare(clustered, forward, 1e-5, 1e-5);
    EXPECT_EQ(s.fractionOver, 0.0) << "max relative error " << s.maxRel;

    const uint32_t asked = st.entries;
    for (uint32_t i = 0; i < r.framesInFlight(); ++i) r.renderFrame();
    const gdi::Image grown = r.readOutput();
    const render::ClusterLightGrid::Statistics after = r.clusters()->statistics();
    EXPECT_EQ(after.overflowed, 0u);
    EXPECT_EQ(after.entries, asked);
    EXPECT_GE(r.clusters()->listCapacity(), asked);
    EXPECT_EQ(after.maxLights, 300u);
    Stats g = compare(grown, forward, 1e-5, 1e-5);
    EXPECT_EQ(g.fractionOver, 0.0) << "after growing: max relative error " << g.maxRel;
}

// A tile list holds at most TileLightCulling::kMaxListLength lights; a tile with more is marked
// to shade every light. 1030 weak lights reaching every pixel overflow every tile: the image
// must still equal the light volumes'. (Their range spheres reach past the far plane, which
// once clipped the volumes' back faces: LightVolumes now draws such lights full screen.)
TEST_P(RenderAccuracy, TileListOverflowShadesEveryLight) {
    assets::Scene scene1 = assets::makeBuiltinScene("lights", {.lights = 1030});
    for (auto& l : scene1.lights) {
        l.position = {0.0f, 3.0f, 0.0f};
        l.range = 100.0f;
        l.intensity = 0.05f;
    }
    auto render = [&](const char* t) {
        render::SceneRenderer r(*device, scene1, {.technique = t, .width = 48, .height = 32});
        r.renderFrame();
        return r.readOutput();
    };
    const gdi::Image deferred = render("deferred");
    Stats s = compare(render("deferred-tiled"), deferred, 1e-3, 1e-3);
    EXPECT_EQ(s.fractionOver, 0.0) << "max relative error " << s.maxRel;
    // More lights than the uniform block holds: the forward shaders' FE_LIGHTS_IN_STORAGE variants.
    // Against deferred's additive blending of 1030 terms in another order: 1 % (a light read from
    // the wrong record is 100 % off).
    const gdi::Image forward = render("forward");
    Stats f = compare(forward, deferred, 1e-2, 1e-2);
    EXPECT_EQ(f.fractionOver, 0.0) << "forward: max relative error " << f.maxRel;
    for (const char* t : {"forward-plus", "clustered-forward"}) {
        Stats l = compare(render(t), forward, 1e-6, 1e-6);
        EXPECT_EQ(l.fractionOver, 0.0) << t << ": max relative error " << l.maxRel;
    }
}

// Light volumes outside the view are not drawn (lightOutOfView): a light ahead is kept, one
// behind the eye or beside the frustum by more than its range is culled, one whose range
// reaches into the view is kept; the same 1e5 units from the origin. That culling changes no
// pixel is TiledCullingDropsNoLight's (deferred's volumes against deferred-tiled's lists over
// builtin:lights, whose lights reach well beyond the view).
TEST(LightVolumeCulling, OnlyLightsWhollyOutsideTheViewAreCulled) {
    for (const glm::vec3 eye : {glm::vec3(0.0f), glm::vec3(1e5f, 0.0f, 1e5f)}) {
        render::FrameConstants f;
        f.cameraPosition = glm::vec4(eye, 1.0f);
        // Looking down -z, 90 degrees vertically, 2:1.
        f.viewProjFromEye = glm::perspectiveRH_ZO(glm::radians(90.0f), 2.0f, 0.1f, 100.0f);
        auto light = [&](glm::vec3 offset, float range) {
            assets::Light l;
            l.type = assets::LightType::Point;
            l.position = eye + offset;
            l.range = range;
            return l;
        };
        EXPECT_FALSE(render::lightOutOfView(light({0, 0, -5}, 1), f));
        EXPECT_TRUE(render::lightOutOfView(light({0, 0, 5}, 1), f));      // behind the eye
        EXPECT_FALSE(render::lightOutOfView(light({0, 0, 0.5f}, 1), f));  // reaching past it
        EXPECT_TRUE(render::lightOutOfView(light({13, 0, -5}, 1), f));    // right: x > 2z + r*sqrt5
        EXPECT_FALSE(render::lightOutOfView(light({11, 0, -5}, 1), f));   // its range reaches in
        EXPECT_TRUE(render::lightOutOfView(light({0, -7.5f, -5}, 1.5f), f));  // below
        EXPECT_FALSE(render::lightOutOfView(light({0, -7.5f, -5}, 2), f));
        assets::Light sun = light({0, 0, 50}, 0);  // unbounded: never culled
        EXPECT_FALSE(render::lightOutOfView(sun, f));
        sun.type = assets::LightType::Directional;
        EXPECT_FALSE(render::lightOutOfView(sun, f));
    }
}

// The light-culling pass walks the lights in view (TileLightCulling::lightsInView): the count in
// the header, the indices below the frame's light count in order, the lights wholly outside the
// view left out, unbounded and directional lights kept; padded for the uniform block.
TEST(TileLightCulling, WalksOnlyTheLightsInViewInOrder) {
    render::FrameConstants f;
    f.cameraPosition = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    f.viewProjFromEye = glm::perspectiveRH_ZO(glm::radians(90.0f), 2.0f, 0.1f, 100.0f);
    auto light = [](glm::vec3 position, float range, assets::LightType type) {
        assets::Light l;
        l.type = type;
        l.position = position;
        l.range = range;
        return l;
    };
    const auto point = assets::LightType::Point;
    const std::vector<assets::Light> lights = {
        light({0, 0, -5}, 1, point),                           // 0: in view
        light({0, 0, 5}, 1, point),                            // 1: behind the eye
        light({11, 0, -5}, 1, point),                          // 2: its range reaches in
        light({13, 0, -5}, 1, point),                          // 3: right of the view
        light({0, 0, 50}, 0, point),                           // 4: unbounded
        light({0, 0, 50}, 1, assets::LightType::Directional),  // 5: directional
        light({0, 0, -5}, 1, point),                           // 6: in view, beyond the count
    };
    const std::vector<uint32_t> block = render::TileLightCulling::lightsInView(lights, 6, f, false);
    EXPECT_EQ(block, (std::vector<uint32_t>{4, 0, 0, 0, 0, 2, 4, 5}));
    const std::vector<uint32_t> uniform =
        render::TileLightCulling::lightsInView(lights, 6, f, true);
    ASSERT_EQ(uniform.size(), 4u + render::GpuScene::kUniformLights);
    EXPECT_TRUE(std::equal(block.begin(), block.end(), uniform.begin()));
    EXPECT_EQ(render::TileLightCulling::lightsInView(lights, 0, f, false),
              (std::vector<uint32_t>{0, 0, 0, 0}));
}

// The cluster grid's slicing (fe_clusters.glsl reads it): slice 0 ends at the near split, the
// other slices are spaced exponentially from there to the scene's far side. Seen from inside the
// scene the split is kNearSplit of the far depth; seen from outside, where the scene begins.
TEST(ClusterSlicing, TheSlicesBeginWhereTheSceneCanBeSeen) {
    const assets::Camera camera =
        assets::Camera::lookAlong({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0f, 0.1f, 1000.0f);
    auto slicing = [&](float nearZ, float farZ) {
        assets::Bounds b;
        b.extend(glm::vec3(-1.0f, -1.0f, -farZ));
        b.extend(glm::vec3(1.0f, 1.0f, -nearZ));
        return render::ClusterLightGrid::slicing(camera, b);
    };
    const glm::vec4 outside = slicing(10.0f, 20.0f);  // the scene 10 to 20 m ahead
    EXPECT_FLOAT_EQ(outside.x, 0.1f);
    EXPECT_NEAR(outside.z, 20.2f, 1e-4f);  // the far side, 1 % margin
    EXPECT_NEAR(outside.w, 9.9f, 1e-4f);   // where the scene begins, 1 % margin
    // The last slice ends at the far side: split * exp((kSlices - 1) / y).
    EXPECT_NEAR(outside.w * std::exp(float(render::ClusterLightGrid::kSlices - 1) / outside.y),
                outside.z, 1e-3f);
    const glm::vec4 inside = slicing(-50.0f, 50.0f);  // the camera stands in the scene
    EXPECT_NEAR(inside.w, inside.z * render::ClusterLightGrid::kNearSplit, 1e-4f);
    EXPECT_GT(inside.w, inside.x);
    const glm::vec4 close =
        slicing(-0.01f, 0.05f);  // a scene nearer than the near plane's 32 times
    EXPECT_GE(close.w, close.x);
    EXPECT_LE(close.w, 0.5f * close.z);
    EXPECT_TRUE(std::isfinite(close.y) && close.y > 0.0f);
}

// The tiled passes and the forward shaders read up to 1024 lights from a uniform block and more
// from the storage buffer, through a second build of each shader (`// fe-variant:
// FE_LIGHTS_IN_STORAGE`, FeShaders.cmake; forward-plus's MSAA variant has a combined one). Both
// builds must exist and differ, on both APIs: a lost marker or an ignored define fails here, and
// TileListOverflowShadesEveryLight (1030 lights) renders through the variants.
TEST(TiledLightsVariants, EveryListShaderHasItsStorageVariant) {
    auto differ = [](const std::string& path, const std::string& a, const std::string& b) {
        const gdi::ShaderBinary& x = shaders::find(a.empty() ? path : path + ":" + a);
        const gdi::ShaderBinary& y = shaders::find(path + ":" + b);
        EXPECT_FALSE(std::ranges::equal(x.vulkan, y.vulkan))
            << path << " " << a << "/" << b << ": the same Vulkan binary";
        EXPECT_FALSE(std::ranges::equal(x.opengl, y.opengl))
            << path << " " << a << "/" << b << ": the same GL binary";
    };
    for (const char* name :
         {"tile_light_culling", "tiled_deferred", "tiled_illumination", "tiled_illumination_s2",
          "tiled_illumination_s4", "tiled_illumination_split"})
        differ(std::string("scene/") + name + ".comp", "", "FE_LIGHTS_IN_STORAGE");
    for (const char* name : {"forward", "forward_ibl", "forward_ibl_prefiltered",
                             "forward_shadowed", "forward_shadowed_cube", "forward_clustered",
                             "forward_clustered_ibl", "forward_clustered_ibl_prefiltered",
                             "forward_plus", "forward_plus_ibl", "forward_plus_ibl_prefiltered"})
        differ(std::string("scene/") + name + ".frag", "", "FE_LIGHTS_IN_STORAGE");
    for (const char* name : {"forward_plus", "forward_plus_ibl", "forward_plus_ibl_prefiltered"}) {
        const std::string path = std::string("scene/") + name + ".frag";
        differ(path, "FE_MULTISAMPLED",
               "FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE");  // both defines, not one
        differ(path, "FE_LIGHTS_IN_STORAGE", "FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE");
    }
    // The statistics pass walks every light at every pixel, for each kind of list.
    differ("scene/light_list_statistics.comp", "", "FE_LIGHTS_IN_STORAGE");
    for (const std::string lists : {"FE_CLUSTER_LISTS", "FE_EVERY_LIGHT"})
        differ("scene/light_list_statistics.comp", lists, lists + "+FE_LIGHTS_IN_STORAGE");
}

// Multi-pass forward adds each light's radiance in its own pass (float blending, in another
// order than the shader's loop): 1e-4 relative. The Z pre-pass shades every pixel with the same
// shader as forward, once: the same image, exactly.
TEST_P(RenderAccuracy, ForwardVariantsMatchForward) {
    // Some emissive spheres: multi-pass must add emission once, not once per light.
    for (size_t i = 0; i < scene.materials.size(); i += 3)
        scene.materials[i].emissiveFactor = {0.2f, 0.1f, 0.05f};
    gdi::Image f = renderImage(*device, scene, "forward");
    Stats multi = compare(renderImage(*device, scene, "forward-multipass"), f, 1e-4, 1e-4);
    EXPECT_EQ(multi.fractionOver, 0.0) << "forward-multipass max relative error " << multi.maxRel;
    Stats z = compare(renderImage(*device, scene, "forward-zprepass"), f, 1e-6, 1e-6);
    EXPECT_EQ(z.fractionOver, 0.0) << "forward-zprepass max relative error " << z.maxRel;
    Stats plus = compare(renderImage(*device, scene, "forward-plus"), f, 1e-6, 1e-6);
    EXPECT_EQ(plus.fractionOver, 0.0) << "forward-plus max relative error " << plus.maxRel;
}

// Forward+ culls ranged lights per 8x8 tile and sums the tile's list in index order: a culled
// light adds exactly 0 (its window is 0 beyond its range), so the image equals forward's, bit for
// bit, with 256 ranged lights, at one sample and at four (where edge fragments outside their
// tile's culled depth bounds walk their cluster's list).
TEST_P(RenderAccuracy, ForwardPlusCullsExactly) {
    const assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 256});
    for (uint32_t msaa : {1u, 4u}) {
        if (msaa > 1 && !(device->info().limits.colorSampleCounts &
                          device->info().limits.depthSampleCounts & msaa))
            continue;
        auto render = [&](const char* t) {
            render::SceneRenderer r(*device, lights,
                                    {.technique = t, .width = 96, .height = 64, .msaa = msaa});
            if (std::string(t) == "forward-plus") {
                // Under MSAA a fragment outside its tile's depth bounds walks its cluster's list, so
                // the grid is assigned then, and only then (builtin:lights has no translucency).
                bool assigns = false;
                for (const auto& p : r.graph().passes())
                    assigns = assigns || (p.name == "light-assignment" && !p.culled);
                EXPECT_EQ(assigns, msaa > 1) << msaa << " samples";
            }
            r.renderFrame();
            return r.readOutput();
        };
        // Under MSAA, making the fallback walk no light fails this at every backend.
        Stats s = compare(render("forward-plus"), render("forward"), 1e-6, 1e-6);
        EXPECT_EQ(s.fractionOver, 0.0) << msaa << " samples: max relative error " << s.maxRel;
    }
}

// --msaa: the forward techniques render into multisampled transients resolved at the end of
// their last pass. Pixels inside surfaces are shaded once at their centre, as without MSAA, so
// they match the single-sample image; silhouette pixels blend coverage, so some differ. The
// deferred techniques refuse, saying why.
TEST_P(RenderAccuracy, MsaaSmoothsSilhouettesOnly) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    const assets::Scene scene =
        assets::makeBuiltinScene("spheres", {.sphereGrid = 2});  // large spheres: few edge pixels
    gdi::Image single = renderImage(*device, scene, "forward", 1, false, true, kSeparable);
    gdi::Image reference;
    for (const char* t : {"forward", "forward-multipass", "forward-zprepass", "forward-plus",
                          "clustered-forward"}) {
        render::RenderSettings s4{.technique = t, .width = kW, .height = kH, .msaa = 4};
        s4.shadingModel = kSeparable;  // compared with the light pre-pass below
        render::SceneRenderer r(*device, scene, s4);
        bool multisampled = false;
        for (const auto& tex : r.graph().textures())
            multisampled = multisampled || (tex.used() && tex.desc.sampleCount == 4);
        EXPECT_TRUE(multisampled) << t << ": no 4-sample target in the graph";
        r.renderFrame();
        gdi::Image img = r.readOutput();
        Stats differs = compare(img, single, 0.02, 1e-3);
        RecordProperty(std::string("changed_") + t, std::to_string(differs.fractionOver));
        std::cout << t << " at 4 samples: " << differs.fractionOver * 100
                  << "% of pixels beyond 2% of the 1-sample image\n";
        EXPECT_GT(differs.fractionOver, 0.005) << t << ": no silhouette pixel changed";
        EXPECT_LT(differs.fractionOver, 0.08) << t << ": more than silhouettes changed";
        if (reference.data.empty()) reference = img;
        Stats same = compare(img, reference, 1e-4, 1e-4);
        EXPECT_EQ(same.fractionOver, 0.0)
            << t << " differs from forward at 4 samples, max " << same.maxRel;
    }
    for (const char* t : {"light-prepass", "light-prepass-unpacked"}) {
        // Hardware MSAA is the deck's argument for the light pre-pass: the material pass is a
        // forward pass, so silhouettes are antialiased while the light pass stays per pixel.
        render::SceneRenderer r(*device, scene,
                                {.technique = t, .width = kW, .height = kH, .msaa = 4});
        uint32_t multisampled = 0;
        for (const auto& tex : r.graph().textures())
            multisampled += tex.used() && tex.desc.sampleCount == 4;
        EXPECT_EQ(multisampled, 3u) << t << ": normals, depth and L_o should be multisampled";
        r.renderFrame();
        gdi::Image img = r.readOutput();
        Stats differs = compare(img, renderImage(*device, scene, t), 0.02, 1e-3);
        Stats vsForward = compare(img, reference, 0.05, 1e-3);
        std::cout << t << " at 4 samples: " << differs.fractionOver * 100
                  << "% of pixels beyond 2% of its 1-sample image, " << vsForward.fractionOver * 100
                  << "% beyond 5% of forward at 4 samples\n";
        EXPECT_GT(differs.fractionOver, 0.005) << t << ": no silhouette pixel changed";
        EXPECT_LT(differs.fractionOver, 0.08) << t << ": more than silhouettes changed";
        EXPECT_LT(vsForward.fractionOver, 0.15)
            << t << " at 4 samples is far from forward at 4 samples";
    }
    const std::string e = fe::testing::errorOf(
        [&] { render::SceneRenderer r(*device, scene, {.technique = "redeferred", .msaa = 4}); });
    EXPECT_NE(e.find("technique redeferred does not take --msaa"), std::string::npos) << e;
    EXPECT_NE(fe::testing::errorOf([&] {
                  render::SceneRenderer r(*device, scene, {.msaa = 3});
              }).find("--msaa must be 1, 2, 4 or 8"),
              std::string::npos);
}

// --msaa for the deferred techniques and the visibility buffer: a multisampled G-buffer (or
// visibility buffer) whose edge pixels are shaded per sample and the rest once (fe_gbuffer.glsl).
// Against forward-zprepass at the same sample count, within the G-buffer techniques' 2 % on all
// but 2 % of pixels (the bound); silhouettes change against the technique's own 1-sample
// image. Shading every pixel once (no edge test) fails the first on every backend.
TEST_P(RenderAccuracy, DeferredTechniquesTakeMsaa) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    auto render = [&](const char* t, uint32_t msaa, uint32_t* multisampled = nullptr) {
        render::SceneRenderer r(*device, scene,
                                {.technique = t, .width = kW, .height = kH, .msaa = msaa});
        if (multisampled)
            for (const auto& tex : r.graph().textures())
                *multisampled += tex.used() && tex.desc.sampleCount == msaa;
        r.renderFrame();
        return r.readOutput();
    };
    const gdi::Image forward = render("forward-zprepass", 4);
    for (const char* t :
         {"deferred", "deferred-tiled", "clustered-deferred", "visibility-buffer"}) {
        uint32_t multisampled = 0;
        const gdi::Image img = render(t, 4, &multisampled);
        // base colour, normal, emissive and depth; or the ids and depth
        EXPECT_GE(multisampled, std::string(t) == "visibility-buffer" ? 2u : 4u) << t;
        const Stats vsForward = compare(img, forward, 0.02, 0.01);
        const Stats vsSingle = compare(img, render(t, 1), 0.02, 1e-3);
        std::cout << t << " at 4 samples: " << vsForward.fractionOver * 100
                  << "% of pixels beyond 2% of forward-zprepass at 4 samples, "
                  << vsSingle.fractionOver * 100 << "% changed from 1 sample\n";
        RecordProperty(std::string("beyond_forward_") + t, std::to_string(vsForward.fractionOver));
        EXPECT_LE(vsForward.fractionOver, 0.02) << t << " max relative error " << vsForward.maxRel;
        EXPECT_GT(vsSingle.fractionOver, 0.005) << t << ": no silhouette pixel changed";
        EXPECT_LT(vsSingle.fractionOver, 0.08) << t << ": more than silhouettes changed";
    }
}

// With shadows under MSAA the visibility buffer's shadowed lights render into a multisampled
// target of their own against the multisampled depth, resolved once and added into L_o: against
// forward-zprepass at 4 samples with the same shadows, within the bound above. Dropping the
// final add (no shadowed light at all) fails it.
TEST_P(RenderAccuracy, VisibilityBufferTakesMsaaWithShadows) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    const assets::Scene scene = assets::makeBuiltinScene("shadows");
    auto render = [&](const char* t) {
        render::RenderSettings s{.technique = t, .width = kW, .height = kH, .msaa = 4};
        s.shadows = {.enabled = true, .mapSize = 512};
        render::SceneRenderer r(*device, scene, s);
        r.renderFrame();
        return r.readOutput();
    };
    const Stats s = compare(render("visibility-buffer"), render("forward-zprepass"), 0.02, 0.01);
    std::cout << "visibility-buffer with shadows at 4 samples: " << s.fractionOver * 100
              << "% of pixels beyond 2% of forward-zprepass\n";
    EXPECT_LE(s.fractionOver, 0.02) << "max relative error " << s.maxRel;
}

// Under MSAA the light lists hold for every sample: the tiles are bounded by every sample's
// depth and the clusters' lists are whole, so with 128 ranged lights deferred-tiled and
// clustered-deferred equal the light volumes (each light's fragment shading the same samples)
// up to float ordering; and the visibility buffer, which shades each triangle of a pixel at its
// centre weighted by its samples as a multisampled forward pass does, equals clustered-forward.
// Culling for sample 0's depth alone (the one-sample bounds) fails the first.
TEST_P(RenderAccuracy, MultisampledListsDropNoLight) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    const assets::Scene lights = assets::makeBuiltinScene("lights", {.lights = 128});
    auto render = [&](const char* t) {
        render::SceneRenderer r(*device, lights,
                                {.technique = t, .width = 96, .height = 64, .msaa = 4});
        r.renderFrame();
        return r.readOutput();
    };
    const gdi::Image volumes = render("deferred");
    for (const char* t : {"deferred-tiled", "clustered-deferred"}) {
        const Stats s = compare(render(t), volumes, 1e-4, 1e-3);
        EXPECT_EQ(s.fractionOver, 0.0) << t << " at 4 samples, max relative error " << s.maxRel;
    }
    const Stats v = compare(render("visibility-buffer"), render("clustered-forward"), 0.02, 0.01);
    EXPECT_EQ(v.fractionOver, 0.0)
        << "visibility-buffer at 4 samples, max relative error " << v.maxRel;
}

// Cameras no view can be made from, and a non-finite exposure, are Errors (they rendered a
// silent black or NaN frame); a refused setCamera keeps the previous camera.
TEST_P(RenderAccuracy, BadCamerasAndExposureAreErrors) {
    using fe::testing::errorOf;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(errorOf([&] {
                  render::SceneRenderer r(*device, scene,
                                          {.width = kW, .height = kH, .exposure = nan});
              }),
              "exposure nan is not a positive number");
    render::SceneRenderer r(*device, scene, {.width = kW, .height = kH});
    r.renderFrame();
    const gdi::Image before = r.readOutput();
    const assets::Camera good = *scene.camera;
    const std::vector<std::pair<std::function<void(assets::Camera&)>, std::string>> bad = {
        {[&](assets::Camera& c) { c.worldFromView[3][0] = nan; }, "not finite (NaN or infinity)"},
        {[](assets::Camera& c) { c.worldFromView = glm::mat4(0.0f); },
         "its transform is singular (no view can be made from it)"},
        {[](assets::Camera& c) { c.yfov = 0; }, "yfov 0.000000 is not in (0, pi) radians"},
        {[](assets::Camera& c) { c.znear = -1; }, "znear -1.000000 is not positive"},
        {[](assets::Camera& c) { c.znear = 10, c.zfar = 1; }, "zfar 1.000000 is not beyond znear"},
        {[](assets::Camera& c) { c.aspectRatio = 0.0f; },
         "aspectRatio 0.000000 is not a positive number"},
    };
    for (const auto& [spoil, why] : bad) {
        assets::Camera c = good;
        spoil(c);
        EXPECT_EQ(errorOf([&] { r.setCamera(c); }),
                  "setCamera: camera '" + good.name + "': " + why);
        assets::Scene withCamera = scene;
        withCamera.camera = c;
        EXPECT_EQ(errorOf([&] {
                      render::SceneRenderer s(*device, withCamera, {.width = kW, .height = kH});
                  }),
                  "scene refused: camera '" + good.name + "': " + why);
    }
    r.renderFrame();
    EXPECT_EQ(compare(r.readOutput(), before, 0.0, 1e-6).fractionOver, 0.0)
        << "the refused cameras changed the view";
}

TEST_P(RenderAccuracy, RedeferredFullRateMatchesForward) {
    gdi::Image f = renderImage(*device, scene, "forward", 1, false, true, kSeparable);
    for (const char* t : {"redeferred", "redeferred-tiled"}) {
        gdi::Image r = renderImage(*device, scene, t, 1);
        Stats s = compare(r, f, 0.02, 0.01);  // same G-buffer rounding as deferred
        EXPECT_LE(s.fractionOver, 0.01) << t << " max relative error " << s.maxRel;
    }
}

// A scene with lights but nothing to light (no mesh instances): every technique renders black,
// with nothing unbound (the visibility buffer's resolve still binds a texture set).
TEST_P(RenderAccuracy, EveryTechniqueRendersASceneWithNothingInIt) {
    assets::Scene empty = assets::makeBuiltinScene("lights", {.lights = 4});
    empty.instances.clear();
    // The contract the visibility buffer's resolve relies on (its dispatches are per set, and
    // its output is written by them): a set even without draws.
    EXPECT_EQ(render::GpuScene(*device, empty).textureSets().size(), 1u);
    for (const render::TechniqueInfo& t : render::techniques()) {
        render::SceneRenderer r(*device, empty, {.technique = t.name, .width = 32, .height = 24});
        r.renderFrame();
        const gdi::Image out = r.readOutput();
        float brightest = 0.0f;
        for (uint32_t y = 0; y < out.height; ++y)
            for (uint32_t x = 0; x < out.width; ++x)
                for (int c = 0; c < 3; ++c) brightest = std::max(brightest, out.texel(x, y)[c]);
        EXPECT_EQ(brightest, 0.0f) << t.name;
    }
}

// The frame runs through the render graph: only the passes the technique needs, the display
// pass culled unless its image is asked for, transient memory aliased, and the GPU display
// image equal to clamp(exposure x L_o) encoded to sRGB.
TEST_P(RenderAccuracy, FrameGraphHasOnlyNeededPassesAndAliasesMemory) {
    const std::map<std::string, std::vector<std::string>> expected = {
        {"forward", {"forward", "display"}},
        {"forward-multipass", {"forward-multipass", "display"}},
        {"forward-zprepass", {"zprepass", "forward-shading", "display"}},
        {"forward-plus", {"zprepass", "light-culling", "forward-plus-shading", "display"}},
        {"clustered-forward",
         {"zprepass", "cluster-bounds", "light-assignment", "clustered-shading", "display"}},
        {"clustered-deferred",
         {"gbuffer", "cluster-bounds", "light-assignment", "clustered-lighting", "display"}},
        {"visibility-buffer",
         {"visibility", "cluster-bounds", "light-assignment", "visibility-resolve", "display"}},
        {"deferred-tiled", {"gbuffer", "light-culling", "tiled-lighting", "display"}},
        {"light-prepass", {"lpp-normals", "lpp-lights", "lpp-material", "display"}},
        {"redeferred-tiled",
         {"gbuffer", "light-culling", "tiled-illumination", "material", "display"}},
        {"deferred", {"gbuffer", "lighting", "emissive", "display"}},
        {"redeferred", {"gbuffer", "illumination", "material", "display"}}};
    for (const auto& [technique, passes] : expected) {
        for (bool display : {false, true}) {
            render::SceneRenderer r(*device, scene,
                                    {.technique = technique,
                                     .width = kW,
                                     .height = kH,
                                     .exposure = 2.0f,
                                     .displayImage = display});
            std::vector<std::string> names;
            for (const auto& p : r.graph().passes()) {
                names.push_back(p.name);
                EXPECT_EQ(p.culled, p.name == "display" && !display) << p.name;
            }
            // forward-plus writes the display image in its shading pass (displayInShading).
            const bool inShading = display && technique == "forward-plus";
            EXPECT_EQ(r.displayInShading(), inShading) << technique;
            std::vector<std::string> want = passes;
            if (inShading) want.pop_back();
            EXPECT_EQ(names, want);  // no transparent pass: the spheres have no BLEND material
            const graph::MemoryReport m = r.graph().memory();
            if (display && technique.find("deferred") != std::string::npos) {
                EXPECT_LT(m.withAliasing, m.withoutAliasing)
                    << r.graph().toDot();  // the display image reuses G-buffer memory
            }
            if (!display) continue;
            r.renderFrame();
            gdi::Image out = r.readOutput(), shown = r.readDisplay();
            ASSERT_EQ(shown.format, gdi::Format::RGBA8_SRGB);
            int wrong = 0;
            for (uint32_t y = 0; y < kH; ++y)
                for (uint32_t x = 0; x < kW; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const float l = std::clamp(2.0f * out.texel(x, y)[c], 0.0f, 1.0f);
                        const float srgb =
                            l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1 / 2.4f) - 0.055f;
                        wrong += std::abs(shown.texel(x, y)[c] - srgb) > 1.5f / 255.0f;
                    }
            EXPECT_EQ(wrong, 0) << technique;
        }
    }
}

// The light pre-pass approximates: the specular colour comes from a monochrome sum and the
// diffuse light's chromaticity, Fresnel is taken at n.v, and (packed) the normal is 8-bit.
// Its error against forward is measured and bounded, not hidden (docs/BENCHMARKS.md).
TEST_P(RenderAccuracy, LightPrepassErrorIsMeasured) {
    gdi::Image f = renderImage(*device, scene, "forward", 1, false, true, kSeparable);
    for (const char* t : {"light-prepass", "light-prepass-unpacked"}) {
        Stats s = compare(renderImage(*device, scene, t), f, 0.05, 0.01);
        std::cout << t << ": " << s.fractionOver * 100.0
                  << "% of pixels beyond 5% relative error (max " << s.maxRel << ")\n";
        RecordProperty(std::string("fraction_over_") + t, std::to_string(s.fractionOver));
        EXPECT_LT(s.fractionOver, 0.15) << t;
        EXPECT_TRUE(std::isfinite(s.maxRel)) << t;
    }
}

// Where the approximate techniques err (docs/BENCHMARKS.md "where it concentrates"): pixels
// beyond 5 % relative error against forward, split by what the CPU reference knows of each pixel:
// silhouettes (a neighbour sees another surface), then interior pixels by the sphere's roughness
// column and metallic row (builtin:spheres 5x5: roughness 0..1 left to right, metallic 0..1 top
// to bottom). The claims the docs make are asserted.
TEST_P(RenderAccuracy, ErrorConcentration) {
    constexpr uint32_t W = 192, H = 144;
    const render::ReferenceImage ref = render::renderReference(scene, *scene.camera, W, H);
    auto image = [&](const char* t, uint32_t scale, bool split) {
        render::RenderSettings s{
            .technique = t, .width = W, .height = H, .illumScale = scale, .illumSplit = split};
        s.shadingModel = kSeparable;
        render::SceneRenderer r(*device, scene, s);
        r.renderFrame();
        return r.readOutput();
    };
    const gdi::Image f = image("forward", 1, false);
    struct Rate {
        uint32_t bad = 0, n = 0;
        double percent() const { return n ? 100.0 * bad / n : 0.0; }
    };
    struct Case {
        const char* technique;
        uint32_t scale;
        bool split;
    };
    for (const Case c : {Case{"light-prepass", 1, false}, Case{"light-prepass-unpacked", 1, false},
                         Case{"redeferred-tiled", 2, false}, Case{"redeferred-tiled", 2, true},
                         Case{"redeferred-tiled", 4, false}}) {
        const gdi::Image img = image(c.technique, c.scale, c.split);
        Rate edge, interior, roughness[5], metal[5];
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x) {
                const int32_t surface = ref.surface[size_t(y) * W + x];
                if (surface < 0) continue;
                bool bad = false;
                const auto a = img.texel(x, y), b = f.texel(x, y);
                for (int k = 0; k < 3; ++k)
                    bad = bad || std::abs(a[k] - b[k]) >
                                     0.05 * std::max({std::abs(a[k]), std::abs(b[k]), 0.01f});
                Rate& r = ref.nearEdge(x, y) ? edge : interior;
                ++r.n, r.bad += bad;
                if (ref.nearEdge(x, y)) continue;
                ++roughness[surface % 5].n, roughness[surface % 5].bad += bad;
                ++metal[surface / 5].n, metal[surface / 5].bad += bad;
            }
        std::ostringstream line;
        line << std::fixed << std::setprecision(1) << c.technique << (c.split ? " split" : "")
             << " scale " << c.scale << ": silhouettes " << edge.percent() << " %, interior "
             << interior.percent() << " %; interior by roughness";
        for (const Rate& r : roughness) line << " " << r.percent();
        line << "; by metallic";
        for (const Rate& r : metal) line << " " << r.percent();
        std::cout << line.str() << "\n";
        RecordProperty(std::string("concentration_") + c.technique + (c.split ? "_split" : "") +
                           std::to_string(c.scale),
                       line.str());
        if (std::string(c.technique).rfind("redeferred", 0) == 0) {
            // A reduced rate errs where neighbouring pixels differ: silhouettes first. At scale 4
            // (spheres about 6 I-buffer texels wide here) it errs nearly everywhere.
            EXPECT_GT(edge.percent(), (c.scale == 2 ? 2.0 : 1.0) * interior.percent())
                << line.str();
        } else {
            // The light pre-pass's specular colour is rebuilt from a monochrome sum: metals,
            // whose specular is coloured by F0 = base colour, carry its error.
            EXPECT_GT(metal[4].percent(), metal[0].percent() + 10.0) << line.str();
        }
    }
}

// A reduced illumination rate is an approximation: its error is measured and bounded. The
// split I-buffer (specular sums at full rate, only L_dg upsampled) must err less than the joint
// one at the same scale: silhouettes and highlights are where the joint upsampling errs.
TEST_P(RenderAccuracy, RedeferredReducedRateErrorIsMeasured) {
    gdi::Image f = renderImage(*device, scene, "forward", 1, false, true, kSeparable);
    for (const char* t : {"redeferred", "redeferred-tiled"})
        for (uint32_t scale : {2u, 4u})
            for (bool split : {false, true}) {
                if (split && std::string(t) == "redeferred")
                    continue;  // refused: one size for the volume pass's targets
                gdi::Image r = renderImage(*device, scene, t, scale, split);
                Stats s = compare(r, f, 0.05, 0.01);
                const std::string name = std::string(t) + (split ? " split" : "") +
                                         " illum-scale " + std::to_string(scale);
                std::cout << name << ": " << s.fractionOver * 100.0
                          << "% of pixels beyond 5% relative error (max " << s.maxRel << ")\n";
                RecordProperty("fraction_over_" + name, std::to_string(s.fractionOver));
                EXPECT_LT(s.fractionOver, 0.5) << name;
                EXPECT_TRUE(std::isfinite(s.maxRel)) << name;
                if (split) {
                    Stats joint = compare(renderImage(*device, scene, t, scale), f, 0.05, 0.01);
                    EXPECT_LT(s.fractionOver, joint.fractionOver * 0.8)
                        << name << " is not better than the joint upsampling";
                }
            }
}

// Consideration A: the material pass at full rate reads w_o.n from the G-buffer (half float)
// instead of rebuilding it from depth and the normal. Both match forward (ExactTechniques); here
// they match each other to half-float precision of w_o.n.
TEST_P(RenderAccuracy, PrecomputedNoVMatchesRebuiltNoV) {
    for (const char* t : {"redeferred", "redeferred-tiled"}) {
        Stats s = compare(renderImage(*device, scene, t, 1, false, true),
                          renderImage(*device, scene, t, 1, false, false), 2e-3, 1e-3);
        std::cout << t << ": precomputed against rebuilt w_o.n, " << s.fractionOver * 100
                  << "% of pixels beyond 0.2% (max " << s.maxRel << ")\n";
        EXPECT_LT(s.fractionOver, 0.01) << t;
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(RenderAccuracy);

// The render director picks light-prepass's packed 8-bit normals only for scenes no smoother
// than kPackedNormalsMinRoughness: there the packed highlight must match the half-float one.
// Measured below it, to show the threshold is where the packing starts to fail.
TEST_P(RenderAccuracy, PackedNormalsHoldFromDirectorThreshold) {
    assets::Scene s = assets::makeBuiltinScene("plane");
    auto peakRatio = [&](float roughness) {
        for (auto& m : s.materials) m.roughness = roughness;
        auto peak = [&](const char* t) {
            render::SceneRenderer r(*device, s, {.technique = t, .width = 97, .height = 73});
            r.renderFrame();
            // Over the whole highlight, not one pixel: the sum of red in the 9x9 block around it.
            const gdi::Image img = r.readOutput();
            double sum = 0;
            for (uint32_t y = 32; y <= 40; ++y)
                for (uint32_t x = 44; x <= 52; ++x) sum += img.texel(x, y)[0];
            return sum;
        };
        return peak("light-prepass") / peak("light-prepass-unpacked");
    };
    for (float r : {0.05f, 0.1f, 0.15f, 0.2f, 0.3f, 0.5f})
        std::cout << "roughness " << r << ": packed / unpacked highlight " << peakRatio(r) << "\n";
    EXPECT_NEAR(peakRatio(render::kPackedNormalsMinRoughness), 1.0, 0.01);
    EXPECT_LT(peakRatio(render::kPackedNormalsMinRoughness / 2), 0.95)
        << "the threshold is not where packing fails";
}

// The roughness clamp: a mirror-smooth plane seen head-on with a point light on the view axis.
// With an odd image size the centre pixel sees n = h exactly, where the alpha^2/(4 pi)-scaled
// specular sum reaches E / (4 pi alpha^2) ~ 1.9e5 for E = 10: beyond half-float range, so an
// I-buffer in 16-bit floats would overflow there (checked: this test fails with RGBA16F sums).
TEST_P(RenderAccuracy, RoughnessClampStaysFiniteAndMatches) {
    assets::Scene s = assets::makeBuiltinScene("plane");
    for (auto& m : s.materials) m.roughness = 0.0f;  // clamped to 0.045 by every technique
    for (auto& l : s.lights) l.intensity = 10.0f;
    auto renderOdd = [&](const std::string& t,
                         render::ShadingModel model = render::ShadingModel::Auto) {
        render::RenderSettings rs{.technique = t, .width = 97, .height = 73};
        rs.shadingModel = model;
        render::SceneRenderer r(*device, s, rs);
        r.renderFrame();
        return r.readOutput();
    };
    const gdi::Image fGltf = renderOdd("forward"), fSeparable = renderOdd("forward", kSeparable);
    EXPECT_GT(fGltf.texel(48, 36)[0], 1000.0f) << "the highlight is not at the centre pixel";
    auto finite = [](const gdi::Image& img) {
        for (size_t i = 0; i < img.data.size() / 4; ++i) {
            float v;
            std::memcpy(&v, &img.data[i * 4], 4);
            if (!std::isfinite(v)) return false;
        }
        return true;
    };
    // The light pre-pass stores the normal (8-bit packed, or half floats): at alpha = 0.002 the
    // lobe is so narrow that the quantised normal moves the highlight, so its peak is measured
    // and reported, not matched; its light buffer must still not overflow.
    for (const char* t : {"light-prepass", "light-prepass-unpacked"}) {
        gdi::Image r = renderOdd(t);
        EXPECT_TRUE(finite(r)) << t << " produced a non-finite value";
        const float ratio = r.texel(48, 36)[0] / fSeparable.texel(48, 36)[0];
        std::cout << t << " at the roughness clamp: highlight peak " << ratio << " x forward's\n";
        RecordProperty(std::string("peak_ratio_") + t, std::to_string(ratio));
        EXPECT_TRUE(std::isfinite(ratio) && ratio > 0.0f) << t;
        // Half-float normals keep the peak within their rounding (lavapipe 0.99998 x, an H100
        // 0.944 x; the bound below is derived there); 8-bit ones lose it (0.014 x).
        if (std::string(t) == "light-prepass-unpacked") {
            EXPECT_NEAR(ratio, 1.0, 0.12) << t;
        }
    }
    for (const char* t : {"deferred", "deferred-tiled", "redeferred", "redeferred-tiled"}) {
        gdi::Image r = renderOdd(t);
        ASSERT_TRUE(finite(r)) << t << " produced a non-finite value";
        const gdi::Image& f = render::findTechnique(t).separableBrdf ? fSeparable : fGltf;
        Stats st = compare(r, f, 0.02, 0.01);
        EXPECT_LE(st.fractionOver, 0.01) << t << " max relative error " << st.maxRel;
        // The peak itself, which a clamping or overflowing 16-bit store would get wrong. The
        // G-buffer's half-float normal is off by up to about 2^-11 radians, and at alpha 0.002
        // that alone moves D's peak by up to (1 + (2^-11 / 0.002)^2)^-2 = 0.89 x: lavapipe lands
        // at 1.000 x, an H100 at 0.945 x (2026-11-27), so 12 % is the bound, not 2 %.
        const float ratio = r.texel(48, 36)[0] / f.texel(48, 36)[0];
        std::cout << t << " at the roughness clamp: highlight peak " << f.texel(48, 36)[0] << ", "
                  << ratio << " x forward's\n";
        EXPECT_NEAR(ratio, 1.0, 0.12) << t << " at the highlight";
    }
}

namespace {
// Every technique that shades the whole material (TechniqueInfo::fullMaterial) renders `scene`
// within 2 % of the CPU reference on 99 % of pixels off silhouettes, under its punctual lights and
// then 64 samples of its environment; `plain` (the scene without the inputs under test) must be
// far from that reference (20 % of pixels), so that dropping the inputs fails. `what` names them.
void expectFullMaterialTechniquesMatchTheReference(gdi::Device& device, const assets::Scene& scene,
                                                   const assets::Scene& plain, const char* what) {
    auto toImage = [](const render::ReferenceImage& ref) {
        std::vector<std::array<float, 4>> texels;
        for (auto& v : ref.radiance) texels.push_back({float(v.x), float(v.y), float(v.z), 1});
        return gdi::Image::fromTexels(kW, kH, gdi::Format::RGBA32F, texels);
    };
    for (uint32_t samples : {0u, 64u}) {
        const render::ReferenceImage ref =
            render::renderReference(scene, *scene.camera, kW, kH, {.iblSamples = samples});
        const gdi::Image cpu = toImage(ref);
        const auto edge = [&](uint32_t x, uint32_t y) { return ref.nearEdge(x, y); };
        const Stats without = compare(
            toImage(render::renderReference(plain, *plain.camera, kW, kH, {.iblSamples = samples})),
            cpu, 0.02, 0.01, edge);
        EXPECT_GE(without.fractionOver, 0.2) << what << " hardly change the reference";
        for (const render::TechniqueInfo& t : render::techniques()) {
            if (!t.fullMaterial(shading::Brdf::Gltf) ||
                (std::string(t.name).find("tiled") != std::string::npos &&
                 !device.info().features.computeShaders))
                continue;
            render::SceneRenderer r(
                device, scene,
                {.technique = t.name, .width = kW, .height = kH, .iblSamples = samples});
            r.renderFrame();
            const Stats st = compare(r.readOutput(), cpu, 0.02, 0.01, edge);
            std::cout << what << ", " << t.name << (samples ? " with 64 sky samples" : ", punctual")
                      << ": " << st.fractionOver * 100
                      << " % beyond 2 % of the reference (without them: "
                      << without.fractionOver * 100 << " %)\n";
            EXPECT_LE(st.fractionOver, 0.01) << what << ", " << t.name << " max " << st.maxRel;
        }
    }
    // The fast path reads them too: against the same frame without them it differs.
    render::RenderSettings fast{
        .technique = "forward", .width = kW, .height = kH, .iblPrefiltered = true};
    render::SceneRenderer with(device, scene, fast), without(device, plain, fast);
    with.renderFrame();
    without.renderFrame();
    EXPECT_GE(compare(with.readOutput(), without.readOutput(), 0.02, 0.01).fractionOver, 0.2)
        << what;
}

}  // namespace

// KHR_materials_ior and KHR_materials_specular (factors): the dielectric's Fresnel F0 =
// min(((ior - 1)/(ior + 1))^2 specularColor, 1) specular, F90 = specular, under punctual light
// and image-based light (sampled and the fast path), on every technique that shades the whole
// material (TechniqueInfo::fullMaterial), against the CPU reference; the default dielectric's
// reference is far from it (so dropping the inputs fails), and the G-buffer techniques say so.
TEST_P(RenderAccuracy, DielectricIorAndSpecularMatchTheReference) {
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(0.0);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        assets::Material& m = scene.materials[i];
        m.metallic = 0.0f;  // dielectrics: where ior and specular act
        m.ior = i % 2 ? 2.4f : 1.2f;
        m.specular = i % 3 ? 0.6f : 1.0f;
        m.specularColor = i % 4 ? glm::vec3(1.0f, 0.5f, 2.0f) : glm::vec3(1.0f);
    }
    assets::Scene plain = scene;
    for (assets::Material& m : plain.materials)
        m.ior = 1.5f, m.specular = 1.0f, m.specularColor = glm::vec3(1.0f);
    expectFullMaterialTechniquesMatchTheReference(*device, scene, plain, "ior and specular");
    // A technique that cannot shows them with the default dielectric, and says which can.
    const std::vector<std::string> w = render::materialWarnings(scene, {.technique = "deferred"});
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(
        w[0].find(
            "technique deferred shades them with F0 0.04, F90 1, no clearcoat and no sheen (its G-buffer does not hold it); "
            "forward, forward-multipass, forward-zprepass, forward-plus, clustered-forward, visibility-buffer "
            "evaluate them"),
        std::string::npos)
        << w[0];
    EXPECT_TRUE(render::materialWarnings(scene, {.technique = "forward"}).empty());
    EXPECT_EQ(render::materialWarnings(
                  scene, {.technique = "forward", .shadingModel = render::ShadingModel::Separable})
                  .size(),
              1u);
    EXPECT_TRUE(render::materialWarnings(plain, {.technique = "deferred"}).empty());
}

// KHR_materials_clearcoat (factors): a GGX layer on the vertex normal over the whole material
// (the base and its emission weighed by 1 - c Fc(n_c.v)), under punctual and image-based light
// (sampled and the fast path), on every technique that shades the whole material, against the
// CPU reference; the reference without the layer is far from it, so dropping it fails.
TEST_P(RenderAccuracy, ClearcoatMatchesTheReference) {
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(0.0);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        assets::Material& m = scene.materials[i];
        m.clearcoat = i % 2 ? 1.0f : 0.5f;
        m.clearcoatRoughness = float(i % 5) * 0.2f;
        m.emissiveFactor = glm::vec3(0.05f, 0.02f, 0.0f);
    }
    assets::Scene plain = scene;
    for (assets::Material& m : plain.materials) m.clearcoat = 0.0f;
    expectFullMaterialTechniquesMatchTheReference(*device, scene, plain, "a clearcoat");
    EXPECT_EQ(render::materialWarnings(scene, {.technique = "deferred-tiled"}).size(), 1u);
}

namespace {
// The spheres behind a pane (KHR_materials_transmission, baseColor a warm tint) over the left
// two-thirds of the view, with a point light between them that shines through the pane
// towards the eye. `pane` sets its roughness, thickness and attenuation.
assets::Scene spheresBehindAPane(const std::function<void(assets::Material&)>& pane) {
    assets::Scene s = assets::makeBuiltinScene("spheres", {.sphereGrid = 5});
    assets::Material glass;
    glass.name = "pane";
    glass.baseColorFactor = glm::vec4(0.9f, 0.7f, 0.5f, 1.0f);
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.transmission = 1.0f;
    glass.doubleSided = true;
    pane(glass);
    s.materials.push_back(glass);
    assets::Mesh mesh;
    mesh.name = "pane";
    mesh.primitives.push_back(assets::makeQuad(1.6f, 3.0f, uint32_t(s.materials.size() - 1)));
    assets::computeBounds(mesh);
    s.meshes.push_back(mesh);
    s.instances.push_back({.meshIndex = uint32_t(s.meshes.size() - 1),
                           .world = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 1.0f)),
                           .name = "pane"});
    s.lights.push_back({.name = "behind the pane",
                        .type = assets::LightType::Point,
                        .color = glm::vec3(1.0f, 0.9f, 0.8f),
                        .intensity = 2.0f,
                        .position = glm::vec3(-1.2f, 0.5f, 0.7f)});
    return s;
}

std::vector<std::array<float, 4>> referenceTexels(const render::ReferenceImage& ref) {
    std::vector<std::array<float, 4>> texels;
    for (auto& v : ref.radiance) texels.push_back({float(v.x), float(v.y), float(v.z), 1});
    return texels;
}
}  // namespace

// KHR_materials_transmission and volume, drawn by the transmission pass every technique shares:
// the opaque scene seen through a pane (thin, rough: a coarser mip of the scene's copy, and a
// tinted volume that shifts it by refraction), a point light shining through it (the punctual
// BTDF), and image-based light, against the CPU reference within 2 % on 99 % of pixels off
// silhouettes. The same pane opaque is far from each reference, so dropping the lobe fails.
TEST_P(RenderAccuracy, TransmissionMatchesTheReference) {
    struct Case {
        const char* what;
        std::function<void(assets::Material&)> pane;
        bool everyTechnique = false;
        uint32_t iblSamples = 0;
    };
    const Case cases[] = {
        {"a thin pane", [](assets::Material&) {}, true},
        // log2(96) x 0.4 = 2.6: levels 2 and 3 of the copy, whose sizes halve evenly (96x72 .. 12x9).
        {"a rough thin pane", [](assets::Material& m) { m.roughness = 0.4f; }},
        {"a tinted volume",
         [](assets::Material& m) {
             m.thickness = 0.6f;
             m.attenuationColor = glm::vec3(0.4f, 0.8f, 1.0f);
             m.attenuationDistance = 0.5f;
         }},
        {"a thin pane under the sky", [](assets::Material& m) { m.roughness = 0.2f; }, false, 64},
    };
    for (const Case& c : cases) {
        assets::Scene withPane = spheresBehindAPane(c.pane);
        assets::Scene opaquePane = spheresBehindAPane([&](assets::Material& m) {
            c.pane(m);
            m.transmission = 0.0f;
        });
        if (c.iblSamples) {
            for (assets::Scene* s : {&withPane, &opaquePane}) {
                s->environment = assets::loadEnvironment("builtin:sky");
                s->environment->sky.sunRadiance = glm::dvec3(0.0);
            }
        }
        // A reference depends on the scene and the BRDF, not the technique: each is traced once.
        std::map<shading::Brdf, render::ReferenceImage> withPaneRefs, opaquePaneRefs;
        auto traced = [&](auto& refs, const assets::Scene& s,
                          const render::ReferenceOptions& o) -> const render::ReferenceImage& {
            auto it = refs.find(o.brdf);
            if (it == refs.end())
                it = refs.emplace(o.brdf, render::renderReference(s, *s.camera, kW, kH, o)).first;
            return it->second;
        };
        for (const render::TechniqueInfo& t : render::techniques()) {
            if (!c.everyTechnique && std::string(t.name) != "forward") continue;
            if (std::string(t.name).find("tiled") != std::string::npos &&
                !device->info().features.computeShaders)
                continue;
            const render::RenderSettings settings{
                .technique = t.name, .width = kW, .height = kH, .iblSamples = c.iblSamples};
            const render::ReferenceOptions options{.iblSamples = c.iblSamples,
                                                   .brdf = render::resolveBrdf(settings)};
            const render::ReferenceImage& ref = traced(withPaneRefs, withPane, options);
            const gdi::Image cpu =
                gdi::Image::fromTexels(kW, kH, gdi::Format::RGBA32F, referenceTexels(ref));
            const auto edge = [&](uint32_t x, uint32_t y) { return ref.nearEdge(x, y); };
            render::SceneRenderer r(*device, withPane, settings);
            r.renderFrame();
            if (std::string(t.name).find("light-prepass") == 0) {
                // Its light buffer approximates the specular (LightPrepassErrorIsMeasured), so its
                // opaque image, seen through the pane, is not the reference's: the pane (the shared
                // pass) must still show through, against the same technique with the pane opaque.
                render::SceneRenderer o(*device, opaquePane, settings);
                o.renderFrame();
                EXPECT_GE(compare(r.readOutput(), o.readOutput(), 0.02, 0.01, edge).fractionOver,
                          0.3)
                    << t.name;
                continue;
            }
            const Stats st = compare(r.readOutput(), cpu, 0.02, 0.01, edge);
            const render::ReferenceImage& opaque = traced(opaquePaneRefs, opaquePane, options);
            const Stats without = compare(
                gdi::Image::fromTexels(kW, kH, gdi::Format::RGBA32F, referenceTexels(opaque)), cpu,
                0.02, 0.01, edge);
            std::cout << c.what << ", " << t.name << ": " << st.fractionOver * 100
                      << " % beyond 2 % of the reference (max " << st.maxRel
                      << "; the pane opaque: " << without.fractionOver * 100 << " %)\n";
            EXPECT_LE(st.fractionOver, 0.01) << c.what << ", " << t.name << " max " << st.maxRel;
            EXPECT_GE(without.fractionOver, 0.3)
                << c.what << ": transmission hardly changes the reference";
        }
    }
}

// KHR_materials_sheen: the Charlie sheen over the base (punctual: sheenColor D V n.l E, the base
// weighed by its albedo table; image-based: the same lobe by the cosine samples, the fast path by
// the irradiance), on every technique that shades the whole material, against the CPU reference;
// without the sheen the reference is far from it, so dropping the lobe fails.
TEST_P(RenderAccuracy, SheenMatchesTheReference) {
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(0.0);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        assets::Material& m = scene.materials[i];
        m.sheenColor = i % 2 ? glm::vec3(1.0f, 0.8f, 0.6f) : glm::vec3(0.3f, 0.6f, 1.0f);
        m.sheenRoughness = 0.25f + float(i % 4) * 0.25f;
    }
    assets::Scene plain = scene;
    for (assets::Material& m : plain.materials) m.sheenColor = glm::vec3(0.0f);
    expectFullMaterialTechniquesMatchTheReference(*device, scene, plain, "a sheen");
    EXPECT_EQ(render::materialWarnings(scene, {.technique = "redeferred"}).size(), 1u);
}

namespace {
// A smooth 4x4 texture (each channel a gradient across it, linear filtering, no mips): magnified
// on the spheres, so the GPU's filtering and the reference's bilinear level 0 agree.
uint32_t addGradientTexture(assets::Scene& s, bool srgb, glm::vec4 from, glm::vec4 to) {
    assets::TextureImage t;
    t.name = "gradient";
    t.width = t.height = 4;
    t.srgb = srgb;
    t.sampler.mipFilter = assets::MipFilter::None;
    t.sampler.mipmaps = false;
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) {
            const glm::vec4 v = glm::mix(
                from, to, glm::vec4(x / 3.0f, y / 3.0f, (x + y) / 6.0f, (3 - x + y) / 6.0f));
            for (int c = 0; c < 4; ++c)
                t.pixels.push_back(uint8_t(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f)));
        }
    s.textures.push_back(t);
    return uint32_t(s.textures.size() - 1);
}
}  // namespace

// The textures of KHR_materials_specular (specular A, specular colour RGB in sRGB) and of
// KHR_materials_clearcoat (factor R, roughness G, the layer's normal map with its scale), on every
// technique that shades the whole material, against the CPU reference reading the same texels;
// without the textures the reference is far from it, so dropping them fails.
TEST_P(RenderAccuracy, SpecularAndClearcoatTexturesMatchTheReference) {
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(0.0);
    const uint32_t colour = addGradientTexture(scene, true, glm::vec4(0.2f, 1.0f, 0.5f, 0.1f),
                                               glm::vec4(1.0f, 0.3f, 1.0f, 1.0f));
    const uint32_t data = addGradientTexture(scene, false, glm::vec4(0.1f, 0.05f, 0.2f, 0.2f),
                                             glm::vec4(1.0f, 0.9f, 0.9f, 1.0f));
    const uint32_t normals = addGradientTexture(scene, false, glm::vec4(0.2f, 0.3f, 0.8f, 1.0f),
                                                glm::vec4(0.8f, 0.7f, 1.0f, 1.0f));
    assets::Scene plain = scene;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        assets::Material& m = scene.materials[i];
        m.metallic = 0.0f;
        m.ior = 2.0f;
        m.clearcoat = 1.0f;
        m.clearcoatRoughness = 0.6f;
        if (i % 2) {
            m.specularTexture = {.index = int32_t(data)};
            m.specularColorTexture = {.index = int32_t(colour)};
        }
        if (i % 3 != 1) {
            m.clearcoatTexture = {.index = int32_t(data)};
            m.clearcoatRoughnessTexture = {.index = int32_t(data)};
        }
        if (i % 3 != 2) {
            m.clearcoatNormalTexture = {.index = int32_t(normals)};
            m.clearcoatNormalScale = 0.8f;
        }
        assets::Material& p = plain.materials[i];
        p.metallic = 0.0f;
        p.ior = 2.0f;
        p.clearcoat = 1.0f;
        p.clearcoatRoughness = 0.6f;
    }
    expectFullMaterialTechniquesMatchTheReference(*device, scene, plain,
                                                  "specular and clearcoat textures");
}
