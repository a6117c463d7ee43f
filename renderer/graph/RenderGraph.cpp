#include "graph/RenderGraph.h"

#include <algorithm>
#include <sstream>

#include "graph/MemoryPlanner.h"

namespace fe::graph {

namespace {
// The buffer usage a transient buffer needs for an access.
gdi::BufferUsage usageFor(gdi::BufferAccess a) {
    using A = gdi::BufferAccess;
    using U = gdi::BufferUsage;
    U u = U::None;
    if (any(a, A::Vertex)) u = u | U::Vertex;
    if (any(a, A::Index)) u = u | U::Index;
    if (any(a, A::Indirect)) u = u | U::Indirect;
    if (any(a, A::Uniform)) u = u | U::Uniform;
    if (any(a, A::StorageRead | A::StorageWrite)) u = u | U::Storage;
    if (any(a, A::CopySrc)) u = u | U::CopySrc;
    if (any(a, A::CopyDst)) u = u | U::CopyDst;
    return u;
}

bool isTarget(gdi::ResourceState s) {
    return s == gdi::ResourceState::RenderTarget || s == gdi::ResourceState::DepthTarget;
}

std::string kib(uint64_t bytes) {
    std::ostringstream o;
    o.precision(1);
    o << std::fixed << double(bytes) / 1024.0 << " KiB";
    return o.str();
}
}  // namespace

bool TextureAccess::reads() const {
    return state == gdi::ResourceState::ShaderRead || load == gdi::LoadOp::Load;
}
// (A resolve destination is a RenderTarget access with DontCare load: a write, not a read.)
bool TextureAccess::writes() const {
    return isTarget(state) || state == gdi::ResourceState::Storage ||
           state == gdi::ResourceState::CopyDst;
}

// ---- declaration ------------------------------------------------------------------------------

void PassBuilder::colorTarget(TextureId t, gdi::LoadOp load, std::array<float, 4> clear,
                              uint32_t layer) {
    graph_.passes_[pass_].accesses.push_back({.texture = t,
                                              .state = gdi::ResourceState::RenderTarget,
                                              .load = load,
                                              .clearColor = clear,
                                              .layer = layer});
}
void PassBuilder::depthTarget(TextureId t, gdi::LoadOp load, float clearDepth, uint32_t layer) {
    graph_.passes_[pass_].accesses.push_back({.texture = t,
                                              .state = gdi::ResourceState::DepthTarget,
                                              .load = load,
                                              .clearDepth = clearDepth,
                                              .layer = layer});
}
void PassBuilder::resolve(TextureId source, TextureId destination) {
    // A depth resolve writes its destination as a depth attachment (the state its barriers name).
    const bool depth = gdi::isDepthFormat(graph_.textures_.at(destination.index).desc.format);
    graph_.passes_[pass_].accesses.push_back(
        {.texture = destination,
         .state = depth ? gdi::ResourceState::DepthTarget : gdi::ResourceState::RenderTarget,
         .load = gdi::LoadOp::DontCare,
         .resolveSource = source});
}
void PassBuilder::sample(TextureId t) {
    graph_.passes_[pass_].accesses.push_back(
        {.texture = t, .state = gdi::ResourceState::ShaderRead});
}
void PassBuilder::storage(TextureId t, bool readToo) {
    graph_.passes_[pass_].accesses.push_back(
        {.texture = t,
         .state = gdi::ResourceState::Storage,
         .load = readToo ? gdi::LoadOp::Load : gdi::LoadOp::DontCare});
}
void PassBuilder::copySource(TextureId t) {
    graph_.passes_[pass_].accesses.push_back(
        {.texture = t, .state = gdi::ResourceState::CopySrc, .load = gdi::LoadOp::Load});
}
void PassBuilder::copyDestination(TextureId t, bool readToo) {
    graph_.passes_[pass_].accesses.push_back(
        {.texture = t,
         .state = gdi::ResourceState::CopyDst,
         .load = readToo ? gdi::LoadOp::Load : gdi::LoadOp::DontCare});
}
void PassBuilder::buffer(BufferId b, gdi::BufferAccess access) {
    graph_.passes_[pass_].buffers.push_back({b, access});
}
void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }
void PassBuilder::asyncCompute() { graph_.passes_[pass_].asyncCompute = true; }

RenderGraph::RenderGraph() = default;
RenderGraph::~RenderGraph() { release(); }

