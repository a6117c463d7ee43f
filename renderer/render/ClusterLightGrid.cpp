#include "render/ClusterLightGrid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"
#include "render/TileLightCulling.h"

namespace fe::render {

ClusterLightGrid::ClusterLightGrid(TechniqueContext& c) : objects_(c.device), ctx_(c) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("clustered light lists need compute shaders, which " +
                         c.device.info().backend + " lacks");
    const RenderSettings& s = c.settings;
    tiles_ = {(s.width + kTilePixels - 1) / kTilePixels,
              (s.height + kTilePixels - 1) / kTilePixels};
    // Every light of the scene is assigned, shadowed ones too (the translucent pass lights with
    // them). The buffer: the entries asked for, (first entry, count) per cluster; the entries in a
    // texture of kIndexWidth texels a row (fe_clusters.glsl says why), as many rows as the
    // device allows (the lists past its end shade every light, counted).
    mostEntries_ = std::max<uint64_t>(1, uint64_t(clusterCount()) * c.scene.lightCount());
    maxRows_ = std::max(1u, c.device.info().limits.maxTextureSize2D);
    const uint64_t wanted =
        uint64_t(clusterCount()) * std::max(1u, std::min(c.scene.lightCount(), kMeanListCapacity));
    createEntries(
        uint32_t(std::clamp<uint64_t>((wanted + kIndexWidth - 1) / kIndexWidth, 1, maxRows_)));
    lists_ = objects_.add(c.device.createBuffer(
        {.size = (1 + kHeaderWords * uint64_t(clusterCount())) * sizeof(uint32_t),
         .usage = gdi::BufferUsage::Storage | gdi::BufferUsage::CopySrc,
         .debugName = "cluster light lists"}));
    for (uint32_t i = 0; i < c.queue.framesInFlight(); ++i)
        asked_.push_back(
            objects_.add(c.device.createBuffer({.size = sizeof(uint32_t),
                                                .usage = gdi::BufferUsage::CopyDst,
                                                .access = gdi::MemoryAccess::Readback,
                                                .debugName = "cluster light entries asked"})));
    askedWritten_.assign(asked_.size(), false);
    // The assignment's scratch: per tile column, a bit per light.
    const uint64_t columns = uint64_t(tiles_.x) * tiles_.y;
    columnMasks_ = objects_.add(c.device.createBuffer(
        {.size = std::max<uint64_t>(4, columns * ((c.scene.lightCount() + 31) / 32) * 4),
         .usage = gdi::BufferUsage::Storage,
         .debugName = "cluster light assignment columns"}));
    // Bound to the assignment whether or not a bounds pass fills it (it reads it only then).
    bounds_ =
        objects_.add(c.device.createBuffer({.size = 2 * uint64_t(clusterCount()) * sizeof(uint32_t),
                                            .usage = gdi::BufferUsage::Storage,
                                            .debugName = "cluster opaque depth bounds"}));
    uniformLights_ = TileLightCulling::lightsFitUniformBlock(c);
    cs_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Compute,
         .binary = TileLightCulling::listPassShader("cluster_light_assignment", uniformLights_)}));
    pipeline_ = objects_.add(c.device.createComputePipeline(
        {.computeShader = cs_, .debugName = "cluster light assignment"}));
}

void ClusterLightGrid::createEntries(uint32_t rows) {
    objects_.destroy(indices_);  // retired once the frames in flight that read it complete
    indices_ = objects_.add(
        ctx_.device.createTexture({.format = gdi::Format::R32U,
                                   .width = kIndexWidth,
                                   .height = rows,
                                   .usage = gdi::TextureUsage::Storage | gdi::TextureUsage::Sampled,
                                   .debugName = "cluster light list entries"}));
    capacity_ = rows * kIndexWidth;
}

void ClusterLightGrid::beginFrame() {
    const size_t slot = ctx_.queue.frameNumber() % asked_.size();
    if (!askedWritten_[slot]) return;
    askedWritten_[slot] = false;
    uint32_t asked = 0;
    std::memcpy(&asked, ctx_.device.map(asked_[slot]), sizeof asked);
    const uint32_t rows = capacity_ / kIndexWidth;
    if (asked <= capacity_ || rows >= maxRows_) return;
    const uint64_t wanted = std::min<uint64_t>(uint64_t(asked) + asked / 4, mostEntries_);
    createEntries(uint32_t(
        std::clamp<uint64_t>((wanted + kIndexWidth - 1) / kIndexWidth, rows + 1, maxRows_)));
    if (declaredIn_)
        declaredIn_->replaceImport(declared_.entries, indices_, ctx_.device.desc(indices_));
}

