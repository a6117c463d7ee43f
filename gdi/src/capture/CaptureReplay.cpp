// Replays a capture file on any device: objects are made again from their descriptions (handle
// ids mapped), data written as it was, each submission's command lists applied from their
// streams (applyStream), and waits, read-backs and presents repeated in the same order.
#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <cstring>
#include <deque>

#include "CaptureFile.h"
#include "CaptureJson.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/CommandRecorder.h"

namespace fe::gdi {

namespace {

using capture::json;
using capture::u32;
using capture::u64;
using Clock = std::chrono::steady_clock;

class Replayer {
public:
    Replayer(Device& device, const ReplayOptions& options)
        : device_(device), options_(options), probe_(*this) {
        map_.keepUnknown = false;
        if (!options_.outDir.empty()) std::filesystem::create_directories(options_.outDir);
    }
    // What the capture left alive is destroyed, views before their textures, pipelines before
    // their shaders, placed textures before their heaps.
    ~Replayer() {
        // Each on its own: one refusal (a lost device) does not keep the others alive.
        auto destroy = [&](auto handle) {
            try {
                device_.destroy(handle);
            } catch (const std::exception&) {}
        };
        try {
            device_.waitIdle();
        } catch (const std::exception&) {}
        for (auto& [c, r] : map_.pipelines) destroy(PipelineHandle{r});
        for (auto& [c, r] : shaders_) destroy(ShaderHandle{r});
        for (uint32_t r : views_) destroy(TextureHandle{r});
        for (auto& [c, r] : map_.textures)
            if (!views_.count(r)) destroy(TextureHandle{r});
        for (auto& [c, r] : heaps_) destroy(HeapHandle{r});
        for (auto& [c, r] : map_.buffers) destroy(BufferHandle{r});
        for (auto& [c, r] : map_.samplers) destroy(SamplerHandle{r});
        for (auto& [c, r] : map_.timers) destroy(TimerHandle{r});
        for (auto& [c, r] : map_.querySets) destroy(QuerySetHandle{r});
    }

    ReplayResult run(const std::string& path) {
        capture::Reader reader(path);
        result_.formatVersion = reader.version();
        capture::Chunk chunk;
        uint64_t index = 0;
        frameStart_ = Clock::now();
        try {
            while (reader.next(chunk)) {
                if (chunk.kind == capture::ChunkKind::Blob) {
                    blobs_.push_back(std::move(chunk.bytes));
                } else if (chunk.kind == capture::ChunkKind::Record) {
                    apply(chunk, index++);
                }
            }
            while (!mappedForRead_.empty()) keepMappedRead(mappedForRead_.begin()->first);
        } catch (const Stopped&) {
            // A probe ended the replay where it was asked to.
        }
        device_.waitIdle();
        result_.draws = probe_.draw, result_.passes = probe_.pass;
        return std::move(result_);
    }

private:
    void apply(const capture::Chunk& chunk, uint64_t index) {
        std::string op = "?";
        try {
            const json r = json::from_cbor(chunk.bytes);
            if (!r.is_object() || !r.contains("op") || !r["op"].is_string())
                throw std::runtime_error("record without an op");
            op = r["op"].get<std::string>();
            if (index == 0 && op != "device")
                throw std::runtime_error("the first record is not the device's");
            const auto it = handlers().find(op);
            if (it == handlers().end()) throw std::runtime_error("unknown call");
            (this->*(it->second))(r);
            ++result_.records;
        } catch (const DeviceLostError&) {
            throw;
        } catch (const Stopped&) {
            throw;
        } catch (const CaptureError& e) {
            throw CaptureError(where(chunk, index, op) + e.what());
        } catch (const std::exception& e) {
            throw CaptureError(where(chunk, index, op) + e.what());
        }
    }
    static std::string where(const capture::Chunk& c, uint64_t index, const std::string& op) {
        return "capture: record " + std::to_string(index) + " (" + op + ") at offset " +
               std::to_string(c.offset) + ": ";
    }

    using Handler = void (Replayer::*)(const json&);
    static const std::unordered_map<std::string, Handler>& handlers() {
        static const std::unordered_map<std::string, Handler> h = {
            {"device", &Replayer::deviceRecord},
            {"createBuffer", &Replayer::createBuffer},
            {"createTexture", &Replayer::createTexture},
            {"createTextureView", &Replayer::createTextureView},
            {"createSampler", &Replayer::createSampler},
            {"createShader", &Replayer::createShader},
            {"createGraphicsPipeline", &Replayer::createGraphicsPipeline},
            {"createComputePipeline", &Replayer::createComputePipeline},
            {"createTimer", &Replayer::createTimer},
            {"createHeap", &Replayer::createHeap},
            {"createQuerySet", &Replayer::createQuerySet},
            {"destroy", &Replayer::destroy},
            {"writeBuffer", &Replayer::writeBuffer},
            {"mapped", &Replayer::mapped},
            {"writeTexture", &Replayer::writeTexture},
            {"writeTextureRegion", &Replayer::writeTextureRegion},
            {"readBuffer", &Replayer::readBuffer},
            {"mapRead", &Replayer::mapRead},
            {"restoreBuffer", &Replayer::restoreBuffer},
            {"restoreTexture", &Replayer::restoreTexture},
            {"queryResults", &Replayer::queryResults},
            {"readTexture", &Replayer::readTexture},
            {"submit", &Replayer::submit},
            {"wait", &Replayer::wait},
            {"waitIdle", &Replayer::waitIdle},
            {"present", &Replayer::present},
            {"frame", &Replayer::frame},
        };
        return h;
    }