TextureId RenderGraph::createTexture(std::string name, const TransientTextureDesc& d) {
    if (d.width == 0 || d.height == 0)
        throw gdi::Error("render graph: texture '" + name + "' has a zero size");
    TextureInfo t;
    t.name = std::move(name);
    if (d.sampleCount != 1 && d.sampleCount != 2 && d.sampleCount != 4 && d.sampleCount != 8)
        throw gdi::Error("render graph: texture '" + name + "' has sample count " +
                         std::to_string(d.sampleCount));
    const bool cube = d.dimension == gdi::TextureDimension::TextureCube;
    if (d.layers == 0 || (cube && d.layers != 6) ||
        d.dimension == gdi::TextureDimension::Texture3D ||
        (d.dimension == gdi::TextureDimension::Texture2D && d.layers != 1))
        throw gdi::Error(
            "render graph: texture '" + t.name + "' has " + std::to_string(d.layers) +
            " layers, which its dimension does not allow (2D: 1, cube: 6, arrays: 1 or more)");
    t.desc = {.dimension = d.dimension,
              .format = d.format,
              .width = d.width,
              .height = d.height,
              .depthOrLayers = d.layers,
              .sampleCount = d.sampleCount,
              .usage = gdi::TextureUsage::None};
    textures_.push_back(std::move(t));
    compiled_ = false;
    return {uint32_t(textures_.size() - 1)};
}

TextureId RenderGraph::importTexture(std::string name, gdi::TextureHandle texture,
                                     const gdi::TextureDesc& desc) {
    if (!texture)
        throw gdi::Error("render graph: imported texture '" + name + "' is a null handle");
    TextureInfo t;
    t.name = std::move(name);
    t.desc = desc;
    t.imported = true;
    textures_.push_back(std::move(t));
    handles_.resize(textures_.size());
    handles_.back() = texture;
    compiled_ = false;
    return {uint32_t(textures_.size() - 1)};
}

void RenderGraph::markOutput(TextureId t) {
    if (t.index >= textures_.size())
        throw gdi::Error("render graph: markOutput with an invalid texture id");
    textures_[t.index].output = true;
    compiled_ = false;
}

BufferId RenderGraph::createBuffer(std::string name, const TransientBufferDesc& d) {
    if (d.size == 0) throw gdi::Error("render graph: buffer '" + name + "' has size 0");
    buffers_.push_back({.name = std::move(name), .size = d.size});
    bufferHandles_.resize(buffers_.size());
    compiled_ = false;
    return {uint32_t(buffers_.size() - 1)};
}

BufferId RenderGraph::importBuffer(std::string name, gdi::BufferHandle buffer, uint64_t size) {
    if (!buffer) throw gdi::Error("render graph: imported buffer '" + name + "' is a null handle");
    buffers_.push_back({.name = std::move(name), .size = size, .imported = true});
    bufferHandles_.resize(buffers_.size());
    bufferHandles_.back() = buffer;
    compiled_ = false;
    return {uint32_t(buffers_.size() - 1)};
}

void RenderGraph::markOutput(BufferId b) {
    if (b.index >= buffers_.size())
        throw gdi::Error("render graph: markOutput with an invalid buffer id");
    buffers_[b.index].output = true;
    compiled_ = false;
}

const BufferInfo& RenderGraph::buffer(BufferId id) const {
    if (id.index >= buffers_.size()) throw gdi::Error("render graph: invalid buffer id");
    return buffers_[id.index];
}

gdi::BufferHandle RenderGraph::handle(BufferId id) const {
    const BufferInfo& b = buffer(id);
    if (!bufferHandles_[id.index])
        throw gdi::Error("render graph: buffer '" + b.name +
                         "' has no GPU buffer (unused, culled or not compiled for a device)");
    return bufferHandles_[id.index];
}

void RenderGraph::addPass(std::string name, const std::function<void(PassBuilder&)>& setup,
                          std::function<void(PassContext&)> execute) {
    passes_.push_back({.name = std::move(name)});
    executors_.push_back({.run = std::move(execute)});
    PassBuilder b(*this, uint32_t(passes_.size() - 1));
    if (setup) setup(b);
    compiled_ = false;
}
void RenderGraph::replaceImport(TextureId id, gdi::TextureHandle texture,
                                const gdi::TextureDesc& desc) {
    if (id.index >= textures_.size()) throw gdi::Error("render graph: invalid texture id");
    TextureInfo& t = textures_[id.index];
    const std::string what = "render graph: replacing imported texture '" + t.name + "': ";
    if (!t.imported) throw gdi::Error(what + "it is not imported");
    if (!texture) throw gdi::Error(what + "a null handle");
    if (desc.dimension != t.desc.dimension || desc.format != t.desc.format ||
        desc.sampleCount != t.desc.sampleCount)
        throw gdi::Error(what + "the new texture differs in dimension, format or samples");
    t.desc = desc;
    handles_[id.index] = texture;
}

const TextureInfo& RenderGraph::texture(TextureId id) const {
    if (id.index >= textures_.size()) throw gdi::Error("render graph: invalid texture id");
    return textures_[id.index];
}

gdi::TextureHandle RenderGraph::handle(TextureId id) const {
    const TextureInfo& t = texture(id);
    if (id.index >= handles_.size() || !handles_[id.index])
        throw gdi::Error("render graph: texture '" + t.name +
                         "' has no GPU texture (unused, culled or not compiled for a device)");
    return handles_[id.index];
}

