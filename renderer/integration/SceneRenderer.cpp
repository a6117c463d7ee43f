#include "integration/SceneRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstring>

#include "assets/AssetError.h"
#include "fe/gdi/ShaderRegistry.h"
#include "reference/CameraMath.h"
#include "render/ShaderSlots.h"
#include "render/TemporalAccumulation.h"

// The scene shaders' registry (cmake/FeShaders.cmake), archived into this library: referenced
// here so that linking the library from an installed package pulls it in.
extern "C" void fe_shaders_link_fe_shaders_scene();

namespace fe::render {

SceneRenderer::SceneRenderer(gdi::Device& device, const assets::Scene& scene,
                             const RenderSettings& s)
    : objects_(device), device_(device), scene_(scene), settings_(s) {
    fe_shaders_link_fe_shaders_scene();
    const TechniqueInfo& technique =
        findTechnique(s.technique);  // an unknown name fails before any GPU work
    if (s.width == 0 || s.height == 0 || s.width > 8192 || s.height > 8192)
        throw gdi::Error("render size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                         " out of range (1..8192 per axis)");
    for (uint32_t r : {s.rates.punctual, s.rates.shadowed, s.rates.iblDiffuse, s.rates.iblSpecular})
        if (r != 0 && r != 1 && r != 2 && r != 4)
            throw gdi::Error("a source's illumination rate must be 1, 2 or 4 (got " +
                             std::to_string(r) + ")");
    const bool rates =
        s.rates.punctual || s.rates.shadowed || s.rates.iblDiffuse || s.rates.iblSpecular;
    if (rates && !technique.illumScale)
        throw gdi::Error("technique " + s.technique +
                         " has no I-buffer: per-source rates need redeferred or redeferred-tiled");
    if (rates && s.illumSplit) throw gdi::Error("--rates and --illum-split cannot be combined");
    if (rates &&
        !s.perSourceRates()) {  // one rate for every source present: the plain reduced-rate path
        settings_.illumScale = s.rate(s.rates.punctual);
        settings_.rates = {};
    }
    if (s.illumScale != 1 && s.illumScale != 2 && s.illumScale != 4)
        throw gdi::Error("illumination scale must be 1, 2 or 4 (got " +
                         std::to_string(s.illumScale) + ")");
    if (!scene.camera) throw gdi::Error("scene has no camera");
    if (!(s.exposure > 0.0f && std::isfinite(s.exposure)))
        throw gdi::Error("exposure " + std::to_string(s.exposure) + " is not a positive number");
    if (s.antiAliasing == AntiAliasing::Taa && s.temporal)
        throw gdi::Error("--aa taa and --temporal both jitter the frame over time: take one");
    try {
        assets::checkFinite(scene);
    } catch (const assets::AssetError& e) {
        throw gdi::Error(std::string("scene refused: ") + e.what());
    }
    camera_ = *scene.camera;
    resolveBrdf(
        s);  // a BRDF the technique cannot evaluate is refused here, before any pass is made
    if (s.msaa != 1 && s.msaa != 2 && s.msaa != 4 && s.msaa != 8)
        throw gdi::Error("--msaa must be 1, 2, 4 or 8 (got " + std::to_string(s.msaa) + ")");
    if (s.msaa > 1 && !technique.msaa) {
        std::string taking;
        for (const TechniqueInfo& t : techniques())
            if (t.msaa) taking += (taking.empty() ? "" : ", ") + std::string(t.name);
        throw gdi::Error("technique " + s.technique +
                         " does not take --msaa: it sums light at the I-buffer's rate from a "
                         "single-sample G-buffer (use " +
                         taking + ")");
    }
    if (s.ibl() && !scene.environment)
        throw gdi::Error(std::string(s.iblPrefiltered ? "--ibl-prefiltered" : "--ibl-samples") +
                         " needs an environment to light the scene with (--environment)");
    if (s.iblPrefiltered && s.iblSamples > 0)
        throw gdi::Error("--ibl-prefiltered and --ibl-samples are two ways of one thing: take one");
    if (s.iblSamples > 65536)
        throw gdi::Error("--ibl-samples must be at most 65536 (got " +
                         std::to_string(s.iblSamples) + ")");
    const ShadowSettings& sh = s.shadows;
    if (sh.enabled) {
        if (sh.mapSize < 16 || sh.mapSize > 16384)
            throw gdi::Error("shadow map size must be 16..16384 (got " +
                             std::to_string(sh.mapSize) + ")");
        if (sh.cascades < 1 || sh.cascades > 4)
            throw gdi::Error("shadow cascades must be 1..4 (got " + std::to_string(sh.cascades) +
                             ")");
        const uint32_t maxCube = device.info().limits.maxTextureSizeCube,
                       max2D = device.info().limits.maxTextureSize2D;
        if (sh.mapSize > std::min(maxCube, max2D))
            throw gdi::Error("shadow map size " + std::to_string(sh.mapSize) + " exceeds what " +
                             device.info().backend + " allows (" +
                             std::to_string(std::min(maxCube, max2D)) + ")");
    }
    const gdi::DeviceLimits& limits = device.info().limits;
    if (s.msaa > 1 && !(limits.colorSampleCounts & limits.depthSampleCounts & s.msaa))
        throw gdi::Error(std::to_string(s.msaa) + " samples are not supported on " +
                         device.info().backend);
    // The per-frame uploads hold the animated instances' joint matrices and weights as well (the
    // regions grow when a frame needs more: many lights, many objects).
    uint64_t poseBytes = 0;
    for (const assets::MeshInstance& i : scene.instances)
        if (i.deformed())
            poseBytes +=
                i.joints.size() * sizeof(glm::mat4) + (i.weights.size() + 3) / 4 * 16 + 256;
    queue_ = std::make_unique<CommandQueue>(device, 2, (256u << 10) + poseBytes);
    gpuScene_ = std::make_unique<GpuScene>(device, scene);
    geometry_ = std::make_unique<GeometryRenderer>(device, *gpuScene_);
    shadowPlan_ = planShadows(scene.lights, *scene.camera, scene.bounds, s.shadows);
    updateLights(scene.lights);
    if (!shadowPlan_.shadowed.empty())
        shadows_ =
            std::make_unique<ShadowMaps>(device, *queue_, *geometry_, shadowPlan_, s.shadows);
    outputTexture_ = objects_.add(device.createTexture(
        {.format = kRadianceFormat,
         .width = s.width,
         .height = s.height,
         .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled |
                  gdi::TextureUsage::Storage | gdi::TextureUsage::CopySrc,
         .debugName = "output L_o"}));
    pointSampler_ = objects_.add(device.createSampler({.minFilter = gdi::Filter::Nearest,
                                                       .magFilter = gdi::Filter::Nearest,
                                                       .addressU = gdi::AddressMode::ClampToEdge,
                                                       .addressV = gdi::AddressMode::ClampToEdge}));
    fullscreenVs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/fullscreen.vert")}));
    if (scene.environment)
        environment_ = std::make_unique<EnvironmentMap>(device, *scene.environment, fullscreenVs_);
    background_ = std::make_unique<BackgroundPass>(device, *queue_, settings_, environment_.get(),
                                                   frameConstants_);
    postProcess_ = std::make_unique<PostProcess>(device, settings_, fullscreenVs_, frameConstants_,
                                                 background_->displayConstants().x);
    context_.reset(new TechniqueContext{device, *queue_, *gpuScene_, *geometry_, settings_, frame_,
                                        frameConstants_, scene.camera->eye(), pointSampler_,
                                        fullscreenVs_});
    if (s.ibl()) {
        EnvironmentLight light{.cube = environment_->cube(), .sampler = environment_->sampler()};
        if (s.iblPrefiltered) {
            prefiltered_ = std::make_unique<PrefilteredEnvironment>(
                device, *scene.environment, environment_->cube(), environment_->sampler(),
                fullscreenVs_);
            light = {.cube = prefiltered_->cube(),
                     .sampler = prefiltered_->sampler(),
                     .lut = prefiltered_->lut(),
                     .sh = prefiltered_->sh()};
        }
        geometry_->setEnvironment(light);
        context_->environmentLight = light;
    }
    context_->shadows = shadows_.get();
    // The cluster grid: for the clustered techniques, for forward-plus under MSAA (an edge
    // fragment outside its tile's depth bounds walks its cluster's list), and for the translucent
    // pass of every technique (which otherwise lights each blended fragment with every light).
    const bool translucentNeedsGrid =
        gpuScene_->hasBlend() && s.translucentClusters && device.info().features.computeShaders;
    if (technique.clusters || (technique.clustersUnderMsaa && s.msaa > 1) || translucentNeedsGrid) {
        clusters_ = std::make_unique<ClusterLightGrid>(*context_);
        context_->clusters = clusters_.get();
    }
    if (!scene.emitters.empty()) vfx_ = std::make_unique<VfxRenderer>(*context_, scene.emitters);
    if (gpuScene_->hasTransmissive()) transmission_ = std::make_unique<TransmissionPass>(*context_);
    if (!gpuScene_->deformations().empty())
        deformation_ = std::make_unique<MeshDeformation>(*context_);
    technique_ = technique.create(*context_);
    // The display image straight from the shading pass: the display pass's sum for background
    // 0, so only where nothing after the technique's passes adds to L_o (blended surfaces,
    // particles, transmission, shadowed lights, a background pass) or reads it (antialiasing,
    // a debug view, the list statistics), at one sample, without the environment's light (its
    // shaders have no such variant).
    displayInShading_ = s.displayInShading && s.displayImage && technique.writesDisplay &&
                        s.msaa <= 1 && s.antiAliasing == AntiAliasing::None &&
                        s.debugView.empty() && !s.lightListStatistics && !s.ibl() &&
                        background_->kind() == Background::Kind::Auto &&
                        background_->displayConstants().x == 0 && !transmission_ &&
                        !gpuScene_->hasBlend() && !vfx_ && !shadows_;
    buildGraph();
    graph_.compile(device, s.aliasing);
}

SceneRenderer::~SceneRenderer() {
    device_.waitIdleOrLost();  // a destructor must not throw, and a lost device runs nothing more
}

// The frame as a graph: the technique's passes, then what every technique shares. The graph
// culls what nothing reads (the display pass unless a display image is asked for).
void SceneRenderer::buildGraph() {
    const RenderSettings& s = settings_;
    graph::RenderGraph& g = graph_;
    output_ = g.importTexture("output L_o", outputTexture_, device_.desc(outputTexture_));
    depth_ = g.createTexture("depth",
                             {.format = kSceneDepthFormat, .width = s.width, .height = s.height});
    if (deformation_)
        deformation_->declare(g);  // first: every pass after it draws the deformed meshes
    context_->display =
        displayInShading_
            ? g.createTexture("display sRGB",
                              {.format = kDisplayFormat, .width = s.width, .height = s.height})
            : graph::TextureId{};
    technique_->declare(g, output_, depth_);
    if (s.lightListStatistics || s.debugView == kLightsEvaluatedView) declareListStatistics(g);
    background_->declare(g, output_, depth_);
    if (transmission_) transmission_->declare(g, output_, depth_);
    if (gpuScene_->hasBlend()) {
        const bool culled = clusters_ && s.translucentClusters;
        const ClusterLightGrid::Lists clusterLists =
            culled ? clusters_->declare(g) : ClusterLightGrid::Lists{};
        g.addPass(
            "transparent",
            [&](graph::PassBuilder& b) {
                b.colorTarget(output_, gdi::LoadOp::Load);
                b.depthTarget(depth_, gdi::LoadOp::Load);
                if (culled) ClusterLightGrid::read(b, clusterLists);
            },
            [this, culled](graph::PassContext& pc) {
                pc.beginRenderPass();
                if (culled) clusters_->bindLists(pc.cmd);
                // Every light, the shadowed ones without their shadows: blended surfaces receive none.
                FrameConstants fc = frame_;
                fc.lightRange = glm::uvec4(0, gpuScene_->lightCount(), 1, 0);
                geometry_->draw(pc.cmd, *queue_,
                                culled ? MeshPass::TransparentClustered : MeshPass::Transparent,
                                {{kRadianceFormat}, kSceneDepthFormat}, queue_->upload(fc),
                                context_->eye);
                pc.cmd.endRenderPass();
            });
    }
    if (vfx_)
        vfx_->declare(g, output_, depth_);  // particles: after every other translucent surface
    graph::TextureId shown = output_;
    if (!s.debugView.empty()) shown = declareDebugView(g);
    display_ = displayInShading_ ? context_->display : postProcess_->declare(g, shown, depth_);
    g.markOutput(output_);
    if (s.displayImage) g.markOutput(display_);
}

// The debug view: the named texture drawn into a texture of L_o's format, which post-processing
// then shows as it would show L_o. Integer and cube textures cannot be shown this way (refused).
graph::TextureId SceneRenderer::declareDebugView(graph::RenderGraph& g) {
    const RenderSettings& s = settings_;
    if (s.debugView == kLightCountView) return declareLightCountView(g);
    if (s.debugView == kLightsEvaluatedView) return declareLightsEvaluatedView(g);
    graph::TextureId source;
    std::string names = std::string(kLightCountView) + ", " + kLightsEvaluatedView;
    for (uint32_t i = 0; i < g.textures().size(); ++i) {
        const graph::TextureInfo& t = g.textures()[i];
        names += (names.empty() ? "" : ", ") + t.name;
        if (t.name == s.debugView) source = graph::TextureId{i};
    }
    if (!source.valid())
        throw gdi::Error("debug view '" + s.debugView +
                         "': this frame has no such texture (it has: " + names + ")");
    const gdi::TextureDesc& desc = g.texture(source).desc;
    const gdi::FormatInfo& format = gdi::formatInfo(desc.format);
    if (format.isInteger || desc.dimension == gdi::TextureDimension::TextureCubeArray ||
        desc.dimension == gdi::TextureDimension::Texture3D || desc.sampleCount > 1)
        throw gdi::Error("debug view '" + s.debugView + "': " + std::string(format.name) + " " +
                         (desc.sampleCount > 1 ? "multisampled " : "") +
                         "textures of this kind cannot be shown");
    const bool layered = desc.dimension == gdi::TextureDimension::Texture2DArray;
    const char* shader = desc.dimension == gdi::TextureDimension::TextureCube
                             ? "scene/debug_view_cube.frag"
                         : layered              ? "scene/debug_view_layered.frag"
                         : format.hasDepth      ? "scene/debug_view_depth.frag"
                         : format.channels == 1 ? "scene/debug_view_grey.frag"
                                                : "scene/debug_view.frag";
    debugViewFs_ = objects_.add(device_.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(shader)}));
    debugViewPipeline_ =
        objects_.add(device_.createGraphicsPipeline({.vertexShader = fullscreenVs_,
                                                     .fragmentShader = debugViewFs_,
                                                     .colorFormats = {kRadianceFormat},
                                                     .debugName = "debug view"}));
    const graph::TextureId view = g.createTexture(
        "debug view", {.format = kRadianceFormat, .width = s.width, .height = s.height});
    addFullscreenPass(g, "debug-view", source, view, debugViewPipeline_, pointSampler_,
                      frameConstants_);
    return view;
}

