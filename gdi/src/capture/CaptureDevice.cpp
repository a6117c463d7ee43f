// The capturing device: a Device that forwards every call and writes it to a capture file.
#include <atomic>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <unordered_set>

#include "CaptureFile.h"
#include "CaptureJson.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/CommandRecorder.h"

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
        : inner_(std::move(inner)), writer_(desc.path, desc.compress), frameLimit_(desc.frames) {
        const DeviceInfo& i = inner_->info();
        record({{"op", "device"}, {"backend", i.backend}, {"device", i.deviceName},
                {"commandSet", capture::commandSetFingerprint()}, {"window", i.features.window}});
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
        if (!recording_) return;
        recording_ = false;
        writer_.finish();
    }
    CaptureStats stats() {
        const capture::WriterStats w = writer_.stats();
        std::lock_guard lock(mutex_);
        return {frames_, w.records, w.blobs, w.dedupedBlobs, w.rawBytes, w.fileBytes, !recording_};
    }

    const DeviceInfo& info() const override { return inner_->info(); }
    bool supportsFormat(Format f, TextureUsage u) const override { return inner_->supportsFormat(f, u); }
    FormatCaps formatCaps(Format f) const override { return inner_->formatCaps(f); }
    PipelineCacheStats openPipelineCache(const std::string& path) override { return inner_->openPipelineCache(path); }
    void savePipelineCache() override { inner_->savePipelineCache(); }
    PipelineCacheStats pipelineCacheStats() const override { return inner_->pipelineCacheStats(); }

    BufferHandle createBuffer(const BufferDesc& desc, ByteSpan initialData) override {
        const BufferHandle h = inner_->createBuffer(desc, initialData);
        record({{"op", "createBuffer"}, {"id", h.id}, {"desc", toJson(desc)}, {"data", blob(initialData)}});
        return h;
    }
    TextureHandle createTexture(const TextureDesc& desc) override {
        const TextureHandle h = inner_->createTexture(desc);
        record({{"op", "createTexture"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    TextureHandle createTextureView(TextureHandle texture, const TextureViewDesc& desc) override {
        const TextureHandle h = inner_->createTextureView(texture, desc);
        record({{"op", "createTextureView"}, {"id", h.id}, {"of", texture.id}, {"desc", toJson(desc)}});
        return h;
    }
    SamplerHandle createSampler(const SamplerDesc& desc) override {
        const SamplerHandle h = inner_->createSampler(desc);
        record({{"op", "createSampler"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    ShaderHandle createShader(const ShaderDesc& desc) override {
        const ShaderHandle h = inner_->createShader(desc);
        const auto& b = desc.binary;
        record({{"op", "createShader"}, {"id", h.id}, {"stage", uint64_t(desc.stage)},
                {"name", b.name ? b.name : ""}, {"entry", desc.entryPoint ? desc.entryPoint : "main"},
                {"vulkan", blob(std::as_bytes(b.vulkan))}, {"opengl", blob(std::as_bytes(b.opengl))}});
        return h;
    }
    PipelineHandle createGraphicsPipeline(const GraphicsPipelineDesc& desc) override {
        const PipelineHandle h = inner_->createGraphicsPipeline(desc);
        record({{"op", "createGraphicsPipeline"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    PipelineHandle createComputePipeline(const ComputePipelineDesc& desc) override {
        const PipelineHandle h = inner_->createComputePipeline(desc);
        record({{"op", "createComputePipeline"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    TimerHandle createTimer() override {
        const TimerHandle h = inner_->createTimer();
        record({{"op", "createTimer"}, {"id", h.id}});
        return h;
    }
    HeapHandle createHeap(const HeapDesc& desc) override {
        const HeapHandle h = inner_->createHeap(desc);
        record({{"op", "createHeap"}, {"id", h.id}, {"desc", toJson(desc)}});
        return h;
    }
    QuerySetHandle createQuerySet(const QuerySetDesc& desc) override {
        const QuerySetHandle h = inner_->createQuerySet(desc);
        record({{"op", "createQuerySet"}, {"id", h.id}, {"desc", toJson(desc)}});
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

    void writeBuffer(BufferHandle b, uint64_t offset, ByteSpan data) override {
        inner_->writeBuffer(b, offset, data);
        std::lock_guard lock(mutex_);
        // The file already holds these bytes: mapped memory compares against them from now on.
        if (const auto it = mapped_.find(b.id); it != mapped_.end())
            std::memcpy(it->second.shadow.data() + offset, data.data(), data.size());
        recordLocked({{"op", "writeBuffer"}, {"id", b.id}, {"offset", offset}, {"data", blob(data)}});
    }
    void writeTexture(TextureHandle t, Subresource at, ByteSpan data) override {
        inner_->writeTexture(t, at, data);
        record({{"op", "writeTexture"}, {"id", t.id}, {"mip", at.mipLevel}, {"layer", at.layer}, {"data", blob(data)}});
    }
    void writeTextureRegion(TextureHandle t, const TextureRegion& region, ByteSpan data, const TexelLayout& layout) override {
        inner_->writeTextureRegion(t, region, data, layout);
        record({{"op", "writeTextureRegion"}, {"id", t.id}, {"region", toJson(region)}, {"layout", toJson(layout)},
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
        recordLocked({{"op", "readTexture"}, {"id", t.id}, {"mip", at.mipLevel}, {"layer", at.layer}});
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
        if (mapped_.count(b.id) || !recording_) return p;
        // What the buffer holds now is written once; later only the bytes that change.
        Mapped& m = mapped_[b.id];
        m.memory = static_cast<std::byte*>(p);
        m.shadow.assign(m.memory, m.memory + inner_->desc(b).size);
        recordLocked({{"op", "mapped"}, {"id", b.id}, {"offset", 0}, {"data", blob(m.shadow)}});
        return p;
    }

    std::unique_ptr<CommandList> createCommandList() override {
        return std::make_unique<RecordingCommandList>(*inner_, inner_->createCommandList());
    }
    FenceValue submit(std::span<CommandList* const> lists) override {
        std::vector<CommandList*> inner;
        std::vector<RecordingCommandList*> recorded;
        for (CommandList* l : lists) {
            auto* r = dynamic_cast<RecordingCommandList*>(l);
            if (!r) throw Error("submit: a command list made by another device");
            recorded.push_back(r);
            inner.push_back(&r->inner());
        }
        std::lock_guard lock(mutex_);
        const FenceValue fence = inner_->submit(inner);
        if (!recording_) {
            for (RecordingCommandList* r : recorded) r->takeStream();
            return fence;
        }
        writeMappedChanges();
        json ids = json::array();
        for (RecordingCommandList* r : recorded) ids.push_back(blob(encodeCommandStream(*r->takeStream())));
        recordLocked({{"op", "submit"}, {"fence", fence}, {"lists", ids}});
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
    std::optional<double> timerNanoseconds(TimerHandle t) override { return inner_->timerNanoseconds(t); }
    // Results the program got are results replay can compare (fe conformance --capture).
    bool queryResults(QuerySetHandle s, uint32_t first, uint32_t count, std::span<uint64_t> out) override {
        const bool ready = inner_->queryResults(s, first, count, out);
        if (ready) record({{"op", "queryResults"}, {"id", s.id}, {"first", first}, {"count", count}});
        return ready;
    }
    uint32_t validationErrorCount() const override { return inner_->validationErrorCount(); }
    LiveObjects liveObjects() const override { return inner_->liveObjects(); }
    bool present(TextureHandle t) override {
        const bool open = inner_->present(t);
        std::lock_guard lock(mutex_);
        recordLocked({{"op", "present"}, {"id", t.id}});
        endFrameLocked();
        return open;
    }
    Image readWindow() override { return inner_->readWindow(); }
    InputState input() const override { return inner_->input(); }
    uint64_t nativeObject(NativeObject what, uint32_t id) const override { return inner_->nativeObject(what, id); }

private:
    struct Mapped {
        std::byte* memory = nullptr;
        std::vector<std::byte> shadow;  // the bytes the file holds for it
    };

    template <class H>
    void destroyed(H h, const char* kind) {
        inner_->destroy(h);
        record({{"op", "destroy"}, {"kind", kind}, {"id", h.id}});
    }
    uint64_t blob(std::span<const std::byte> bytes) { return recording_ ? writer_.blob(bytes) : 0; }
    uint64_t blob(const std::vector<std::byte>& bytes) { return blob(std::span<const std::byte>(bytes)); }
    void record(const json& j) {
        std::lock_guard lock(mutex_);
        recordLocked(j);
    }
    void recordLocked(const json& j) {
        if (recording_) writer_.record(json::to_cbor(j));
    }
    void endFrameLocked() {
        submittedSinceFrame_ = false;
        if (!recording_) return;
        recordLocked({{"op", "frame"}, {"index", frames_}});
        ++frames_;
        if (frameLimit_ && frames_ >= frameLimit_) {
            recording_ = false;
            writer_.finish();
        }
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
                    if (m.memory[k] != m.shadow[k]) end = k + 1, same = 0;
                    else ++same;
                }
                std::memcpy(m.shadow.data() + i, m.memory + i, end - i);
                recordLocked({{"op", "mapped"}, {"id", id}, {"offset", i},
                              {"data", blob(std::span<const std::byte>(m.shadow.data() + i, end - i))}});
                i = end;
            }
        }
    }

    std::unique_ptr<Device> inner_;
    capture::Writer writer_;
    std::mutex mutex_;  // the file's record order is the order calls completed in
    std::atomic<bool> recording_ = true;
    FenceValue completedRecorded_ = 0;  // the newest fence isComplete said was done, as written
    uint32_t frameLimit_ = 0, frames_ = 0;
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

void finishCapture(Device& device) {
    if (auto* c = dynamic_cast<CaptureDevice*>(&device)) c->finish();
}

}  // namespace fe::gdi
