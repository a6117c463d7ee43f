// Layer 6: the plain data of a render graph: texture ids, compiled texture records and the
// memory plan, shared by RenderGraph and MemoryPlanner.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "fe/gdi/Device.h"

namespace fe::graph {

struct TextureId {
    uint32_t index = ~0u;
    bool valid() const { return index != ~0u; }
    bool operator==(const TextureId&) const = default;
};

// A buffer the graph orders: imported (the renderer's own, kept across frames) or transient
// (created by compile(device) with the usages its passes need; contents undefined each frame).
struct BufferId {
    uint32_t index = ~0u;
    bool valid() const { return index != ~0u; }
    bool operator==(const BufferId&) const = default;
};

struct BufferInfo {
    std::string name;
    uint64_t size = 0;
    gdi::BufferUsage usage = gdi::BufferUsage::None;  // transient: derived from the passes
    bool imported = false;
    bool output = false;                // read after the frame (e.g. read back): writers survive
    int firstPass = -1, lastPass = -1;  // indices into passes(), -1: unused
    bool used() const { return firstPass >= 0; }
};

enum class AliasingMode : uint8_t {
    None,         // every transient texture gets its own memory
    Memory,       // transient textures share heap bytes when their lifetimes do not overlap
    ObjectReuse,  // textures of one format and size share an object (APIs without heaps)
};

struct TextureInfo {
    std::string name;
    gdi::TextureDesc desc;  // usage as derived from the passes
    bool imported = false;
    bool output = false;
    int firstPass = -1, lastPass = -1;  // indices into passes(), -1: unused
    uint64_t size = 0, alignment = 1;   // memory requirements (transient only)
    uint64_t offset = 0;                // in the heap (AliasingMode::Memory)
    int physical = -1;                  // shared object index (ObjectReuse), own index otherwise
    bool ownMemory = false;  // lazily allocated on its own: outside the plan (CompileOptions)
    bool used() const { return firstPass >= 0; }
    bool overlaps(const TextureInfo& o) const {
        return used() && o.used() && firstPass <= o.lastPass && o.firstPass <= lastPass;
    }
};

struct MemoryReport {
    uint64_t withoutAliasing =
        0;  // every used transient texture in memory of its own (Memory: back to back in one heap, aligned)
    uint64_t withAliasing = 0;  // what the plan allocates (heap size, or the shared objects)
    uint32_t transientTextures = 0;
    uint32_t allocations = 0;  // distinct memory blocks / objects after aliasing
};

}  // namespace fe::graph
