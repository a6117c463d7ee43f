#include "render/PostProcess.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderFeatures.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
const char* tonemapShader(shading::Tonemap t) {
    switch (t) {
        case shading::Tonemap::Aces:
            return "scene/display_aces.frag";
        case shading::Tonemap::PbrNeutral:
            return "scene/display_pbr_neutral.frag";
        case shading::Tonemap::Clamp:
            break;
    }
    return "scene/display.frag";
}
}  // namespace

PostProcess::PostProcess(gdi::Device& device, const RenderSettings& settings,
                         gdi::ShaderHandle fullscreenVs, const UploadAllocation& frameConstants,
                         uint32_t background)
    : objects_(device), device_(device), settings_(settings), frameConstants_(frameConstants) {
    const gdi::SamplerDesc clamp{.addressU = gdi::AddressMode::ClampToEdge,
                                 .addressV = gdi::AddressMode::ClampToEdge};
    gdi::SamplerDesc point = clamp;
    point.minFilter = point.magFilter = gdi::Filter::Nearest;
    pointSampler_ = objects_.add(device.createSampler(point));
    linearSampler_ = objects_.add(device.createSampler(clamp));
    auto fragment = [&](const char* name) {
        return objects_.add(device.createShader(
            {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(name)}));
    };
    tonemapFs_ = fragment(tonemapShader(settings.tonemap));
    // Specialized for the background: the paths of the others are not run (ShaderFeatures).
    tonemapPipeline_ = objects_.add(device.createGraphicsPipeline(
        {.vertexShader = fullscreenVs,
         .fragmentShader = tonemapFs_,
         .colorFormats = {kDisplayFormat},
         .specialization = declaredConstants(
             device, {tonemapFs_}, {gdi::SpecializationConstant::of(kBackgroundId, background)}),
         .debugName = "tonemap"}));
    if (settings.antiAliasing == AntiAliasing::Taa) {
        taaFs_ = fragment("scene/taa_resolve.frag");
        taaPipeline_ =
            objects_.add(device.createGraphicsPipeline({.vertexShader = fullscreenVs,
                                                        .fragmentShader = taaFs_,
                                                        .colorFormats = {gdi::Format::RGBA32F},
                                                        .debugName = "taa resolve"}));
        copyFs_ = fragment("scene/copy.frag");
        copyPipeline_ =
            objects_.add(device.createGraphicsPipeline({.vertexShader = fullscreenVs,
                                                        .fragmentShader = copyFs_,
                                                        .colorFormats = {gdi::Format::RGBA32F},
                                                        .debugName = "taa keep"}));
        history_ = objects_.add(device.createTexture(
            {.format = gdi::Format::RGBA32F,
             .width = settings.width,
             .height = settings.height,
             .usage = gdi::TextureUsage::Sampled | gdi::TextureUsage::RenderTarget,
             .debugName = "taa history"}));
    }
    if (settings.antiAliasing == AntiAliasing::Fxaa) {
        fxaaFs_ = fragment("scene/fxaa.frag");
        fxaaPipeline_ =
            objects_.add(device.createGraphicsPipeline({.vertexShader = fullscreenVs,
                                                        .fragmentShader = fxaaFs_,
                                                        .colorFormats = {kDisplayFormat},
                                                        .debugName = "fxaa"}));
    }
}

glm::vec2 PostProcess::jitter(uint64_t frameIndex) const {
    if (settings_.antiAliasing != AntiAliasing::Taa) return glm::vec2(0.0f);
    // The radical inverse of n in `base`: the Halton sequence, well spread over any prefix.
    auto halton = [](uint64_t n, uint64_t base) {
        double f = 1.0, r = 0.0;
        for (; n > 0; n /= base) f /= double(base), r += f * double(n % base);
        return float(r);
    };
    const uint64_t n = frameIndex % 8 + 1;
    return glm::vec2(halton(n, 2), halton(n, 3)) - 0.5f;
}

void PostProcess::beginFrame(CommandQueue& queue, const glm::mat4& viewProjUnjittered,
                             bool historyValid) {
    if (settings_.antiAliasing != AntiAliasing::Taa) return;
    struct {
        glm::mat4 prevViewProj;
        glm::vec4 params;
    } constants{previousViewProj_, glm::vec4(historyValid ? 1.0f : 0.0f, 0.1f, 0.0f, 0.0f)};
    taaConstants_ = queue.upload(constants);
    previousViewProj_ = viewProjUnjittered;
}

