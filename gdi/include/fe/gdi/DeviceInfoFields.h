// DeviceLimits and DeviceFeatures field by field, named as in the struct: the one list every
// report of them uses (`fe info`, `fe info --json`, the conformance report, benchmarks).
//
// Adding a field to DeviceLimits or DeviceFeatures: add its one line below. Forgetting it fails
// the build (the static_asserts at the end count the struct's fields). Fields must be scalars
// (integers, bools, enums) or small structs; a C array would be counted element by element.
#pragma once
#include <cstddef>
#include <utility>

#include "fe/gdi/Device.h"

namespace fe::gdi {

template <class Visitor>
constexpr void forEachField(const DeviceLimits& l, Visitor&& visit) {
    visit("maxTextureSize2D", l.maxTextureSize2D);
    visit("maxTextureSize3D", l.maxTextureSize3D);
    visit("maxTextureSizeCube", l.maxTextureSizeCube);
    visit("maxTextureArrayLayers", l.maxTextureArrayLayers);
    visit("colorSampleCounts", l.colorSampleCounts);
    visit("depthSampleCounts", l.depthSampleCounts);
    visit("maxColorAttachments", l.maxColorAttachments);
    visit("maxComputeWorkGroupInvocations", l.maxComputeWorkGroupInvocations);
    visit("maxComputeWorkGroupCount", l.maxComputeWorkGroupCount);  // x, y, z
    visit("maxStorageTextures", l.maxStorageTextures);
    visit("maxUniformBufferRange", l.maxUniformBufferRange);
    visit("maxStorageBufferRange", l.maxStorageBufferRange);
    visit("maxAllocationSize", l.maxAllocationSize);
    visit("uniformBufferOffsetAlignment", l.uniformBufferOffsetAlignment);
    visit("storageBufferOffsetAlignment", l.storageBufferOffsetAlignment);
    visit("maxViewportSize", l.maxViewportSize);
    visit("viewportBounds", l.viewportBounds);  // min, max
    visit("maxTessellationPatchSize", l.maxTessellationPatchSize);
    visit("timestampPeriodNs", l.timestampPeriodNs);
}

template <class Visitor>
constexpr void forEachField(const DeviceFeatures& f, Visitor&& visit) {
    visit("timestamps", f.timestamps);
    visit("computeShaders", f.computeShaders);
    visit("debugLabels", f.debugLabels);
    visit("validation", f.validation);
    visit("memoryAliasing", f.memoryAliasing);
    visit("window", f.window);
    visit("textureCubeArray", f.textureCubeArray);
    visit("storageImageExtendedFormats", f.storageImageExtendedFormats);
    visit("depthClamp", f.depthClamp);
    visit("depthBiasClamp", f.depthBiasClamp);
    visit("multiDrawIndirect", f.multiDrawIndirect);
    visit("drawIndirectCount", f.drawIndirectCount);
    visit("textureCompressionBC", f.textureCompressionBC);
    visit("occlusionQueries", f.occlusionQueries);
    visit("pipelineStatistics", f.pipelineStatistics);
    visit("robustBufferAccess", f.robustBufferAccess);
    visit("lazilyAllocatedMemory", f.lazilyAllocatedMemory);
    visit("asyncCompute", f.asyncCompute);
    visit("asyncCopy", f.asyncCopy);
    visit("geometryShaders", f.geometryShaders);
    visit("tessellationShaders", f.tessellationShaders);
}

namespace detail {
// Aggregate field count: the most initializers T{...} accepts (each converts to any type).
struct AnyField {
    template <class T>
    constexpr operator T() const;
};
template <class T, size_t... I>
constexpr bool bracesAccept(std::index_sequence<I...>) {
    return requires { T{(void(I), AnyField{})...}; };
}
template <class T, size_t N = 0>
constexpr size_t fieldCount() {
    if constexpr (bracesAccept<T>(std::make_index_sequence<N + 1>{}))
        return fieldCount<T, N + 1>();
    else
        return N;
}
template <class T>
constexpr size_t visitedCount() {
    size_t n = 0;
    forEachField(T{}, [&](const char*, const auto&) { ++n; });
    return n;
}
}  // namespace detail

static_assert(
    detail::visitedCount<DeviceLimits>() == detail::fieldCount<DeviceLimits>(),
    "a DeviceLimits field is missing from forEachField(DeviceLimits) in DeviceInfoFields.h: add its line");
static_assert(
    detail::visitedCount<DeviceFeatures>() == detail::fieldCount<DeviceFeatures>(),
    "a DeviceFeatures field is missing from forEachField(DeviceFeatures) in DeviceInfoFields.h: add its line");

}  // namespace fe::gdi