    std::span<const std::byte> blob(const json& r, const char* key) const {
        const uint64_t id = u64(r, key);
        if (id == 0) return {};
        if (id > blobs_.size())
            throw std::runtime_error("data block " + std::to_string(id) +
                                     " is not in the file before it");
        return blobs_[id - 1];
    }
    // The id a create record names, checked before the object is made (so a refusal leaves
    // nothing behind): an id that is null or already in use is damage.
    static uint32_t freeId(const std::unordered_map<uint32_t, uint32_t>& m, const json& r) {
        const uint32_t captured = u32(r, "id");
        if (captured == 0 || m.count(captured))
            throw std::runtime_error("object id " + std::to_string(captured) +
                                     " is null or already in use");
        return captured;
    }
    static void bind(std::unordered_map<uint32_t, uint32_t>& m, uint32_t captured,
                     uint32_t replayed) {
        m.emplace(captured, replayed);
    }
    static uint32_t lookup(const std::unordered_map<uint32_t, uint32_t>& m, uint32_t captured) {
        if (captured == 0) return 0;
        const auto it = m.find(captured);
        return it == m.end() ? HandleMap::kUnknownId : it->second;
    }
    BufferHandle buffer(const json& r, const char* key = "id") const {
        return {lookup(map_.buffers, u32(r, key))};
    }
    TextureHandle texture(const json& r, const char* key = "id") const {
        return {lookup(map_.textures, u32(r, key))};
    }

