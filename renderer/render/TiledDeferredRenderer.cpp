#include "render/TiledDeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

TiledDeferredRenderer::TiledDeferredRenderer(TechniqueContext& c) : TechniqueRenderer(c) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("technique deferred-tiled needs compute shaders, which " + c.device.info().backend + " lacks");
    cs_ = c.device.createShader({.stage = gdi::ShaderStage::Compute, .binary = shaders::find("scene/tiled_deferred.comp")});
    std::vector<gdi::BindingSlot> b = GBuffer::computeSlots(true);
    b.push_back({kSlotRadianceOut, gdi::BindingType::StorageTexture, gdi::ShaderStage::Compute});
    pipeline_ = c.device.createComputePipeline({.computeShader = cs_, .bindings = b, .debugName = "tiled lighting"});
}

TiledDeferredRenderer::~TiledDeferredRenderer() {
    ctx_.device.destroy(pipeline_);
    ctx_.device.destroy(cs_);
}

void TiledDeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    g.addPass("tiled-lighting", [&](graph::PassBuilder& b) {
        gbuffer_.sampleIn(b, true);
        b.storage(output);
    }, [this, output](graph::PassContext& pc) {
        bindFrameAndLights(pc.cmd, pipeline_);
        gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true);
        pc.cmd.setStorageTexture(kSlotRadianceOut, pc.texture(output));
        const RenderSettings& s = ctx_.settings;
        pc.cmd.dispatch((s.width + kTileSize - 1) / kTileSize, (s.height + kTileSize - 1) / kTileSize);
    });
}

}  // namespace fe::render