graph::TextureId PostProcess::declare(graph::RenderGraph& g, graph::TextureId radiance,
                                      graph::TextureId depth) {
    const RenderSettings& s = settings_;
    const bool fxaa = s.antiAliasing == AntiAliasing::Fxaa;
    if (s.antiAliasing == AntiAliasing::Taa) {
        // Resolve into a transient, then keep that as the next frame's history (a side effect:
        // nothing this frame reads it).
        const graph::TextureId history =
            g.importTexture("taa history", history_, device_.desc(history_));
        const graph::TextureId resolved = g.createTexture(
            "taa L_o", {.format = gdi::Format::RGBA32F, .width = s.width, .height = s.height});
        g.addPass(
            "taa-resolve",
            [&](graph::PassBuilder& b) {
                b.sample(radiance);
                b.sample(depth);
                b.sample(history);
                b.colorTarget(resolved);
            },
            [this, radiance, depth, history](graph::PassContext& pc) {
                pc.beginRenderPass();
                pc.cmd.setPipeline(taaPipeline_);
                pc.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset,
                                        frameConstants_.size);
                pc.cmd.setUniformBuffer(kSlotTaa, taaConstants_.buffer, taaConstants_.offset,
                                        taaConstants_.size);
                pc.cmd.setTexture(kSlotRadiance, pc.texture(radiance), pointSampler_);
                pc.cmd.setTexture(kSlotDepth, pc.texture(depth), pointSampler_);
                pc.cmd.setTexture(kSlotHistory0, pc.texture(history), linearSampler_);
                pc.cmd.draw(3);
                pc.cmd.endRenderPass();
            });
        g.addPass(
            "taa-keep",
            [&](graph::PassBuilder& b) {
                b.sample(resolved);
                b.colorTarget(history, gdi::LoadOp::DontCare);
                b.sideEffect();
            },
            [this, resolved](graph::PassContext& pc) {
                pc.beginRenderPass();
                pc.cmd.setPipeline(copyPipeline_);
                pc.cmd.setUniformBuffer(kSlotFrame, frameConstants_.buffer, frameConstants_.offset,
                                        frameConstants_.size);
                pc.cmd.setTexture(kSlotRadiance, pc.texture(resolved), pointSampler_);
                pc.cmd.draw(3);
                pc.cmd.endRenderPass();
            });
        radiance = resolved;
    }
    // With FXAA the tone-mapped image is an intermediate (sRGB-encoded, as FXAA's thresholds and
    // 8-bit precision expect); without, the tone mapper writes the display image itself.
    const graph::TextureId tonemapped =
        g.createTexture(fxaa ? "tonemapped sRGB" : "display sRGB",
                        {.format = kDisplayFormat, .width = s.width, .height = s.height});
    addFullscreenPass(g, fxaa ? "tonemap" : "display", radiance, tonemapped, tonemapPipeline_,
                      pointSampler_, frameConstants_);
    if (!fxaa) return tonemapped;
    const graph::TextureId display = g.createTexture(
        "display sRGB", {.format = kDisplayFormat, .width = s.width, .height = s.height});
    addFullscreenPass(g, "fxaa", tonemapped, display, fxaaPipeline_, linearSampler_,
                      frameConstants_);
    return display;
}

void addFullscreenPass(graph::RenderGraph& g, const char* name, graph::TextureId source,
                       graph::TextureId target, gdi::PipelineHandle pipeline,
                       gdi::SamplerHandle sampler, const UploadAllocation& frameConstants) {
    g.addPass(
        name,
        [&](graph::PassBuilder& b) {
            b.sample(source);
            b.colorTarget(target);
        },
        [source, pipeline, sampler, constants = &frameConstants](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setPipeline(pipeline);
            pc.cmd.setUniformBuffer(kSlotFrame, constants->buffer, constants->offset,
                                    constants->size);
            pc.cmd.setTexture(kSlotRadiance, pc.texture(source), sampler);
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
}

}  // namespace fe::render
