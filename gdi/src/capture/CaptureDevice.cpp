// The capturing device: a Device that forwards every call and writes it to a capture file.
#include "fe/gdi/ShaderCompiler.h"
#include <algorithm>
#include <atomic>
#include <map>
#include <numeric>
#include <tuple>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <unordered_set>

#include "CaptureFile.h"
#include "CaptureJson.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/CommandRecorder.h"
#include "fe/gdi/ExclusiveUse.h"

namespace fe::gdi {

namespace {

using capture::json;
using capture::toJson;

// Mapped Upload memory is compared with what was last written to the file at each submit; the
// changed bytes are written in runs, merged across gaps shorter than this.
constexpr size_t kMappedGap = 64;

class CaptureDevice final : public Device {
public:
    CaptureDevice(std::unique_ptr<Device> inner, const CaptureDesc& desc)
        : inner_(std::move(inner)),
          info_(portable(inner_->info())),
          writer_(desc.path, desc.compress),
          frameLimit_(desc.frames),
          firstFrame_(desc.firstFrame),
          beforeRange_(desc.firstFrame > 0) {
        const DeviceInfo& i = inner_->info();
        writer_.record(json::to_cbor(json{{"op", "device"},
                                          {"backend", i.backend},
                                          {"device", i.deviceName},
                                          {"commandSet", capture::commandSetFingerprint()},
                                          {"window", i.features.window},
                                          {"firstFrame", firstFrame_}}));
        recording_ = !beforeRange_;
    }
    ~CaptureDevice() override {
        try {
            finish();
        } catch (const std::exception&) {
            // A destructor cannot report it: finishCapture() is where a program sees it.
        }
    }

    void finish() {
        std::lock_guard lock(mutex_);
        if (finished_) return;
        finished_ = true;
        recording_ = false;
        beforeRange_ = false;
        writer_.finish();
    }
    void markFrameEnd() {
        std::lock_guard lock(mutex_);
        if (submittedSinceFrame_) endFrameLocked();
    }
    CaptureStats stats() {
        const capture::WriterStats w = writer_.stats();
        std::lock_guard lock(mutex_);
        const uint32_t captured = frames_ > firstFrame_ ? frames_ - firstFrame_ : 0;
        return {captured, w.records, w.blobs, w.dedupedBlobs, w.rawBytes, w.fileBytes, finished_};
    }

    const DeviceInfo& info() const override { return info_; }
    bool supportsFormat(Format f, TextureUsage u) const override {
        return inner_->supportsFormat(f, u);
    }
    FormatCaps formatCaps(Format f) const override { return inner_->formatCaps(f); }
    PipelineCacheStats openPipelineCache(const std::string& path) override {
        return inner_->openPipelineCache(path);
    }
    void savePipelineCache() override { inner_->savePipelineCache(); }
    PipelineCacheStats pipelineCacheStats() const override { return inner_->pipelineCacheStats(); }

