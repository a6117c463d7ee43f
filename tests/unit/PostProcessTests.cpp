// Post-processing (render/PostProcess.h) on every backend: the GPU's tone mappers match their
// CPU twins (shading/Tonemap.h), FXAA brings silhouettes toward a multisampled image while
// leaving flat regions alone, and the chain's intermediate shares transient memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "integration/SceneRenderer.h"
#include "reference/ImageMetrics.h"
#include "shading/Tonemap.h"

using namespace fe;
using shading::Tonemap;

namespace {

struct Rendered {
    gdi::Image linear, display;
    graph::MemoryReport memory;
    graph::AliasingMode aliasing;
    bool displayInShading = false;
    std::set<std::string> passes;  // those the graph ran (not culled)
};

Rendered renderWith(gdi::Device& d, const assets::Scene& scene, render::RenderSettings s) {
    s.displayImage = true;
    render::SceneRenderer r(d, scene, s);
    r.renderFrame();
    std::set<std::string> passes;
    for (const graph::PassInfo& p : r.graph().passes())
        if (!p.culled) passes.insert(p.name);
    return {r.readOutput(),       r.readDisplay(),      r.graph().memory(),
            r.graph().aliasing(), r.displayInShading(), std::move(passes)};
}

// The largest channel difference of pixel (x, y) between two RGBA8 images, in 1/255 steps.
double maxChannelDiff(const gdi::Image& a, const gdi::Image& b, uint32_t x, uint32_t y) {
    double m = 0;
    for (int c = 0; c < 3; ++c)
        m = std::max(m, std::abs(double(a.texel(x, y)[c]) - b.texel(x, y)[c]) * 255.0);
    return m;
}

// maxChannelDiff over the pixels where `only` says so.
template <class Pred>
std::vector<double> channelDiffs(const gdi::Image& a, const gdi::Image& b, Pred only) {
    std::vector<double> diffs;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            if (only(x, y)) diffs.push_back(maxChannelDiff(a, b, x, y));
    return diffs;
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

// A heat-map debug view's pixels: black (no surface), of the colour (0, green, 1) (sRGB-encoded),
// or anything else.
struct HeatPixels {
    size_t black = 0, matching = 0, other = 0;
};
HeatPixels heatPixels(const gdi::Image& display, float green) {
    HeatPixels h;
    for (uint32_t y = 0; y < display.height; ++y)
        for (uint32_t x = 0; x < display.width; ++x) {
            const auto c = display.texel(x, y);
            if (c[0] + c[1] + c[2] == 0.0f)
                ++h.black;
            else if (c[0] == 0.0f && c[2] == 1.0f && std::abs(c[1] - green) < 0.01f)
                ++h.matching;
            else
                ++h.other;
        }
    return h;
}

size_t distinctColours(const gdi::Image& display) {
    std::set<std::array<float, 3>> colours;
    for (uint32_t y = 0; y < display.height; ++y)
        for (uint32_t x = 0; x < display.width; ++x) {
            const auto c = display.texel(x, y);
            colours.insert({c[0], c[1], c[2]});
        }
    return colours.size();
}

}  // namespace

TEST(Tonemap, OperatorsKeepTheirPromises) {
    using shading::tonemap;
    const glm::dvec3 dim(0.5, 0.3, 0.2);
    EXPECT_EQ(tonemap(Tonemap::Clamp, dim), dim);
    EXPECT_EQ(tonemap(Tonemap::Clamp, glm::dvec3(3.0)), glm::dvec3(1.0));
    // PBR Neutral: a base colour below the compression start comes out exactly, less the 0.04 offset.
    const glm::dvec3 n = tonemap(Tonemap::PbrNeutral, dim);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(n[c], dim[c] - 0.04, 1e-12);
    // Both curves rise monotonically and never reach past 1, however bright.
    double prevA = -1, prevN = -1;
    for (double x = 0.0; x < 1e4; x = x * 1.5 + 0.01) {
        const double a = tonemap(Tonemap::Aces, glm::dvec3(x)).r,
                     p = tonemap(Tonemap::PbrNeutral, glm::dvec3(x)).r;
        EXPECT_GE(a, prevA) << x;
        EXPECT_GE(p, prevN) << x;
        EXPECT_LE(a, 1.0);
        EXPECT_LE(p, 1.0);
        prevA = a, prevN = p;
    }
    EXPECT_GT(tonemap(Tonemap::Aces, glm::dvec3(1e4)).r, 0.99);
    EXPECT_GT(tonemap(Tonemap::PbrNeutral, glm::dvec3(1e4)).r, 0.99);
    EXPECT_NEAR(tonemap(Tonemap::Aces, glm::dvec3(0.0)).r, 0.0, 1e-12);
    // Neutral keeps a saturated bright colour's hue order and desaturates it toward white.
    const glm::dvec3 hot = tonemap(Tonemap::PbrNeutral, glm::dvec3(8.0, 2.0, 0.5));
    EXPECT_GT(hot.r, hot.g);
    EXPECT_GT(hot.g, hot.b);
    EXPECT_GT(hot.b / hot.r, 0.5 / 8.0);
    for (const char* name : {"clamp", "aces", "pbr-neutral"})
        EXPECT_EQ(shading::tonemapName(*shading::parseTonemap(name)), std::string(name));
    EXPECT_FALSE(shading::parseTonemap("reinhard"));
}

class PostProcess : public fe::testing::BackendTest {
protected:
    PostProcess() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

// The display image of each tone mapper is the CPU operator applied to the frame's own L_o
// (over-exposed 4x so the curves' upper parts are exercised): within 1/255 plus rounding.
TEST_P(PostProcess, GpuTonemappersMatchTheCpuOperators) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 3});
    for (Tonemap t : {Tonemap::Clamp, Tonemap::Aces, Tonemap::PbrNeutral}) {
        render::RenderSettings s{.technique = "forward", .width = 64, .height = 48};
        s.exposure = 4.0f;
        s.tonemap = t;
        const Rendered r = renderWith(*device, scene, s);
        std::vector<glm::dvec3> linear;
        for (uint32_t y = 0; y < r.linear.height; ++y)
            for (uint32_t x = 0; x < r.linear.width; ++x) {
                const auto l = r.linear.texel(x, y);
                linear.emplace_back(l[0], l[1], l[2]);
            }
        const render::DisplayImage cpu =
            render::toDisplay(r.linear.width, r.linear.height, linear, s.exposure, t);
        double worst = 0;
        size_t bright = 0;
        for (uint32_t y = 0; y < r.display.height; ++y)
            for (uint32_t x = 0; x < r.display.width; ++x) {
                const size_t i = size_t(y) * r.display.width + x;
                for (int c = 0; c < 3; ++c) {
                    worst = std::max(
                        worst, std::abs(double(r.display.texel(x, y)[c]) - cpu.rgb[i][c]) * 255.0);
                    bright += linear[i][c] * s.exposure > 1.0;
                }
            }
        EXPECT_LE(worst, 1.5) << shading::tonemapName(t);
        EXPECT_GT(bright, 100u) << "the scene must reach past 1 for the test to mean anything";
    }
}

