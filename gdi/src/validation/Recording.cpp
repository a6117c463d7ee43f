// Shared validation: What a list checks while recording: bindings and their ranges, vertex inputs, draws and
// dispatches, viewports, depth bias and per-draw constants.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

void indirect(const BufferDesc& d, const std::string& name, uint64_t offset, uint32_t drawCount,
              uint32_t stride, uint32_t recordSize, const DeviceFeatures& features,
              const char* what) {
    const std::string w = std::string(what) + ": " + label("buffer", name.c_str());
    if (!any(d.usage, BufferUsage::Indirect)) fail(w, "lacks Indirect usage");
    if (offset % 4) fail(w, "offset " + std::to_string(offset) + " is not a multiple of 4");
    if (drawCount > 1 && !features.multiDrawIndirect)
        fail(w, "drawCount > 1 needs multiDrawIndirect");
    if (drawCount > 1 && (stride < recordSize || stride % 4))
        fail(w, "stride " + std::to_string(stride) + " must be a multiple of 4 of at least " +
                    std::to_string(recordSize));
    if (drawCount == 0) return;
    const uint64_t bytes = uint64_t(drawCount - 1) * stride + recordSize;
    if (offset > d.size || bytes > d.size - offset)
        fail(w, std::to_string(drawCount) + " record(s) from offset " + std::to_string(offset) +
                    " exceed its size " + std::to_string(d.size));
}

void bufferRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    fail(label("buffer", d.debugName), std::string(what) + ": range [" + std::to_string(offset) +
                                           ", " + std::to_string(offset + size) +
                                           ") exceeds its size " + std::to_string(d.size));
}

void bindingRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (size == 0 && offset <= d.size)
        fail(label("buffer", d.debugName), std::string(what) + ": empty range (offset " +
                                               std::to_string(offset) +
                                               " is the end of the buffer)");
    bufferRangeFailed(d, offset, size, what);
}

void wrongTextureDimensionFailed(uint32_t slot, uint8_t expected, uint8_t bound,
                                 const char* pipelineName) {
    fail(label("pipeline", pipelineName),
         "slot " + std::to_string(slot) + " is declared a " + textureKindName(expected) +
             " in its shader, but the texture bound there is a " + textureKindName(bound) +
             (expected == kTexture2DMultisampleKind || bound == kTexture2DMultisampleKind
                  ? " (sampler2DMS takes multisampled textures, the other kinds single-sample ones)"
                  : " (bind a view of that kind: createTextureView with .dimension)"));
}

void VertexInputs::setVertexBuffer(uint32_t index, const BufferDesc& d, const std::string& name,
                                   uint64_t offset) {
    if (index >= kMaxVertexBuffers)
        throw Error("setVertexBuffer: index " + std::to_string(index) + " out of range (at most " +
                    std::to_string(kMaxVertexBuffers) + " vertex buffers)");
    bufferUsage(d, BufferUsage::Vertex, name, "setVertexBuffer");
    if (offset >= d.size) bufferRange(d, offset, 1, "setVertexBuffer");
    buffers_[index] = {d.size - offset, name};
    bound_ |= 1u << index;
    update();
}

void VertexInputs::setIndexBuffer(const BufferDesc& d, const std::string& name, IndexType type,
                                  uint64_t offset) {
    bufferUsage(d, BufferUsage::Index, name, "setIndexBuffer");
    if (offset >= d.size) bufferRange(d, offset, 1, "setIndexBuffer");
    const uint32_t bytes = type == IndexType::U16 ? 2 : 4;
    if (offset % bytes)
        fail(label("buffer", name.c_str()), "setIndexBuffer: offset " + std::to_string(offset) +
                                                " is not a multiple of " + std::to_string(bytes) +
                                                " (the index size)");
    indexBound_ = true;
    indexOffset_ = offset;
    indexBytes_ = bytes;
    indices_ = (d.size - offset) / bytes;
    indexName_ = name;
}