    void deviceRecord(const json& r) {
        result_.capturedBackend = r.at("backend").get<std::string>();
        if (u64(r, "commandSet") != capture::commandSetFingerprint())
            throw std::runtime_error(
                "recorded with another build's command set; its command lists cannot be read here");
    }
    void createBuffer(const json& r) {
        freeId(map_.buffers, r);
        BufferDesc d = capture::bufferDesc(r.at("desc"), strings_);
        // A trimmed capture's state is written into it (restoreBuffer).
        if (r.contains("restore") && d.access == MemoryAccess::GpuOnly)
            d.usage = d.usage | BufferUsage::CopyDst;
        const BufferHandle h = device_.createBuffer(d, blob(r, "data"));
        bind(map_.buffers, u32(r, "id"), h.id);
        bufferNames_[u32(r, "id")] =
            d.debugName ? d.debugName : "buffer " + std::to_string(u32(r, "id"));
    }
    void createTexture(const json& r) {
        freeId(map_.textures, r);
        TextureDesc d = capture::textureDesc(r.at("desc"), strings_);
        if (unplacedHeaps_.count(d.heap.id))
            d.heap = {}, d.heapOffset = 0;
        else
            d.heap = {lookup(heaps_, d.heap.id)};
        if (r.contains("restore") &&  // a trimmed capture's state is written into it
            !any(d.usage, TextureUsage::Transient)) {  // (restoreTexture); a transient has none
            TextureDesc writable = d;
            writable.usage = d.usage | TextureUsage::CopyDst;
            if (device_.supportsFormat(d.format, writable.usage)) d = writable;
        }
        const TextureHandle h = createReadableTexture(d);
        bind(map_.textures, u32(r, "id"), h.id);
        names_[h.id] = d.debugName ? d.debugName : "texture " + std::to_string(u32(r, "id"));
        textureNames_[u32(r, "id")] = names_[h.id];
    }
    void createTextureView(const json& r) {
        freeId(map_.textures, r);
        const TextureViewDesc d = capture::textureViewDesc(r.at("desc"), strings_);
        const TextureHandle h = device_.createTextureView(texture(r, "of"), d);
        bind(map_.textures, u32(r, "id"), h.id);
        views_.insert(h.id);
        names_[h.id] = d.debugName ? d.debugName : "view " + std::to_string(u32(r, "id"));
        textureNames_[u32(r, "id")] = names_[h.id];
    }
    void createSampler(const json& r) {
        freeId(map_.samplers, r);
        const SamplerHandle h = device_.createSampler(capture::samplerDesc(r.at("desc"), strings_));
        bind(map_.samplers, u32(r, "id"), h.id);
    }
    void createShader(const json& r) {
        auto words = [&](const char* key) -> std::span<const uint32_t> {
            const auto bytes = blob(r, key);
            if (bytes.size() % 4)
                throw std::runtime_error(std::string("SPIR-V '") + key + "' is not whole words");
            auto& w = code_.emplace_back(bytes.size() / 4);
            if (!bytes.empty())
                std::memcpy(w.data(), bytes.data(), bytes.size());  // empty: both may be null
            return w;
        };
        freeId(shaders_, r);
        ShaderDesc d{.stage = capture::shaderStage(r),
                     .binary = {.name = capture::text(r, "name", strings_),
                                .vulkan = words("vulkan"),
                                .opengl = words("opengl")},
                     .entryPoint = capture::text(r, "entry", strings_)};
        if (!d.binary.name) d.binary.name = "";
        if (!d.entryPoint) throw std::runtime_error("field 'entry' is missing");
        const ShaderHandle h = device_.createShader(d);
        bind(shaders_, u32(r, "id"), h.id);
        shaderNames_[u32(r, "id")] = d.binary.name;
    }
    void createGraphicsPipeline(const json& r) {
        freeId(map_.pipelines, r);
        GraphicsPipelineDesc d = capture::graphicsPipelineDesc(r.at("desc"), strings_);
        PipelineInfo& info = pipelines_[u32(r, "id")];
        info = {d.debugName ? d.debugName : "pipeline " + std::to_string(u32(r, "id")),
                {shaderNames_[d.vertexShader.id], shaderNames_[d.fragmentShader.id]},
                usedSlots(d.bindings)};
        for (ShaderHandle h : {d.tessControlShader, d.tessEvaluationShader, d.geometryShader})
            if (h) info.shaders.push_back(shaderNames_[h.id]);
        for (size_t i = 0; i < d.vertexBuffers.size(); ++i)
            info.uses.insert("vertex buffer " + std::to_string(i));
        for (ShaderHandle* h : {&d.vertexShader, &d.fragmentShader, &d.tessControlShader,
                                &d.tessEvaluationShader, &d.geometryShader})
            *h = {lookup(shaders_, h->id)};
        bind(map_.pipelines, u32(r, "id"), device_.createGraphicsPipeline(d).id);
    }
    void createComputePipeline(const json& r) {
        freeId(map_.pipelines, r);
        ComputePipelineDesc d = capture::computePipelineDesc(r.at("desc"), strings_);
        pipelines_[u32(r, "id")] = {
            d.debugName ? d.debugName : "pipeline " + std::to_string(u32(r, "id")),
            {shaderNames_[d.computeShader.id]},
            usedSlots(d.bindings)};
        d.computeShader = {lookup(shaders_, d.computeShader.id)};
        bind(map_.pipelines, u32(r, "id"), device_.createComputePipeline(d).id);
    }
    void createTimer(const json& r) {
        bind(map_.timers, freeId(map_.timers, r), device_.createTimer().id);
    }
    // A device without memory aliasing (GL) gives each placed texture memory of its own: what
    // aliasing saves is memory, and a correct program never reads one texture through another.
    void createHeap(const json& r) {
        const uint32_t id = freeId(heaps_, r);
        if (unplacedHeaps_.count(id))
            throw std::runtime_error("object id " + std::to_string(id) + " is already in use");
        const HeapDesc d = capture::heapDesc(r.at("desc"), strings_);
        if (!device_.info().features.memoryAliasing) {
            unplacedHeaps_.insert(u32(r, "id"));
            return;
        }
        bind(heaps_, u32(r, "id"), device_.createHeap(d).id);
    }
    void createQuerySet(const json& r) {
        freeId(map_.querySets, r);
        const QuerySetDesc d = capture::querySetDesc(r.at("desc"), strings_);
        bind(map_.querySets, u32(r, "id"), device_.createQuerySet(d).id);
        querySetTypes_[u32(r, "id")] = d.type;
    }
    // The id is forgotten only once the device has destroyed the object: a refused destroy (a
    // texture with live views, say) leaves it for the end of the replay.
    template <class H>
    void destroyIn(std::unordered_map<uint32_t, uint32_t>& m, uint32_t id) {
        const uint32_t replayed = lookup(m, id);
        device_.destroy(H{replayed});
        m.erase(id);
        if constexpr (std::is_same_v<H, TextureHandle>) views_.erase(replayed);
    }
    void destroy(const json& r) {
        const std::string kind = r.at("kind").get<std::string>();
        const uint32_t id = u32(r, "id");
        if (kind == "buffer") {
            keepMappedRead(id);
            destroyIn<BufferHandle>(map_.buffers, id);
        } else if (kind == "texture") {
            destroyIn<TextureHandle>(map_.textures, id);
        } else if (kind == "sampler") {
            destroyIn<SamplerHandle>(map_.samplers, id);
        } else if (kind == "shader") {
            destroyIn<ShaderHandle>(shaders_, id);
        } else if (kind == "pipeline") {
            destroyIn<PipelineHandle>(map_.pipelines, id);
        } else if (kind == "timer") {
            destroyIn<TimerHandle>(map_.timers, id);
        } else if (kind == "heap") {
            if (!unplacedHeaps_.erase(id)) destroyIn<HeapHandle>(heaps_, id);
        } else if (kind == "querySet") {
            destroyIn<QuerySetHandle>(map_.querySets, id);
        } else {
            throw std::runtime_error("unknown object kind '" + kind + "'");
        }
    }
    void writeBuffer(const json& r) {
        device_.writeBuffer(buffer(r), u64(r, "offset"), blob(r, "data"));
    }
    // What the program wrote into mapped Upload memory: written the same way here, so the GPU
    // reads it from mapped memory as it did (writeBuffer would wait for the work in flight).
    void mapped(const json& r) {
        const BufferHandle b = buffer(r);
        const uint64_t offset = u64(r, "offset");
        const auto data = blob(r, "data");
        const BufferDesc& d = device_.desc(b);
        if (offset > d.size || data.size() > d.size - offset)
            throw std::runtime_error("mapped bytes beyond the buffer's end");
        if (d.access != MemoryAccess::Upload)
            throw std::runtime_error("mapped bytes for a buffer that is not Upload memory");
        if (!data.empty())
            std::memcpy(static_cast<std::byte*>(device_.map(b)) + offset, data.data(), data.size());
    }
    void writeTexture(const json& r) {
        device_.writeTexture(texture(r), {u32(r, "mip"), u32(r, "layer")}, blob(r, "data"));
    }
    void writeTextureRegion(const json& r) {
        device_.writeTextureRegion(texture(r), capture::textureRegion(r.at("region")),
                                   blob(r, "data"), capture::texelLayout(r.at("layout")));
    }
    void readBuffer(const json& r) {
        const auto bytes = device_.readBuffer(buffer(r), u64(r, "offset"), u64(r, "size"));
        result_.buffers.push_back({result_.frames, bufferNames_[u32(r, "id")], bytes});
    }
    // Readback memory the program mapped: what it holds when the buffer goes (or the replay
    // ends) is kept, as the program could read it.
    void mapRead(const json& r) {
        const BufferHandle b = buffer(r);
        if (device_.desc(b).access != MemoryAccess::Readback)
            throw std::runtime_error("mapRead of a buffer that is not Readback memory");
        mappedForRead_[u32(r, "id")] = {b, static_cast<const uint8_t*>(device_.map(b))};
    }
    void keepMappedRead(uint32_t captured) {
        const auto it = mappedForRead_.find(captured);
        if (it == mappedForRead_.end()) return;
        device_.waitIdle();
        const uint8_t* p = it->second.second;
        result_.buffers.push_back(
            {result_.frames, bufferNames_[captured], {p, p + device_.desc(it->second.first).size}});
        mappedForRead_.erase(it);
    }
    // Occlusion results compare across devices; timestamps and pipeline statistics do not.
    void queryResults(const json& r) {
        const uint32_t id = u32(r, "id"), first = u32(r, "first"), count = u32(r, "count");
        const auto type = querySetTypes_.find(id);
        if (type == querySetTypes_.end())
            throw std::runtime_error("query set " + std::to_string(id) + " does not exist");
        if (type->second != QueryType::Occlusion && type->second != QueryType::AnySamplesPassed)
            return;
        if (count > 4096) throw std::runtime_error("more queries than a set holds");
        std::vector<uint64_t> values(count);
        device_.waitIdle();
        if (!device_.queryResults({lookup(map_.querySets, id)}, first, count, values))
            throw std::runtime_error(
                "the queries' results are not available after the work completed");
        const auto* bytes = reinterpret_cast<const uint8_t*>(values.data());
        result_.buffers.push_back(
            {result_.frames, "queries of set " + std::to_string(id), {bytes, bytes + count * 8}});
    }
    // A trimmed capture's state: what an object held when the captured range began. A device
    // that refuses it (a depth format it cannot upload to, say) leaves it undefined and counts it.
    void restoreBuffer(const json& r) {
        const BufferHandle b = buffer(r);
        const auto data = blob(r, "data");
        const BufferDesc& d = device_.desc(b);
        if (data.size() != d.size)
            throw std::runtime_error("restored contents are not the buffer's size");
        if (d.access == MemoryAccess::Upload) {
            std::memcpy(device_.map(b), data.data(), data.size());
        } else if (d.access == MemoryAccess::GpuOnly) {
            device_.writeBuffer(b, 0, data);
        }
    }
    void restoreTexture(const json& r) {
        try {
            device_.writeTexture(texture(r), {u32(r, "mip"), u32(r, "layer")}, blob(r, "data"));
        } catch (const DeviceLostError&) {
            throw;
        } catch (const Error&) {
            ++result_.unrestored;
        }
    }
    void readTexture(const json& r) {
        const TextureHandle t = texture(r);
        keep(t, device_.readTexture(t, {u32(r, "mip"), u32(r, "layer")}), false);
    }
    void submit(const json& r) {
        const json& lists = r.at("lists");
        if (!lists.is_array()) throw std::runtime_error("field 'lists' is not an array");
        const QueueKind queue = queueOf(r);
        SubmitDesc desc;
        if (r.contains("waitFor")) desc.waitFor = replayedFence(u64(r, "waitFor"));
        std::vector<std::unique_ptr<CommandList>> recorded;
        std::vector<CommandList*> raw;
        for (size_t i = 0; i < lists.size() && !probe_.stop; ++i) {
            const json one = {{"data", lists[i]}};
            const auto bytes = blob(one, "data");
            const auto stream = decodeCommandStream(bytes);
            auto list = device_.createCommandList({.queue = queue});
            probe_.newList();
            applyStream(*stream, device_, *list, map_, &probe_);
            raw.push_back(list.get());
            recorded.push_back(std::move(list));
        }
        const FenceValue replayed = device_.submit(raw, desc);
        fences_[u64(r, "fence")] = replayed;
        ++result_.submits;
        result_.commandLists += raw.size();
        probe_.collect();
        if (probe_.stop) throw Stopped{};
    }
    // A captured fence maps to the newest replayed fence at or before it (fences only grow).
    FenceValue replayedFence(uint64_t captured) const {
        const auto it = fences_.upper_bound(captured);
        return it == fences_.begin() ? 0 : std::prev(it)->second;
    }
    void wait(const json& r) {
        if (const FenceValue f = replayedFence(u64(r, "fence"))) device_.wait(f);
    }
    // "queue": absent (graphics), or "graphics", "compute", "copy".
    static QueueKind queueOf(const json& r) {
        if (!r.contains("queue")) return QueueKind::Graphics;
        const json& q = r.at("queue");
        for (QueueKind k : {QueueKind::Graphics, QueueKind::Compute, QueueKind::Copy})
            if (q.is_string() && q.get<std::string>() == queueKindName(k)) return k;
        throw std::runtime_error("field 'queue' is not graphics, compute or copy");
    }
    void waitIdle(const json&) { device_.waitIdle(); }
    void present(const json& r) {
        const TextureHandle t = texture(r);
        if (options_.present && device_.info().features.window) {
            device_.present(t);
            return;
        }
        keep(t, device_.readTexture(t, {}), true);
    }
    void frame(const json&) {
        const auto now = Clock::now();
        result_.frameMilliseconds.push_back(
            std::chrono::duration<double, std::milli>(now - frameStart_).count());
        frameStart_ = now;
        ++result_.frames;
    }

