#include "render/GBuffer.h"

#include "render/ShaderSlots.h"

namespace fe::render {

void GBuffer::declare(graph::RenderGraph& g, TechniqueContext& ctx, graph::TextureId sceneDepth) {
    const uint32_t w = ctx.settings.width, h = ctx.settings.height;
    gb0 = g.createTexture("gbuffer0 base colour+metallic", {.format = kFormat0, .width = w, .height = h});
    gb1 = g.createTexture("gbuffer1 normal+roughness", {.format = kFormat1, .width = w, .height = h});
    gb2 = g.createTexture("gbuffer2 emissive+unlit", {.format = kFormat2, .width = w, .height = h});
    depth = sceneDepth;
    g.addPass("gbuffer", [&](graph::PassBuilder& b) {
        b.colorTarget(gb0);
        b.colorTarget(gb1);
        b.colorTarget(gb2, gdi::LoadOp::Clear, {0, 0, 0, -1});  // alpha -1: nothing drawn (fe_scene.glsl)
        b.depthTarget(depth);
    }, [&ctx](graph::PassContext& pc) {
        pc.beginRenderPass();
        ctx.geometry.draw(pc.cmd, ctx.queue, MeshPass::GBuffer, {{kFormat0, kFormat1, kFormat2}, kSceneDepthFormat},
                          ctx.frameConstants, ctx.eye);
        pc.cmd.endRenderPass();
    });
}

void GBuffer::bind(gdi::CommandList& cmd, const graph::PassContext& pc, gdi::SamplerHandle sampler, bool albedo) const {
    if (albedo) cmd.setTexture(kSlotGBuffer0, pc.texture(gb0), sampler);
    cmd.setTexture(kSlotGBuffer1, pc.texture(gb1), sampler);
    cmd.setTexture(kSlotGBuffer2, pc.texture(gb2), sampler);
    cmd.setTexture(kSlotDepth, pc.texture(depth), sampler);
}

void GBuffer::sampleIn(graph::PassBuilder& b, bool albedo) const {
    if (albedo) b.sample(gb0);
    for (auto t : {gb1, gb2, depth}) b.sample(t);
}

}  // namespace fe::render
