#include "render/TransmissionPass.h"

#include <algorithm>
#include <cmath>

#include "render/ShaderSlots.h"

namespace fe::render {

TransmissionPass::TransmissionPass(TechniqueContext& context)
    : objects_(context.device), ctx_(context) {
    const RenderSettings& s = ctx_.settings;
    // L_o's format, so that a copy fills level 0; its mips need linear filtering (Vulkan makes
    // them by linear blits), which every device this engine has met offers for RGBA32F. One
    // without it gets the sharp copy alone: rough transmission then does not blur.
    const bool filtered = ctx_.device.formatCaps(kRadianceFormat).linearFilter;
    mips_ = filtered ? uint32_t(std::floor(std::log2(double(std::max(s.width, s.height))))) + 1 : 1;
    copy_ = objects_.add(
        ctx_.device.createTexture({.format = kRadianceFormat,
                                   .width = s.width,
                                   .height = s.height,
                                   .mipLevels = mips_,
                                   .usage = gdi::TextureUsage::Sampled |
                                            gdi::TextureUsage::CopySrc | gdi::TextureUsage::CopyDst,
                                   .debugName = "transmission: opaque scene copy"}));
    const gdi::Filter filter = filtered ? gdi::Filter::Linear : gdi::Filter::Nearest;
    sampler_ = objects_.add(ctx_.device.createSampler(
        {.minFilter = filter,
         .magFilter = filter,
         .mipFilter = filtered ? gdi::MipFilter::Linear : gdi::MipFilter::None,
         .addressU = gdi::AddressMode::ClampToEdge,
         .addressV = gdi::AddressMode::ClampToEdge}));
}

void TransmissionPass::declare(graph::RenderGraph& g, graph::TextureId radiance,
                               graph::TextureId depth) {
    const graph::TextureId copy =
        g.importTexture("transmission: opaque scene copy", copy_, ctx_.device.desc(copy_));
    g.addPass(
        "transmission-source",
        [&](graph::PassBuilder& b) {
            b.copySource(radiance);
            b.copyDestination(copy);
        },
        [this, radiance](graph::PassContext& pc) {
            pc.cmd.copyTexture(copy_, gdi::TextureRegion{}, pc.texture(radiance),
                               gdi::TextureRegion{});
            if (mips_ == 1) return;
            // Level 0, written by the copy, is what the first blit reads.
            const gdi::TextureBarrier level0{.texture = copy_,
                                             .before = gdi::ResourceState::CopyDst,
                                             .after = gdi::ResourceState::CopySrc,
                                             .baseMip = 0,
                                             .mipCount = 1};
            pc.cmd.barrier(&level0, 1);
            pc.cmd.generateMips(copy_);
        });
    g.addPass(
        "transmission",
        [&](graph::PassBuilder& b) {
            b.colorTarget(radiance, gdi::LoadOp::Load);
            b.depthTarget(depth, gdi::LoadOp::Load);
            b.sample(copy);
        },
        [this](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setTexture(kSlotTransmitted, copy_, sampler_);
            // Every light (the shadowed ones without their shadows, as for blended surfaces), under
            // the glTF model: transmission is one of its lobes.
            FrameConstants fc = ctx_.frame;
            fc.lightRange = glm::uvec4(0, ctx_.scene.lightCount(), 1, 0);
            fc.shading.x = 0u;  // FE_BRDF_GLTF
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::Transmission,
                               {{kRadianceFormat}, kSceneDepthFormat}, ctx_.queue.upload(fc),
                               ctx_.eye);
            pc.cmd.endRenderPass();
        });
}

}  // namespace fe::render
