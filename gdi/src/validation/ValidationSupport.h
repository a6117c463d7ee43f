// The wording every check shares: object labels, usage names and the Error they throw. Internal
// to the validation files (Validation.h is the interface).
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

#include "fe/gdi/Faults.h"
#include "fe/gdi/Validation.h"

namespace fe::gdi::validate {

inline std::string label(const char* kind, const char* name) {
    return std::string(kind) + (name && *name ? std::string(" '") + name + "'" : std::string());
}

// "A|B" for the usage an object has; "A or B" for the usages a call accepts (separator " or ").
template <class Usage>
inline std::string usageNames(Usage u, std::initializer_list<std::pair<Usage, const char*>> names,
                              const char* separator) {
    std::string out;
    for (const auto& [bit, n] : names)
        if (any(u, bit)) out += (out.empty() ? "" : separator) + std::string(n);
    return out.empty() ? "None" : out;
}

inline std::string bufferUsageNames(BufferUsage u, const char* separator = "|") {
    using B = BufferUsage;
    return usageNames(u,
                      {{B::Vertex, "Vertex"},
                       {B::Index, "Index"},
                       {B::Uniform, "Uniform"},
                       {B::Storage, "Storage"},
                       {B::CopySrc, "CopySrc"},
                       {B::CopyDst, "CopyDst"},
                       {B::Indirect, "Indirect"}},
                      separator);
}

inline std::string textureUsageNames(TextureUsage u, const char* separator = "|") {
    using T = TextureUsage;
    return usageNames(u,
                      {{T::Sampled, "Sampled"},
                       {T::RenderTarget, "RenderTarget"},
                       {T::Storage, "Storage"},
                       {T::CopySrc, "CopySrc"},
                       {T::CopyDst, "CopyDst"},
                       {T::Transient, "Transient"}},
                      separator);
}

[[noreturn]] inline void fail(const std::string& what, const std::string& why) {
    throw Error(what + ": " + why);
}

// Bytes beyond what one allocation of the device may take (0: no limit known).
inline void allocationFits(const std::string& what, uint64_t bytes, const DeviceLimits& limits) {
    if (limits.maxAllocationSize && bytes > limits.maxAllocationSize)
        fail(what, std::to_string(bytes) + " bytes exceed the device's maxAllocationSize (" +
                       std::to_string(limits.maxAllocationSize) + " bytes)");
}

inline const char* kindName(BindingType t) {
    switch (t) {
        case BindingType::UniformBuffer:
            return "a uniform buffer";
        case BindingType::StorageBuffer:
            return "a storage buffer";
        case BindingType::SampledTexture:
            return "a sampled texture";
        case BindingType::StorageTexture:
            return "a storage texture";
    }
    return "?";
}

}  // namespace fe::gdi::validate