// ---- compile ----------------------------------------------------------------------------------

void RenderGraph::cull() {
    // Backwards: a pass survives if it has side effects or writes something still needed; what
    // it reads is then needed, and what it overwrites entirely is not needed before it.
    // Buffer writes are partial (atomics, appends): they never end a buffer's need.
    std::vector<bool> needed(textures_.size(), false), bufferNeeded(buffers_.size(), false);
    for (size_t i = 0; i < textures_.size(); ++i) needed[i] = textures_[i].output;
    for (size_t i = 0; i < buffers_.size(); ++i) bufferNeeded[i] = buffers_[i].output;
    for (size_t p = passes_.size(); p-- > 0;) {
        PassInfo& pass = passes_[p];
        bool alive = pass.sideEffect;
        for (const TextureAccess& a : pass.accesses)
            alive = alive || (a.writes() && needed[a.texture.index]);
        for (const BufferUse& u : pass.buffers)
            alive = alive || (u.writes() && bufferNeeded[u.buffer.index]);
        pass.culled = !alive;
        if (!alive) continue;
        for (const TextureAccess& a : pass.accesses)
            if (a.writes() && !a.reads() && !a.partial) needed[a.texture.index] = false;
        for (const TextureAccess& a : pass.accesses)
            if (a.reads()) needed[a.texture.index] = true;
        for (const BufferUse& u : pass.buffers)
            if (u.reads()) bufferNeeded[u.buffer.index] = true;
    }
}

void RenderGraph::computeLifetimes() {
    int lastAlive = -1;
    for (size_t p = 0; p < passes_.size(); ++p) {
        if (passes_[p].culled) continue;
        lastAlive = int(p);
        for (const TextureAccess& a : passes_[p].accesses) {
            TextureInfo& t = textures_[a.texture.index];
            if (t.firstPass < 0) {
                t.firstPass = int(p);
                if (a.reads() && !t.imported)
                    throw gdi::Error("render graph: pass '" + passes_[p].name +
                                     "' reads transient texture '" + t.name +
                                     "' before any pass writes it");
            }
            t.lastPass = int(p);
            if (t.imported) continue;
            t.desc.usage = t.desc.usage |
                           (a.state == gdi::ResourceState::Storage   ? gdi::TextureUsage::Storage
                            : a.state == gdi::ResourceState::CopySrc ? gdi::TextureUsage::CopySrc
                            : a.state == gdi::ResourceState::CopyDst ? gdi::TextureUsage::CopyDst
                            : a.writes() ? gdi::TextureUsage::RenderTarget
                                         : gdi::TextureUsage::Sampled);
        }
    }
    for (size_t p = 0; p < passes_.size(); ++p) {
        if (passes_[p].culled) continue;
        for (const BufferUse& u : passes_[p].buffers) {
            BufferInfo& b = buffers_[u.buffer.index];
            if (b.firstPass < 0) b.firstPass = int(p);
            b.lastPass = int(p);
            if (!b.imported) b.usage = b.usage | usageFor(u.access);
        }
    }
    // Outputs live to the end of the frame: they are read after it.
    for (TextureInfo& t : textures_)
        if (t.output && t.used()) {
            t.lastPass = std::max(t.lastPass, lastAlive);
            if (!t.imported) t.desc.usage = t.desc.usage | gdi::TextureUsage::CopySrc;
        }
    markTransientAttachments();
}

// An attachment of one pass only, begun from a clear or nothing and read by no later pass (so
// stored DontCare, not resolved into): its contents live inside the pass. Transient usage lets
// Vulkan skip its memory on tile GPUs (lazily allocated) and every driver skip its stores.
void RenderGraph::markTransientAttachments() {
    for (size_t i = 0; i < textures_.size(); ++i) {
        TextureInfo& t = textures_[i];
        if (t.imported || t.output || !t.used() || t.firstPass != t.lastPass ||
            t.desc.usage != gdi::TextureUsage::RenderTarget || t.desc.mipLevels != 1)
            continue;
        bool passLocal = true;
        for (const TextureAccess& a : passes_[size_t(t.firstPass)].accesses)
            if (a.texture.index == i && (a.reads() || a.resolveSource.valid())) passLocal = false;
        if (passLocal) t.desc.usage = t.desc.usage | gdi::TextureUsage::Transient;
    }
}

