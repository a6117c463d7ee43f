#include "render/GBuffer.h"

#include "render/ShaderSlots.h"

namespace fe::render {

void GBuffer::declare(graph::RenderGraph& g, TechniqueContext& ctx, graph::TextureId sceneDepth) {
    const uint32_t w = ctx.settings.width, h = ctx.settings.height;
    gb0 = g.createTexture("gbuffer0 base colour+metallic",
                          {.format = kFormat0, .width = w, .height = h});
    gb1 =
        g.createTexture("gbuffer1 normal+roughness", {.format = kFormat1, .width = w, .height = h});
    gb2 = g.createTexture("gbuffer2 emissive+unlit", {.format = kFormat2, .width = w, .height = h});
    depth = sceneDepth;
    noOcclusion = ctx.scene.white();
    const bool occlusion = ctx.settings.ibl() && ctx.scene.hasOcclusion();
    if (occlusion)
        gb3 = g.createTexture("gbuffer3 occlusion", {.format = kFormat3, .width = w, .height = h});
    g.addPass(
        "gbuffer",
        [&](graph::PassBuilder& b) {
            b.colorTarget(gb0);
            b.colorTarget(gb1);
            b.colorTarget(gb2, gdi::LoadOp::Clear,
                          {0, 0, 0, -1});  // alpha -1: nothing drawn (fe_scene.glsl)
            if (occlusion) b.colorTarget(gb3);
            b.depthTarget(depth);
        },
        [&ctx, occlusion](graph::PassContext& pc) {
            pc.beginRenderPass();
            MeshPassTargets targets{{kFormat0, kFormat1, kFormat2}, kSceneDepthFormat};
            if (occlusion)
                targets.colorFormats.push_back(
                    kFormat3);  // the G-buffer shader's occlusion variant
            ctx.geometry.draw(pc.cmd, ctx.queue, MeshPass::GBuffer, targets, ctx.frameConstants,
                              ctx.eye);
            pc.cmd.endRenderPass();
        });
}

void GBuffer::bind(gdi::CommandList& cmd, const graph::PassContext& pc, gdi::SamplerHandle sampler,
                   bool albedo) const {
    if (albedo) cmd.setTexture(kSlotGBuffer0, pc.texture(gb0), sampler);
    cmd.setTexture(kSlotGBuffer1, pc.texture(gb1), sampler);
    cmd.setTexture(kSlotGBuffer2, pc.texture(gb2), sampler);
    cmd.setTexture(kSlotDepth, pc.texture(depth), sampler);
}

void GBuffer::bindOcclusion(gdi::CommandList& cmd, const graph::PassContext& pc,
                            gdi::SamplerHandle sampler) const {
    cmd.setTexture(kSlotGBuffer3, gb3.valid() ? pc.texture(gb3) : noOcclusion, sampler);
}

void GBuffer::sampleOcclusionIn(graph::PassBuilder& b) const {
    if (gb3.valid()) b.sample(gb3);
}

void GBuffer::sampleIn(graph::PassBuilder& b, bool albedo) const {
    if (albedo) b.sample(gb0);
    for (auto t : {gb1, gb2, depth}) b.sample(t);
}

}  // namespace fe::render
