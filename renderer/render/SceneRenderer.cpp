#include "render/SceneRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "reference/CameraMath.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
constexpr gdi::Format kOutputFormat = gdi::Format::RGBA32F;  // linear L_o, exact enough for .pfm
constexpr gdi::Format kDepthFormat = gdi::Format::D32F;
constexpr gdi::Format kDisplayFormat = gdi::Format::RGBA8_SRGB;  // what a screen shows
// G-buffer: base colour + metallic, world normal + roughness, emissive + unlit flag.
constexpr gdi::Format kGb0 = gdi::Format::RGBA8_SRGB, kGb1 = gdi::Format::RGBA16F, kGb2 = gdi::Format::RGBA16F;
// I-buffer: L_dg fits half floats; the alpha^2/(4 pi)-scaled specular sums reach ~2e4 x E at
// the roughness clamp, beyond half range for bright lights, so they are 32-bit.
constexpr gdi::Format kI0 = gdi::Format::RGBA16F, kI1 = gdi::Format::RGBA32F, kI2 = gdi::Format::RGBA32F;

std::vector<gdi::BindingSlot> gbufferSlots(bool albedo) {
    std::vector<gdi::BindingSlot> s;
    if (albedo) s.push_back({kSlotGBuffer0, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    s.push_back({kSlotGBuffer1, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    s.push_back({kSlotGBuffer2, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    s.push_back({kSlotDepth, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    return s;
}
}  // namespace

const char* techniqueName(Technique t) {
    switch (t) {
        case Technique::Deferred: return "deferred";
        case Technique::Redeferred: return "redeferred";
        default: return "forward";
    }
}

Technique techniqueFromName(const std::string& name) {
    if (name == "forward") return Technique::Forward;
    if (name == "deferred") return Technique::Deferred;
    if (name == "redeferred") return Technique::Redeferred;
    throw gdi::Error("unknown technique '" + name + "' (valid: forward, deferred, redeferred)");
}

SceneRenderer::SceneRenderer(gdi::Device& device, const assets::Scene& scene, const RenderSettings& s)
    : device_(device), scene_(scene), settings_(s) {
    if (s.width == 0 || s.height == 0 || s.width > 8192 || s.height > 8192)
        throw gdi::Error("render size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                         " out of range (1..8192 per axis)");
    if (s.illumScale != 1 && s.illumScale != 2 && s.illumScale != 4)
        throw gdi::Error("illumination scale must be 1, 2 or 4 (got " + std::to_string(s.illumScale) + ")");
    if (!scene.camera) throw gdi::Error("scene has no camera");
    queue_ = std::make_unique<CommandQueue>(device, 2);
    gpuScene_ = std::make_unique<GpuScene>(device, scene);
    geometry_ = std::make_unique<GeometryRenderer>(device, *gpuScene_);
    outputTexture_ = device.createTexture({.format = kOutputFormat, .width = s.width, .height = s.height,
                                           .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled |
                                                    gdi::TextureUsage::CopySrc,
                                           .debugName = "output L_o"});
    pointSampler_ = device.createSampler({.minFilter = gdi::Filter::Nearest, .magFilter = gdi::Filter::Nearest,
                                          .addressU = gdi::AddressMode::ClampToEdge,
                                          .addressV = gdi::AddressMode::ClampToEdge});
    fullscreenVs_ = device.createShader({.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/fullscreen.vert")});
    const gdi::BindingSlot frameSlot{kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics};
    if (s.technique == Technique::Deferred) {
        volumes_ = std::make_unique<LightVolumes>(device, "scene/deferred_light.frag", std::vector{kOutputFormat},
                                                  gbufferSlots(true));
        lightingFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/emissive.frag")});
        lightingPipeline_ = device.createGraphicsPipeline({
            .vertexShader = fullscreenVs_, .fragmentShader = lightingFs_,
            .blend = {{.enable = true, .srcColor = gdi::BlendFactor::One, .dstColor = gdi::BlendFactor::One,
                       .srcAlpha = gdi::BlendFactor::One, .dstAlpha = gdi::BlendFactor::One}},
            .colorFormats = {kOutputFormat},
            .bindings = {frameSlot, {kSlotGBuffer2, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}},
            .debugName = "emissive"});
    } else if (s.technique == Technique::Redeferred) {
        volumes_ = std::make_unique<LightVolumes>(device, "scene/illumination.frag", std::vector{kI0, kI1, kI2},
                                                  gbufferSlots(false));
        lightingFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/material.frag")});
        std::vector<gdi::BindingSlot> b = gbufferSlots(true);
        b.push_back(frameSlot);
        for (uint32_t slot : {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2})
            b.push_back({slot, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
        lightingPipeline_ = device.createGraphicsPipeline({.vertexShader = fullscreenVs_, .fragmentShader = lightingFs_,
                                                           .colorFormats = {kOutputFormat}, .bindings = b,
                                                           .debugName = "material"});
    }
    displayFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/display.frag")});
    displayPipeline_ = device.createGraphicsPipeline(
        {.vertexShader = fullscreenVs_, .fragmentShader = displayFs_, .colorFormats = {kDisplayFormat},
         .bindings = {frameSlot, {kSlotRadiance, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}},
         .debugName = "display"});
    buildGraph();
    graph_.compile(device, s.aliasing);
}

SceneRenderer::~SceneRenderer() {
    device_.waitIdleOrLost();  // a destructor must not throw, and a lost device runs nothing more
    for (auto p : {lightingPipeline_, displayPipeline_}) device_.destroy(p);
    for (auto sh : {fullscreenVs_, lightingFs_, displayFs_}) device_.destroy(sh);
    device_.destroy(pointSampler_);
    volumes_.reset();
    geometry_.reset();
    device_.destroy(outputTexture_);
    gpuScene_.reset();
    queue_.reset();
}

void SceneRenderer::bindGBuffer(gdi::CommandList& cmd, bool albedo) {
    const gdi::TextureHandle gb0 = graph_.handle(gb0_), gb1 = graph_.handle(gb1_), gb2 = graph_.handle(gb2_);
    if (albedo) cmd.setTexture(kSlotGBuffer0, gb0, pointSampler_);
    cmd.setTexture(kSlotGBuffer1, gb1, pointSampler_);
    cmd.setTexture(kSlotGBuffer2, gb2, pointSampler_);
    cmd.setTexture(kSlotDepth, graph_.handle(depth_), pointSampler_);
}

// The frame as a graph. Only what the technique and the scene need is declared; the graph
// culls what nothing reads (the display pass unless a display image is asked for).
void SceneRenderer::buildGraph() {
    const RenderSettings& s = settings_;
    graph::RenderGraph& g = graph_;
    const glm::vec3 eye = scene_.camera->eye();
    // The two pass bodies the techniques share: light volumes over the G-buffer, and one
    // full-screen triangle with the frame constants and some graph textures bound.
    auto lightVolumes = [this](bool albedo) {
        return [this, albedo](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            bindGBuffer(ctx.cmd, albedo);
            volumes_->draw(ctx.cmd, *queue_, *gpuScene_, frameConstants_);
            ctx.cmd.endRenderPass();
        };
    };
    using SlotTextures = std::vector<std::pair<uint32_t, graph::TextureId>>;
    auto fullscreen = [this](gdi::PipelineHandle pipeline, SlotTextures inputs) {
        return [this, pipeline, inputs](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            ctx.cmd.setPipeline(pipeline);
            ctx.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset, frameConstants_.size);
            for (const auto& [slot, id] : inputs) ctx.cmd.setTexture(slot, ctx.texture(id), pointSampler_);
            ctx.cmd.draw(3);
            ctx.cmd.endRenderPass();
        };
    };
    output_ = g.importTexture("output L_o", outputTexture_, device_.desc(outputTexture_));
    depth_ = g.createTexture("depth", {.format = kDepthFormat, .width = s.width, .height = s.height});

    if (s.technique == Technique::Forward) {
        g.addPass("forward", [&](graph::PassBuilder& b) {
            b.colorTarget(output_);
            b.depthTarget(depth_);
        }, [this, eye](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            geometry_->draw(ctx.cmd, *queue_, MeshPass::Forward, {{kOutputFormat}, kDepthFormat}, frameConstants_, eye);
            ctx.cmd.endRenderPass();
        });
    } else {
        gb0_ = g.createTexture("gbuffer0 base colour+metallic", {.format = kGb0, .width = s.width, .height = s.height});
        gb1_ = g.createTexture("gbuffer1 normal+roughness", {.format = kGb1, .width = s.width, .height = s.height});
        gb2_ = g.createTexture("gbuffer2 emissive+unlit", {.format = kGb2, .width = s.width, .height = s.height});
        g.addPass("gbuffer", [&](graph::PassBuilder& b) {
            for (auto t : {gb0_, gb1_, gb2_}) b.colorTarget(t);
            b.depthTarget(depth_);
        }, [this, eye](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            geometry_->draw(ctx.cmd, *queue_, MeshPass::GBuffer, {{kGb0, kGb1, kGb2}, kDepthFormat}, frameConstants_, eye);
            ctx.cmd.endRenderPass();
        });
    }
    if (s.technique == Technique::Deferred) {
        g.addPass("lighting", [&](graph::PassBuilder& b) {
            for (auto t : {gb0_, gb1_, gb2_, depth_}) b.sample(t);
            b.colorTarget(output_);
        }, lightVolumes(true));
        g.addPass("emissive", [&](graph::PassBuilder& b) {
            b.sample(gb2_);
            b.colorTarget(output_, gdi::LoadOp::Load);
        }, fullscreen(lightingPipeline_, {{kSlotGBuffer2, gb2_}}));
    } else if (s.technique == Technique::Redeferred) {
        const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale, ih = (s.height + s.illumScale - 1) / s.illumScale;
        i0_ = g.createTexture("ibuffer0 L_dg", {.format = kI0, .width = iw, .height = ih});
        i1_ = g.createTexture("ibuffer1 L_sg1", {.format = kI1, .width = iw, .height = ih});
        i2_ = g.createTexture("ibuffer2 L_sg2", {.format = kI2, .width = iw, .height = ih});
        g.addPass("illumination", [&](graph::PassBuilder& b) {
            for (auto t : {gb1_, gb2_, depth_}) b.sample(t);
            for (auto t : {i0_, i1_, i2_}) b.colorTarget(t);
        }, lightVolumes(false));
        g.addPass("material", [&](graph::PassBuilder& b) {
            for (auto t : {gb0_, gb1_, gb2_, depth_, i0_, i1_, i2_}) b.sample(t);
            b.colorTarget(output_);
        }, fullscreen(lightingPipeline_, {{kSlotGBuffer0, gb0_}, {kSlotGBuffer1, gb1_}, {kSlotGBuffer2, gb2_},
                                           {kSlotDepth, depth_}, {kSlotIBuffer0, i0_}, {kSlotIBuffer1, i1_},
                                           {kSlotIBuffer2, i2_}}));
    }
    if (gpuScene_->hasBlend()) {
        g.addPass("transparent", [&](graph::PassBuilder& b) {
            b.colorTarget(output_, gdi::LoadOp::Load);
            b.depthTarget(depth_, gdi::LoadOp::Load);
        }, [this, eye](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            geometry_->draw(ctx.cmd, *queue_, MeshPass::Transparent, {{kOutputFormat}, kDepthFormat}, frameConstants_, eye);
            ctx.cmd.endRenderPass();
        });
    }
    display_ = g.createTexture("display sRGB", {.format = kDisplayFormat, .width = s.width, .height = s.height});
    g.addPass("display", [&](graph::PassBuilder& b) {
        b.sample(output_);
        b.colorTarget(display_);
    }, fullscreen(displayPipeline_, {{kSlotRadiance, output_}}));
    g.markOutput(output_);
    if (s.displayImage) g.markOutput(display_);
}

void SceneRenderer::renderFrame() {
    const RenderSettings& s = settings_;
    const assets::Camera& cam = *scene_.camera;
    FrameConstants fc{};
    fc.viewProj = viewProjection(cam, float(s.width) / float(s.height));
    fc.invViewProj = glm::inverse(fc.viewProj);
    fc.cameraPosition = glm::vec4(cam.eye(), s.exposure);
    fc.viewport = glm::vec4(s.width, s.height, 1.0f / s.width, 1.0f / s.height);
    const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale, ih = (s.height + s.illumScale - 1) / s.illumScale;
    fc.illumViewport = glm::vec4(iw, ih, 1.0f / iw, 1.0f / ih);
    fc.counts = glm::uvec4(gpuScene_->lightCount(), s.illumScale, 0, 0);

    gdi::CommandList& cmd = queue_->beginFrame();
    frameConstants_ = queue_->upload(fc);
    graph_.execute(cmd);
    lastFence_ = queue_->endFrame();
}

gdi::Image SceneRenderer::readOutput() {
    device_.wait(lastFence_);
    return device_.readTexture(outputTexture_);
}

gdi::Image SceneRenderer::readDisplay() {
    if (!settings_.displayImage) throw gdi::Error("readDisplay: the renderer was created without RenderSettings::displayImage");
    device_.wait(lastFence_);
    return device_.readTexture(graph_.handle(display_));
}

gdi::TextureHandle SceneRenderer::displayTexture() {
    if (!settings_.displayImage) throw gdi::Error("displayTexture: the renderer was created without RenderSettings::displayImage");
    return graph_.handle(display_);
}

std::vector<PassTiming> SceneRenderer::passTimings() {
    device_.wait(lastFence_);
    return graph_.passTimings();
}

}  // namespace fe::render