// Per buffer: the accesses of its last write, and the kinds of read made visible since (or
// made since, for the next write to wait for). A read after a write waits for it once per
// kind of read; a write waits for the previous write and every read since.
void RenderGraph::planBufferBarriers() {
    struct Track {
        uint32_t lastWrite = 0, readsSince = 0, visibleTo = 0;
    };
    std::vector<Track> track(buffers_.size());
    for (PassInfo& pass : passes_) {
        pass.bufferBarriers.clear();
        if (pass.culled) continue;
        for (const BufferUse& u : pass.buffers) {
            Track& t = track[u.buffer.index];
            const uint32_t access = uint32_t(u.access);
            const uint32_t reads = access & ~BufferUse::kWriteBits;
            if (u.writes()) {
                if (t.lastWrite || t.readsSince)
                    pass.bufferBarriers.push_back(
                        {u.buffer, gdi::BufferAccess(t.lastWrite | t.readsSince), u.access});
                t = {access & BufferUse::kWriteBits, reads,
                     0};  // its own reads are the pass's business
            } else if (t.lastWrite && (reads & ~t.visibleTo)) {
                pass.bufferBarriers.push_back({u.buffer, gdi::BufferAccess(t.lastWrite), u.access});
                t.visibleTo |= reads;
                t.readsSince |= reads;
            } else {
                t.readsSince |= reads;
            }
        }
    }
}

void RenderGraph::checkBufferUses() const {
    for (const PassInfo& pass : passes_)
        for (size_t k = 0; k < pass.buffers.size(); ++k) {
            const BufferUse& u = pass.buffers[k];
            if (u.buffer.index >= buffers_.size())
                throw gdi::Error("render graph: pass '" + pass.name +
                                 "' uses an invalid buffer id");
            if (u.access == gdi::BufferAccess::None)
                throw gdi::Error("render graph: pass '" + pass.name + "' uses buffer '" +
                                 buffers_[u.buffer.index].name + "' with no access");
            for (size_t m = 0; m < k; ++m)
                if (pass.buffers[m].buffer == u.buffer)
                    throw gdi::Error("render graph: pass '" + pass.name + "' declares buffer '" +
                                     buffers_[u.buffer.index].name +
                                     "' twice (give every access in one call)");
        }
}

void RenderGraph::planBarriers() {
    // Every texture stays in one state until a pass needs another, or a pass writes what a
    // previous pass wrote (write-after-write between passes needs ordering too).
    std::vector<gdi::ResourceState> state(textures_.size(), gdi::ResourceState::Undefined);
    std::vector<bool> seen(textures_.size(), false);
    for (PassInfo& pass : passes_) {
        pass.barriers.clear();
        if (pass.culled) continue;
        for (const TextureAccess& a : pass.accesses) {
            const uint32_t i = a.texture.index;
            const TextureInfo& t = textures_[i];
            if (!seen[i]) {
                seen[i] = true;
                // Imported textures: earlier work is ordered by the backend when the graph
                // switches automatic barriers off. Transients start Undefined: their memory may
                // hold another texture's bytes.
                if (!t.imported)
                    pass.barriers.push_back({a.texture, gdi::ResourceState::Undefined, a.state});
            } else if (state[i] != a.state || a.writes()) {
                pass.barriers.push_back({a.texture, state[i], a.state});
            }
            state[i] = a.state;
        }
    }
}

// Async compute: runs of consecutive async passes become groups on the compute queue. A group
// may fork after the last graphics pass that shares a texture or buffer with it and must join
// before the first later one that does; the graphics passes between run beside it. Sharing
// nothing is what keeps the planned barriers right: each resource of the group is used by the
// graphics queue only before the fork (ordered by the compute submission's wait) or after the
// join (by the graphics submission's wait), so the barriers the serial order planned hold.
// Groups whose windows overlap share one compute list: it forks at the later fork and joins at
// the earlier join. A group that would leave its window with no graphics pass beside it runs in
// order on the graphics list.
void RenderGraph::planAsyncCompute() {
    for (PassInfo& p : passes_) p.forkBefore = p.joinBefore = -1;
    auto shares = [&](size_t a, size_t b) {
        for (const TextureAccess& x : passes_[a].accesses)
            for (const TextureAccess& y : passes_[b].accesses)
                if (x.texture == y.texture) return true;
        for (const BufferUse& x : passes_[a].buffers)
            for (const BufferUse& y : passes_[b].buffers)
                if (x.buffer == y.buffer) return true;
        return false;
    };
    struct Window {
        int fork = 0, join = 0;
        std::vector<int> members;
    };
    const int n = int(passes_.size());
    auto beside = [&](const Window& w) {
        for (int q = w.fork; q < w.join; ++q)
            if (!passes_[q].culled &&
                std::find(w.members.begin(), w.members.end(), q) == w.members.end())
                return true;
        return false;
    };
    std::vector<Window> windows;
    for (int first = 0; first < n;) {
        if (passes_[first].culled || !passes_[first].asyncCompute) {
            ++first;
            continue;
        }
        Window g;  // the group: async passes with no graphics pass between them
        int last = first;
        for (int q = first; q < n && (passes_[q].culled || passes_[q].asyncCompute); ++q)
            if (!passes_[q].culled) g.members.push_back(q), last = q;
        auto sharesGroup = [&](int q) {
            for (int m : g.members)
                if (shares(size_t(m), size_t(q))) return true;
            return false;
        };
        g.join = n;
        for (int q = first - 1; q >= 0 && g.fork == 0; --q)
            if (!passes_[q].culled && sharesGroup(q)) g.fork = q + 1;
        for (int q = last + 1; q < n && g.join == n; ++q)
            if (!passes_[q].culled && sharesGroup(q)) g.join = q;
        first = last + 1;
        if (!windows.empty() && g.fork < windows.back().join) {  // overlapping: one list
            Window merged = windows.back();
            merged.fork = std::max(merged.fork, g.fork);
            merged.join = std::min(merged.join, g.join);
            merged.members.insert(merged.members.end(), g.members.begin(), g.members.end());
            if (merged.fork < merged.join && beside(merged)) windows.back() = merged;
        } else if (beside(g)) {
            windows.push_back(g);
        }
    }
    for (const Window& w : windows)
        for (int m : w.members) {
            passes_[m].forkBefore = w.fork, passes_[m].joinBefore = w.join;
            // Alive over the whole window: nothing beside the group may share its memory.
            for (const TextureAccess& a : passes_[m].accesses) {
                TextureInfo& t = textures_[a.texture.index];
                t.firstPass = std::min(t.firstPass, w.fork);
                t.lastPass = std::max(t.lastPass, w.join - 1);
            }
        }
}

