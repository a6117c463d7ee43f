// Layer 2 (GDI abstraction), for the backends: native pipeline objects shared by the equal
// pipelines of one device. A renderer made again for another scene or technique asks for the
// same post-process, background and material pipelines as the one before it; compiling each
// again cost a third of a frame-graph test's time on the software rasterizers (a Vulkan
// pipeline 7 ms, a GL program 4 ms, the same on every call). Vulkan's VkPipelineCache does not
// help there (Mesa 22's lavapipe keeps nothing in it) and Mesa's GL refuses program binaries of
// SPIR-V programs, so the device keeps the native objects themselves: a pipeline whose key
// (every field of its description, its shaders by their code) equals one alive or recently
// destroyed shares that one's objects, and a destroyed pipeline's objects wait, up to
// kKeptUnusedPipelines of them, least recently used dropped first, for the next equal one.
#pragma once
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// How many pipelines no longer used a device keeps for reuse.
inline constexpr size_t kKeptUnusedPipelines = 128;

// A pipeline's key: its description as the capture format records every field of it (the one
// list of what a pipeline is), with each shader handle replaced by `codeOf(handle)`, which
// names the shader by its code, entry point and stage. Equal keys make the same native pipeline.
std::string pipelineKey(const GraphicsPipelineDesc& d,
                        const std::function<uint64_t(ShaderHandle)>& codeOf);
std::string pipelineKey(const ComputePipelineDesc& d,
                        const std::function<uint64_t(ShaderHandle)>& codeOf);

// The shared objects by key, with how many pipelines use each. `Native` is what the backend
// destroys when the last user is gone and the object leaves the kept set. Thread-safe.
template <class Native>
class SharedPipelines {
public:
    explicit SharedPipelines(size_t keepUnused = kKeptUnusedPipelines) : keep_(keepUnused) {}

    // The objects made for `key` before, now with one user more; nothing when there are none.
    std::optional<Native> acquire(const std::string& key) {
        std::lock_guard lock(mutex_);
        auto it = entries_.find(key);
        if (it == entries_.end()) return std::nullopt;
        if (it->second.users++ == 0) unused_.erase(it->second.unusedAt);
        ++shared_;
        return it->second.native;
    }
    // Objects just made for `key`, used by one pipeline.
    void add(const std::string& key, const Native& native) {
        std::lock_guard lock(mutex_);
        entries_[key] = Entry{native, 1, {}};
    }
    // One user fewer. Returns what must be destroyed now: nothing while a pipeline uses the
    // objects or while they are among the kept unused ones, else the least recently used.
    std::vector<Native> release(const std::string& key) {
        std::lock_guard lock(mutex_);
        std::vector<Native> drop;
        auto it = entries_.find(key);
        if (it == entries_.end() || it->second.users == 0 || --it->second.users > 0) return drop;
        it->second.unusedAt = unused_.insert(unused_.end(), key);
        while (unused_.size() > keep_) {
            auto oldest = entries_.find(unused_.front());
            drop.push_back(oldest->second.native);
            entries_.erase(oldest);
            unused_.pop_front();
        }
        return drop;
    }
    // Everything, used or not (the device goes): the caller destroys each once.
    std::vector<Native> clear() {
        std::lock_guard lock(mutex_);
        std::vector<Native> all;
        for (auto& [key, e] : entries_) all.push_back(e.native);
        entries_.clear();
        unused_.clear();
        return all;
    }
    // Pipelines that took the objects of an earlier equal one.
    uint32_t sharedCount() const {
        std::lock_guard lock(mutex_);
        return shared_;
    }

private:
    struct Entry {
        Native native;
        uint32_t users = 0;
        std::list<std::string>::iterator unusedAt;  // in unused_ while users == 0
    };
    mutable std::mutex mutex_;
    size_t keep_;
    std::map<std::string, Entry> entries_;
    std::list<std::string> unused_;  // least recently used first
    uint32_t shared_ = 0;
};

}  // namespace fe::gdi