    void keep(TextureHandle t, Image image, bool presented) {
        ReplayImage out{.frame = result_.frames,
                        .name = names_[t.id],
                        .presented = presented,
                        .image = std::move(image)};
        if (!options_.outDir.empty()) {
            std::string file = out.name;
            for (char& c : file)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
            const std::string path = options_.outDir + "/frame" + std::to_string(out.frame) + "_" +
                                     std::to_string(result_.images.size()) + "_" + file + ".png";
            try {
                writePng(out.image, path);
            } catch (const Error&) {
                // A format PNG cannot show (integer, depth): the image is still in the result.
            }
        }
        result_.images.push_back(std::move(out));
    }

    struct Stopped {};
    bool timing() const { return options_.passTimes && device_.info().features.timestamps; }
    bool probing() const {
        return options_.snapshotPasses || options_.stopAfterDraw || options_.stopAfterPass ||
               options_.skipDraw;
    }
    // Probing reads render targets back, so they get CopySrc where the format allows it (a
    // placed texture whose memory needs would change keeps its usage).
    TextureHandle createReadableTexture(const TextureDesc& d) {
        if (!probing() || !any(d.usage, TextureUsage::RenderTarget) ||
            any(d.usage, TextureUsage::CopySrc) || d.sampleCount > 1)
            return device_.createTexture(d);
        TextureDesc readable = d;  // a Transient one becomes an ordinary target to be read
        readable.usage = TextureUsage(uint32_t(d.usage) & ~uint32_t(TextureUsage::Transient)) |
                         TextureUsage::CopySrc;
        if (!device_.supportsFormat(d.format, readable.usage)) return device_.createTexture(d);
        try {
            return device_.createTexture(readable);
        } catch (const Error&) {
            return device_.createTexture(d);
        }
    }

