// The render director (layer 8): for scenes that need each choice, what it chose, why, and
// what the scene renderer then built: passes and transient textures, not only the name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "assets/Environment.h"
#include "integration/FrameWarnings.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"

using namespace fe;

namespace {

struct Built {
    std::string technique;
    std::vector<std::string> passes;    // surviving passes, in order
    std::vector<std::string> textures;  // transient textures the graph allocated
    std::vector<std::string> reasons;
};

// The device as the director sees it on a CPU rasterizer, where an error budget is spent on
// reduced rates (on a GPU it chooses the visibility buffer, which has none): the budget tests
// take this path on every device, the probe frames still rendered by the real one.
gdi::DeviceInfo asCpuRasterizer(const gdi::DeviceInfo& info) {
    gdi::DeviceInfo cpu = info;
    cpu.softwareRasterizer = true;
    return cpu;
}

Built build(gdi::Device& device, const assets::Scene& scene, render::RenderSettings request,
            render::DirectorOptions options = {}) {
    request.width = 64;
    request.height = 48;
    const gdi::DeviceInfo info =
        options.errorBudgetPercent > 0 ? asCpuRasterizer(device.info()) : device.info();
    const render::DirectorChoice c = render::direct(scene, request, info, &device, options);
    render::SceneRenderer r(device, scene, c.settings);
    r.renderFrame();
    Built b{c.settings.technique, {}, {}, c.reasons};
    for (const auto& p : r.graph().passes())
        if (!p.culled) b.passes.push_back(p.name);
    for (const auto& t : r.graph().textures())
        if (!t.imported && t.used()) b.textures.push_back(t.name);
    return b;
}

bool anyStartsWith(const std::vector<std::string>& v, const std::string& prefix) {
    return std::any_of(v.begin(), v.end(),
                       [&](const std::string& s) { return s.rfind(prefix, 0) == 0; });
}

class RenderDirector : public fe::testing::BackendTest {
protected:
    RenderDirector() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

}  // namespace

// One light: forward, with no G-buffer and no I-buffer allocated.
TEST_P(RenderDirector, FewLightsGetForwardAndNoGBuffer) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    const Built b = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(b.technique, "forward");
    EXPECT_EQ(b.passes,
              (std::vector<std::string>{"forward"}));  // display culled: no image asked for
    EXPECT_EQ(b.textures, (std::vector<std::string>{"depth"}));
    EXPECT_NE(b.reasons[0].find("1 light(s) covering the screen 1.0 times"), std::string::npos)
        << b.reasons[0];
}

// Many ranged lights covering the screen many times over, on a CPU rasterizer (every device of
// this suite but a lent GPU's): Forward+, a depth pre-pass and tile lists, no G-buffer and no
// I-buffer; on a GPU the visibility buffer (ManyLightsOnAGpuGetTheVisibilityBuffer).
TEST_P(RenderDirector, ManyLightsGetForwardPlusOnACpuRasterizer) {
    if (!device->info().features.computeShaders) GTEST_SKIP() << "no compute shaders";
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 512});
    const Built b = build(*device, scene, {.technique = "auto"});
    if (!device->info().softwareRasterizer) {
        EXPECT_EQ(b.technique, "visibility-buffer");
        return;
    }
    EXPECT_EQ(b.technique, "forward-plus");
    EXPECT_EQ(b.passes,
              (std::vector<std::string>{"zprepass", "light-culling", "forward-plus-shading"}));
    EXPECT_FALSE(anyStartsWith(b.textures, "gbuffer"));
    EXPECT_FALSE(anyStartsWith(b.textures, "ibuffer"));
    EXPECT_NE(b.reasons[0].find("512 light(s) (512 with a range) covering the screen"),
              std::string::npos)
        << b.reasons[0];
    EXPECT_NE(b.reasons[0].find("on a CPU rasterizer"), std::string::npos) << b.reasons[0];
    EXPECT_NE(b.reasons[0].find("tiles hold their depth tightly"), std::string::npos)
        << b.reasons[0];
}

// More lights than forward takes, but small on screen: light volumes, no compute pass.
TEST_P(RenderDirector, LightsCoveringLittleGetLightVolumes) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 8});
    const render::SceneNeeds n = render::sceneNeeds(scene, 64.0f / 48.0f);
    ASSERT_LT(n.lightCoverage, render::kTiledMinCoverage);
    const Built b = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(b.technique, "deferred");
    EXPECT_EQ(b.passes, (std::vector<std::string>{"gbuffer", "lighting", "emissive"}));
    EXPECT_FALSE(anyStartsWith(b.textures, "ibuffer"));
}

