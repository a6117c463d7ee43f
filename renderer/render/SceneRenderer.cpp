#include "render/SceneRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "reference/CameraMath.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
constexpr gdi::Format kOutputFormat = gdi::Format::RGBA32F;  // linear L_o, exact enough for .pfm
constexpr gdi::Format kDepthFormat = gdi::Format::D32F;
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

gdi::TextureHandle SceneRenderer::makeTarget(const char* name, gdi::Format format, uint32_t w, uint32_t h) {
    gdi::TextureHandle t = device_.createTexture({.format = format, .width = w, .height = h,
                                                  .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled |
                                                           gdi::TextureUsage::CopySrc,
                                                  .debugName = name});
    ownedTextures_.push_back(t);
    targets_.push_back({name, format, w, h});
    return t;
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
    output_ = makeTarget("output L_o", kOutputFormat, s.width, s.height);
    depth_ = makeTarget("depth", kDepthFormat, s.width, s.height);
    pointSampler_ = device.createSampler({.minFilter = gdi::Filter::Nearest, .magFilter = gdi::Filter::Nearest,
                                          .addressU = gdi::AddressMode::ClampToEdge,
                                          .addressV = gdi::AddressMode::ClampToEdge});
    fullscreenVs_ = device.createShader({.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/fullscreen.vert")});
    if (s.technique != Technique::Forward) {
        gb0_ = makeTarget("gbuffer0 base colour+metallic", kGb0, s.width, s.height);
        gb1_ = makeTarget("gbuffer1 normal+roughness", kGb1, s.width, s.height);
        gb2_ = makeTarget("gbuffer2 emissive+unlit", kGb2, s.width, s.height);
    }
    const gdi::BindingSlot frameSlot{kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics};
    if (s.technique == Technique::Deferred) {
        volumes_ = std::make_unique<LightVolumes>(device, "scene/deferred_light.frag", std::vector{kOutputFormat},
                                                  gbufferSlots(true));
        fullscreenFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/emissive.frag")});
        fullscreenPipeline_ = device.createGraphicsPipeline({
            .vertexShader = fullscreenVs_, .fragmentShader = fullscreenFs_,
            .blend = {{.enable = true, .srcColor = gdi::BlendFactor::One, .dstColor = gdi::BlendFactor::One,
                       .srcAlpha = gdi::BlendFactor::One, .dstAlpha = gdi::BlendFactor::One}},
            .colorFormats = {kOutputFormat},
            .bindings = {frameSlot, {kSlotGBuffer2, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}},
            .debugName = "emissive"});
    } else if (s.technique == Technique::Redeferred) {
        const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale, ih = (s.height + s.illumScale - 1) / s.illumScale;
        i0_ = makeTarget("ibuffer0 L_dg", kI0, iw, ih);
        i1_ = makeTarget("ibuffer1 L_sg1", kI1, iw, ih);
        i2_ = makeTarget("ibuffer2 L_sg2", kI2, iw, ih);
        volumes_ = std::make_unique<LightVolumes>(device, "scene/illumination.frag", std::vector{kI0, kI1, kI2},
                                                  gbufferSlots(false));
        fullscreenFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/material.frag")});
        std::vector<gdi::BindingSlot> b = gbufferSlots(true);
        b.push_back(frameSlot);
        for (uint32_t slot : {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2})
            b.push_back({slot, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
        fullscreenPipeline_ = device.createGraphicsPipeline({.vertexShader = fullscreenVs_, .fragmentShader = fullscreenFs_,
                                                             .colorFormats = {kOutputFormat}, .bindings = b,
                                                             .debugName = "material"});
    }
}

SceneRenderer::~SceneRenderer() {
    queue_->waitIdle();
    for (auto& t : timers_) device_.destroy(t.timer);
    device_.destroy(fullscreenPipeline_);
    device_.destroy(fullscreenVs_);
    device_.destroy(fullscreenFs_);
    device_.destroy(pointSampler_);
    volumes_.reset();
    geometry_.reset();
    for (auto t : ownedTextures_) device_.destroy(t);
    gpuScene_.reset();
    queue_.reset();
}

void SceneRenderer::beginTimed(gdi::CommandList& cmd, const char* name) {
    if (timerCursor_ == timers_.size()) timers_.push_back({name, device_.createTimer()});
    timers_[timerCursor_].name = name;
    cmd.pushDebugGroup(name);
    if (device_.info().features.timestamps) cmd.beginTimer(timers_[timerCursor_].timer);
}

void SceneRenderer::endTimed(gdi::CommandList& cmd) {
    if (device_.info().features.timestamps) cmd.endTimer(timers_[timerCursor_].timer);
    cmd.popDebugGroup();
    ++timerCursor_;
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
    timerCursor_ = 0;
    UploadAllocation frame = queue_->upload(fc);
    const glm::vec3 eye = cam.eye();

    if (s.technique == Technique::Forward) {
        beginTimed(cmd, "forward");
        cmd.beginRenderPass({.colors = {{.texture = output_}}, .depth = {.texture = depth_}});
        geometry_->draw(cmd, *queue_, MeshPass::Forward, {{kOutputFormat}, kDepthFormat}, frame, eye);
        cmd.endRenderPass();
        endTimed(cmd);
    } else {
        beginTimed(cmd, "gbuffer");
        cmd.beginRenderPass({.colors = {{.texture = gb0_}, {.texture = gb1_}, {.texture = gb2_}}, .depth = {.texture = depth_}});
        geometry_->draw(cmd, *queue_, MeshPass::GBuffer, {{kGb0, kGb1, kGb2}, kDepthFormat}, frame, eye);
        cmd.endRenderPass();
        endTimed(cmd);
        auto bindGBuffer = [&](bool albedo) {
            if (albedo) cmd.setTexture(kSlotGBuffer0, gb0_, pointSampler_);
            cmd.setTexture(kSlotGBuffer1, gb1_, pointSampler_);
            cmd.setTexture(kSlotGBuffer2, gb2_, pointSampler_);
            cmd.setTexture(kSlotDepth, depth_, pointSampler_);
        };
        if (s.technique == Technique::Deferred) {
            beginTimed(cmd, "lighting");
            cmd.beginRenderPass({.colors = {{.texture = output_}}});
            bindGBuffer(true);
            volumes_->draw(cmd, *queue_, *gpuScene_, frame);
            endTimed(cmd);  // timer end inside the pass is allowed; begin is not
            cmd.setPipeline(fullscreenPipeline_);
            cmd.setUniformBuffer(kSlotFrame, frame.buffer, frame.offset, frame.size);
            cmd.setTexture(kSlotGBuffer2, gb2_, pointSampler_);
            cmd.draw(3);
            cmd.endRenderPass();
        } else {
            beginTimed(cmd, "illumination");
            cmd.beginRenderPass({.colors = {{.texture = i0_}, {.texture = i1_}, {.texture = i2_}}});
            bindGBuffer(false);
            volumes_->draw(cmd, *queue_, *gpuScene_, frame);
            cmd.endRenderPass();
            endTimed(cmd);
            beginTimed(cmd, "material");
            cmd.beginRenderPass({.colors = {{.texture = output_}}});
            cmd.setPipeline(fullscreenPipeline_);
            cmd.setUniformBuffer(kSlotFrame, frame.buffer, frame.offset, frame.size);
            bindGBuffer(true);
            cmd.setTexture(kSlotIBuffer0, i0_, pointSampler_);
            cmd.setTexture(kSlotIBuffer1, i1_, pointSampler_);
            cmd.setTexture(kSlotIBuffer2, i2_, pointSampler_);
            cmd.draw(3);
            cmd.endRenderPass();
            endTimed(cmd);
        }
    }
    if (gpuScene_->hasBlend()) {
        beginTimed(cmd, "transparent");
        cmd.beginRenderPass({.colors = {{.texture = output_, .load = gdi::LoadOp::Load}},
                             .depth = {.texture = depth_, .load = gdi::LoadOp::Load}});
        geometry_->draw(cmd, *queue_, MeshPass::Transparent, {{kOutputFormat}, kDepthFormat}, frame, eye);
        cmd.endRenderPass();
        endTimed(cmd);
    }
    lastFence_ = queue_->endFrame();
}

gdi::Image SceneRenderer::readOutput() {
    device_.wait(lastFence_);
    return device_.readTexture(output_);
}

std::vector<PassTiming> SceneRenderer::passTimings() {
    std::vector<PassTiming> out;
    device_.wait(lastFence_);
    if (!device_.info().features.timestamps) return out;
    for (size_t i = 0; i < timerCursor_; ++i)
        if (auto ns = device_.timerNanoseconds(timers_[i].timer)) out.push_back({timers_[i].name, *ns / 1e6});
    return out;
}

}  // namespace fe::render
