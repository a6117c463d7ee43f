#include "render/ForwardRenderer.h"

namespace fe::render {

void ForwardRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    g.addPass("forward", [&](graph::PassBuilder& b) {
        b.colorTarget(output);
        b.depthTarget(depth);
    }, [this](graph::PassContext& pc) {
        pc.beginRenderPass();
        ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::Forward, {{kRadianceFormat}, kSceneDepthFormat}, ctx_.frameConstants,
                           ctx_.eye);
        pc.cmd.endRenderPass();
    });
}

}  // namespace fe::render
