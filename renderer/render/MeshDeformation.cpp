#include "render/MeshDeformation.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/GpuScene.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
// mesh_deform.comp's DeformConstants.
struct DeformConstants {
    glm::uvec4 vertexRange;  // rest first, output first, count, flat normals
    glm::uvec4 sources;      // first influence (~0: none), first joint vec4, first delta, targets
    glm::uvec4 weights;      // first weight (floats)
};
}  // namespace

MeshDeformation::MeshDeformation(TechniqueContext& c) : objects_(c.device), ctx_(c) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("skinned or morphed meshes are deformed by a compute shader, which this device lacks");
    shader_ = objects_.add(c.device.createShader({.stage = gdi::ShaderStage::Compute, .binary = shaders::find("scene/mesh_deform.comp")}));
    pipeline_ = objects_.add(c.device.createComputePipeline({.computeShader = shader_, .debugName = "mesh deformation"}));
}

void MeshDeformation::declare(graph::RenderGraph& g) {
    // The vertices are read by nearly every pass, which do not declare it: the pass orders its
    // writes after the previous frame's reads and before this frame's with barriers of its own.
    g.addPass("deform meshes", [&](graph::PassBuilder& b) { b.sideEffect(); },
              [this](graph::PassContext& pc) { record(pc.cmd); });
}

void MeshDeformation::record(gdi::CommandList& cmd) {
    const GpuScene& gpu = ctx_.scene;
    const assets::Scene& scene = gpu.scene();
    // The pose: each deformed instance's joint matrices, then its weights, 4 to a vec4.
    std::vector<glm::vec4> pose;
    std::vector<uint32_t> jointFirst(scene.instances.size(), 0), weightFirst(scene.instances.size(), 0);
    uint32_t previous = ~0u;
    for (const Deformation& d : gpu.deformations()) {
        if (d.instance == previous) continue;
        previous = d.instance;
        const assets::MeshInstance& inst = scene.instances[d.instance];
        jointFirst[d.instance] = uint32_t(pose.size());
        for (const glm::mat4& m : inst.joints) pose.insert(pose.end(), {m[0], m[1], m[2], m[3]});
        weightFirst[d.instance] = uint32_t(pose.size() * 4);
        for (size_t w = 0; w < inst.weights.size(); w += 4) {
            glm::vec4 v(0.0f);
            for (size_t k = 0; k < 4 && w + k < inst.weights.size(); ++k) v[int(k)] = inst.weights[w + k];
            pose.push_back(v);
        }
    }
    if (pose.empty()) pose.emplace_back(0.0f);
    const UploadAllocation posed = ctx_.queue.upload(gdi::bytesOf(pose));
    const gdi::BufferHandle vertices = gpu.vertexBuffer();
    using A = gdi::BufferAccess;
    cmd.barrier(gdi::BufferBarrier{.buffer = vertices, .before = A::Vertex | A::StorageRead, .after = A::StorageRead | A::StorageWrite});
    cmd.setPipeline(pipeline_);
    cmd.setStorageBuffer(kSlotVertices, vertices);
    cmd.setStorageBuffer(kSlotSkin, gpu.skinBuffer());
    cmd.setStorageBuffer(kSlotMorphTargets, gpu.morphBuffer());
    cmd.setStorageBuffer(kSlotPose, posed.buffer, posed.offset, posed.size);
    for (const Deformation& d : gpu.deformations()) {
        const assets::MeshInstance& inst = scene.instances[d.instance];
        const bool skinned = d.skinFirst != ~0u && !inst.joints.empty();
        const uint32_t targets = std::min<uint32_t>(d.targetCount, uint32_t(inst.weights.size()));
        cmd.setConstants(DeformConstants{
            .vertexRange = {d.restFirst, d.outputFirst, d.vertexCount, d.flatNormals ? 1u : 0u},
            .sources = {skinned ? d.skinFirst : ~0u, jointFirst[d.instance], d.morphFirst, targets},
            .weights = {weightFirst[d.instance], 0u, 0u, 0u}});
        cmd.dispatch((d.vertexCount + 63) / 64);
    }
    cmd.barrier(gdi::BufferBarrier{.buffer = vertices, .before = A::StorageWrite, .after = A::Vertex | A::StorageRead});
}

}  // namespace fe::render