// The light-list statistics pass: the length of the list each pixel's surface walks, from the
// technique's tile lists or the cluster grid (every light where it has none), and how many
// lights reach that surface (shaders/scene/light_list_statistics.comp).
void SceneRenderer::declareListStatistics(graph::RenderGraph& g) {
    const LightLists lists = technique_->lightLists();
    if (lists.kind == LightLists::Kind::NotMeasured) return;
    const RenderSettings& s = settings_;
    auto countTexture = [&](const char* name) {
        return objects_.add(
            device_.createTexture({.format = gdi::Format::R32U,
                                   .width = s.width,
                                   .height = s.height,
                                   .usage = gdi::TextureUsage::Storage |
                                            gdi::TextureUsage::Sampled | gdi::TextureUsage::CopySrc,
                                   .debugName = name}));
    };
    listCounts_ = countTexture("lights evaluated");
    reachingCounts_ = countTexture("lights reaching");
    const bool clusters = lists.kind == LightLists::Kind::Clusters,
               tiles = lists.kind == LightLists::Kind::Tiles;
    // It walks every light at every pixel: from the uniform block where they fit (fe_scene.glsl).
    const bool uniformLights =
        GpuScene::lightsFitUniformBlock(uint32_t(scene_.lights.size()), device_.info().limits);
    std::string variant = clusters ? "FE_CLUSTER_LISTS" : tiles ? "" : "FE_EVERY_LIGHT";
    if (!uniformLights)
        variant += variant.empty() ? "FE_LIGHTS_IN_STORAGE" : "+FE_LIGHTS_IN_STORAGE";
    listStatisticsCs_ = objects_.add(
        device_.createShader({.stage = gdi::ShaderStage::Compute,
                              .binary = shaders::find("scene/light_list_statistics.comp" +
                                                      (variant.empty() ? "" : ":" + variant))}));
    listStatisticsPipeline_ = objects_.add(device_.createComputePipeline(
        {.computeShader = listStatisticsCs_, .debugName = "light-list statistics"}));
    const graph::TextureId counts =
        g.importTexture("lights evaluated", listCounts_, device_.desc(listCounts_));
    const graph::TextureId reaching =
        g.importTexture("lights reaching", reachingCounts_, device_.desc(reachingCounts_));
    listCountsId_ = counts;
    // It counts what an opaque pixel walks: the bounded parts (the whole lists where the
    // technique's grid is not bounded, under MSAA).
    const ClusterLightGrid::Lists clusterLists =
        clusters ? clusters_->declareBounded(g, depth_) : ClusterLightGrid::Lists{};
    g.addPass(
        "light-list-statistics",
        [&](graph::PassBuilder& b) {
            b.sample(depth_);
            if (clusters) ClusterLightGrid::read(b, clusterLists);
            if (tiles) b.sample(lists.tiles);
            b.storage(counts);
            b.storage(reaching);
        },
        [this, clusters, tiles, lists, counts, reaching, uniformLights](graph::PassContext& pc) {
            pc.cmd.setPipeline(listStatisticsPipeline_);
            pc.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset,
                                    frameConstants_.size);
            gpuScene_->bindLights(pc.cmd, kSlotLights, uniformLights);
            pc.cmd.setTexture(kSlotDepth, pc.texture(depth_), pointSampler_);
            if (clusters) clusters_->bindLists(pc.cmd);
            if (tiles) pc.cmd.setTexture(kSlotTileLights, pc.texture(lists.tiles), pointSampler_);
            pc.cmd.setStorageTexture(kSlotRadianceOut, pc.texture(counts));
            pc.cmd.setStorageTexture(kSlotTileLightsOut, pc.texture(reaching));
            pc.cmd.dispatch((settings_.width + 7) / 8, (settings_.height + 7) / 8);
        });
    g.markOutput(counts);
    g.markOutput(reaching);
}

