// Layer 7: forward with a Z pre-pass (Carmack's, in the deck): opaque geometry is first drawn
// depth-only, front to back; then every pixel is shaded once, by the surface whose depth
// EQUALs the pre-pass depth, with no depth writes. The pre-pass and the shading pass are one
// graph pass each, so their GPU times are reported apart.
#pragma once
#include <vector>

#include "render/TechniqueRenderer.h"

namespace fe::render {

class ForwardZPrepassRenderer final : public TechniqueRenderer {
public:
    using TechniqueRenderer::TechniqueRenderer;
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;

private:
    std::vector<UploadAllocation> objects_;  // object constants, shared by both passes of a frame
};

}  // namespace fe::render