void VertexInputs::setPipeline(const std::vector<VertexBinding>* bindings,
                               const std::string* pipelineName) {
    bindings_ = bindings;
    pipelineName_ = pipelineName;
    required_ = bindings ? (1u << bindings->size()) - 1u : 0u;
    update();
}

void VertexInputs::clear() {
    bound_ = 0;
    indexBound_ = false;
    indices_ = 0;
    update();
}

void VertexInputs::update() {
    vertices_ = instances_ = ~uint64_t(0);
    if (!bindings_) return;
    for (uint32_t i = 0; i < bindings_->size(); ++i) {
        const VertexBinding& b = (*bindings_)[i];
        if (!(bound_ >> i & 1u) || b.stride == 0) continue;
        const uint64_t available = buffers_[i].available;
        const uint64_t elements = available < b.extent ? 0 : (available - b.extent) / b.stride + 1;
        uint64_t& capacity = b.perInstance ? instances_ : vertices_;
        capacity = std::min(capacity, elements);
    }
}

void VertexInputs::notReady(const char* what) const {
    const uint32_t missing = required_ & ~bound_;
    throw Error(std::string(what) + ": pipeline '" +
                (pipelineName_ ? *pipelineName_ : std::string()) + "' reads vertex buffer " +
                std::to_string(std::countr_zero(missing)) +
                ", which is not bound (setVertexBuffer)");
}

void VertexInputs::outside(const char* what, uint32_t count, uint32_t instanceCount, uint32_t first,
                           uint32_t firstInstance) const {
    const bool instances = uint64_t(firstInstance) + instanceCount > instances_;
    throw Error(std::string(what) + ": " + (instances ? "instances [" : "vertices [") +
                std::to_string(instances ? firstInstance : first) + ", " +
                std::to_string(instances ? uint64_t(firstInstance) + instanceCount
                                         : uint64_t(first) + count) +
                ") reach past the bound vertex buffers of pipeline '" +
                (pipelineName_ ? *pipelineName_ : std::string()) + "', which hold " +
                std::to_string(instances ? instances_ : vertices_));
}

void VertexInputs::indexedOutside(uint32_t count, uint32_t instanceCount, uint32_t first,
                                  uint32_t firstInstance) const {
    if (!indexBound_) throw Error("drawIndexed without an index buffer");
    if (uint64_t(first) + count > indices_)
        fail(label("buffer", indexName_.c_str()),
             "drawIndexed: indices [" + std::to_string(first) + ", " +
                 std::to_string(uint64_t(first) + count) +
                 ") reach past the index buffer, which holds " + std::to_string(indices_) +
                 " from offset " + std::to_string(indexOffset_));
    outside("drawIndexed", 0, instanceCount, 0, firstInstance);
}

void VertexInputs::indexedIndirect(const char* what) const {
    if (!indexBound_) throw Error(std::string(what) + " without an index buffer");
    if (indexOffset_ != 0)
        throw Error(std::string(what) +
                    ": the index buffer must be bound at offset 0 (records hold firstIndex)");
}

void badViewport(const Viewport& v, const ViewportLimits& l) {
    std::string why;
    if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.width) &&
          std::isfinite(v.height)))
        why = "not finite";
    else if (v.height < 0)
        why =
            "a negative height (Vulkan's y flip) is not supported: clip space is already Vulkan's, y down, on every "
            "backend; flip y in the projection instead";
    else if (!(v.width > 0 && v.height > 0))
        why = "width and height must be positive";
    else if (!(v.width <= l.maxSize && v.height <= l.maxSize))
        why = "width and height must be at most the device's maxViewportSize (" +
              std::to_string(uint64_t(l.maxSize)) + ")";
    else if (!(v.x >= l.lo && v.y >= l.lo && v.x + v.width <= l.hi && v.y + v.height <= l.hi))
        why = "x, y, x + width and y + height must lie within the device's viewportBounds [" +
              std::to_string(int64_t(l.lo)) + ", " + std::to_string(int64_t(l.hi)) + "]";
    else
        why = "minDepth and maxDepth must lie in [0, 1]";
    throw Error("setViewport {" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                std::to_string(v.width) + ", " + std::to_string(v.height) + ", " +
                std::to_string(v.minDepth) + ", " + std::to_string(v.maxDepth) + "}: " + why);
}

