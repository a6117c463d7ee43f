// Layer 6 (Organisation): the render graph.
//
// A frame is declared as passes that say which textures they write (colour/depth targets)
// and read (sampled), and which buffers they read and write, with how (BufferAccess: indirect
// arguments, vertices, storage, copies). compile() then
//   1. culls every pass whose results nothing uses (outputs and side effects are roots),
//   2. computes each texture's first and last use among the surviving passes,
//   3. plans memory for the transient textures: textures whose lifetimes do not overlap share
//      bytes of one heap (Vulkan: placed images) or share whole objects (OpenGL),
//   4. derives the barriers before each pass from the state each texture moves between, and
//      for buffers from each write and the reads after it (buffer memory barriers).
// execute() records the passes in order, each in a debug group and a GPU timer, with the
// backend's automatic barriers off: the graph's barriers are the only synchronisation.
//
//   graph::RenderGraph g;
//   auto depth = g.createTexture("depth", {.format = gdi::Format::D32F, .width = w, .height = h});
//   auto out = g.importTexture("output", outputTexture);
//   g.addPass("forward", [&](graph::PassBuilder& b) {
//       b.colorTarget(out);
//       b.depthTarget(depth);
//   }, [&](graph::PassContext& ctx) {
//       ctx.beginRenderPass();
//       ... draws on ctx.cmd ...
//       ctx.cmd.endRenderPass();
//   });
//   g.markOutput(out);
//   g.compile(device);            // plan + create transient textures
//   g.execute(cmd);               // every frame
//
// A compiled graph is kept and executed frame after frame; transient memory is allocated once
// at compile and reused by every frame (recompile when the frame's structure changes).
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "graph/GraphTypes.h"

