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
    addFullscreenPass(g, fxaa ? "tonemap" : "display", radiance, tonemapped, tonemapPipeline_, pointSampler_, frameConstants_);
    if (!fxaa) return tonemapped;
    const graph::TextureId display = g.createTexture("display sRGB", {.format = kDisplayFormat, .width = s.width, .height = s.height});
    addFullscreenPass(g, "fxaa", tonemapped, display, fxaaPipeline_, linearSampler_, frameConstants_);
    return display;
}

void addFullscreenPass(graph::RenderGraph& g, const char* name, graph::TextureId source, graph::TextureId target,
                       gdi::PipelineHandle pipeline, gdi::SamplerHandle sampler, const UploadAllocation& frameConstants) {
    g.addPass(name, [&](graph::PassBuilder& b) {
        b.sample(source);
        b.colorTarget(target);
    }, [source, pipeline, sampler, constants = &frameConstants](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setPipeline(pipeline);
        pc.cmd.setUniformBuffer(kSlotFrame, constants->buffer, constants->offset, constants->size);
        pc.cmd.setTexture(kSlotRadiance, pc.texture(source), sampler);
        pc.cmd.draw(3);
        pc.cmd.endRenderPass();
    });
}

}  // namespace fe::render