void badDispatch(uint32_t x, uint32_t y, uint32_t z, const DeviceLimits& l) {
    throw Error("dispatch(" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                std::to_string(z) + "): beyond the device's maxComputeWorkGroupCount (" +
                std::to_string(l.maxComputeWorkGroupCount[0]) + ", " +
                std::to_string(l.maxComputeWorkGroupCount[1]) + ", " +
                std::to_string(l.maxComputeWorkGroupCount[2]) + ")");
}

void wrongBindingKindFailed(uint32_t slot, BindingType expected, BindingType bound,
                            const char* pipelineName) {
    fail(label("draw/dispatch with pipeline", pipelineName),
         "slot " + std::to_string(slot) + " expects " + kindName(expected) + " but " +
             kindName(bound) + " is bound");
}

void missingBindingsFailed(uint64_t missing, const char* pipelineName) {
    std::string slots;
    for (int i = 0; i < 64; ++i)
        if (missing & (uint64_t(1) << i)) slots += (slots.empty() ? "" : ", ") + std::to_string(i);
    fail(label("draw/dispatch with pipeline", pipelineName),
         "missing binding for slot(s) " + slots);
}

void badConstantsRange(uint32_t offset, size_t size) {
    fail("setConstants", "offset " + std::to_string(offset) + " and size " + std::to_string(size) +
                             " must be multiples of 4, the size not 0, and offset + size at most " +
                             std::to_string(kMaxConstantBytes) + " (kMaxConstantBytes)");
}

BindingLimits uniformBindingLimits(const DeviceLimits& l) {
    return {l.uniformBufferOffsetAlignment ? l.uniformBufferOffsetAlignment - 1u : 0u,
            l.maxUniformBufferRange ? l.maxUniformBufferRange : ~uint64_t(0),
            "uniformBufferOffsetAlignment", "maxUniformBufferRange"};
}

BindingLimits storageBindingLimits(const DeviceLimits& l) {
    return {l.storageBufferOffsetAlignment ? l.storageBufferOffsetAlignment - 1u : 0u,
            l.maxStorageBufferRange ? l.maxStorageBufferRange : ~uint64_t(0),
            "storageBufferOffsetAlignment", "maxStorageBufferRange"};
}

void bindingLimits(uint64_t offset, uint64_t size, const BindingLimits& limits, const char* what) {
    if (offset & limits.alignMask)
        throw Error(std::string(what) + ": offset " + std::to_string(offset) +
                    " is not a multiple of the device's " + limits.alignmentName + " (" +
                    std::to_string(limits.alignMask + 1) + ")");
    if (size > limits.maxRange)
        throw Error(std::string(what) + ": " + std::to_string(size) +
                    " bytes exceed the device's " + limits.rangeName + " (" +
                    std::to_string(limits.maxRange) + ")");
}

void depthBias(float constant, float slope, float clamp, const DeviceFeatures& features) {
    if (!std::isfinite(constant) || !std::isfinite(slope) || !std::isfinite(clamp))
        throw Error("setDepthBias: values must be finite");
    if (clamp != 0 && !features.depthBiasClamp)
        throw Error("setDepthBias: depth bias clamp is not supported on this device");
}

void notFilterable(const std::string& texture, Format format, const std::string& sampler) {
    throw Error(
        "setTexture: " + label("sampler", sampler.c_str()) + " filters linearly, but " +
        label("texture", texture.c_str()) + " (" + std::string(formatInfo(format).name) +
        ") cannot be filtered linearly on this device (FormatCaps::linearFilter); use Nearest filters, or a "
        "comparison sampler for depth");
}

}  // namespace fe::gdi::validate