// Without MSAA, the deep scene with translucent banners and many lights, on a CPU rasterizer:
// a probe frame finds its cluster lists about as short as its depth-bounded tile lists (a deep
// scene), so clustered-forward (measured fastest there); --verbose says why, with the probe's
// figures, translucency included. builtin:lights gets forward-plus (ManyLightsGetForwardPlus...).
TEST_P(RenderDirector, ManyLightsInTheDeepAtriumGetClusteredForwardAndSayWhy) {
    if (!device->info().features.computeShaders) GTEST_SKIP() << "no compute shaders";
    const assets::Scene scene = assets::makeBuiltinScene("atrium", {.lights = 256});
    const Built b = build(*device, scene, {.technique = "auto"});
    if (!device->info().softwareRasterizer) {
        EXPECT_EQ(b.technique, "visibility-buffer");
        return;
    }
    EXPECT_EQ(b.technique, "clustered-forward") << b.reasons[0];
    EXPECT_EQ(b.passes, (std::vector<std::string>{"zprepass", "cluster-bounds", "light-assignment",
                                                  "clustered-shading", "transparent"}));
    EXPECT_NE(b.reasons[0].find("a probe frame's lists walk"), std::string::npos) << b.reasons[0];
    EXPECT_NE(b.reasons[0].find("a deep scene"), std::string::npos) << b.reasons[0];
    EXPECT_TRUE(anyStartsWith(
        b.reasons,
        std::to_string(render::sceneNeeds(scene, 64.0f / 48.0f).blendPrimitives) +
            " translucent primitive(s): their pass lights them from the light cluster grid"));
}

// --msaa with many lights: clustered forward, multisampled and exact (measured fastest with MSAA).
TEST_P(RenderDirector, MsaaWithManyLightsGetsClusteredForward) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    const Built b = build(*device, scene, {.technique = "auto", .msaa = 4});
    EXPECT_EQ(b.technique, "clustered-forward");
    EXPECT_EQ(b.passes,
              (std::vector<std::string>{"zprepass", "light-assignment", "clustered-shading"}));
    EXPECT_TRUE(anyStartsWith(b.textures, "msaa L_o"));
    EXPECT_FALSE(anyStartsWith(b.textures, "gbuffer"));
    EXPECT_NE(b.reasons[0].find("keeps hardware MSAA"), std::string::npos) << b.reasons[0];
}

// Without compute shaders, --msaa with many lights: the light pre-pass, multisampled; packed
// normals unless the scene has materials smoother than the packing holds.
TEST_P(RenderDirector, MsaaWithManyLightsAndNoComputeGetsLightPrepass) {
    if (!(device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    gdi::DeviceInfo noCompute = device->info();
    noCompute.features.computeShaders = false;
    auto build = [&](const assets::Scene& sc, render::RenderSettings requested) {
        requested.width = 64;
        requested.height = 48;
        const render::DirectorChoice c = render::direct(sc, requested, noCompute);
        render::SceneRenderer r(*device, sc, c.settings);
        Built out{c.settings.technique, {}, {}, c.reasons};
        for (const auto& p : r.graph().passes())
            if (!p.culled) out.passes.push_back(p.name);
        for (const auto& t : r.graph().textures())
            if (!t.imported && t.used()) out.textures.push_back(t.name);
        return out;
    };
    const Built b = build(scene, {.technique = "auto", .msaa = 4});
    EXPECT_EQ(b.technique, "light-prepass");
    EXPECT_EQ(b.passes, (std::vector<std::string>{"lpp-normals", "lpp-lights", "lpp-material"}));
    EXPECT_TRUE(anyStartsWith(b.textures, "msaa lpp normal.xy+roughness (packed)"));
    EXPECT_TRUE(anyStartsWith(b.textures, "msaa L_o"));
    EXPECT_FALSE(anyStartsWith(b.textures, "gbuffer"));
    for (auto& m : scene.materials) m.roughness = render::kPackedNormalsMinRoughness / 2;
    const Built smooth = build(scene, {.technique = "auto", .msaa = 4});
    EXPECT_EQ(smooth.technique, "light-prepass-unpacked");
    EXPECT_TRUE(anyStartsWith(smooth.textures, "msaa lpp normal+roughness"));
    EXPECT_NE(smooth.reasons[1].find("below 0.20"), std::string::npos) << smooth.reasons[1];
}

// An error budget admits a reduced illumination rate only as far as a probe frame shows it
// within the budget; without a budget there is no I-buffer.
TEST_P(RenderDirector, ReducedRateOnlyWithinTheErrorBudget) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 512});
    const Built generous =
        build(*device, scene, {.technique = "auto"}, {.errorBudgetPercent = 100});
    EXPECT_EQ(generous.technique, "redeferred-tiled");
    EXPECT_TRUE(anyStartsWith(generous.textures, "ibuffer0 L_dg"));
    EXPECT_NE(generous.reasons[1].find("illum-scale 4: probe frame"), std::string::npos)
        << generous.reasons[1];
    const Built strict = build(*device, scene, {.technique = "auto"}, {.errorBudgetPercent = 0.01});
    EXPECT_EQ(strict.technique, "deferred-tiled");
    EXPECT_FALSE(anyStartsWith(strict.textures, "ibuffer"));
    EXPECT_NE(strict.reasons[1].find("no reduced illumination rate: probe frames"),
              std::string::npos)
        << strict.reasons[1];
    // Between the two: a budget just above what scale 2 measured admits scale 2, not 4.
    const render::DirectorChoice c =
        render::direct(scene, {.technique = "auto", .width = 64, .height = 48},
                       asCpuRasterizer(device->info()), device.get(), {.errorBudgetPercent = 0.01});
    const std::string& line = c.reasons[1];
    const double atScale2 = std::stod(line.substr(line.find(", ") + 2));
    const double atScale4 = std::stod(line.substr(line.find("probe frames ") + 13));
    ASSERT_LT(atScale2, atScale4) << line;
    const Built middle = build(*device, scene, {.technique = "auto"},
                               {.errorBudgetPercent = (atScale2 + atScale4) / 2});
    EXPECT_EQ(middle.technique, "redeferred-tiled");
    EXPECT_NE(middle.reasons[1].find("illum-scale 2"), std::string::npos) << middle.reasons[1];
}