// forward-plus writes the display image in its shading pass where nothing after it changes L_o
// (SceneRenderer::displayInShading): the display pass's image, pixel for pixel, under each tone
// mapper (over-exposed so the curves' upper parts count), with no display pass in the frame; and
// the display pass again wherever something after the shading reads or changes L_o.
TEST_P(PostProcess, ForwardPlusWritesTheDisplayPassImageItself) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 3});
    for (Tonemap t : {Tonemap::Clamp, Tonemap::Aces, Tonemap::PbrNeutral}) {
        render::RenderSettings s{.technique = "forward-plus", .width = 64, .height = 48};
        s.exposure = 3.0f;
        s.tonemap = t;
        const Rendered fused = renderWith(*device, scene, s);
        s.displayInShading = false;
        const Rendered separate = renderWith(*device, scene, s);
        const char* name = shading::tonemapName(t);
        EXPECT_TRUE(fused.displayInShading) << name;
        EXPECT_FALSE(fused.passes.count("display")) << name;
        EXPECT_FALSE(separate.displayInShading) << name;
        EXPECT_TRUE(separate.passes.count("display")) << name;
        const std::vector<double> diffs =
            channelDiffs(fused.display, separate.display, [](uint32_t, uint32_t) { return true; });
        EXPECT_EQ(*std::max_element(diffs.begin(), diffs.end()), 0.0) << name;
        EXPECT_GT(distinctColours(fused.display), 20u)
            << name << ": a lit scene, not a cleared image";
    }
    // What comes after the shading keeps the display pass: antialiasing, a debug view, MSAA.
    render::RenderSettings fxaa{.technique = "forward-plus", .width = 64, .height = 48};
    fxaa.antiAliasing = render::AntiAliasing::Fxaa;
    render::RenderSettings debug{.technique = "forward-plus", .width = 64, .height = 48};
    debug.debugView = "depth";
    render::RenderSettings msaa{.technique = "forward-plus", .width = 64, .height = 48, .msaa = 4};
    for (const render::RenderSettings& s : {fxaa, debug, msaa}) {
        const Rendered r = renderWith(*device, scene, s);
        EXPECT_FALSE(r.displayInShading);
        EXPECT_TRUE(
            r.passes.count(s.antiAliasing == render::AntiAliasing::Fxaa ? "tonemap" : "display"));
    }
}

