// Layer 7: Forward+ (tiled forward shading: Harada, McKee and Yang 2012). A depth pre-pass, the
// light-culling pass of the tiled techniques on its depth (per-tile lists, TileLightCulling),
// then one forward pass where depth is EQUAL whose light loop walks the pixel's tile list
// (MeshPass::ForwardTiled, forward_plus*.frag). Forward, so it takes --msaa: the pre-pass depth
// is resolved (sample 0) for culling, and a fragment outside the depth bounds its tile was
// culled for shades every light, so an edge sample never loses one.
#pragma once
#include <memory>
#include <vector>

#include "render/TechniqueRenderer.h"
#include "render/TileLightCulling.h"

namespace fe::render {

class ForwardPlusRenderer final : public TechniqueRenderer {
public:
    explicit ForwardPlusRenderer(TechniqueContext& context);
    void declare(graph::RenderGraph& graph, graph::TextureId output, graph::TextureId depth) override;

private:
    TileLightCulling culling_;
    std::vector<UploadAllocation> objects_;  // object constants, shared by the passes of a frame
};

}  // namespace fe::render
