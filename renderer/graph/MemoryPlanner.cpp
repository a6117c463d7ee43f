#include "graph/MemoryPlanner.h"

#include <algorithm>
#include <numeric>

namespace fe::graph {

namespace {
uint64_t alignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }

bool transient(const TextureInfo& t) { return !t.imported && t.used() && !t.ownMemory; }

bool sameObject(const gdi::TextureDesc& a, const gdi::TextureDesc& b) {
    return a.dimension == b.dimension && a.depthOrLayers == b.depthOrLayers &&
           a.format == b.format && a.width == b.width && a.height == b.height &&
           a.mipLevels == b.mipLevels && a.sampleCount == b.sampleCount &&
           any(a.usage, gdi::TextureUsage::Transient) == any(b.usage, gdi::TextureUsage::Transient);
}

MemoryReport placeInHeap(std::vector<TextureInfo>& textures, std::vector<uint32_t>& order) {
    MemoryReport r;
    // Largest first packs best; ties by first use keep the plan stable.
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (textures[a].size != textures[b].size) return textures[a].size > textures[b].size;
        return textures[a].firstPass < textures[b].firstPass;
    });
    std::vector<uint32_t> placed;
    for (uint32_t i : order) {
        TextureInfo& t = textures[i];
        uint64_t offset = 0;
        for (bool moved = true; moved;) {  // bump past every conflicting block until none is left
            moved = false;
            for (uint32_t j : placed) {
                const TextureInfo& o = textures[j];
                if (!t.overlaps(o)) continue;
                if (offset < o.offset + o.size && o.offset < offset + t.size) {
                    offset = alignUp(o.offset + o.size, t.alignment);
                    moved = true;
                }
            }
        }
        t.offset = offset;
        t.physical = int(i);
        placed.push_back(i);
        r.withAliasing = std::max(r.withAliasing, offset + t.size);
    }
    // Without aliasing the same heap holds every texture back to back. Alignment padding can
    // make the greedy plan longer than that in rare cases; then the plain layout is used.
    uint64_t end = 0;
    std::vector<uint64_t> sequential;
    for (uint32_t i : order) {
        end = alignUp(end, textures[i].alignment);
        sequential.push_back(end);
        end += textures[i].size;
    }
    r.withoutAliasing = end;
    if (r.withAliasing > end) {
        for (size_t k = 0; k < order.size(); ++k) textures[order[k]].offset = sequential[k];
        r.withAliasing = end;
    }
    r.allocations = placed.empty() ? 0 : 1;
    return r;
}

MemoryReport reuseObjects(std::vector<TextureInfo>& textures, std::vector<uint32_t>& order) {
    MemoryReport r;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return textures[a].firstPass < textures[b].firstPass;
    });
    struct Object {
        uint32_t owner;  // first texture of the object: its description and index
        int busyUntil;
    };
    std::vector<Object> objects;
    for (uint32_t i : order) {
        TextureInfo& t = textures[i];
        auto it = std::find_if(objects.begin(), objects.end(), [&](const Object& o) {
            return o.busyUntil < t.firstPass && sameObject(textures[o.owner].desc, t.desc);
        });
        if (it == objects.end()) {
            objects.push_back({i, t.lastPass});
            r.withAliasing += t.size;
            t.physical = int(i);
        } else {
            it->busyUntil = t.lastPass;
            t.physical = int(it->owner);
        }
        t.offset = 0;
    }
    // A shared object is created with every usage of the textures it stands for.
    for (uint32_t i : order)
        textures[textures[i].physical].desc.usage =
            textures[textures[i].physical].desc.usage | textures[i].desc.usage;
    for (uint32_t i : order) textures[i].desc.usage = textures[textures[i].physical].desc.usage;
    r.allocations = uint32_t(objects.size());
    return r;
}
}  // namespace

MemoryReport planMemory(std::vector<TextureInfo>& textures, AliasingMode mode) {
    std::vector<uint32_t> order;
    uint64_t total = 0;
    for (uint32_t i = 0; i < textures.size(); ++i)
        if (transient(textures[i])) {
            order.push_back(i);
            total += textures[i].size;
        }
    MemoryReport r;
    if (mode == AliasingMode::Memory) {
        r = placeInHeap(textures, order);
    } else if (mode == AliasingMode::ObjectReuse) {
        r = reuseObjects(textures, order);
    } else {
        for (uint32_t i : order) textures[i].physical = int(i), textures[i].offset = 0;
        r.withAliasing = total;
        r.allocations = uint32_t(order.size());
    }
    if (mode != AliasingMode::Memory) r.withoutAliasing = total;
    r.transientTextures = uint32_t(order.size());
    return r;
}

}  // namespace fe::graph
