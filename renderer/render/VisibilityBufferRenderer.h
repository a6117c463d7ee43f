// Layer 7: the visibility buffer (Burns and Hunt 2013, "The Visibility Buffer: A Cache-Friendly
// Approach to Deferred Shading"): one geometry pass writes a 32-bit triangle id and the depth
// per pixel (8 bytes a pixel, against the G-buffer's 24), then a compute pass rebuilds each
// pixel's surface from its triangle (vertices pulled from the scene's buffers, barycentrics
// of the view ray, texture gradients from the neighbouring pixels' rays) and shades its
// cluster's lights (ClusterLightGrid), once. Without bindless textures the resolve runs once
// per texture set of the scene's materials (GpuScene::textureSets; the built-in scenes have
// one), each dispatch shading the pixels of its set. Shadowed lights add forward passes
// tested EQUAL against the visibility pass's depth, which pulls the same vertices mesh.vert reads.
// With --msaa N they render into a multisampled target of their own against the multisampled
// depth, resolved once after the last and added into L_o by a full-screen pass.
#pragma once
#include <memory>
#include <vector>

#include "render/TechniqueRenderer.h"

namespace fe::render {

class VisibilityBufferRenderer final : public TechniqueRenderer {
public:
    explicit VisibilityBufferRenderer(TechniqueContext& context);
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    LightLists lightLists() const override { return {LightLists::Kind::Clusters, {}}; }
    static constexpr gdi::Format kIdFormat = gdi::Format::R32U;
    static constexpr uint32_t kGroupSize =
        16;  // pixels per work group side (fe_visibility_resolve_pass.glsl)

private:
    gdi::DeviceObjects objects_;
    bool uniformLights_ = false;
    gdi::BufferHandle draws_;  // every draw's ObjectConstants, in scene order
    gdi::ShaderHandle cs_;
    std::unique_ptr<FeatureComputePipelines> pipelines_;  // by the frame's ShaderFeatures
    gdi::ShaderHandle addFs_;          // --msaa with shadows: the resolved shadowed lights ...
    gdi::PipelineHandle addPipeline_;  // ... added into L_o
    std::vector<UploadAllocation>
        objectUploads_;  // the visibility pass's, reused by the shadowed lights' passes
};

}  // namespace fe::render
