// Layer 7: multi-pass forward (the deck's "option 2"): the scene is drawn once per light, the
// first time with depth writes, emissive and unlit terms, then once more per further light
// with depth test EQUAL, adding that light's radiance. Its cost grows with objects x lights,
// which is what it is here to show.
#pragma once
#include <vector>

#include "render/TechniqueRenderer.h"

namespace fe::render {

class ForwardMultipassRenderer final : public TechniqueRenderer {
public:
    using TechniqueRenderer::TechniqueRenderer;
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    // More lights than this are refused with the reason: each would be a pass over the scene
    // (the stability suite's 4096 and 65536 lights).
    static constexpr uint32_t kMaxLights = 1024;

private:
    std::vector<UploadAllocation> objects_;  // object constants, uploaded once per frame
};

}  // namespace fe::render
