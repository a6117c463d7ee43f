// Layer 7: tiled deferred shading: the G-buffer, then the lights culled per 16x16 screen tile
// against the tile's depth bounds, and one compute pass in which every pixel shades only its
// tile's lights, once, writing L_o with no blending (shaders/include/fe_tiled_deferred_pass.glsl).
// The culling runs as a pass of its own (TileLightCulling) or, with
// RenderSettings::tileCullingPass off, inside the shading dispatch in shared memory.
// clustered-deferred is the same technique reading the light cluster grid (ClusterLightGrid):
// its lists do not depend on the depth, so the translucent pass after it reads them too.
#pragma once
#include <memory>

#include "render/ShadowedLightVolumes.h"

#include "render/EnvironmentLighting.h"
#include "render/GBuffer.h"
#include "render/TileLightCulling.h"

namespace fe::render {

class TiledDeferredRenderer final : public TechniqueRenderer {
public:
    enum class Lists { Tiles, Clusters };
    explicit TiledDeferredRenderer(TechniqueContext& context, Lists lists = Lists::Tiles);
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    // The one-pass form culls in shared memory: its lists are not kept (reported as every light).
    LightLists lightLists() const override {
        if (clusters_) return {LightLists::Kind::Clusters, {}};
        return culling_ ? LightLists{LightLists::Kind::Tiles, tiles_} : LightLists{};
    }
    static constexpr uint32_t kTileSize = 16;  // pixels per work group side

private:
    gdi::DeviceObjects objects_;
    std::unique_ptr<ShadowedLightVolumes> shadowed_;  // with shadows: each shadowed light's pass
    GBuffer gbuffer_;
    std::unique_ptr<EnvironmentLighting> ibl_;  // with --ibl-samples
    std::unique_ptr<TileLightCulling>
        culling_;            // null: culled in the shading dispatch, or clusters
    bool clusters_ = false;  // the lists of ctx_.clusters
    graph::TextureId tiles_;
    gdi::ShaderHandle cs_;
    std::unique_ptr<FeatureComputePipelines> pipelines_;  // by the frame's ShaderFeatures
};

}  // namespace fe::render