// With several illumination sources (unshadowed lights, shadowed lights, the environment's
// diffuse and specular light) the budget is spent per source: each gets the lowest rate whose
// probe frame, with the rates already chosen, stays within it; the graph then has an I-buffer per
// rate and upsamples each reduced one. A budget of 0.01 % admits none.
TEST_P(RenderDirector, RatesPerSourceWithinTheErrorBudget) {
    assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 256});
    scene.environment = assets::loadEnvironment("builtin:sky");
    render::RenderSettings request{
        .technique = "auto", .width = 64, .height = 48, .iblPrefiltered = true};
    request.shadows = {.enabled = true, .mapSize = 256, .pointBudget = 2};
    const double budget = 8.0;
    const render::DirectorChoice c = render::direct(scene, request, asCpuRasterizer(device->info()),
                                                    device.get(), {.errorBudgetPercent = budget});
    std::string why;
    for (const auto& r : c.reasons) why += r + "\n";
    size_t sourceLines = 0;
    for (const auto& r : c.reasons) sourceLines += r.rfind("source ", 0) == 0;
    EXPECT_EQ(sourceLines, 4u) << why;
    ASSERT_NE(c.settings.technique.find("redeferred"), std::string::npos) << why;
    const render::SourceRates& rates = c.settings.rates;
    EXPECT_TRUE(rates.punctual > 1 || rates.shadowed > 1 || rates.iblDiffuse > 1 ||
                rates.iblSpecular > 1)
        << why;
    // What it chose holds: within the budget of the exact image.
    render::RenderSettings exact = request;
    exact.technique = device->info().features.computeShaders ? "deferred-tiled" : "deferred";
    render::SceneRenderer reference(*device, scene, exact), chosen(*device, scene, c.settings);
    reference.renderFrame();
    chosen.renderFrame();
    EXPECT_LE(render::percentPixelsOver5Of255(chosen.readOutput(), reference.readOutput(), 1.0f),
              budget)
        << why;
    if (c.settings.perSourceRates()) {
        std::vector<std::string> passes;
        for (const auto& p : chosen.graph().passes())
            if (!p.culled) passes.push_back(p.name);
        EXPECT_TRUE(anyStartsWith(passes, "upsample I-buffer 1/")) << why;
    }
    std::cout << why;
    const render::DirectorChoice strict =
        render::direct(scene, request, asCpuRasterizer(device->info()), device.get(),
                       {.errorBudgetPercent = 0.01});
    EXPECT_EQ(strict.settings.technique, exact.technique);
    EXPECT_EQ(strict.settings.rates.punctual + strict.settings.rates.iblDiffuse, 0u);
}