    // Follows the primary streams record by record: counts draws and passes, knows what is
    // bound, and reads targets back where the options ask.
    class Probe final : public ApplyObserver {
    public:
        explicit Probe(Replayer& r) : r_(r) {}
        uint64_t draw = 0, pass = 0;

        bool before(cmd::Op op, const std::byte* record, CommandList& list) override {
            cmd::CommandStream::dispatch(op, record, [&](const auto& rec) { checkWork(rec); });
            if (op == cmd::Op::BeginRenderPass && r_.timing()) {
                const QuerySetHandle set =
                    r_.device_.createQuerySet({.type = QueryType::Timestamp, .count = 2});
                timestampSets_.push_back(set);
                list.writeTimestamp(set, 0);
            }
            if (!isDraw(op) || !r_.options_.skipDraw || *r_.options_.skipDraw != draw) return true;
            drawDone(op, list);  // left out, but counted (and a stop there still stops)
            return false;
        }
        void adjustPass(RenderPassDesc& p) override {
            if (r_.probing()) {
                for (ColorAttachment& c : p.colors) c.store = StoreOp::Store;
                if (p.depth.texture) p.depth.store = StoreOp::Store;
            }
            open_ = p;
        }
        void after(cmd::Op op, const std::byte* record, CommandList& list) override {
            cmd::CommandStream::dispatch(op, record, [&](const auto& rec) { note(rec); });
            if (op == cmd::Op::BeginRenderPass) {
                inPass_ = true, drawsInPass_ = 0, firstDraw_ = draw, groupsAtPass_ = groups_.size();
                // Unnamed passes (a render graph names its passes by debug group) take the group's name.
                passName_ = open_.debugName    ? open_.debugName
                            : !groups_.empty() ? groups_.back()
                                               : "pass " + std::to_string(pass);
            } else if (op == cmd::Op::EndRenderPass) {
                inPass_ = false;
                if (r_.timing() && !timestampSets_.empty()) {
                    list.writeTimestamp(timestampSets_.back(), 1);
                    timed_.push_back(
                        {timestampSets_.back(), {r_.result_.frames, pass, passName_, 0}});
                }
                const bool stopHere =
                    r_.options_.stopAfterPass && *r_.options_.stopAfterPass == passName_;
                if (r_.options_.snapshotPasses || stopHere) readTargets(list, stopHere);
                if (stopHere) closeList(list);
                stop = stop || stopHere;
                ++pass;
            } else if (isDraw(op)) {
                drawDone(op, list);
            }
        }
        // Each command list starts with automatic barriers and no debug groups.
        void newList() {
            automaticBarriers_ = true;
            groups_.clear();
            timers_.clear();
        }
        // After the submission: the targets read, as images.
        void collect() {
            collectTimes();
            if (pending_.empty() && buffers_.empty()) return;
            r_.device_.waitIdle();
            for (Pending& p : pending_) {
                for (auto& [buffer, image] : p.reads) {
                    const auto bytes = r_.device_.readBuffer(buffer, 0, image.image.data.size());
                    image.image.data.assign(bytes.begin(), bytes.end());
                    p.snapshot.targets.push_back(std::move(image));
                }
                if (p.stop)
                    r_.result_.stopTargets = std::move(p.snapshot);
                else
                    r_.result_.passSnapshots.push_back(std::move(p.snapshot));
            }
            pending_.clear();
            for (BufferHandle b : buffers_) r_.device_.destroy(b);
            buffers_.clear();
        }

