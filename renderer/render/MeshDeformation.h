// Layer 7: glTF skins and morph targets on the device. Every animated primitive
// (GpuScene::deformations) has vertices of its own beside the rest pose; the "deform meshes"
// pass, first in the frame, writes them: the rest pose morphed by the instance's weights and
// skinned by its joint matrices (assets::MeshInstance, kept by assets::poseScene), one compute
// dispatch for them all (scene/mesh_deform.comp: a table says which primitive each work group
// deforms). Every later pass (each technique, the shadow maps, the visibility buffer's resolve,
// light assignment) reads those vertices as it reads any, so they all see the same deformed
// mesh, and captures hold the dispatch like any other work.
#pragma once
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "graph/RenderGraph.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class MeshDeformation {
public:
    // Throws gdi::Error when the device has no compute shaders (no backend of ours lacks them).
    explicit MeshDeformation(TechniqueContext& context);
    MeshDeformation(const MeshDeformation&) = delete;
    MeshDeformation& operator=(const MeshDeformation&) = delete;

    // Adds the pass; it uploads the instances' current joints and weights and deforms, in the
    // first frame and in each frame after poseChanged(); a still pose costs nothing (the
    // deformed vertices stay in the vertex buffer).
    void declare(graph::RenderGraph& graph);
    void poseChanged() { dirty_ = true; }

private:
    void record(gdi::CommandList& cmd);

    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    gdi::ShaderHandle shader_;
    gdi::PipelineHandle pipeline_;
    gdi::BufferHandle records_,
        groups_;  // what each deformation reads and writes; each work group's deformation
    uint32_t groupCount_ = 0;
    bool dirty_ = true;
    std::vector<uint32_t> jointFirst_,
        weightFirst_;                   // per instance: where its joints and weights go in the pose
    std::vector<uint32_t> jointCount_;  // ... and how many joints it was laid out for
};

}  // namespace fe::render