namespace fe::graph {

// A texture the graph creates and whose memory it may alias. Usage is derived from the passes.
struct TransientTextureDesc {
    gdi::Format format = gdi::Format::RGBA8;
    uint32_t width = 1;
    uint32_t height = 1;
    // > 1: a multisampled target, read by a resolve or sampled per sample (sampler2DMS)
    uint32_t sampleCount = 1;
    // Layered textures (shadow cascades in a Texture2DArray, a point light's TextureCube): each
    // pass renders into one layer (PassBuilder's `layer`) and shaders sample every layer.
    gdi::TextureDimension dimension = gdi::TextureDimension::Texture2D;
    uint32_t layers = 1;  // TextureCube: 6
};

struct TransientBufferDesc {
    uint64_t size = 0;
};

// How a pass uses a buffer: `access` says how (flags); StorageWrite and CopyDst are writes.
struct BufferUse {
    BufferId buffer;
    gdi::BufferAccess access = gdi::BufferAccess::StorageRead;
    static constexpr uint32_t kWriteBits =
        uint32_t(gdi::BufferAccess::StorageWrite) | uint32_t(gdi::BufferAccess::CopyDst);
    bool writes() const { return (uint32_t(access) & kWriteBits) != 0; }
    bool reads() const { return (uint32_t(access) & ~kWriteBits) != 0; }
};

// How a pass uses a texture.
struct TextureAccess {
    TextureId texture;
    gdi::ResourceState state = gdi::ResourceState::ShaderRead;
    gdi::LoadOp load = gdi::LoadOp::Load;  // targets only
    std::array<float, 4> clearColor{0, 0, 0, 0};
    float clearDepth = 1.0f;
    // Valid for a resolve destination: the multisampled target of the same pass it receives.
    // Resolves write in the colour-output stage on Vulkan, depth too, so the state is RenderTarget.
    TextureId resolveSource;
    uint32_t layer = 0;    // targets: the layer rendered into (layered textures)
    bool partial = false;  // a target that is one layer of several: the others keep their contents
    bool reads() const;    // sampled, or a target or storage image whose old contents are loaded
    bool writes() const;   // a target or a storage image
};

class PassBuilder {
public:
    // Attachments in declaration order (colour index 0, 1, ...). `layer`: the layer of a layered
    // texture this pass renders into; passes writing different layers all survive culling.
    void colorTarget(TextureId texture, gdi::LoadOp load = gdi::LoadOp::Clear,
                     std::array<float, 4> clear = {0, 0, 0, 0}, uint32_t layer = 0);
    void depthTarget(TextureId texture, gdi::LoadOp load = gdi::LoadOp::Clear,
                     float clearDepth = 1.0f, uint32_t layer = 0);
    // At the end of the pass, the multisampled target `source` (colour: the average of each
    // pixel's samples; depth: sample 0) is written into single-sample `destination`.
    void resolve(TextureId source, TextureId destination);
    void sample(TextureId texture);
    // Written as a storage image (compute); `readToo`: its earlier contents are read as well.
    void storage(TextureId texture, bool readToo = false);
    // Read, or written, by copies (copyTexture) and mip generation (generateMips, which reads
    // and writes its texture: the destination's state); `readToo`: earlier contents are kept.
    // Ordering copies within the pass (a copy's destination read by the next) is the pass's own
    // barrier.
    void copySource(TextureId texture);
    void copyDestination(TextureId texture, bool readToo = false);
    // Buffers: every access of the pass to the buffer, as flags (Indirect | StorageRead, ...).
    // Writes (StorageWrite, CopyDst) are taken as partial: earlier contents stay needed.
    void buffer(BufferId buffer, gdi::BufferAccess access);
    // The pass has effects the graph cannot see: never culled.
    void sideEffect();
    // The pass may run on the compute queue beside the graphics passes that share no texture
    // or buffer with it (execute(CommandQueue&)). It records compute work only: dispatches,
    // copies, barriers, timers; no targets (an Error at compile).
    void asyncCompute();

private:
    friend class RenderGraph;
    explicit PassBuilder(class RenderGraph& g, uint32_t pass) : graph_(g), pass_(pass) {}
    RenderGraph& graph_;
    uint32_t pass_;
};

class PassContext {
public:
    gdi::CommandList& cmd;
    gdi::TextureHandle texture(TextureId id) const;
    gdi::BufferHandle buffer(BufferId id) const;
    // Begins a render pass on the declared targets with their load ops and clear values.
    void beginRenderPass();

private:
    friend class RenderGraph;
    PassContext(gdi::CommandList& c, const class RenderGraph& g, uint32_t pass)
        : cmd(c), graph_(g), pass_(pass) {}
    const RenderGraph& graph_;
    uint32_t pass_;
};

struct CompileOptions {
    AliasingMode aliasing = AliasingMode::Memory;
    // Size and alignment of a texture's memory; default: width x height x bytes per pixel, 256-aligned.
    std::function<gdi::MemoryRequirements(const gdi::TextureDesc&)> requirements;
    // Transient attachments (one pass's, TextureUsage::Transient) get memory of their own, lazily
    // allocated, instead of a place in the plan (DeviceFeatures::lazilyAllocatedMemory).
    bool lazilyAllocated = false;
};

// A state change the graph records before a pass (gdi::TextureBarrier once textures exist).
struct PlannedBarrier {
    TextureId texture;
    gdi::ResourceState before = gdi::ResourceState::Undefined;
    gdi::ResourceState after = gdi::ResourceState::ShaderRead;
};
// A buffer dependency the graph records before a pass (a gdi::BufferBarrier, whole buffer).
struct PlannedBufferBarrier {
    BufferId buffer;
    gdi::BufferAccess before = gdi::BufferAccess::StorageWrite;
    gdi::BufferAccess after = gdi::BufferAccess::StorageRead;
};

struct PassInfo {
    std::string name;
    std::vector<TextureAccess> accesses;
    std::vector<BufferUse> buffers;
    bool sideEffect = false;
    bool culled = false;
    bool asyncCompute = false;  // PassBuilder::asyncCompute
    // Planned by compile for an async compute pass: it starts on the compute queue once the
    // graphics passes before `forkBefore` have been submitted, the graphics passes from there up
    // to `joinBefore` run beside it, and those from `joinBefore` on wait for it (passes_.size():
    // the frame's end). -1: it runs in order on the graphics list (its window would overlap an
    // earlier async pass's).
    int forkBefore = -1, joinBefore = -1;
    std::vector<PlannedBarrier> barriers;  // recorded before the pass
    std::vector<PlannedBufferBarrier> bufferBarriers;
};

struct PassTiming {
    std::string name;
    double gpuMilliseconds = 0;
};

class RenderGraph {
public:
    RenderGraph();
    ~RenderGraph();
    RenderGraph(const RenderGraph&) = delete;
    RenderGraph& operator=(const RenderGraph&) = delete;

