#include "render/GBuffer.h"

#include "render/ShaderSlots.h"

namespace fe::render {

std::string GBuffer::shader(const TechniqueContext& ctx, const std::string& name, bool occlusion) {
    if (ctx.settings.msaa <= 1) return name;
    return name + ":FE_MULTISAMPLED" + (occlusion && hasOcclusion(ctx) ? "+FE_OCCLUSION" : "");
}

bool GBuffer::hasOcclusion(const TechniqueContext& ctx) {
    return ctx.settings.ibl() && ctx.scene.hasOcclusion();
}

void GBuffer::declare(graph::RenderGraph& g, TechniqueContext& ctx, graph::TextureId sceneDepth) {
    const uint32_t w = ctx.settings.width, h = ctx.settings.height;
    samples = ctx.settings.msaa;
    auto target = [&](const char* name, gdi::Format format) {
        return g.createTexture(samples > 1 ? std::string("msaa ") + name : std::string(name),
                               {.format = format, .width = w, .height = h, .sampleCount = samples});
    };
    gb0 = target("gbuffer0 base colour+metallic", kFormat0);
    gb1 = target("gbuffer1 normal+roughness", kFormat1);
    gb2 = target("gbuffer2 emissive+unlit", kFormat2);
    depth = samples > 1 ? target("depth", kSceneDepthFormat) : sceneDepth;
    noOcclusion = ctx.scene.white();
    const bool occlusion = hasOcclusion(ctx);
    if (occlusion) gb3 = target("gbuffer3 occlusion", kFormat3);
    const uint32_t n = samples;
    g.addPass(
        "gbuffer",
        [&](graph::PassBuilder& b) {
            b.colorTarget(gb0);
            b.colorTarget(gb1);
            b.colorTarget(gb2, gdi::LoadOp::Clear,
                          {0, 0, 0, -1});  // alpha -1: nothing drawn (fe_scene.glsl)
            if (occlusion) b.colorTarget(gb3);
            b.depthTarget(depth);
            if (depth != sceneDepth) b.resolve(depth, sceneDepth);  // sample 0, for what follows
        },
        [&ctx, occlusion, n](graph::PassContext& pc) {
            pc.beginRenderPass();
            MeshPassTargets targets{{kFormat0, kFormat1, kFormat2}, kSceneDepthFormat, n};
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
    if (gb3.valid())
        cmd.setTexture(kSlotGBuffer3, pc.texture(gb3), sampler);
    else if (samples == 1)  // the multisampled variant without FE_OCCLUSION reads none
        cmd.setTexture(kSlotGBuffer3, noOcclusion, sampler);
}

void GBuffer::sampleOcclusionIn(graph::PassBuilder& b) const {
    if (gb3.valid()) b.sample(gb3);
}

void GBuffer::sampleIn(graph::PassBuilder& b, bool albedo) const {
    if (albedo) b.sample(gb0);
    for (auto t : {gb1, gb2, depth}) b.sample(t);
}

}  // namespace fe::render