// --brdf gltf with auto: never a technique that needs the separable BRDF (the light pre-pass under
// MSAA without compute shaders, redeferred under an error budget), which would refuse the frame.
TEST_P(RenderDirector, GltfAskedNeverGetsASeparableTechnique) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    gdi::DeviceInfo noCompute = device->info();
    noCompute.features.computeShaders = false;
    render::RenderSettings request{.technique = "auto", .width = 64, .height = 48, .msaa = 4};
    request.shadingModel = render::ShadingModel::Gltf;
    const render::DirectorChoice msaa = render::direct(scene, request, noCompute);
    EXPECT_EQ(msaa.settings.technique, "forward") << msaa.reasons[0];
    EXPECT_FALSE(render::findTechnique(msaa.settings.technique).separableBrdf);
    request.msaa = 1;
    const render::DirectorChoice budget =
        render::direct(scene, request, device->info(), device.get(), {.errorBudgetPercent = 8.0});
    std::string why;
    for (const auto& r : budget.reasons) why += r + "\n";
    EXPECT_FALSE(render::findTechnique(budget.settings.technique).separableBrdf) << why;
    EXPECT_NE(why.find("unused, --brdf gltf asked for"), std::string::npos) << why;
    render::SceneRenderer r(*device, scene, budget.settings);  // it renders: no refusal
    r.renderFrame();
}

// Materials only the forward family and the visibility buffer show (KHR_materials_ior / specular /
// clearcoat): auto never picks a G-buffer technique for them, and says why; without them the
// choice is what it was.
TEST_P(RenderDirector, FullMaterialsKeepAForwardTechnique) {
    assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    const render::RenderSettings request{.technique = "auto", .width = 64, .height = 48};
    gdi::DeviceInfo noCompute = device->info();
    noCompute.features.computeShaders = false;
    const std::string before = render::direct(scene, request, noCompute).settings.technique;
    ASSERT_FALSE(render::findTechnique(before).fullMaterial(shading::Brdf::Gltf))
        << before << ": the test needs a G-buffer choice";
    scene.materials[0].clearcoat = 1.0f;
    const render::DirectorChoice c = render::direct(scene, request, noCompute);
    std::string why;
    for (const auto& r : c.reasons) why += r + "\n";
    EXPECT_EQ(c.settings.technique, "forward") << why;
    EXPECT_NE(why.find("rather than " + before + ": "), std::string::npos) << why;
    EXPECT_TRUE(render::materialWarnings(scene, c.settings).empty());
    if (device->info().features.computeShaders) {
        const render::DirectorChoice withCompute = render::direct(scene, request, device->info());
        EXPECT_TRUE(
            render::findTechnique(withCompute.settings.technique).fullMaterial(shading::Brdf::Gltf))
            << withCompute.settings.technique;
    }
}

// BLEND primitives bring the transparent pass; without them there is none.
TEST_P(RenderDirector, TransparentPassOnlyForBlendPrimitives) {
    assets::Scene scene = assets::makeBuiltinScene("plane");
    Built opaque = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(std::count(opaque.passes.begin(), opaque.passes.end(), "transparent"), 0);
    EXPECT_EQ(opaque.reasons.back(), "no transparent pass: no BLEND primitives");
    for (auto& m : scene.materials) m.alphaMode = assets::AlphaMode::Blend;
    Built blend = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(std::count(blend.passes.begin(), blend.passes.end(), "transparent"), 1);
    EXPECT_EQ(blend.reasons.back(), "transparent pass: 1 BLEND primitive(s)");
}

// An asked-for technique is kept; a reduced illumination rate outside redeferred is dropped,
// with its reason, and only redeferred allocates an I-buffer.
TEST_P(RenderDirector, AskedTechniqueIsKept) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    const Built r = build(*device, scene, {.technique = "redeferred", .illumScale = 2});
    EXPECT_EQ(r.technique, "redeferred");
    EXPECT_TRUE(anyStartsWith(r.textures, "ibuffer"));
    const Built f = build(*device, scene, {.technique = "deferred", .illumScale = 2});
    EXPECT_FALSE(anyStartsWith(f.textures, "ibuffer"));
    EXPECT_NE(f.reasons[1].find("illumination scale 2 ignored"), std::string::npos);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(RenderDirector);

// Without compute shaders many lights fall back to light volumes (no device needed).
TEST(RenderDirectorChoice, WithoutComputeShadersManyLightsGetDeferred) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 512});
    gdi::DeviceInfo noCompute;
    noCompute.backend = "test";
    const render::DirectorChoice c = render::direct(scene, {.technique = "auto"}, noCompute);
    EXPECT_EQ(c.settings.technique, "deferred");
    EXPECT_NE(c.reasons[0].find("no compute shaders on test"), std::string::npos) << c.reasons[0];
}

