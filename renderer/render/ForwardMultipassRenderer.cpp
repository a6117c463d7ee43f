#include "render/ForwardMultipassRenderer.h"

namespace fe::render {

void ForwardMultipassRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                       graph::TextureId depth) {
    if (ctx_.scene.lightCount() > kMaxLights)
        throw gdi::Error("forward-multipass draws the scene once per light: " +
                         std::to_string(ctx_.scene.lightCount()) +
                         " lights would be as many passes (at most " + std::to_string(kMaxLights) +
                         "; forward, deferred or deferred-tiled take any number)");
    const ForwardTargets t = forwardTargets(g, output, depth);
    g.addPass(
        "forward-multipass",
        [&](graph::PassBuilder& b) {
            b.colorTarget(t.color);
            b.depthTarget(t.depth);
            t.resolveIn(b);
        },
        [this, t](graph::PassContext& pc) {
            pc.beginRenderPass();
            objects_.clear();
            const MeshPassTargets& targets = t.formats;
            // With no light at all, one pass still lays down depth, emissive and unlit surfaces.
            const uint32_t lights = std::max(1u, ctx_.frame.counts.x);
            for (uint32_t i = 0; i < lights; ++i) {
                FrameConstants fc = ctx_.frame;
                fc.lightRange = glm::uvec4(i, ctx_.frame.counts.x ? 1u : 0u, i == 0 ? 1u : 0u, 0u);
                const UploadAllocation perLight = ctx_.queue.upload(fc);
                ctx_.geometry.draw(pc.cmd, ctx_.queue,
                                   i == 0 ? MeshPass::Forward : MeshPass::ForwardAdditive, targets,
                                   perLight, ctx_.eye, &objects_);
            }
            pc.cmd.endRenderPass();
        });
    declareShadowedForward(g, t, &objects_);
}

}  // namespace fe::render
