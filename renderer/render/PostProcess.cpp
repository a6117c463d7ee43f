#include "render/PostProcess.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
const char* tonemapShader(shading::Tonemap t) {
    switch (t) {
        case shading::Tonemap::Aces: return "scene/display_aces.frag";
        case shading::Tonemap::PbrNeutral: return "scene/display_pbr_neutral.frag";
        case shading::Tonemap::Clamp: break;
    }
    return "scene/display.frag";
}
}  // namespace

PostProcess::PostProcess(gdi::Device& device, const RenderSettings& settings, gdi::ShaderHandle fullscreenVs,
                         const UploadAllocation& frameConstants)
    : device_(device), settings_(settings), frameConstants_(frameConstants) {
    const gdi::SamplerDesc clamp{.addressU = gdi::AddressMode::ClampToEdge, .addressV = gdi::AddressMode::ClampToEdge};
    gdi::SamplerDesc point = clamp;
    point.minFilter = point.magFilter = gdi::Filter::Nearest;
    pointSampler_ = device.createSampler(point);
    linearSampler_ = device.createSampler(clamp);
    const std::vector<gdi::BindingSlot> bindings = {
        {kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics},
        {kSlotRadiance, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}};
    tonemapFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(tonemapShader(settings.tonemap))});
    tonemapPipeline_ = device.createGraphicsPipeline({.vertexShader = fullscreenVs, .fragmentShader = tonemapFs_,
                                                      .colorFormats = {kDisplayFormat}, .bindings = bindings,
                                                      .debugName = "tonemap"});
    if (settings.antiAliasing == AntiAliasing::Fxaa) {
        fxaaFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/fxaa.frag")});
        fxaaPipeline_ = device.createGraphicsPipeline({.vertexShader = fullscreenVs, .fragmentShader = fxaaFs_,
                                                       .colorFormats = {kDisplayFormat}, .bindings = bindings,
                                                       .debugName = "fxaa"});
    }
}

PostProcess::~PostProcess() {
    for (gdi::PipelineHandle p : {tonemapPipeline_, fxaaPipeline_})
        if (p) device_.destroy(p);
    for (gdi::ShaderHandle s : {tonemapFs_, fxaaFs_})
        if (s) device_.destroy(s);
    device_.destroy(pointSampler_);
    device_.destroy(linearSampler_);
}

graph::TextureId PostProcess::declare(graph::RenderGraph& g, graph::TextureId radiance) {
    const RenderSettings& s = settings_;
    const bool fxaa = s.antiAliasing == AntiAliasing::Fxaa;
    // With FXAA the tone-mapped image is an intermediate (sRGB-encoded, as FXAA's thresholds and
    // 8-bit precision expect); without, the tone mapper writes the display image itself.
    const graph::TextureId tonemapped = g.createTexture(fxaa ? "tonemapped sRGB" : "display sRGB",
                                                        {.format = kDisplayFormat, .width = s.width, .height = s.height});
    g.addPass(fxaa ? "tonemap" : "display", [&](graph::PassBuilder& b) {
        b.sample(radiance);
        b.colorTarget(tonemapped);
    }, [this, radiance](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setPipeline(tonemapPipeline_);
        pc.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset, frameConstants_.size);
        pc.cmd.setTexture(kSlotRadiance, pc.texture(radiance), pointSampler_);
        pc.cmd.draw(3);
        pc.cmd.endRenderPass();
    });
    if (!fxaa) return tonemapped;
    const graph::TextureId display = g.createTexture("display sRGB", {.format = kDisplayFormat, .width = s.width, .height = s.height});
    g.addPass("fxaa", [&](graph::PassBuilder& b) {
        b.sample(tonemapped);
        b.colorTarget(display);
    }, [this, tonemapped](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setPipeline(fxaaPipeline_);
        pc.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset, frameConstants_.size);
        pc.cmd.setTexture(kSlotRadiance, pc.texture(tonemapped), linearSampler_);
        pc.cmd.draw(3);
        pc.cmd.endRenderPass();
    });
    return display;
}

}  // namespace fe::render