// On a GPU (not a software rasterizer), many lights get the visibility buffer, measured fastest
// there (an H200); the same scene on a CPU rasterizer gets forward-plus, and with an error budget
// deferred-tiled, the exact technique the reduced rates start from.
TEST(RenderDirectorChoice, ManyLightsOnAGpuGetTheVisibilityBuffer) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 512});
    gdi::DeviceInfo gpu;
    gpu.backend = "test";
    gpu.features.computeShaders = true;
    gpu.softwareRasterizer = false;
    const render::DirectorChoice c = render::direct(scene, {.technique = "auto"}, gpu);
    EXPECT_EQ(c.settings.technique, "visibility-buffer");
    EXPECT_NE(c.reasons[0].find("on a GPU"), std::string::npos) << c.reasons[0];
    gpu.softwareRasterizer = true;
    EXPECT_EQ(render::direct(scene, {.technique = "auto"}, gpu).settings.technique, "forward-plus");
    // An error budget with no device to probe on leaves nothing to reduce: forward-plus still.
    EXPECT_EQ(
        render::direct(scene, {.technique = "auto"}, gpu, nullptr, {.errorBudgetPercent = 1.0})
            .settings.technique,
        "forward-plus");
}

// Every technique with an I-buffer keeps its illumination scale; the others drop it.
TEST(RenderDirectorChoice, IllumScaleKeptWhereThereIsAnIBuffer) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    gdi::DeviceInfo device;
    for (const char* t : {"redeferred", "redeferred-tiled"})
        EXPECT_EQ(
            render::direct(scene, {.technique = t, .illumScale = 2}, device).settings.illumScale,
            2u)
            << t;
    for (const char* t : {"deferred", "deferred-tiled", "forward", "light-prepass"})
        EXPECT_EQ(
            render::direct(scene, {.technique = t, .illumScale = 2}, device).settings.illumScale,
            1u)
            << t;
}

// Screen coverage: a light whose range sphere holds the eye covers the screen; one behind the
// eye covers nothing; one far away covers its projected disc.
TEST(RenderDirectorChoice, LightCoverage) {
    assets::Scene scene = assets::makeBuiltinScene("plane");
    const assets::Camera& cam = *scene.camera;
    assets::Light l;
    l.type = assets::LightType::Point;
    l.range = 1.0f;
    scene.lights = {l};
    scene.lights[0].position = cam.eye();
    EXPECT_DOUBLE_EQ(render::sceneNeeds(scene, 1.0f).lightCoverage, 1.0);
    scene.lights[0].position = cam.eye() - cam.forward() * 5.0f;
    EXPECT_DOUBLE_EQ(render::sceneNeeds(scene, 1.0f).lightCoverage, 0.0);
    scene.lights[0].position = cam.eye() + cam.forward() * 10.0f;
    const double d = 10.0, rho = 1.0 / (std::sqrt(d * d - 1.0) * std::tan(cam.yfov / 2));
    EXPECT_NEAR(render::sceneNeeds(scene, 2.0f).lightCoverage, 3.14159265358979 * rho * rho / 8.0,
                1e-6);
    scene.lights[0].type = assets::LightType::Directional;
    EXPECT_DOUBLE_EQ(render::sceneNeeds(scene, 1.0f).lightCoverage, 1.0);
}

// The roughness range reads metallic-roughness textures: a texture's smallest G scales the factor.
TEST(RenderDirectorChoice, RoughnessRangeReadsTextures) {
    assets::Scene scene = assets::makeBuiltinScene("plane");
    for (auto& m : scene.materials) m.roughness = 0.8f;
    render::SceneNeeds n = render::sceneNeeds(scene, 1.0f);
    EXPECT_FLOAT_EQ(n.minRoughness, 0.8f);
    assets::TextureImage t{
        .name = "mr", .width = 2, .height = 1, .pixels = {0, 255, 0, 255, 0, 51, 0, 255}};
    scene.textures.push_back(t);
    for (auto& m : scene.materials)
        m.metallicRoughnessTexture.index = int32_t(scene.textures.size() - 1);
    n = render::sceneNeeds(scene, 1.0f);
    EXPECT_FLOAT_EQ(n.minRoughness, 0.8f * 0.2f);
    EXPECT_FLOAT_EQ(n.maxRoughness, 0.8f);
}
