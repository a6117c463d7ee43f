// Layer 7: forward shading over light lists, after a depth pre-pass.
//  forward-plus (Forward+, tiled forward shading: Harada, McKee and Yang 2012): the light-culling
//    pass of the tiled techniques on the pre-pass depth (per-tile lists, TileLightCulling), then
//    one forward pass where depth is EQUAL whose light loop walks the pixel's tile list
//    (MeshPass::ForwardTiled, forward_plus*.frag). With --msaa the pre-pass depth is resolved
//    (sample 0) for culling, and a fragment outside the depth bounds its tile was culled for
//    walks its cluster's list (ClusterLightGrid, built then too), so an edge sample never loses
//    a light and never walks every light.
//  clustered-forward (Olsson, Billeter and Assarsson 2012): the same shading pass walking the
//    fragment's cluster list (ClusterLightGrid, MeshPass::ForwardClustered); at one sample the
//    lists are bounded by the pre-pass depth (declareBounded), under MSAA they need none.
#pragma once
#include <memory>
#include <vector>

#include "render/TechniqueRenderer.h"
#include "render/TileLightCulling.h"

namespace fe::render {

class ForwardPlusRenderer final : public TechniqueRenderer {
public:
    enum class Lists { Tiles, Clusters };
    ForwardPlusRenderer(TechniqueContext& context, Lists lists);
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    LightLists lightLists() const override {
        return culling_ ? LightLists{LightLists::Kind::Tiles, tiles_}
                        : LightLists{LightLists::Kind::Clusters, {}};
    }

private:
    graph::TextureId tiles_;
    std::unique_ptr<TileLightCulling> culling_;  // the tile lists; null: the cluster grid's
    std::vector<UploadAllocation> objects_;  // object constants, shared by the passes of a frame
};

}  // namespace fe::render