namespace {
// An R32U image's texels other than all ones (no surface), in row order.
std::vector<uint32_t> surfaceTexels(const gdi::Image& image) {
    std::vector<uint32_t> texels(size_t(image.width) * image.height);
    std::memcpy(texels.data(), image.data.data(), texels.size() * sizeof(uint32_t));
    std::erase(texels, 0xffffffffu);
    return texels;
}
}  // namespace

LightListStatistics SceneRenderer::lightListStatistics() {
    if (!settings_.lightListStatistics)
        throw gdi::Error(
            "lightListStatistics: the renderer was created without RenderSettings::lightListStatistics");
    LightListStatistics out;
    switch (technique_->lightLists().kind) {
        case LightLists::Kind::EveryLight:
            out.lists = "every light";
            break;
        case LightLists::Kind::Tiles:
            out.lists = "tile lists";
            break;
        case LightLists::Kind::Clusters:
            out.lists = "cluster lists";
            break;
        case LightLists::Kind::NotMeasured:
            out.lists = "not measured (light volumes or reduced-rate lists)";
            return out;
    }
    device_.wait(lastFence_);
    std::vector<uint32_t> counts = surfaceTexels(device_.readTexture(listCounts_));
    const std::vector<uint32_t> reaching = surfaceTexels(device_.readTexture(reachingCounts_));
    out.measured = true;
    out.pixels = uint32_t(counts.size());
    double reachSum = 0;
    for (uint32_t r : reaching) {
        reachSum += r & 0x7fffffffu;
        out.pixelsMissingALight += r >> 31;
    }
    if (counts.empty()) return out;
    out.reaching = reachSum / double(reaching.size());
    std::sort(counts.begin(), counts.end());
    double sum = 0;
    for (uint32_t n : counts) sum += n;
    out.mean = sum / double(counts.size());
    out.p95 = counts[std::min(counts.size() - 1, size_t(double(counts.size()) * 0.95))];
    out.max = counts.back();
    return out;
}