    TextureId createTexture(std::string name, const TransientTextureDesc& desc);
    TextureId importTexture(std::string name, gdi::TextureHandle texture,
                            const gdi::TextureDesc& desc);
    // Points an imported texture at another of the same kind, format and samples (a buffer that
    // grew: its size may differ) for the frames recorded from now on; no recompile is needed.
    void replaceImport(TextureId id, gdi::TextureHandle texture, const gdi::TextureDesc& desc);
    void markOutput(TextureId texture);  // its producers are never culled
    BufferId createBuffer(std::string name, const TransientBufferDesc& desc);
    BufferId importBuffer(std::string name, gdi::BufferHandle buffer, uint64_t size);
    void markOutput(BufferId buffer);  // read after the frame: its writers are never culled
    void addPass(std::string name, const std::function<void(PassBuilder&)>& setup,
                 std::function<void(PassContext&)> execute);

    // Plans without a device (unit tests, reports). Throws gdi::Error on a malformed graph.
    void compile(const CompileOptions& options);
    // Plans for the device (Memory aliasing where it has heaps, ObjectReuse elsewhere, or None
    // when aliasing is false) and creates the transient textures and the pass timers.
    void compile(gdi::Device& device, bool aliasing = true);

    // Records every surviving pass. Requires compile(device). `afterPass`, when given, runs after
    // each pass with its name (a profiling run flushes and waits there); the graph then records
    // on into the same list.
    void execute(gdi::CommandList& cmd,
                 const std::function<void(const std::string& pass)>& afterPass = {});
    // Records the frame into the queue's lists: the async compute passes (PassInfo::forkBefore)
    // on compute-queue lists, the graphics list cut and submitted at each fork and join, the
    // graphics passes after a join waiting for the compute work (CommandQueue::graphicsWaits).
    // The caller ends the frame (CommandQueue::endFrame).
    void execute(render::CommandQueue& queue);

    const std::vector<PassInfo>& passes() const { return passes_; }
    const std::vector<TextureInfo>& textures() const { return textures_; }
    const TextureInfo& texture(TextureId id) const;
    gdi::TextureHandle handle(TextureId id) const;  // after compile(device)
    const std::vector<BufferInfo>& buffers() const { return buffers_; }
    const BufferInfo& buffer(BufferId id) const;
    gdi::BufferHandle handle(BufferId id) const;  // imported, or transient after compile(device)
    MemoryReport memory() const { return memory_; }
    AliasingMode aliasing() const { return aliasing_; }
    // GPU time per executed pass of the last executed frame, once its fence has signalled.
    std::vector<PassTiming> passTimings() const;
    // Graphviz: passes as boxes (culled ones dashed), textures as ellipses with lifetime and memory.
    std::string toDot() const;

private:
    friend class PassBuilder;
    friend class PassContext;
    void release();
    void cull();
    void computeLifetimes();
    void markTransientAttachments();
    void planBarriers();
    void planAsyncCompute();
    void recordPass(gdi::CommandList& cmd, size_t p);
    void planBufferBarriers();
    void checkBufferUses() const;
    void checkResolve(const PassInfo& pass, const TextureAccess& a, const TextureInfo& dst) const;

    struct Executor {
        std::function<void(PassContext&)> run;
        gdi::TimerHandle timer;
        bool timed = false;
    };
    // What compile(device) created (the pass timers, the transient textures and the heap they
    // are placed in), released on recompile and destruction.
    std::optional<gdi::DeviceObjects> objects_;
    std::vector<TextureInfo> textures_;
    std::vector<gdi::TextureHandle> handles_;  // per texture
    std::vector<BufferInfo> buffers_;
    std::vector<gdi::BufferHandle> bufferHandles_;  // per buffer
    std::vector<PassInfo> passes_;
    std::vector<Executor> executors_;
    MemoryReport memory_;
    AliasingMode aliasing_ = AliasingMode::None;
    bool compiled_ = false;
    gdi::Device* device_ = nullptr;  // of compile(device)
};

}  // namespace fe::graph