    private:
        template <class R>
        void checkWork(const R&) {}
        void checkWork(const cmd::Draw& r) {
            checkVertices(uint64_t(r.vertexCount) * r.instanceCount);
        }
        void checkWork(const cmd::DrawIndexed& r) {
            checkVertices(uint64_t(r.indexCount) * r.instanceCount);
        }
        void checkWork(const cmd::Dispatch& r) {
            const uint64_t groups = uint64_t(r.groupsX) * r.groupsY * r.groupsZ;
            if (groups > r_.options_.maxDispatchGroups)
                throw std::runtime_error("a dispatch of " + std::to_string(groups) +
                                         " work groups is beyond this replay's limit (" +
                                         std::to_string(r_.options_.maxDispatchGroups) +
                                         ", ReplayOptions::maxDispatchGroups)");
        }
        void checkVertices(uint64_t vertices) {
            if (vertices > r_.options_.maxDrawVertices)
                throw std::runtime_error("draw " + std::to_string(draw) + " of " +
                                         std::to_string(vertices) +
                                         " vertices is beyond this replay's limit (" +
                                         std::to_string(r_.options_.maxDrawVertices) +
                                         ", ReplayOptions::maxDrawVertices)");
        }
        void collectTimes() {
            if (timestampSets_.empty()) return;
            r_.device_.waitIdle();
            for (auto& [set, time] : timed_) {
                std::array<uint64_t, 2> ns{};
                if (r_.device_.queryResults(set, 0, 2, ns) && ns[1] >= ns[0]) {
                    time.gpuMilliseconds = double(ns[1] - ns[0]) * 1e-6;
                    r_.result_.passTimes.push_back(time);
                }
            }
            for (QuerySetHandle set : timestampSets_) r_.device_.destroy(set);
            timestampSets_.clear();
            timed_.clear();
        }
        void drawDone(cmd::Op op, CommandList& list) {
            if (r_.options_.stopAfterDraw && *r_.options_.stopAfterDraw == draw) {
                r_.result_.stoppedAt = context(cmd::opName(op));
                // The list is closed as the program would have: groups opened in the pass, the
                // pass, then the groups around it.
                if (inPass_) {
                    for (; groups_.size() > groupsAtPass_; groups_.pop_back()) list.popDebugGroup();
                    list.endRenderPass();
                    readTargets(list, true);
                }
                closeList(list);
                stop = true;
            }
            ++draw, ++drawsInPass_;
        }
        // An early stop ends the list as the program would have: the debug groups still open, then
        // the timers begun and not ended (a render graph times each pass), outermost last.
        void closeList(CommandList& list) {
            for (; !groups_.empty(); groups_.pop_back()) list.popDebugGroup();
            for (uint32_t timer : timers_)
                list.endTimer(TimerHandle{lookup(r_.map_.timers, timer)});
            timers_.clear();
        }
        struct Pending {
            PassSnapshot snapshot;
            bool stop = false;
            std::vector<std::pair<BufferHandle, ReplayImage>> reads;
        };
        static bool isDraw(cmd::Op op) {
            return op == cmd::Op::Draw || op == cmd::Op::DrawIndexed ||
                   op == cmd::Op::DrawIndirect || op == cmd::Op::DrawIndexedIndirect ||
                   op == cmd::Op::DrawIndirectCount || op == cmd::Op::DrawIndexedIndirectCount ||
                   op == cmd::Op::ExecuteSecondary;
        }
        // Copies each readable attachment of the pass that just ended into a Readback buffer.
        void readTargets(CommandList& list, bool stopHere) {
            Pending p{.snapshot = {pass, passName_, firstDraw_, drawsInPass_, {}},
                      .stop = stopHere};
            auto read = [&](TextureHandle t, Subresource at, const std::string& what,
                            ResourceState state) {
                if (!t) return;
                BufferHandle buffer;
                try {
                    const TextureDesc& d = r_.device_.desc(t);
                    const uint64_t bytes = textureByteSize(d, at.mipLevel);
                    buffer = r_.device_.createBuffer({.size = bytes,
                                                      .usage = BufferUsage::CopyDst,
                                                      .access = MemoryAccess::Readback});
                    // Buffers outlive the list's submission even when the copy is refused.
                    buffers_.push_back(buffer);
                    // With the program's own barriers (automatic ones off), the copy brings its own
                    // and gives the texture back in the state the program left it in.
                    const TextureBarrier toCopy{
                        t, state, ResourceState::CopySrc, at.mipLevel, 1, at.layer, 1};
                    if (!automaticBarriers_) list.barrier(&toCopy, 1);
                    list.copyTextureToBuffer(buffer, 0, t, at);
                    const TextureBarrier back{
                        t, ResourceState::CopySrc, state, at.mipLevel, 1, at.layer, 1};
                    if (!automaticBarriers_) list.barrier(&back, 1);
                    ReplayImage image{.frame = r_.result_.frames,
                                      .name = what + ": " + r_.names_[t.id]};
                    image.image = {std::max(1u, d.width >> at.mipLevel),
                                   std::max(1u, d.height >> at.mipLevel), d.format,
                                   std::vector<uint8_t>(bytes)};
                    p.reads.emplace_back(buffer, std::move(image));
                } catch (const Error&) {
                    // Not readable (a view, multisampled, no CopySrc): left out of the snapshot.
                }
            };
            for (size_t i = 0; i < open_.colors.size(); ++i) {
                const ColorAttachment& c = open_.colors[i];
                if (c.resolveTexture)
                    read(c.resolveTexture, c.resolveSubresource, "colour " + std::to_string(i),
                         ResourceState::RenderTarget);
                else
                    read(c.texture, {c.mipLevel, c.layer}, "colour " + std::to_string(i),
                         ResourceState::RenderTarget);
            }
            read(open_.depth.texture, {open_.depth.mipLevel, open_.depth.layer}, "depth",
                 ResourceState::DepthTarget);
            pending_.push_back(std::move(p));
        }
        DrawContext context(const char* command) const {
            DrawContext c{.draw = draw,
                          .pass = pass,
                          .drawInPass = drawsInPass_,
                          .passName = passName_,
                          .groups = groups_,
                          .command = command};
            const auto it = r_.pipelines_.find(pipeline_);
            if (it == r_.pipelines_.end()) return c;
            c.pipeline = it->second.name;
            for (const std::string& s : it->second.shaders)
                if (!s.empty()) c.shaders.push_back(s);
            // What the pipeline reads: its binding slots, its vertex buffers, the index buffer of
            // an indexed draw (bindings persist across passes; the rest is not this draw's).
            const bool indexed =
                std::string_view(command).find("Indexed") != std::string_view::npos;
            // A pipeline without declared bindings (taken from its shaders) shows every binding.
            const bool declared =
                std::any_of(it->second.uses.begin(), it->second.uses.end(),
                            [](const std::string& k) { return k.rfind("vertex buffer", 0) != 0; });
            for (const auto& [slot, name] : bound_) {
                const bool vertex = slot.rfind("vertex buffer", 0) == 0,
                           index = slot == "index buffer";
                if ((index && indexed) || (vertex && it->second.uses.count(slot)) ||
                    (!vertex && !index && (!declared || it->second.uses.count(slot))))
                    c.resources.push_back(slot + ": " + name);
            }
            return c;
        }
        std::string buffer(BufferHandle b) const { return name(r_.bufferNames_, b.id); }
        std::string texture(TextureHandle t) const { return name(r_.textureNames_, t.id); }
        static std::string name(const std::unordered_map<uint32_t, std::string>& m, uint32_t id) {
            const auto it = m.find(id);
            return it == m.end() ? "#" + std::to_string(id) : it->second;
        }
        // What each record tells about the state a draw sees (captured ids: names are the capture's).
        template <class R>
        void note(const R&) {}
        void note(const cmd::PushDebugGroup& r) {
            groups_.push_back(cmd::view(r, r.name) ? cmd::view(r, r.name) : "");
        }
        void note(const cmd::PopDebugGroup&) {
            if (!groups_.empty()) groups_.pop_back();
        }
        void note(const cmd::BeginTimer& r) { timers_.push_back(r.timer.id); }
        void note(const cmd::EndTimer& r) { std::erase(timers_, r.timer.id); }
        void note(const cmd::SetPipeline& r) { pipeline_ = r.pipeline.id; }
        void note(const cmd::SetAutomaticBarriers& r) { automaticBarriers_ = r.enabled; }
        void note(const cmd::SetVertexBuffer& r) {
            bound_["vertex buffer " + std::to_string(r.index)] = buffer(r.buffer);
        }
        void note(const cmd::SetIndexBuffer& r) { bound_["index buffer"] = buffer(r.buffer); }
        void note(const cmd::SetUniformBuffer& r) {
            bound_["uniform buffer " + std::to_string(r.slot)] = buffer(r.buffer);
        }
        void note(const cmd::SetStorageBuffer& r) {
            bound_["storage buffer " + std::to_string(r.slot)] = buffer(r.buffer);
        }
        void note(const cmd::SetTexture& r) {
            bound_["texture " + std::to_string(r.slot)] = texture(r.texture);
        }
        void note(const cmd::SetStorageTexture& r) {
            bound_["storage texture " + std::to_string(r.slot)] = texture(r.texture);
        }

