#include "render/MeshDeformation.h"

#include <algorithm>

#include "fe/gdi/ShaderRegistry.h"
#include "render/GpuScene.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
// mesh_deform.comp's Deformation record.
struct DeformationRecord {
    glm::uvec4 vertexRange;  // rest first, output first, count, flat normals
    glm::uvec4 sources;      // first influence (~0: none), first joint vec4, first delta, targets
    glm::uvec4 weights;      // first weight (floats), first work group
};
constexpr uint32_t kGroupSize = 64;  // mesh_deform.comp's local_size_x
constexpr uint32_t kMaxGroupsPerDispatch = 65535;
}  // namespace

// The records and the group table are fixed for the scene (where each instance's joints and
// weights go in the pose buffer follows from its skin and target count); each frame uploads the
// pose alone. One dispatch rather than one per primitive: on lavapipe 256 dispatches of 9 work
// groups (builtin:crowd, 256 reeds) took 22 ms a frame.
MeshDeformation::MeshDeformation(TechniqueContext& c) : objects_(c.device), ctx_(c) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error(
            "skinned or morphed meshes are deformed by a compute shader, which this device lacks");
    shader_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Compute, .binary = shaders::find("scene/mesh_deform.comp")}));
    pipeline_ = objects_.add(c.device.createComputePipeline(
        {.computeShader = shader_, .debugName = "mesh deformation"}));
    const GpuScene& gpu = c.scene;
    const assets::Scene& scene = gpu.scene();
    jointFirst_.assign(scene.instances.size(), 0);
    weightFirst_.assign(scene.instances.size(), 0);
    jointCount_.assign(scene.instances.size(), 0);
    uint32_t vec4s = 0, previous = ~0u;
    for (const Deformation& d : gpu.deformations()) {
        if (d.instance == previous) continue;
        previous = d.instance;
        const assets::MeshInstance& inst = scene.instances[d.instance];
        jointFirst_[d.instance] = vec4s;
        jointCount_[d.instance] = uint32_t(inst.joints.size());
        vec4s += uint32_t(inst.joints.size()) * 4;
        weightFirst_[d.instance] = vec4s * 4;
        vec4s += uint32_t(inst.weights.size() + 3) / 4;
    }
    std::vector<DeformationRecord> records;
    std::vector<uint32_t> groups;
    for (const Deformation& d : gpu.deformations()) {
        const assets::MeshInstance& inst = scene.instances[d.instance];
        const bool skinned = d.skinFirst != ~0u && !inst.joints.empty();
        const uint32_t targets = std::min<uint32_t>(d.targetCount, uint32_t(inst.weights.size()));
        records.push_back(
            {.vertexRange = {d.restFirst, d.outputFirst, d.vertexCount, d.flatNormals ? 1u : 0u},
             .sources = {skinned ? d.skinFirst : ~0u, jointFirst_[d.instance], d.morphFirst,
                         targets},
             .weights = {weightFirst_[d.instance], uint32_t(groups.size()), 0u, 0u}});
        groups.insert(groups.end(), (d.vertexCount + kGroupSize - 1) / kGroupSize,
                      uint32_t(records.size() - 1));
    }
    groupCount_ = uint32_t(groups.size());
    if (groups.empty()) groups.push_back(0), records.emplace_back();
    records_ =
        objects_.add(c.device.createBuffer({.size = records.size() * sizeof(DeformationRecord),
                                            .usage = gdi::BufferUsage::Storage,
                                            .debugName = "mesh deformations"},
                                           gdi::bytesOf(records)));
    groups_ = objects_.add(c.device.createBuffer({.size = groups.size() * sizeof(uint32_t),
                                                  .usage = gdi::BufferUsage::Storage,
                                                  .debugName = "mesh deformation work groups"},
                                                 gdi::bytesOf(groups)));
}

void MeshDeformation::declare(graph::RenderGraph& g) {
    // The vertices are read by nearly every pass, which do not declare it: the pass orders its
    // writes after the previous frame's reads and before this frame's with barriers of its own.
    g.addPass(
        "deform meshes", [&](graph::PassBuilder& b) { b.sideEffect(); },
        [this](graph::PassContext& pc) { record(pc.cmd); });
}

void MeshDeformation::record(gdi::CommandList& cmd) {
    if (!dirty_) return;
    dirty_ = false;
    const GpuScene& gpu = ctx_.scene;
    const assets::Scene& scene = gpu.scene();
    // The pose: each deformed instance's joint matrices, then its weights, 4 to a vec4, where
    // the records expect them.
    std::vector<glm::vec4> pose;
    uint32_t previous = ~0u;
    for (const Deformation& d : gpu.deformations()) {
        if (d.instance == previous) continue;
        previous = d.instance;
        const assets::MeshInstance& inst = scene.instances[d.instance];
        // The records were laid out for these counts (poseScene keeps them: one matrix per joint
        // of the skin, one weight per target); a scene changed by hand otherwise would deform
        // with another instance's matrices.
        if (inst.joints.size() != jointCount_[d.instance])
            throw gdi::Error("mesh deformation: instance '" + inst.name + "' has " +
                             std::to_string(inst.joints.size()) +
                             " joint matrices where the renderer was made for " +
                             std::to_string(jointCount_[d.instance]) +
                             " (change a scene's skins by posing it, not by hand)");
        pose.resize(jointFirst_[d.instance]);
        for (const glm::mat4& m : inst.joints) pose.insert(pose.end(), {m[0], m[1], m[2], m[3]});
        for (size_t w = 0; w < inst.weights.size(); w += 4) {
            glm::vec4 v(0.0f);
            for (size_t k = 0; k < 4 && w + k < inst.weights.size(); ++k)
                v[int(k)] = inst.weights[w + k];
            pose.push_back(v);
        }
    }
    if (pose.empty()) pose.emplace_back(0.0f);
    const UploadAllocation posed = ctx_.queue.upload(gdi::bytesOf(pose));
    const gdi::BufferHandle vertices = gpu.vertexBuffer();
    using A = gdi::BufferAccess;
    cmd.barrier(gdi::BufferBarrier{.buffer = vertices,
                                   .before = A::Vertex | A::StorageRead,
                                   .after = A::StorageRead | A::StorageWrite});
    cmd.setPipeline(pipeline_);
    cmd.setStorageBuffer(kSlotVertices, vertices);
    cmd.setStorageBuffer(kSlotSkin, gpu.skinBuffer());
    cmd.setStorageBuffer(kSlotMorphTargets, gpu.morphBuffer());
    cmd.setStorageBuffer(kSlotPose, posed.buffer, posed.offset, posed.size);
    cmd.setStorageBuffer(kSlotDeformations, records_);
    cmd.setStorageBuffer(kSlotDeformGroups, groups_);
    for (uint32_t first = 0; first < groupCount_; first += kMaxGroupsPerDispatch) {
        cmd.setConstants(glm::uvec4(first, 0u, 0u, 0u));
        cmd.dispatch(std::min(kMaxGroupsPerDispatch, groupCount_ - first));
    }
    cmd.barrier(gdi::BufferBarrier{
        .buffer = vertices, .before = A::StorageWrite, .after = A::Vertex | A::StorageRead});
}

}  // namespace fe::render