// FXAA against no antialiasing, both measured against 4x MSAA: on the silhouettes (where the
// single-sample image differs from the multisampled one) it must come closer, and in flat regions
// (every pixel of a 3x3 block within 1/255 of MSAA's) it must leave almost every pixel alone.
// Measured on every backend: silhouette error 47.2 -> 16.3 (1/255 steps, largest channel).
TEST_P(PostProcess, FxaaSmoothsSilhouettesAndLeavesFlatRegions) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    render::RenderSettings s{.technique = "forward", .width = 96, .height = 72};
    const Rendered none = renderWith(*device, scene, s);
    s.antiAliasing = render::AntiAliasing::Fxaa;
    const Rendered fxaa = renderWith(*device, scene, s);
    s.antiAliasing = render::AntiAliasing::None;
    s.msaa = 4;
    const Rendered msaa = renderWith(*device, scene, s);
    const uint32_t w = none.display.width, h = none.display.height;
    std::vector<double> d(size_t(w) * h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            d[size_t(y) * w + x] = maxChannelDiff(none.display, msaa.display, x, y);
    auto edge = [&](uint32_t x, uint32_t y) { return d[size_t(y) * w + x] > 8.0; };
    auto flat = [&](uint32_t x, uint32_t y) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int xx = std::clamp(int(x) + dx, 0, int(w) - 1),
                          yy = std::clamp(int(y) + dy, 0, int(h) - 1);
                if (d[size_t(yy) * w + xx] > 1.0) return false;
            }
        return true;
    };
    const std::vector<double> edgeNone = channelDiffs(none.display, msaa.display, edge);
    const std::vector<double> edgeFxaa = channelDiffs(fxaa.display, msaa.display, edge);
    ASSERT_GT(edgeNone.size(), 50u);
    EXPECT_LT(mean(edgeFxaa), 0.8 * mean(edgeNone))
        << "silhouette error: fxaa " << mean(edgeFxaa) << ", none " << mean(edgeNone);
    const std::vector<double> flatChange = channelDiffs(fxaa.display, none.display, flat);
    const size_t changed =
        std::count_if(flatChange.begin(), flatChange.end(), [](double v) { return v > 2.0; });
    ASSERT_GT(flatChange.size(), 1000u);
    // Measured 1.0 % on every backend: specular highlights are high-contrast interiors FXAA smooths.
    EXPECT_LT(double(changed), 0.02 * double(flatChange.size()))
        << changed << " of " << flatChange.size() << " flat pixels changed";
    std::cout << "[ fxaa ] " << GetParam()
              << ": silhouette error (mean of the largest channel, 1/255) none " << mean(edgeNone)
              << ", fxaa " << mean(edgeFxaa) << " over " << edgeNone.size()
              << " pixels; flat pixels changed " << changed << " of " << flatChange.size() << "\n";
}

