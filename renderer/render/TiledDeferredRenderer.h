// Layer 7: tiled deferred shading: the G-buffer, then one compute pass in which each 16x16
// screen tile culls the lights against its depth bounds and every pixel shades only its
// tile's lights, once, writing L_o with no blending (shaders/scene/tiled_deferred.comp).
#pragma once
#include "render/GBuffer.h"

namespace fe::render {

class TiledDeferredRenderer final : public TechniqueRenderer {
public:
    explicit TiledDeferredRenderer(TechniqueContext& context);
    ~TiledDeferredRenderer() override;
    void declare(graph::RenderGraph& graph, graph::TextureId output, graph::TextureId depth) override;
    static constexpr uint32_t kTileSize = 16;

private:
    GBuffer gbuffer_;
    gdi::ShaderHandle cs_;
    gdi::PipelineHandle pipeline_;
};

}  // namespace fe::render