// A resolve's source is a multisampled target of the same pass; its destination a
// single-sample texture of the same format and size.
void RenderGraph::checkResolve(const PassInfo& pass, const TextureAccess& a,
                               const TextureInfo& dst) const {
    if (a.resolveSource.index >= textures_.size())
        throw gdi::Error("render graph: pass '" + pass.name + "' resolves an invalid texture id");
    const TextureInfo& src = textures_[a.resolveSource.index];
    const std::string what = "render graph: pass '" + pass.name + "' resolves '" + src.name +
                             "' into '" + dst.name + "': ";
    const bool target =
        std::any_of(pass.accesses.begin(), pass.accesses.end(), [&](const TextureAccess& o) {
            return o.texture == a.resolveSource && o.writes() && !o.resolveSource.valid();
        });
    if (!target) throw gdi::Error(what + "the source is not a target of this pass");
    if (src.desc.sampleCount == 1) throw gdi::Error(what + "the source is single-sample");
    if (dst.desc.sampleCount != 1) throw gdi::Error(what + "the destination is multisampled");
    if (src.desc.format != dst.desc.format || src.desc.width != dst.desc.width ||
        src.desc.height != dst.desc.height)
        throw gdi::Error(what + "format or size differ");
}

void RenderGraph::compile(const CompileOptions& options) {
    for (size_t p = 0; p < passes_.size(); ++p) {
        const PassInfo& pass = passes_[p];
        uint32_t w = 0, h = 0;
        bool depth = false;
        for (size_t k = 0; k < pass.accesses.size(); ++k) {
            const TextureAccess& a = pass.accesses[k];
            if (a.texture.index >= textures_.size())
                throw gdi::Error("render graph: pass '" + pass.name +
                                 "' uses an invalid texture id");
            const TextureInfo& t = textures_[a.texture.index];
            for (size_t m = 0; m < k; ++m)
                if (pass.accesses[m].texture == a.texture)
                    throw gdi::Error("render graph: pass '" + pass.name + "' uses texture '" +
                                     t.name +
                                     "' twice (a target cannot also be sampled in the same pass)");
            if (pass.asyncCompute && (isTarget(a.state) || a.resolveSource.valid()))
                throw gdi::Error(
                    "render graph: pass '" + pass.name +
                    "' may run on the compute queue (asyncCompute) but renders into '" + t.name +
                    "'");
            if (a.resolveSource.valid()) {
                checkResolve(pass, a, t);
                continue;
            }
            if (a.writes() && a.state != gdi::ResourceState::Storage &&
                a.layer >= t.desc.depthOrLayers)
                throw gdi::Error("render graph: pass '" + pass.name + "' renders into layer " +
                                 std::to_string(a.layer) + " of '" + t.name + "', which has " +
                                 std::to_string(t.desc.depthOrLayers));
            // Storage images are addressed by the shader and copies by their regions, not a
            // render area: any sizes may mix.
            if (!isTarget(a.state)) continue;
            const bool isDepth = gdi::isDepthFormat(t.desc.format);
            if ((a.state == gdi::ResourceState::DepthTarget) != isDepth)
                throw gdi::Error("render graph: pass '" + pass.name + "': texture '" + t.name +
                                 "' (" + std::string(gdi::formatInfo(t.desc.format).name) +
                                 ") cannot be a " + (isDepth ? "colour" : "depth") + " target");
            if (a.state == gdi::ResourceState::DepthTarget && depth)
                throw gdi::Error("render graph: pass '" + pass.name + "' has two depth targets");
            depth = depth || isDepth;
            if (w == 0) w = t.desc.width, h = t.desc.height;
            if (t.desc.width != w || t.desc.height != h)
                throw gdi::Error("render graph: pass '" + pass.name + "': target '" + t.name +
                                 "' is " + std::to_string(t.desc.width) + "x" +
                                 std::to_string(t.desc.height) + ", the others " +
                                 std::to_string(w) + "x" + std::to_string(h));
        }
    }
    for (PassInfo& pass : passes_)
        for (TextureAccess& a : pass.accesses)
            a.partial = a.writes() && a.state != gdi::ResourceState::Storage &&
                        textures_[a.texture.index].desc.depthOrLayers > 1;
    for (TextureInfo& t : textures_) {
        t.firstPass = t.lastPass = -1;
        t.offset = 0;
        t.physical = -1;
        t.ownMemory = false;
        if (!t.imported) t.desc.usage = gdi::TextureUsage::None;
    }
    checkBufferUses();
    for (BufferInfo& b : buffers_) {
        b.firstPass = b.lastPass = -1;
        if (!b.imported) b.usage = gdi::BufferUsage::None;
    }
    cull();
    computeLifetimes();
    planAsyncCompute();
    for (size_t i = 0; i < textures_.size(); ++i) {
        TextureInfo& t = textures_[i];
        if (t.imported || !t.used()) continue;
        if (options.lazilyAllocated && any(t.desc.usage, gdi::TextureUsage::Transient))
            t.ownMemory = true, t.physical = int(i);
        if (options.requirements) {
            gdi::MemoryRequirements r = options.requirements(t.desc);
            t.size = r.size;
            t.alignment = std::max<uint64_t>(1, r.alignment);
        } else {
            t.size = uint64_t(t.desc.width) * t.desc.height *
                     gdi::formatInfo(t.desc.format).bytesPerPixel * t.desc.sampleCount *
                     t.desc.depthOrLayers;
            t.alignment = 256;
        }
    }
    memory_ = planMemory(textures_, options.aliasing);
    aliasing_ = options.aliasing;
    planBarriers();
    planBufferBarriers();
    compiled_ = true;
}