// TAA: 16 frames of a still camera, each jittered within the pixel and blended into the
// reprojected history, bring silhouettes toward 4x MSAA like supersampling; flat regions stay.
// Under camera motion (an orbit over the frames) the clamped history does not smear: the
// result stays near the single-sample frame of the final camera.
TEST_P(PostProcess, TaaConvergesTowardMultisamplingAndDoesNotGhost) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    render::RenderSettings s{.technique = "forward", .width = 96, .height = 72};
    s.displayImage = true;
    const Rendered none = renderWith(*device, scene, s);
    auto taaFrames = [&](uint32_t frames, float orbitDegrees) {
        render::RenderSettings t = s;
        t.antiAliasing = render::AntiAliasing::Taa;
        render::SceneRenderer r(*device, scene, t);
        for (uint32_t f = 0; f < frames; ++f) {
            const float a =
                orbitDegrees * float(f) / float(std::max(1u, frames - 1)) * 0.0174532925f;
            r.setCamera(scene.camera->orbited(scene.bounds.center(), a));
            r.renderFrame();
        }
        return r.readDisplay();
    };
    const gdi::Image taa = taaFrames(16, 0.0f);
    render::RenderSettings m = s;
    m.msaa = 4;
    const Rendered msaa = renderWith(*device, scene, m);
    const uint32_t w = 96, h = 72;
    const auto diff = maxChannelDiff;
    std::vector<double> edgeNone, edgeTaa;
    size_t flat = 0, flatChanged = 0;
    for (uint32_t y = 1; y + 1 < h; ++y)
        for (uint32_t x = 1; x + 1 < w; ++x) {
            if (diff(none.display, msaa.display, x, y) > 8.0) {
                edgeNone.push_back(diff(none.display, msaa.display, x, y));
                edgeTaa.push_back(diff(taa, msaa.display, x, y));
            }
            bool isFlat = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    isFlat = isFlat && diff(none.display, msaa.display, x + dx, y + dy) <= 1.0;
            if (isFlat) ++flat, flatChanged += diff(taa, none.display, x, y) > 4.0;
        }
    ASSERT_GT(edgeNone.size(), 50u);
    EXPECT_LT(mean(edgeTaa), 0.7 * mean(edgeNone))
        << "silhouette error: taa " << mean(edgeTaa) << ", none " << mean(edgeNone);
    EXPECT_LT(double(flatChanged), 0.05 * double(flat))
        << flatChanged << " of " << flat << " flat pixels changed";
    // Motion: 30 degrees of orbit over 8 frames, compared with the final camera's plain frame.
    const gdi::Image moving = taaFrames(8, 30.0f);
    render::RenderSettings last = s;
    render::SceneRenderer r(*device, scene, last);
    r.setCamera(scene.camera->orbited(scene.bounds.center(), 30.0f * 0.0174532925f));
    r.renderFrame();
    const gdi::Image finalFrame = r.readDisplay();
    // Away from the final frame's edges (where antialiasing itself differs from one sample), a
    // pixel far from the final frame is history left behind by the motion: a ghost.
    size_t ghosts = 0;
    for (uint32_t y = 1; y + 1 < h; ++y)
        for (uint32_t x = 1; x + 1 < w; ++x) {
            double lo = 1e9, hi = -1e9;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto c = finalFrame.texel(x + dx, y + dy);
                    lo = std::min(lo, double(c[0] + c[1] + c[2])),
                    hi = std::max(hi, double(c[0] + c[1] + c[2]));
                }
            if ((hi - lo) * 255.0 < 24.0) ghosts += diff(moving, finalFrame, x, y) > 24.0;
        }
    EXPECT_LT(double(ghosts), 0.01 * w * h)
        << ghosts << " pixels away from edges far from the final camera's frame (ghosting)";
    std::cout << "[ taa ] " << GetParam() << ": silhouette error none " << mean(edgeNone)
              << ", taa " << mean(edgeTaa) << " over " << edgeNone.size()
              << " pixels; flat pixels changed " << flatChanged << " of " << flat
              << "; under motion " << ghosts << " pixels away from edges beyond 24/255\n";
}

