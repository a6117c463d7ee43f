#include "render/ForwardRenderer.h"

namespace fe::render {

void ForwardRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                              graph::TextureId depth) {
    const ForwardTargets t = forwardTargets(g, output, depth);
    g.addPass(
        "forward",
        [&](graph::PassBuilder& b) {
            b.colorTarget(t.color);
            b.depthTarget(t.depth);
            t.resolveIn(b);
        },
        [this, t](graph::PassContext& pc) {
            pc.beginRenderPass();
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::Forward, t.formats,
                               ctx_.frameConstants, ctx_.eye);
            pc.cmd.endRenderPass();
        });
    declareShadowedForward(g, t, nullptr);
}

}  // namespace fe::render