glm::vec4 ClusterLightGrid::slicing(const assets::Camera& camera, const assets::Bounds& bounds) {
    const float nearDepth = camera.znear;
    float farDepth = 2.0f * nearDepth, nearestDepth = 0.0f;
    if (!bounds.empty()) {
        const glm::mat4 view = camera.viewFromWorld();
        nearestDepth = std::numeric_limits<float>::max();
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner((c & 1) ? bounds.max.x : bounds.min.x,
                                   (c & 2) ? bounds.max.y : bounds.min.y,
                                   (c & 4) ? bounds.max.z : bounds.min.z);
            const float depth = -(view * glm::vec4(corner, 1.0f)).z;
            farDepth = std::max(farDepth, depth);
            nearestDepth = std::min(nearestDepth, depth);
        }
    }
    farDepth =
        std::min(farDepth * 1.01f, camera.zfar);  // a margin for rounding; never past the far plane
    farDepth = std::max(farDepth, 2.0f * nearDepth);
    // The near split: slice 0 takes everything before it, so the exponential slices are not
    // spent on the first metres in front of the camera, where little is seen (Doom 2016 does
    // the same). It lies at kNearSplit of the far depth, or where the scene begins when the
    // camera looks at it from outside (rounding margin kept), never before the near plane.
    const float split = std::clamp(std::max(farDepth * kNearSplit, nearestDepth * 0.99f), nearDepth,
                                   0.5f * farDepth);
    return {nearDepth, float(kSlices - 1) / std::log(farDepth / split), farDepth, split};
}

ClusterLightGrid::Lists ClusterLightGrid::declare(graph::RenderGraph& g) {
    return declareLists(g, {});
}

ClusterLightGrid::Lists ClusterLightGrid::declareBounded(graph::RenderGraph& g,
                                                         graph::TextureId opaqueDepth) {
    if (!opaqueDepth.valid())
        throw gdi::Error("ClusterLightGrid::declareBounded: no opaque depth given");
    return declareLists(g, ctx_.settings.clusterDepthBounds ? opaqueDepth : graph::TextureId{});
}

ClusterLightGrid::Lists ClusterLightGrid::declareLists(graph::RenderGraph& g,
                                                       graph::TextureId opaqueDepth) {
    // Read when the frame is recorded, after every reader of the graph has declared itself.
    if (!opaqueDepth.valid()) wholeListsRead_ = true;
    if (declaredIn_ == &g) return declared_;
    declaredIn_ = &g;
    bounded_ = opaqueDepth.valid();
    wholeListsRead_ = !bounded_;
    declared_ = {
        .headers = g.importBuffer("cluster light lists", lists_, ctx_.device.desc(lists_).size),
        .entries =
            g.importTexture("cluster light list entries", indices_, ctx_.device.desc(indices_))};
    g.markOutput(declared_.headers);  // statistics() reads it back
    const graph::BufferId bounds = bounded_ ? declareBounds(g, opaqueDepth) : graph::BufferId{};
    g.addPass(
        "light-assignment",
        [&](graph::PassBuilder& b) {
            b.buffer(declared_.headers, gdi::BufferAccess::StorageWrite);
            b.storage(declared_.entries);
            if (bounded_) b.buffer(bounds, gdi::BufferAccess::StorageRead);
            // Unbounded, it reads only the lights: it runs beside the depth or G-buffer pass.
            if (ctx_.settings.asyncCompute) b.asyncCompute();
        },
        [this](graph::PassContext& pc) { recordAssignment(pc.cmd); });
    return declared_;
}

graph::BufferId ClusterLightGrid::declareBounds(graph::RenderGraph& g,
                                                graph::TextureId opaqueDepth) {
    if (!boundsPipeline_) {  // made here: a grid only blended surfaces read never compiles it
        boundsCs_ = objects_.add(
            ctx_.device.createShader({.stage = gdi::ShaderStage::Compute,
                                      .binary = shaders::find("scene/cluster_bounds.comp")}));
        boundsPipeline_ = objects_.add(ctx_.device.createComputePipeline(
            {.computeShader = boundsCs_, .debugName = "cluster bounds"}));
    }
    const graph::BufferId bounds =
        g.importBuffer("cluster opaque depth bounds", bounds_, ctx_.device.desc(bounds_).size);
    g.addPass(
        "cluster-bounds",
        [&](graph::PassBuilder& b) {
            b.sample(opaqueDepth);
            b.buffer(bounds, gdi::BufferAccess::StorageWrite);
        },
        [this, opaqueDepth](graph::PassContext& pc) {
            pc.cmd.setPipeline(boundsPipeline_);
            const UploadAllocation& fc = ctx_.frameConstants;
            pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
            pc.cmd.setTexture(kSlotDepth, pc.texture(opaqueDepth), ctx_.pointSampler);
            pc.cmd.setStorageBuffer(kSlotClusterBounds, bounds_);
            pc.cmd.dispatch(tiles_.x, tiles_.y);
        });
    return bounds;
}