        Replayer& r_;
        RenderPassDesc open_;
        bool inPass_ = false;
        std::string passName_;
        uint64_t firstDraw_ = 0, drawsInPass_ = 0;
        std::vector<std::string> groups_;
        std::vector<uint32_t> timers_;  // begun and not yet ended in this list (captured ids)
        uint32_t pipeline_ = 0;
        std::map<std::string, std::string> bound_;
        std::vector<Pending> pending_;
        std::vector<BufferHandle> buffers_;          // read-back buffers of the current submission
        std::vector<QuerySetHandle> timestampSets_;  // one per timed pass of the submission
        std::vector<std::pair<QuerySetHandle, PassTime>>
            timed_;  // the passes whose end was written
        bool automaticBarriers_ = true;
        size_t groupsAtPass_ = 0;  // debug groups open when the pass began
    };

    Device& device_;
    ReplayOptions options_;
    ReplayResult result_;
    Probe probe_;
    std::unordered_map<uint32_t, std::string> bufferNames_, textureNames_,
        shaderNames_;  // captured id -> name
    struct PipelineInfo {
        std::string name;
        std::vector<std::string> shaders;
        std::set<std::string> uses;  // binding keys as the probe names them ("texture 3", ...)
    };
    static std::set<std::string> usedSlots(const std::vector<BindingSlot>& bindings) {
        std::set<std::string> keys;
        for (const BindingSlot& b : bindings) {
            const char* kind = b.type == BindingType::UniformBuffer    ? "uniform buffer "
                               : b.type == BindingType::StorageBuffer  ? "storage buffer "
                               : b.type == BindingType::SampledTexture ? "texture "
                                                                       : "storage texture ";
            keys.insert(kind + std::to_string(b.slot));
        }
        return keys;
    }
    std::unordered_map<uint32_t, PipelineInfo> pipelines_;  // captured id ->
    HandleMap map_;
    std::unordered_map<uint32_t, uint32_t> shaders_, heaps_;
    std::unordered_map<uint32_t, std::pair<BufferHandle, const uint8_t*>>
        mappedForRead_;                                      // captured id ->
    std::unordered_map<uint32_t, QueryType> querySetTypes_;  // captured id ->
    std::unordered_set<uint32_t> unplacedHeaps_;       // captured heaps this device cannot make
    std::unordered_set<uint32_t> views_;               // replayed ids of texture views
    std::unordered_map<uint32_t, std::string> names_;  // replayed texture id -> name
    std::map<uint64_t, FenceValue> fences_;            // captured fence -> replayed fence
    std::vector<std::vector<std::byte>> blobs_;
    std::deque<std::vector<uint32_t>> code_;  // SPIR-V words, aligned
    capture::Strings strings_;
    Clock::time_point frameStart_;
};

}  // namespace

CaptureSummary summarizeCapture(const std::string& path) {
    capture::Reader reader(path);
    CaptureSummary s{.formatVersion = reader.version(),
                     .fileBytes = std::filesystem::file_size(path)};
    capture::Chunk chunk;
    while (reader.next(chunk)) {
        s.rawBytes += chunk.bytes.size();
        if (chunk.kind == capture::ChunkKind::Blob) ++s.blobs;
        if (chunk.kind != capture::ChunkKind::Record) continue;
        std::string op;
        try {
            const json r = json::from_cbor(chunk.bytes);
            op = r.is_object() && r.contains("op") && r["op"].is_string()
                     ? r["op"].get<std::string>()
                     : "";
            if (op == "device") {
                s.backend = r.value("backend", std::string());
                s.device = r.value("device", std::string());
                s.firstFrame = r.value("firstFrame", 0u);
            }
        } catch (const std::exception& e) {
            throw CaptureError("capture: record " + std::to_string(s.records) + " at offset " +
                               std::to_string(chunk.offset) + ": " + e.what());
        }
        s.frames += op == "frame";
        s.submits += op == "submit";
        ++s.records;
    }
    return s;
}

ReplayResult replayCapture(const std::string& path, Device& device, const ReplayOptions& options) {
    return Replayer(device, options).run(path);
}

}  // namespace fe::gdi