void RenderGraph::release() {
    if (!device_) return;
    device_->waitIdleOrLost();  // also run by the destructor, which must not throw
    objects_.reset();           // newest first: the placed textures before their heap
    for (Executor& e : executors_) e.timer = {};
    for (size_t i = 0; i < textures_.size(); ++i)
        if (i < handles_.size() && !textures_[i].imported) handles_[i] = {};
    for (size_t i = 0; i < buffers_.size(); ++i)
        if (!buffers_[i].imported) bufferHandles_[i] = {};
    device_ = nullptr;
}

void RenderGraph::compile(gdi::Device& device, bool aliasing) {
    release();
    const bool heaps = device.info().features.memoryAliasing;
    CompileOptions options;
    options.aliasing = !aliasing ? AliasingMode::None
                       : heaps   ? AliasingMode::Memory
                                 : AliasingMode::ObjectReuse;
    options.lazilyAllocated = device.info().features.lazilyAllocatedMemory;
    if (heaps)
        options.requirements = [&](const gdi::TextureDesc& d) {
            return device.textureMemoryRequirements(d);
        };
    compile(options);

    device_ = &device;
    objects_.emplace(device);
    handles_.resize(textures_.size());
    gdi::HeapHandle heap;
    if (aliasing_ == AliasingMode::Memory && memory_.withAliasing > 0)
        heap = objects_->add(device.createHeap(
            {.size = memory_.withAliasing, .debugName = "render graph transients"}));
    for (size_t i = 0; i < textures_.size(); ++i) {
        const TextureInfo& t = textures_[i];
        if (t.imported || !t.used()) continue;
        if (aliasing_ == AliasingMode::ObjectReuse && t.physical != int(i))
            continue;  // shares below
        gdi::TextureDesc d = t.desc;
        d.debugName = t.name.c_str();
        if (heap && !t.ownMemory) d.heap = heap, d.heapOffset = t.offset;
        handles_[i] = objects_->add(device.createTexture(d));
    }
    for (size_t i = 0; i < textures_.size(); ++i)
        if (!textures_[i].imported && textures_[i].used() && !handles_[i])
            handles_[i] = handles_[textures_[i].physical];
    for (size_t i = 0; i < buffers_.size(); ++i) {
        const BufferInfo& b = buffers_[i];
        if (b.imported || !b.used()) continue;
        bufferHandles_[i] = objects_->add(
            device.createBuffer({.size = b.size, .usage = b.usage, .debugName = b.name.c_str()}));
    }
    if (device.info().features.timestamps)
        for (size_t p = 0; p < passes_.size(); ++p)
            if (!passes_[p].culled) executors_[p].timer = objects_->add(device.createTimer());
}