// With FXAA the tone-mapped image is a transient of its own. The chain never costs aliasing a
// saving it had, and where the graph places textures in one heap (Vulkan) the intermediate takes
// memory the technique is done with (deferred: the G-buffer after the lighting pass), so the
// frame needs no more memory than without FXAA. GL reuses only whole objects of one description:
// there the intermediate takes over the base colour G-buffer's object and the display image,
// which took it before, needs one of its own (measured: 12288 bytes more at 64x48).
TEST_P(PostProcess, FxaaIntermediateSharesTransientMemory) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    render::RenderSettings s{.technique = "deferred", .width = 64, .height = 48};
    const Rendered plain = renderWith(*device, scene, s);
    s.antiAliasing = render::AntiAliasing::Fxaa;
    const Rendered fxaa = renderWith(*device, scene, s);
    const uint64_t intermediate = 64u * 48u * 4u;
    EXPECT_GE(fxaa.memory.withoutAliasing, plain.memory.withoutAliasing + intermediate);
    EXPECT_GE(fxaa.memory.withoutAliasing - fxaa.memory.withAliasing,
              plain.memory.withoutAliasing - plain.memory.withAliasing);
    if (fxaa.aliasing == graph::AliasingMode::Memory)
        EXPECT_LE(fxaa.memory.withAliasing, plain.memory.withAliasing)
            << "the intermediate should need no memory of its own";
    else
        EXPECT_LE(fxaa.memory.withAliasing, plain.memory.withAliasing + intermediate);
}

// Debug views (fe view): an intermediate texture shown in place of L_o. The G-buffer's normals
// show |n| (every lit sphere pixel non-black, unlike the background), depth shows as grey, and an
// unknown name is refused with the names the frame has.
TEST_P(PostProcess, DebugViewShowsAnIntermediateTexture) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    render::RenderSettings s{.technique = "deferred", .width = 64, .height = 48};
    s.debugView = "gbuffer1 normal+roughness";
    const Rendered normals = renderWith(*device, scene, s);
    s.debugView = "depth";
    const Rendered depth = renderWith(*device, scene, s);
    s.debugView.clear();
    const Rendered frame = renderWith(*device, scene, s);
    size_t differs = 0, grey = 0;
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const auto n = normals.display.texel(x, y), f = frame.display.texel(x, y),
                       d = depth.display.texel(x, y);
            differs += std::abs(n[0] - f[0]) + std::abs(n[1] - f[1]) + std::abs(n[2] - f[2]) > 0.1f;
            grey += d[0] == d[1] && d[1] == d[2];
        }
    EXPECT_GT(differs, 64u * 48u / 4) << "the normals view looks like the frame";
    EXPECT_EQ(grey, 64u * 48u) << "depth is one channel, shown as grey";
    s.debugView = "nothing";
    const std::string error = fe::testing::errorOf([&] { renderWith(*device, scene, s); });
    EXPECT_NE(error.find("debug view 'nothing': this frame has no such texture (it has: "),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("gbuffer1 normal+roughness"), std::string::npos) << error;
}