LightListStatistics measureLightLists(gdi::Device& device, const assets::Scene& scene,
                                      RenderSettings settings,
                                      const std::function<void(SceneRenderer&)>& prepare) {
    settings.lightListStatistics = true;
    settings.displayImage = false;
    SceneRenderer r(device, scene, settings);
    if (prepare) prepare(r);
    r.renderFrame();
    // Cluster lists that overflowed have grown within framesInFlight frames (ClusterLightGrid::
    // beginFrame): the statistics are those of the frames after that.
    for (uint32_t i = 0;
         i <= r.framesInFlight() && r.clusters() && r.clusters()->statistics().overflowed; ++i)
        r.renderFrame();
    return r.lightListStatistics();
}

// The "light count" debug view: a heat map of how many lights reach each pixel's surface.
graph::TextureId SceneRenderer::declareLightCountView(graph::RenderGraph& g) {
    const RenderSettings& s = settings_;
    debugViewFs_ = objects_.add(
        device_.createShader({.stage = gdi::ShaderStage::Fragment,
                              .binary = shaders::find("scene/debug_light_count.frag")}));
    debugViewPipeline_ =
        objects_.add(device_.createGraphicsPipeline({.vertexShader = fullscreenVs_,
                                                     .fragmentShader = debugViewFs_,
                                                     .colorFormats = {kRadianceFormat},
                                                     .debugName = "debug view light count"}));
    const graph::TextureId view = g.createTexture(
        "debug view", {.format = kRadianceFormat, .width = s.width, .height = s.height});
    g.addPass(
        "debug-view",
        [&](graph::PassBuilder& b) {
            b.sample(depth_);
            b.colorTarget(view);
        },
        [this](graph::PassContext& pc) {
            FrameConstants fc = frame_;
            fc.lightRange =
                glm::uvec4(0, gpuScene_->lightCount(), 0, 0);  // every light, shadowed ones too
            const UploadAllocation constants = queue_->upload(fc);
            pc.beginRenderPass();
            pc.cmd.setPipeline(debugViewPipeline_);
            pc.cmd.setUniformBuffer(kSlotFrame, constants.buffer, constants.offset, constants.size);
            pc.cmd.setStorageBuffer(kSlotLights, gpuScene_->lightBuffer());
            pc.cmd.setTexture(kSlotDepth, pc.texture(depth_), pointSampler_);
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
    return view;
}

graph::TextureId SceneRenderer::declareLightsEvaluatedView(graph::RenderGraph& g) {
    const RenderSettings& s = settings_;
    const LightLists lists = technique_->lightLists();
    if (lists.kind == LightLists::Kind::NotMeasured)
        throw gdi::Error(
            std::string("debug view '") + kLightsEvaluatedView + "': technique " + s.technique +
            " walks no per-pixel light list (light volumes or reduced-rate lists), so it is not measured");
    const bool everyLight = lists.kind == LightLists::Kind::EveryLight;
    debugViewFs_ = objects_.add(device_.createShader(
        {.stage = gdi::ShaderStage::Fragment,
         .binary = shaders::find(std::string("scene/debug_lights_evaluated.frag") +
                                 (everyLight ? ":FE_EVERY_LIGHT" : ""))}));
    debugViewPipeline_ =
        objects_.add(device_.createGraphicsPipeline({.vertexShader = fullscreenVs_,
                                                     .fragmentShader = debugViewFs_,
                                                     .colorFormats = {kRadianceFormat},
                                                     .debugName = "debug view lights evaluated"}));
    const graph::TextureId view = g.createTexture(
        "debug view", {.format = kRadianceFormat, .width = s.width, .height = s.height});
    const graph::TextureId counts = listCountsId_;
    g.addPass(
        "debug-view",
        [&](graph::PassBuilder& b) {
            b.sample(depth_);
            if (!everyLight) b.sample(counts);
            b.colorTarget(view);
        },
        [this, everyLight, counts](graph::PassContext& pc) {
            FrameConstants fc = frame_;
            fc.lightRange = glm::uvec4(0, gpuScene_->unshadowedLightCount(), 0,
                                       0);  // each shadowed light has its own pass
            const UploadAllocation constants = queue_->upload(fc);
            pc.beginRenderPass();
            pc.cmd.setPipeline(debugViewPipeline_);
            pc.cmd.setUniformBuffer(kSlotFrame, constants.buffer, constants.offset, constants.size);
            pc.cmd.setTexture(kSlotDepth, pc.texture(depth_), pointSampler_);
            if (!everyLight) pc.cmd.setTexture(kSlotTileLights, pc.texture(counts), pointSampler_);
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
    return view;
}

void SceneRenderer::updateLights(const std::vector<assets::Light>& lights) {
    if (lights.size() != shadowPlan_.order.size())
        throw gdi::Error("updateLights: " + std::to_string(lights.size()) +
                         " lights where the renderer was made for " +
                         std::to_string(shadowPlan_.order.size()));
    sceneLights_ = lights;
    std::vector<assets::Light> ordered;
    ordered.reserve(lights.size());
    for (uint32_t i : shadowPlan_.order) ordered.push_back(lights[i]);
    gpuScene_->updateLights(ordered, shadowPlan_.unshadowedCount);
}

void SceneRenderer::setCamera(const assets::Camera& camera) {
    try {
        assets::checkCamera(camera);
    } catch (const assets::AssetError& e) {
        throw gdi::Error(std::string("setCamera: ") + e.what());
    }
    camera_ = camera;
    context_->eye = camera.eye();
}

void SceneRenderer::updatePose() {
    gpuScene_->updatePose();
    if (deformation_) deformation_->poseChanged();
    updateLights(scene_.lights);
    if (scene_.camera) setCamera(*scene_.camera);
}

void SceneRenderer::renderFrame() { recordFrame({}); }

bool SceneRenderer::timersAccountForFrame(const std::vector<PassTiming>& passes, double frameMs) {
    double sum = 0;
    for (const PassTiming& p : passes) sum += p.gpuMilliseconds;
    return !passes.empty() && sum >= kTimersAccountFor * frameMs;
}

std::vector<PassTiming> SceneRenderer::profilePasses() {
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point t) {
        return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
    };
    device_.wait(lastFence_);
    std::vector<PassTiming> out;
    double overhead = std::numeric_limits<double>::infinity();
    recordFrame([&](const std::string& pass) {
        Clock::time_point t = Clock::now();
        device_.wait(queue_->flush());
        out.push_back({pass, ms(t)});
        t = Clock::now();
        device_.wait(queue_->flush());  // the same list, now empty: what a submission costs
        overhead = std::min(overhead, ms(t));
    });
    device_.wait(lastFence_);
    for (PassTiming& p : out) p.gpuMilliseconds = std::max(0.0, p.gpuMilliseconds - overhead);
    return out;
}

SceneRenderer::PassTimes SceneRenderer::measurePassTimes(const PassSamples& timestamps,
                                                         const std::vector<double>& frameMs,
                                                         uint32_t profiled) {
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    PassTimes out{.method = "gpu-timestamps", .passes = timestamps, .timestamps = timestamps};
    std::vector<PassTiming> medians;
    double sum = 0;
    for (const auto& [name, samples] : timestamps)
        medians.push_back({name, median(samples)}), sum += medians.back().gpuMilliseconds;
    const double frame = median(frameMs);
    out.timestampShare = frame > 0 ? sum / frame : 0.0;
    if (timersAccountForFrame(medians, frame) || profiled == 0) return out;
    out.method = "flush-and-wait";
    out.passes.clear();
    for (uint32_t f = 0; f < profiled; ++f)
        for (const PassTiming& p : profilePasses()) {
            auto it = std::find_if(out.passes.begin(), out.passes.end(),
                                   [&](const auto& e) { return e.first == p.name; });
            if (it == out.passes.end()) it = out.passes.insert(out.passes.end(), {p.name, {}});
            it->second.push_back(p.gpuMilliseconds);
        }
    return out;
}

void SceneRenderer::recordFrame(const std::function<void(const std::string&)>& afterPass) {
    const RenderSettings& s = settings_;
    const assets::Camera& cam = camera_;
    FrameConstants& fc = frame_;
    fc = {};
    const glm::mat4 unjittered = viewProjection(cam, float(s.width) / float(s.height));
    // TAA: every pass of the frame sees the projection moved by a sub-pixel offset (clip x and y
    // shifted by 2 x offset / size), so successive frames sample different points of each pixel.
    const glm::vec2 jitter = postProcess_->jitter(frameIndex_);
    fc.viewProj =
        glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * jitter.x / float(s.width),
                                                  2.0f * jitter.y / float(s.height), 0.0f)) *
        unjittered;
    fc.invViewProj = glm::inverse(fc.viewProj);
    fc.view = cam.viewFromWorld();
    glm::mat4 rotation = fc.view;  // eye space: the view without its translation
    rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    fc.viewProjFromEye =
        glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * jitter.x / float(s.width),
                                                  2.0f * jitter.y / float(s.height), 0.0f)) *
        projection(cam, float(s.width) / float(s.height)) * rotation;
    fc.invViewProjFromEye = glm::inverse(fc.viewProjFromEye);
    fc.cameraPosition = glm::vec4(cam.eye(), s.exposure);
    const glm::uvec2 background = background_->displayConstants();
    geometry_->setBrdf(resolveBrdf(s));
    fc.shading = glm::uvec4(resolveBrdf(s) == shading::Brdf::Separable ? 1u : 0u, background.x,
                            background.y, cam.orthographic ? 1u : 0u);
    fc.viewport = glm::vec4(s.width, s.height, 1.0f / s.width, 1.0f / s.height);
    const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale,
                   ih = (s.height + s.illumScale - 1) / s.illumScale;
    fc.illumViewport = glm::vec4(iw, ih, 1.0f / iw, 1.0f / ih);
    fc.temporal = glm::vec4(float(s.illumScale / 2), float(s.illumScale / 2), 0.0f, 0.0f);
    if (s.temporal) {
        const glm::uvec2 o = temporalOffset(s.illumScale, frameIndex_);
        const float history = frameIndex_ == 0               ? 0.0f
                              : fc.viewProj == prevViewProj_ ? 1.0f
                                                             : 2.0f;  // none, still, moved
        fc.temporal = glm::vec4(float(o.x), float(o.y), history, TemporalAccumulation::kMaxFrames);
    }
    fc.prevViewProj = frameIndex_ > 0 ? prevViewProj_ : fc.viewProj;
    prevViewProj_ = fc.viewProj;
    ++frameIndex_;
    // The techniques' own loops light the unshadowed lights; each shadowed one has its passes.
    const uint32_t unshadowed = gpuScene_->unshadowedLightCount();
    fc.counts = glm::uvec4(unshadowed, s.illumScale, s.iblSamples, gpuScene_->lightCount());
    fc.clusters = ClusterLightGrid::slicing(cam, scene_.bounds);
    // forward: the unshadowed lights, with emissive
    fc.lightRange = glm::uvec4(0, unshadowed, 1, 0);

    gdi::CommandList& cmd = queue_->beginFrame();
    if (clusters_) clusters_->beginFrame();  // the lists grow after an overflow
    frameConstants_ = queue_->upload(fc);
    // History from the second frame on; camera motion is handled by reprojection and clamping.
    postProcess_->beginFrame(*queue_, unjittered, frameIndex_ > 1);
    if (shadows_)
        shadows_->update(cam, projectionAspect(cam, float(s.width) / float(s.height)),
                         scene_.bounds, sceneLights_);
    // Async compute cuts the frame into submissions; a profiling run (afterPass) keeps one list.
    if (s.asyncCompute && !afterPass)
        graph_.execute(*queue_);
    else
        graph_.execute(cmd, afterPass);
    lastFence_ = queue_->endFrame();
}

gdi::Image SceneRenderer::readOutput() {
    device_.wait(lastFence_);
    return device_.readTexture(outputTexture_);
}

gdi::Image SceneRenderer::readDisplay() {
    if (!settings_.displayImage)
        throw gdi::Error(
            "readDisplay: the renderer was created without RenderSettings::displayImage");
    device_.wait(lastFence_);
    return device_.readTexture(graph_.handle(display_));
}

gdi::TextureHandle SceneRenderer::displayTexture() {
    if (!settings_.displayImage)
        throw gdi::Error(
            "displayTexture: the renderer was created without RenderSettings::displayImage");
    return graph_.handle(display_);
}

std::vector<PassTiming> SceneRenderer::passTimings() {
    device_.wait(lastFence_);
    return graph_.passTimings();
}

}  // namespace fe::render