// ---- execute ----------------------------------------------------------------------------------

gdi::TextureHandle PassContext::texture(TextureId id) const { return graph_.handle(id); }
gdi::BufferHandle PassContext::buffer(BufferId id) const { return graph_.handle(id); }

void PassContext::beginRenderPass() {
    const PassInfo& pass = graph_.passes_[pass_];
    gdi::RenderPassDesc rp;
    std::vector<TextureId> colorIds;
    for (const TextureAccess& a : pass.accesses) {
        if (!isTarget(a.state) || a.resolveSource.valid())
            continue;  // storage images are no attachments
        const TextureInfo& t = graph_.textures_[a.texture.index];
        // Contents nobody reads after this pass need not reach memory (a resolved multisampled
        // target's samples usually are not).
        const bool keep = t.imported || t.output || t.lastPass > int(pass_);
        const gdi::StoreOp store = keep ? gdi::StoreOp::Store : gdi::StoreOp::DontCare;
        if (a.state == gdi::ResourceState::DepthTarget) {
            rp.depth = {.texture = texture(a.texture),
                        .layer = a.layer,
                        .load = a.load,
                        .store = store,
                        .clearDepth = a.clearDepth};
        } else {
            gdi::ColorAttachment c{
                .texture = texture(a.texture), .layer = a.layer, .load = a.load, .store = store};
            std::copy(a.clearColor.begin(), a.clearColor.end(), c.clear);
            rp.colors.push_back(c);
            colorIds.push_back(a.texture);
        }
    }
    for (const TextureAccess& a : pass.accesses) {
        if (!a.resolveSource.valid()) continue;
        const auto it = std::find(colorIds.begin(), colorIds.end(), a.resolveSource);
        if (it != colorIds.end())
            rp.colors[size_t(it - colorIds.begin())].resolveTexture = texture(a.texture);
        else
            rp.depth.resolveTexture = texture(a.texture);
    }
    if (rp.colors.empty() && !rp.depth.texture)
        throw gdi::Error("render graph: pass '" + pass.name +
                         "' begins a render pass but declared no targets");
    cmd.beginRenderPass(rp);
}

void RenderGraph::execute(gdi::CommandList& cmd,
                          const std::function<void(const std::string&)>& afterPass) {
    if (!compiled_ || !device_) throw gdi::Error("render graph: execute before compile(device)");
    cmd.setAutomaticBarriers(false);
    for (size_t p = 0; p < passes_.size(); ++p) {
        if (passes_[p].culled) continue;
        recordPass(cmd, p);
        if (afterPass) {
            afterPass(passes_[p].name);
            cmd.setAutomaticBarriers(false);  // a submitted list starts over with the default
        }
    }
    cmd.setAutomaticBarriers(true);
}

void RenderGraph::recordPass(gdi::CommandList& cmd, size_t p) {
    const PassInfo& pass = passes_[p];
    std::vector<gdi::TextureBarrier> barriers;
    for (const PlannedBarrier& b : pass.barriers)
        barriers.push_back({handle(b.texture), b.before, b.after});
    cmd.barrier(barriers.data(), uint32_t(barriers.size()));
    std::vector<gdi::BufferBarrier> bufferBarriers;
    for (const PlannedBufferBarrier& b : pass.bufferBarriers)
        bufferBarriers.push_back(
            {.buffer = handle(b.buffer), .before = b.before, .after = b.after});
    cmd.barrier(bufferBarriers.data(), uint32_t(bufferBarriers.size()));
    cmd.pushDebugGroup(pass.name.c_str());
    Executor& e = executors_[p];
    if (e.timer) cmd.beginTimer(e.timer);
    PassContext ctx(cmd, *this, uint32_t(p));
    if (e.run) e.run(ctx);
    if (e.timer) cmd.endTimer(e.timer);
    cmd.popDebugGroup();
    e.timed = bool(e.timer);
}

void RenderGraph::execute(render::CommandQueue& queue) {
    if (!compiled_ || !device_) throw gdi::Error("render graph: execute before compile(device)");
    gdi::CommandList* graphics = &queue.graphics();
    graphics->setAutomaticBarriers(false);
    auto cut = [&] {  // submits the graphics list so far and continues in a new one
        graphics->setAutomaticBarriers(true);
        const gdi::FenceValue fence = queue.submitGraphics();
        graphics = &queue.graphics();
        graphics->setAutomaticBarriers(false);
        return fence;
    };
    int join = -1;
    gdi::FenceValue computeDone = 0;
    const int n = int(passes_.size());
    for (int p = 0; p <= n; ++p) {
        if (p == join) {  // the graphics passes from here on wait for the group
            if (p < n) cut();
            queue.graphicsWaits(computeDone);
            join = -1;
        }
        if (p == n) break;
        gdi::CommandList* compute = nullptr;
        for (int m = p; m < n; ++m) {  // a group forking here: its passes on a compute list
            if (passes_[m].culled || passes_[m].forkBefore != p) continue;
            if (!compute) {
                const gdi::FenceValue before = cut();
                compute = &queue.compute();
                compute->setAutomaticBarriers(false);
                computeDone = before;  // the compute submission waits for the graphics before it
            }
            recordPass(*compute, size_t(m));
            join = passes_[m].joinBefore;
        }
        if (compute) {
            compute->setAutomaticBarriers(true);
            computeDone = queue.submitCompute(*compute, computeDone);
        }
        if (!passes_[p].culled && passes_[p].forkBefore < 0) recordPass(*graphics, size_t(p));
    }
    graphics->setAutomaticBarriers(true);
}