    BufferHandle createBuffer(const BufferDesc& desc, ByteSpan initialData) override {
        const BufferHandle h = inner_->createBuffer(desc, initialData);
        created("buffer", h.id,
                {{"op", "createBuffer"},
                 {"id", h.id},
                 {"desc", toJson(desc)},
                 {"data", kept(initialData)}});
        return h;
    }
    TextureHandle createTexture(const TextureDesc& desc) override {
        const TextureHandle h = inner_->createTexture(desc);
        created("texture", h.id, {{"op", "createTexture"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    TextureHandle createTextureView(TextureHandle texture, const TextureViewDesc& desc) override {
        const TextureHandle h = inner_->createTextureView(texture, desc);
        created("texture", h.id,
                {{"op", "createTextureView"},
                 {"id", h.id},
                 {"of", texture.id},
                 {"desc", toJson(desc)}});
        return h;
    }
    SamplerHandle createSampler(const SamplerDesc& desc) override {
        const SamplerHandle h = inner_->createSampler(desc);
        created("sampler", h.id, {{"op", "createSampler"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    ShaderHandle createShader(const ShaderDesc& given) override {
        // A source is compiled here, so the capture holds the binaries any backend replays.
        const ShaderDesc desc = withCompiledSource(given);
        const ShaderHandle h = inner_->createShader(desc);
        const auto& b = desc.binary;
        created("shader", h.id,
                {{"op", "createShader"},
                 {"id", h.id},
                 {"stage", uint64_t(desc.stage)},
                 {"name", b.name ? b.name : ""},
                 {"entry", desc.entryPoint ? desc.entryPoint : "main"},
                 {"vulkan", kept(std::as_bytes(b.vulkan))},
                 {"opengl", kept(std::as_bytes(b.opengl))}});
        return h;
    }
    PipelineHandle createGraphicsPipeline(const GraphicsPipelineDesc& desc) override {
        const PipelineHandle h = inner_->createGraphicsPipeline(desc);
        created("pipeline", h.id,
                {{"op", "createGraphicsPipeline"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    PipelineHandle createComputePipeline(const ComputePipelineDesc& desc) override {
        const PipelineHandle h = inner_->createComputePipeline(desc);
        created("pipeline", h.id,
                {{"op", "createComputePipeline"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    TimerHandle createTimer() override {
        const TimerHandle h = inner_->createTimer();
        created("timer", h.id, {{"op", "createTimer"}, {"id", h.id}});
        return h;
    }
    HeapHandle createHeap(const HeapDesc& desc) override {
        const HeapHandle h = inner_->createHeap(desc);
        created("heap", h.id, {{"op", "createHeap"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    QuerySetHandle createQuerySet(const QuerySetDesc& desc) override {
        const QuerySetHandle h = inner_->createQuerySet(desc);
        created("querySet", h.id, {{"op", "createQuerySet"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    MemoryRequirements textureMemoryRequirements(const TextureDesc& d) const override {
        return inner_->textureMemoryRequirements(d);
    }

    void destroy(BufferHandle h) override {
        inner_->destroy(h);
        std::lock_guard lock(mutex_);
        mapped_.erase(h.id);
        mappedForRead_.erase(h.id);
        forget("buffer", h.id);
        recordLocked({{"op", "destroy"}, {"kind", "buffer"}, {"id", h.id}});
    }
    void destroy(TextureHandle h) override { destroyed(h, "texture"); }
    void destroy(SamplerHandle h) override { destroyed(h, "sampler"); }
    void destroy(ShaderHandle h) override { destroyed(h, "shader"); }
    void destroy(PipelineHandle h) override { destroyed(h, "pipeline"); }
    void destroy(TimerHandle h) override { destroyed(h, "timer"); }
    void destroy(HeapHandle h) override { destroyed(h, "heap"); }
    void destroy(QuerySetHandle h) override { destroyed(h, "querySet"); }

    const BufferDesc& desc(BufferHandle h) const override { return inner_->desc(h); }
    const TextureDesc& desc(TextureHandle h) const override { return inner_->desc(h); }
    const ShaderInterface& shaderInterface(ShaderHandle h) const override {
        return inner_->shaderInterface(h);
    }

    void writeBuffer(BufferHandle b, uint64_t offset, ByteSpan data) override {
        inner_->writeBuffer(b, offset, data);
        std::lock_guard lock(mutex_);
        // The file already holds these bytes: mapped memory compares against them from now on.
        if (const auto it = mapped_.find(b.id); it != mapped_.end())
            std::memcpy(it->second.shadow.data() + offset, data.data(), data.size());
        recordLocked(
            {{"op", "writeBuffer"}, {"id", b.id}, {"offset", offset}, {"data", blob(data)}});
    }
    void writeTexture(TextureHandle t, Subresource at, ByteSpan data) override {
        inner_->writeTexture(t, at, data);
        std::lock_guard lock(mutex_);
        // Before the range, textures that cannot be read back keep what the program wrote.
        if (beforeRange_ && !readable(inner_->desc(t)))
            textureShadows_[{t.id, at.mipLevel, at.layer}].assign(data.begin(), data.end());
        recordLocked({{"op", "writeTexture"},
                      {"id", t.id},
                      {"mip", at.mipLevel},
                      {"layer", at.layer},
                      {"data", blob(data)}});
    }
    void writeTextureRegion(TextureHandle t, const TextureRegion& region, ByteSpan data,
                            const TexelLayout& layout) override {
        inner_->writeTextureRegion(t, region, data, layout);
        record({{"op", "writeTextureRegion"},
                {"id", t.id},
                {"region", toJson(region)},
                {"layout", toJson(layout)},
                {"data", blob(data)}});
    }
    std::vector<uint8_t> readBuffer(BufferHandle b, uint64_t offset, uint64_t size) override {
        auto bytes = inner_->readBuffer(b, offset, size);
        record({{"op", "readBuffer"}, {"id", b.id}, {"offset", offset}, {"size", size}});
        return bytes;
    }
    Image readTexture(TextureHandle t, Subresource at) override {
        Image image = inner_->readTexture(t, at);
        std::lock_guard lock(mutex_);
        recordLocked(
            {{"op", "readTexture"}, {"id", t.id}, {"mip", at.mipLevel}, {"layer", at.layer}});
        if (submittedSinceFrame_) endFrameLocked();
        return image;
    }

    void* map(BufferHandle b) override {
        void* p = inner_->map(b);
        if (inner_->desc(b).access == MemoryAccess::Readback) {
            // The program reads this memory: replay keeps what it holds (ReplayResult::buffers).
            std::lock_guard lock(mutex_);
            if (mappedForRead_.insert(b.id).second) recordLocked({{"op", "mapRead"}, {"id", b.id}});
            return p;
        }
        if (inner_->desc(b).access != MemoryAccess::Upload) return p;
        std::lock_guard lock(mutex_);
        if (mapped_.count(b.id) || finished_) return p;
        // What the buffer holds now is written once; later only the bytes that change.
        Mapped& m = mapped_[b.id];
        m.memory = static_cast<std::byte*>(p);
        m.shadow.assign(m.memory, m.memory + inner_->desc(b).size);
        recordLocked({{"op", "mapped"}, {"id", b.id}, {"offset", 0}, {"data", blob(m.shadow)}});
        return p;
    }

    using Device::createCommandList;
    std::unique_ptr<CommandList> createCommandList(const CommandListDesc& desc) override {
        // Checked against info_; the recorder's own stream is guarded as the inner list is.
        auto list = std::make_unique<RecordingCommandList>(*this, inner_->createCommandList(desc));
        return info_.features.validation ? exclusiveUse(std::move(list)) : std::move(list);
    }
    using Device::submit;
    FenceValue submit(std::span<CommandList* const> lists, const SubmitDesc& desc) override {
        std::vector<CommandList*> inner;
        std::vector<RecordingCommandList*> recorded;
        const ClaimedLists claimed(lists, "submit");
        for (CommandList* l : claimed.lists()) {
            auto* r = dynamic_cast<RecordingCommandList*>(l);
            if (!r) throw Error("submit: a command list made by another device");
            recorded.push_back(r);
            inner.push_back(&r->inner());
        }
        std::lock_guard lock(mutex_);
        const FenceValue fence = inner_->submit(inner, desc);
        submittedSinceFrame_ = true;  // frames are counted before the range too
        if (!recording_) {
            for (RecordingCommandList* r : recorded) r->takeStream();
            return fence;
        }
        writeMappedChanges();
        json ids = json::array();
        for (RecordingCommandList* r : recorded)
            ids.push_back(blob(encodeCommandStream(*r->takeStream())));
        json op = {{"op", "submit"}, {"fence", fence}, {"lists", ids}};
        if (!inner.empty() && inner[0]->queue() != QueueKind::Graphics)
            op["queue"] = queueKindName(inner[0]->queue());
        if (desc.waitFor) op["waitFor"] = desc.waitFor;
        recordLocked(op);
        submittedSinceFrame_ = true;
        return fence;
    }
    void wait(FenceValue fence) override {
        inner_->wait(fence);
        record({{"op", "wait"}, {"fence", fence}});
    }
    // A completed poll is a wait the program relied on (it may now overwrite mapped memory the
    // work read), so replay waits there too. Each fence is written once.
    bool isComplete(FenceValue fence) override {
        const bool done = inner_->isComplete(fence);
        if (!done) return false;
        std::lock_guard lock(mutex_);
        if (fence > completedRecorded_) {
            completedRecorded_ = fence;
            recordLocked({{"op", "wait"}, {"fence", fence}});
        }
        return true;
    }
    void waitIdle() override {
        inner_->waitIdle();
        record({{"op", "waitIdle"}});
    }
    std::optional<double> timerNanoseconds(TimerHandle t) override {
        return inner_->timerNanoseconds(t);
    }
    // Results the program got are results replay can compare (fe conformance --capture).
    bool queryResults(QuerySetHandle s, uint32_t first, uint32_t count,
                      std::span<uint64_t> out) override {
        const bool ready = inner_->queryResults(s, first, count, out);
        if (ready)
            record({{"op", "queryResults"}, {"id", s.id}, {"first", first}, {"count", count}});
        return ready;
    }
    uint32_t validationErrorCount() const override { return inner_->validationErrorCount(); }
    LiveObjects liveObjects() const override { return inner_->liveObjects(); }
    bool present(TextureHandle t) override {
        const bool open = inner_->present(t);
        std::lock_guard lock(mutex_);
        recordLocked({{"op", "present"}, {"id", t.id}});
        if (submittedSinceFrame_) endFrameLocked();
        return open;
    }
    Image readWindow() override { return inner_->readWindow(); }
    InputState input() const override { return inner_->input(); }
    uint64_t nativeObject(NativeObject what, uint32_t id) const override {
        return inner_->nativeObject(what, id);
    }

private:
    struct Mapped {
        std::byte* memory = nullptr;
        std::vector<std::byte> shadow;  // the bytes the file holds for it
    };

    template <class H>
    void destroyed(H h, const char* kind) {
        inner_->destroy(h);
        std::lock_guard lock(mutex_);
        forget(kind, h.id);
        recordLocked({{"op", "destroy"}, {"kind", kind}, {"id", h.id}});
    }
    uint64_t blob(std::span<const std::byte> bytes) { return recording_ ? writer_.blob(bytes) : 0; }
    // A create record's data: a blob id while recording; the bytes themselves before the range
    // (the record is kept until the range starts and is written then).
    json kept(std::span<const std::byte> bytes) {
        if (bytes.empty()) return 0;
        if (recording_) return writer_.blob(bytes);
        if (beforeRange_) {
            const auto* p = reinterpret_cast<const uint8_t*>(bytes.data());
            return json::binary(std::vector<uint8_t>(p, p + bytes.size()));
        }
        return 0;
    }
    void created(const char* kind, uint32_t id, json j) {
        std::lock_guard lock(mutex_);
        if (beforeRange_)
            live_[{kind, id}] = {sequence_++, std::move(j)};
        else
            recordLocked(j);
    }
    // Before the range: an object destroyed is not part of the state, except shaders, which the
    // live pipelines made from them still need when the state is written.
    void forget(const std::string& kind, uint32_t id) {
        if (!beforeRange_) return;
        const auto it = live_.find({kind, id});
        if (it == live_.end()) return;
        if (kind == "shader") deadShaders_[id] = std::move(it->second);
        live_.erase(it);
        if (kind == "texture")
            std::erase_if(textureShadows_,
                          [&](const auto& e) { return std::get<0>(e.first) == id; });
    }
    static bool readable(const TextureDesc& d) {
        return d.sampleCount == 1 && formatInfo(d.format).bytesPerBlock == 0 &&
               d.dimension != TextureDimension::Texture3D;
    }
    uint64_t blob(const std::vector<std::byte>& bytes) {
        return blob(std::span<const std::byte>(bytes));
    }
    void record(const json& j) {
        std::lock_guard lock(mutex_);
        recordLocked(j);
    }
    void recordLocked(const json& j) {
        if (recording_) writer_.record(json::to_cbor(j));
    }
    void endFrameLocked() {
        submittedSinceFrame_ = false;
        if (finished_) return;
        recordLocked({{"op", "frame"}, {"index", frames_}});
        ++frames_;
        if (beforeRange_ && frames_ == firstFrame_) {
            writeState();
        } else if (recording_ && frameLimit_ && frames_ - firstFrame_ >= frameLimit_) {
            finished_ = true;
            recording_ = false;
            writer_.finish();
        }
    }
    // The range starts: every live object is written as it is now, its contents read back from
    // the device (or, for textures that cannot be read, what the program wrote), so replay
    // starts from the same state without the frames before.
    void writeState() {
        inner_->waitIdle();
        beforeRange_ = false;
        recording_ = true;
        static const std::map<std::string, int> rank = {{"createHeap", 0},
                                                        {"createBuffer", 1},
                                                        {"createTexture", 2},
                                                        {"createTextureView", 3},
                                                        {"createSampler", 4},
                                                        {"createShader", 5},
                                                        {"createGraphicsPipeline", 6},
                                                        {"createComputePipeline", 6},
                                                        {"createTimer", 7},
                                                        {"createQuerySet", 8}};
        std::vector<std::pair<std::pair<int, uint64_t>, Kept*>> order;
        for (auto& [key, k] : live_)
            order.push_back({{rank.at(k.create["op"].get<std::string>()), k.sequence}, &k});
        for (auto& [id, k] : deadShaders_) order.push_back({{5, k.sequence}, &k});
        std::sort(order.begin(), order.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& [ranked, k] : order) {
            for (const char* field : {"data", "vulkan", "opengl"})
                if (k->create.contains(field) && k->create[field].is_binary())
                    k->create[field] =
                        writer_.blob(std::as_bytes(std::span(k->create[field].get_binary())));
            const std::string op = k->create["op"].get<std::string>();
            const uint32_t id = k->create["id"].get<uint32_t>();
            if (op == "createBuffer") {
                k->create["data"] = 0;
                k->create["restore"] = true;
                recordLocked(k->create);
                const BufferHandle b{id};
                const auto bytes = inner_->readBuffer(b, 0, inner_->desc(b).size);
                recordLocked({{"op", "restoreBuffer"},
                              {"id", id},
                              {"data", blob(std::as_bytes(std::span(bytes)))}});
            } else if (op == "createTexture") {
                writeTextureState(k->create, TextureHandle{id});
            } else {
                recordLocked(k->create);
            }
        }
        for (auto& [id, k] : deadShaders_)
            recordLocked({{"op", "destroy"}, {"kind", "shader"}, {"id", id}});
        for (auto& [id, m] : mapped_) {
            m.shadow.assign(m.memory, m.memory + m.shadow.size());
            recordLocked({{"op", "mapped"}, {"id", id}, {"offset", 0}, {"data", blob(m.shadow)}});
        }
        for (uint32_t id : mappedForRead_) recordLocked({{"op", "mapRead"}, {"id", id}});
        live_.clear();
        deadShaders_.clear();
        textureShadows_.clear();
    }
    void writeTextureState(json& create, TextureHandle t) {
        const TextureDesc& d = inner_->desc(t);
        const uint32_t layers = d.dimension == TextureDimension::Texture3D ? 1 : d.depthOrLayers;
        std::vector<json> restores;
        for (uint32_t mip = 0; mip < d.mipLevels; ++mip)
            for (uint32_t layer = 0; layer < layers; ++layer) {
                std::vector<uint8_t> bytes;
                if (readable(d)) {
                    try {
                        bytes = inner_->readTexture(t, {mip, layer}).data;
                    } catch (const Error&) {
                        // A format this device cannot read back: the state holds no contents for it.
                    }
                } else if (const auto s = textureShadows_.find({t.id, mip, layer});
                           s != textureShadows_.end()) {
                    const auto* p = reinterpret_cast<const uint8_t*>(s->second.data());
                    bytes.assign(p, p + s->second.size());
                }
                if (!bytes.empty())
                    restores.push_back({{"op", "restoreTexture"},
                                        {"id", t.id},
                                        {"mip", mip},
                                        {"layer", layer},
                                        {"data", blob(std::as_bytes(std::span(bytes)))}});
            }
        if (!restores.empty()) create["restore"] = true;
        recordLocked(create);
        for (const json& r : restores) recordLocked(r);
    }
    // Runs of bytes the program changed in mapped memory since they were last written.
    void writeMappedChanges() {
        for (auto& [id, m] : mapped_) {
            const size_t size = m.shadow.size();
            size_t i = 0;
            while (i < size) {
                if (m.memory[i] == m.shadow[i]) {
                    ++i;
                    continue;
                }
                size_t end = i + 1, same = 0;
                for (size_t k = end; k < size && same < kMappedGap; ++k) {
                    if (m.memory[k] != m.shadow[k])
                        end = k + 1, same = 0;
                    else
                        ++same;
                }
                std::memcpy(m.shadow.data() + i, m.memory + i, end - i);
                recordLocked(
                    {{"op", "mapped"},
                     {"id", id},
                     {"offset", i},
                     {"data", blob(std::span<const std::byte>(m.shadow.data() + i, end - i))}});
                i = end;
            }
        }
    }

    // The inner device's, with buffer offset alignments a multiple of 256, the most Vulkan allows
    // and what GL drivers ask (NVIDIA's GL: 256, its Vulkan: 64): a program that aligns its
    // offsets as info() says records a capture every backend replays.
    static DeviceInfo portable(DeviceInfo i) {
        i.limits.uniformBufferOffsetAlignment =
            std::lcm(std::max(i.limits.uniformBufferOffsetAlignment, 1u), 256u);
        i.limits.storageBufferOffsetAlignment =
            std::lcm(std::max(i.limits.storageBufferOffsetAlignment, 1u), 256u);
        return i;
    }
    std::unique_ptr<Device> inner_;
    const DeviceInfo info_;
    capture::Writer writer_;
    std::mutex mutex_;  // the file's record order is the order calls completed in
    struct Kept {
        uint64_t sequence = 0;
        json create;
    };
    uint32_t frameLimit_ = 0;
    uint32_t firstFrame_ = 0;
    bool beforeRange_ = false, finished_ = false;
    std::atomic<bool> recording_ = true;
    uint64_t sequence_ = 0;
    std::map<std::pair<std::string, uint32_t>, Kept> live_;  // before the range: kind, id ->
    std::map<uint32_t, Kept> deadShaders_;
    std::map<std::tuple<uint32_t, uint32_t, uint32_t>, std::vector<std::byte>>
        textureShadows_;                // id, mip, layer ->
    FenceValue completedRecorded_ = 0;  // the newest fence isComplete said was done, as written
    uint32_t frames_ = 0;
    bool submittedSinceFrame_ = false;
    std::unordered_map<uint32_t, Mapped> mapped_;
    std::unordered_set<uint32_t> mappedForRead_;
};

}  // namespace

std::unique_ptr<Device> makeCaptureDevice(std::unique_ptr<Device> inner, const CaptureDesc& desc) {
    if (!inner) throw Error("makeCaptureDevice: no device to capture");
    if (desc.path.empty()) throw Error("makeCaptureDevice: no capture file named");
    return std::make_unique<CaptureDevice>(std::move(inner), desc);
}

std::optional<CaptureStats> captureStats(Device& device) {
    if (auto* c = dynamic_cast<CaptureDevice*>(&device)) return c->stats();
    return std::nullopt;
}

void markFrameEnd(Device& device) {
    if (auto* c = dynamic_cast<CaptureDevice*>(&device)) c->markFrameEnd();
}

void finishCapture(Device& device) {
    if (auto* c = dynamic_cast<CaptureDevice*>(&device)) c->finish();
}

}  // namespace fe::gdi
