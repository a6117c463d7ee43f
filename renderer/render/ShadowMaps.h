// Layer 7 (Render): shadow maps on the render graph. For each light the plan shadows
// (ShadowPlan.h), declare() adds the passes that render its map, one per layer (cascade or
// cube face), then lets the technique add the pass that accumulates that light with the map.
// Each map is a transient texture that lives from its first layer's pass to its light's
// accumulation pass, so the graph gives every shadowed light the same memory in turn.
#pragma once
#include <functional>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/GeometryRenderer.h"
#include "render/GpuScene.h"
#include "render/ShadowPlan.h"

namespace fe::render {

class ShadowMaps {
public:
    // std140, as fe_shadow.glsl's ShadowBlock.
    struct Constants {
        glm::mat4 viewProj[4];
        glm::vec4 cascadeEnds;
        glm::vec4 texelWorld;
        glm::vec4 depthParams;
        glm::uvec4 params;  // x light buffer index, y cascade count (0: spot or cube)
    };
    // What an accumulation pass needs of one shadowed light.
    struct Light {
        uint32_t index = 0;     // into plan().shadowed
        uint32_t gpuLight = 0;  // the light's index in the light buffer
        ShadowKind kind = ShadowKind::Spot;
        graph::TextureId map;
        bool last = false;  // the last shadowed light (a forward technique resolves MSAA there)
    };
    using Accumulate = std::function<void(graph::RenderGraph&, const Light&)>;

    ShadowMaps(gdi::Device& device, CommandQueue& queue, GeometryRenderer& geometry,
               const ShadowPlan& plan, const ShadowSettings& settings);
    ShadowMaps(const ShadowMaps&) = delete;
    ShadowMaps& operator=(const ShadowMaps&) = delete;

    const ShadowPlan& plan() const { return plan_; }
    bool any() const { return !plan_.shadowed.empty(); }
    // Per frame, before the graph runs: the maps' projections for this camera and these lights
    // (scene order) and their uploads.
    void update(const assets::Camera& camera, float aspect, const assets::AABB& bounds,
                const std::vector<assets::Light>& sceneLights);
    // For each shadowed light: its map's passes, then `accumulate`.
    void declare(graph::RenderGraph& g, const Accumulate& accumulate);
    // Binds a shadowed light's constants and map (kSlotShadow, kSlotShadowMap).
    void bind(gdi::CommandList& cmd, const graph::PassContext& pc, const Light& light) const;

private:
    gdi::DeviceObjects objects_;
    CommandQueue& queue_;
    GeometryRenderer& geometry_;
    ShadowPlan plan_;
    ShadowSettings settings_;
    gdi::SamplerHandle sampler_;
    std::vector<UploadAllocation> constants_;  // per shadowed light
    std::vector<std::vector<UploadAllocation>>
        layers_;  // per shadowed light and layer: the casters' frame constants
    std::vector<glm::vec3> lightPositions_;  // per shadowed light, for the casters' draw order
    std::vector<UploadAllocation> objectConstants_;  // shared by every caster pass of a frame
};

}  // namespace fe::render