std::vector<PassTiming> RenderGraph::passTimings() const {
    std::vector<PassTiming> out;
    if (!device_) return out;
    for (size_t p = 0; p < passes_.size(); ++p)
        if (executors_[p].timed)
            if (auto ns = device_->timerNanoseconds(executors_[p].timer))
                out.push_back({passes_[p].name, *ns / 1e6});
    return out;
}

// ---- report -----------------------------------------------------------------------------------

std::string RenderGraph::toDot() const {
    auto quote = [](const std::string& s) {
        std::string q = "\"";
        for (char c : s) q += (c == '"' ? std::string("\\\"") : std::string(1, c));
        return q + "\"";
    };
    static const char* modeNames[] = {"none", "memory", "object reuse"};
    std::ostringstream o;
    o << "digraph RenderGraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n";
    o << "  label="
      << quote("transient memory: " + kib(memory_.withoutAliasing) + " without aliasing, " +
               kib(memory_.withAliasing) + " with (" + modeNames[int(aliasing_)] + ")")
      << ";\n";
    for (size_t p = 0; p < passes_.size(); ++p) {
        const PassInfo& pass = passes_[p];
        std::string label = std::to_string(p) + ": " + pass.name;
        for (const PlannedBarrier& b : pass.barriers)
            label += "\\n" + textures_[b.texture.index].name + ": " +
                     gdi::resourceStateName(b.before) + " -> " + gdi::resourceStateName(b.after);
        if (pass.culled) label += "\\n(culled)";
        o << "  p" << p << " [shape=box, label=" << quote(label)
          << (pass.culled ? ", style=dashed, color=gray50, fontcolor=gray50"
                          : ", style=filled, fillcolor=lightblue")
          << "];\n";
    }
    for (size_t i = 0; i < textures_.size(); ++i) {
        const TextureInfo& t = textures_[i];
        std::string label = t.name + "\\n" + std::string(gdi::formatInfo(t.desc.format).name) +
                            " " + std::to_string(t.desc.width) + "x" +
                            std::to_string(t.desc.height);
        if (t.imported) label += "\\nimported";
        if (!t.used())
            label += "\\nunused";
        else
            label += "\\npasses " + std::to_string(t.firstPass) + "-" + std::to_string(t.lastPass);
        if (!t.imported && t.used()) {
            label += "\\n" + kib(t.size);
            if (aliasing_ == AliasingMode::Memory) label += " @ " + std::to_string(t.offset);
            if (aliasing_ == AliasingMode::ObjectReuse && t.physical != int(i))
                label += "\\nreuses " + textures_[t.physical].name;
        }
        o << "  t" << i << " [shape=ellipse, label=" << quote(label)
          << (t.output ? ", peripheries=2" : "") << (t.used() ? "" : ", style=dashed, color=gray50")
          << "];\n";
    }
    for (size_t i = 0; i < buffers_.size(); ++i) {
        const BufferInfo& b = buffers_[i];
        std::string label = b.name + "\\nbuffer " + std::to_string(b.size) + " B" +
                            (b.imported ? "\\nimported" : "");
        o << "  b" << i << " [shape=cylinder, label=" << quote(label)
          << (b.used() ? "" : ", style=dashed, color=gray50") << "];\n";
    }
    for (size_t p = 0; p < passes_.size(); ++p)
        for (const BufferUse& u : passes_[p].buffers) {
            const std::string style = passes_[p].culled ? " [style=dashed, color=gray50]" : "";
            if (u.reads()) o << "  b" << u.buffer.index << " -> p" << p << style << ";\n";
            if (u.writes()) o << "  p" << p << " -> b" << u.buffer.index << style << ";\n";
        }
    for (size_t p = 0; p < passes_.size(); ++p)
        for (const TextureAccess& a : passes_[p].accesses) {
            const std::string style = passes_[p].culled ? " [style=dashed, color=gray50]" : "";
            if (a.reads()) o << "  t" << a.texture.index << " -> p" << p << style << ";\n";
            if (a.writes()) o << "  p" << p << " -> t" << a.texture.index << style << ";\n";
        }
    o << "}\n";
    return o.str();
}

}  // namespace fe::graph