// Shadow maps as debug views: the sun's cascades (a 2D array: layer 0) and the lamp's cube (its
// six faces unfolded) show as grey depths that vary across the view, not one flat value.
TEST_P(PostProcess, DebugViewShowsShadowMaps) {
    const assets::Scene scene = assets::makeBuiltinScene("shadows");
    for (const char* map : {"shadow 0 map", "shadow 2 map"}) {
        render::RenderSettings s{.technique = "deferred", .width = 96, .height = 64};
        s.shadows = {.enabled = true, .mapSize = 256};
        s.debugView = map;
        const Rendered r = renderWith(*device, scene, s);
        std::set<float> greys;
        size_t coloured = 0;
        for (uint32_t y = 0; y < r.display.height; ++y)
            for (uint32_t x = 0; x < r.display.width; ++x) {
                const auto c = r.display.texel(x, y);
                greys.insert(c[0]);
                coloured += c[0] != c[1] || c[1] != c[2];
            }
        EXPECT_EQ(coloured, 0u) << map;
        EXPECT_GE(greys.size(), 8u) << map << ": a shadow map of a scene should hold many depths";
    }
}

// The "light count" heat map: builtin:plane has one unbounded light, so every pixel of the plane
// shows the colour of one light (and anything else black); builtin:lights (short-range
// lights) shows several counts.
TEST_P(PostProcess, LightCountHeatMap) {
    render::RenderSettings s{.technique = "forward", .width = 64, .height = 48};
    s.debugView = render::SceneRenderer::kLightCountView;
    const Rendered plane = renderWith(*device, assets::makeBuiltinScene("plane"), s);
    const HeatPixels one = heatPixels(plane.display, 0.388f);  // heat(1/32), sRGB-encoded
    EXPECT_GT(one.matching,
              64u * 48u / 4);  // the plane fills most of the view; any background stays black
    EXPECT_EQ(one.other, 0u) << one.black << " black pixels";
    assets::BuiltinOptions o;
    o.lights = 64;
    const Rendered lights = renderWith(*device, assets::makeBuiltinScene("lights", o), s);
    EXPECT_GE(distinctColours(lights.display), 4u)
        << "short-range lights should reach different pixels in different numbers";
}

// The "lights evaluated" heat map: forward walks every light, so builtin:plane (one light) shows
// heat(log2(2) / 8) = (0, 0.5, 1) on the whole plane; Forward+ in builtin:atrium walks tile lists
// of many lengths (more colours, and the same count where its statistics say so); light volumes
// are not measured and the view is refused, naming why.
TEST_P(PostProcess, LightsEvaluatedHeatMap) {
    render::RenderSettings s{.technique = "forward", .width = 64, .height = 48};
    s.debugView = render::SceneRenderer::kLightsEvaluatedView;
    const Rendered plane = renderWith(*device, assets::makeBuiltinScene("plane"), s);
    const HeatPixels one = heatPixels(plane.display, 0.735f);  // sRGB-encoded 0.5
    EXPECT_GT(one.matching, 64u * 48u / 4);
    EXPECT_EQ(one.other, 0u);

    assets::BuiltinOptions o;
    o.lights = 256;
    const assets::Scene atrium = assets::makeBuiltinScene("atrium", o);
    s.technique = "forward-plus";
    const Rendered tiles = renderWith(*device, atrium, s);
    EXPECT_GE(distinctColours(tiles.display), 6u)
        << "tile lists of many lengths should show many colours";

    s.technique = "deferred";
    try {
        renderWith(*device, atrium, s);
        ADD_FAILURE() << "deferred's light volumes have no list to show";
    } catch (const gdi::Error& e) {
        EXPECT_NE(std::string(e.what()).find("not measured"), std::string::npos) << e.what();
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(PostProcess);