void ClusterLightGrid::recordAssignment(gdi::CommandList& cmd) {
    cmd.setPipeline(pipeline_);
    const UploadAllocation& fc = ctx_.frameConstants;
    cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
    TileLightCulling::bindLights(cmd, ctx_, uniformLights_);
    cmd.setStorageBuffer(kSlotClusterLights, lists_);
    cmd.setStorageBuffer(kSlotClusterColumns, columnMasks_);
    cmd.setStorageBuffer(kSlotClusterBounds, bounds_);  // read only when bounded
    cmd.setStorageTexture(kSlotClusterIndicesOut, indices_);
    // Mark each column's lights, count each cluster's, place the lists in header order, fill
    // them (cluster_light_assignment.comp): no atomics, the same layout on every device.
    constexpr auto rw = gdi::BufferAccess::StorageRead | gdi::BufferAccess::StorageWrite;
    const gdi::BufferBarrier between[2] = {{.buffer = lists_, .before = rw, .after = rw},
                                           {.buffer = columnMasks_, .before = rw, .after = rw}};
    const uint32_t columns = tiles_.x * tiles_.y;
    const uint32_t groups[4] = {columns, columns, 1, columns};  // one to place
    for (uint32_t phase = 0; phase < 4; ++phase) {
        if (phase) cmd.barrier(between, 2);
        cmd.setConstants(glm::uvec4(phase, bounded_ ? 1u : 0u, wholeListsRead_ ? 1u : 0u, 0u));
        cmd.dispatch(groups[phase]);
    }
    // The entries this frame asked for, for beginFrame framesInFlight frames on.
    const size_t slot = ctx_.queue.frameNumber() % asked_.size();
    cmd.barrier(gdi::BufferBarrier{
        .buffer = lists_, .before = rw, .after = gdi::BufferAccess::CopySrc, .size = 4});
    cmd.copyBuffer(asked_[slot], 0, lists_, 0, sizeof(uint32_t));
    cmd.barrier(gdi::BufferBarrier{
        .buffer = lists_, .before = gdi::BufferAccess::CopySrc, .after = rw, .size = 4});
    askedWritten_[slot] = true;
}

void ClusterLightGrid::read(graph::PassBuilder& b, const Lists& lists) {
    b.buffer(lists.headers, gdi::BufferAccess::StorageRead);
    b.sample(lists.entries);
}

void ClusterLightGrid::bindLists(gdi::CommandList& cmd) const {
    cmd.setStorageBuffer(kSlotClusterLights, lists_);
    cmd.setTexture(kSlotClusterIndices, indices_, ctx_.pointSampler);
}

ClusterLightGrid::Statistics ClusterLightGrid::statistics() const {
    const std::vector<uint8_t> bytes =
        ctx_.device.readBuffer(lists_, 0, ctx_.device.desc(lists_).size);
    std::vector<uint32_t> words(bytes.size() / sizeof(uint32_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    Statistics s{.clusters = clusterCount(), .entries = words[0]};
    uint64_t sum = 0, boundedSum = 0;
    for (uint32_t c = 0; c < s.clusters; ++c) {
        const uint32_t count = words[2 + kHeaderWords * size_t(c)],
                       bounded = words[3 + kHeaderWords * size_t(c)];
        if (count == 0xffffffffu) {
            ++s.overflowed;
            continue;
        }
        s.nonEmpty += count > 0;
        s.maxLights = std::max(s.maxLights, count);
        sum += count;
        boundedSum += bounded;
    }
    s.meanLights = s.nonEmpty ? double(sum) / s.nonEmpty : 0.0;
    s.meanBoundedLights = s.nonEmpty ? double(boundedSum) / s.nonEmpty : 0.0;
    s.bounded = bounded_;
    return s;
}

}  // namespace fe::render
