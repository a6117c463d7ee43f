// Layer 7: forward shading, one pass, every light in the fragment shader's loop.
#pragma once
#include "render/TechniqueRenderer.h"

namespace fe::render {

class ForwardRenderer final : public TechniqueRenderer {
public:
    using TechniqueRenderer::TechniqueRenderer;
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
};

}  // namespace fe::render
