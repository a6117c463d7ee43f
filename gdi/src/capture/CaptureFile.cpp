#include "CaptureFile.h"

#include <zstd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/CommandStream.h"

namespace fe::gdi::capture {

namespace {

constexpr uint64_t kMaxQueuedBytes = uint64_t(256) << 20;
constexpr int kZstdLevel = 1;  // fast: capture must keep up with the frame

template <class T>
void put(std::vector<std::byte>& out, T v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}
template <class T>
T get(const std::byte* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

// Two independent 64-bit hashes and the size: equal keys mean equal bytes in practice (a
// collision needs both hashes to collide at once).
std::string contentKey(std::span<const std::byte> bytes) {
    const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    uint64_t fnv = 14695981039346656037ull;
    for (std::byte b : bytes) fnv = (fnv ^ uint64_t(b)) * 1099511628211ull;
    const uint64_t keys[3] = {uint64_t(bytes.size()), uint64_t(std::hash<std::string_view>{}(view)),
                              fnv};
    return std::string(reinterpret_cast<const char*>(keys), sizeof keys);
}

[[noreturn]] void refuse(uint64_t offset, const std::string& what) {
    throw CaptureError("capture: offset " + std::to_string(offset) + ": " + what);
}

}  // namespace

uint64_t commandSetFingerprint() {
    uint64_t h = 14695981039346656037ull;
    auto mix = [&](std::string_view s, uint64_t size) {
        for (char c : s) h = (h ^ uint64_t(uint8_t(c))) * 1099511628211ull;
        h = (h ^ size) * 1099511628211ull;
    };
#define FE_COMMAND(Name, Fields) mix(#Name, sizeof(cmd::Name));
#define FE_BACKEND_COMMAND(Name, Fields)  // in no capture
#include "fe/gdi/CommandSet.inc"
#undef FE_BACKEND_COMMAND
#undef FE_COMMAND
    return h;
}

Writer::Writer(const std::string& path, bool compress) : compress_(compress) {
    out_.open(path, std::ios::binary | std::ios::trunc);
    if (!out_) throw Error("capture: cannot write '" + path + "'");
    std::vector<std::byte> header;
    for (char c : kMagic) header.push_back(std::byte(c));
    put<uint32_t>(header, kVersion);
    put<uint32_t>(header, 0);
    out_.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
    stats_.fileBytes = header.size();
    thread_ = std::thread([this] { run(); });
}

Writer::~Writer() {
    try {
        finish();
    } catch (const std::exception&) {
        // The destructor of a capturing device must not throw; finish() was the place to see it.
    }
}

uint64_t Writer::blob(std::span<const std::byte> bytes) {
    if (bytes.empty()) return 0;
    std::string key = contentKey(bytes);
    {
        std::lock_guard lock(mutex_);
        if (const auto it = blobIds_.find(key); it != blobIds_.end()) {
            ++stats_.dedupedBlobs;
            return it->second;
        }
    }
    std::vector<std::byte> copy(bytes.begin(), bytes.end());
    std::unique_lock lock(mutex_);
    // Ids follow the order of the blob chunks in the file, so the id is taken as it is queued.
    if (const auto it = blobIds_.find(key); it != blobIds_.end()) return it->second;
    const uint64_t id = ++stats_.blobs;
    blobIds_.emplace(std::move(key), id);
    stats_.rawBytes += copy.size();
    changed_.wait(lock, [&] { return queuedBytes_ < kMaxQueuedBytes || done_; });
    queuedBytes_ += copy.size();
    queue_.push_back({ChunkKind::Blob, std::move(copy)});
    changed_.notify_all();
    return id;
}

void Writer::record(std::vector<uint8_t> cbor) {
    std::vector<std::byte> bytes(cbor.size());
    std::memcpy(bytes.data(), cbor.data(), cbor.size());
    std::unique_lock lock(mutex_);
    ++stats_.records;
    stats_.rawBytes += bytes.size();
    changed_.wait(lock, [&] { return queuedBytes_ < kMaxQueuedBytes || done_; });
    queuedBytes_ += bytes.size();
    queue_.push_back({ChunkKind::Record, std::move(bytes)});
    changed_.notify_all();
}

void Writer::finish() {
    {
        std::unique_lock lock(mutex_);
        if (finished_) return;
        finished_ = true;
        queue_.push_back({ChunkKind::End, {}});
        done_ = true;
        changed_.notify_all();
    }
    thread_.join();
    out_.close();
    if (!error_.empty()) throw Error(error_);
}

WriterStats Writer::stats() {
    std::lock_guard lock(mutex_);
    return stats_;
}

void Writer::run() {
    for (;;) {
        Chunk c;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return !queue_.empty(); });
            c = std::move(queue_.front());
            queue_.pop_front();
        }
        if (error_.empty()) write(c);
        std::lock_guard lock(mutex_);
        queuedBytes_ -= c.bytes.size();
        changed_.notify_all();
        if (c.kind == ChunkKind::End) return;
    }
}

void Writer::write(const Chunk& c) {
    std::vector<std::byte> stored;
    Encoding encoding = Encoding::Raw;
    // Small chunks are not worth a zstd frame.
    if (compress_ && c.bytes.size() >= 256) {
        stored.resize(ZSTD_compressBound(c.bytes.size()));
        const size_t n =
            ZSTD_compress(stored.data(), stored.size(), c.bytes.data(), c.bytes.size(), kZstdLevel);
        if (!ZSTD_isError(n) && n < c.bytes.size()) {
            stored.resize(n);
            encoding = Encoding::Zstd;
        }
    }
    const std::vector<std::byte>& body = encoding == Encoding::Zstd ? stored : c.bytes;
    std::vector<std::byte> header;
    put<uint32_t>(header, uint32_t(c.kind));
    put<uint32_t>(header, uint32_t(encoding));
    put<uint64_t>(header, body.size());
    put<uint64_t>(header, c.bytes.size());
    out_.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
    out_.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
    if (!out_) {
        error_ = "capture: writing the file failed (disk full?)";
        return;
    }
    std::lock_guard lock(mutex_);
    stats_.fileBytes += header.size() + body.size();
}

Reader::Reader(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw CaptureError("capture: '" + path + "' is not a readable file");
    std::ifstream in(path, std::ios::binary);
    const auto size = std::filesystem::file_size(path, ec);
    if (!in || ec) throw CaptureError("capture: cannot read '" + path + "'");
    file_.resize(size);
    in.read(reinterpret_cast<char*>(file_.data()), std::streamsize(size));
    if (!in) throw CaptureError("capture: cannot read '" + path + "'");
    if (file_.size() < kHeaderBytes || std::memcmp(file_.data(), kMagic, sizeof kMagic) != 0)
        refuse(0, "not a capture file (no FECAPTUR header)");
    version_ = get<uint32_t>(file_.data() + 8);
    if (version_ == 0 || version_ > kVersion)
        refuse(8, "format version " + std::to_string(version_) + "; this build reads version " +
                      std::to_string(kVersion));
}

bool Reader::next(Chunk& chunk) {
    if (ended_) return false;
    const uint64_t at = at_;
    if (file_.size() - at < kChunkHeaderBytes)
        refuse(at,
               "file ends before its end record (truncated: the capturing program did not finish)");
    const auto kind = get<uint32_t>(file_.data() + at);
    const auto encoding = get<uint32_t>(file_.data() + at + 4);
    const auto stored = get<uint64_t>(file_.data() + at + 8);
    const auto raw = get<uint64_t>(file_.data() + at + 16);
    if (kind < uint32_t(ChunkKind::Blob) || kind > uint32_t(ChunkKind::End))
        refuse(at, "unknown chunk kind " + std::to_string(kind));
    if (encoding > uint32_t(Encoding::Zstd))
        refuse(at, "unknown chunk encoding " + std::to_string(encoding));
    if (stored > file_.size() - at - kChunkHeaderBytes)
        refuse(at, "chunk of " + std::to_string(stored) + " bytes runs past the end of the file");
    if (raw > kMaxChunkBytes)
        refuse(at,
               "chunk of " + std::to_string(raw) + " bytes is larger than a capture chunk may be");
    if (encoding == uint32_t(Encoding::Raw) && raw != stored)
        refuse(at, "raw chunk's two sizes differ");
    const std::byte* body = file_.data() + at + kChunkHeaderBytes;
    chunk.kind = ChunkKind(kind);
    chunk.offset = at;
    if (encoding == uint32_t(Encoding::Raw)) {
        chunk.bytes.assign(body, body + stored);
    } else {
        const unsigned long long content = ZSTD_getFrameContentSize(body, stored);
        if (content != raw)
            refuse(at, "compressed chunk does not hold the " + std::to_string(raw) +
                           " bytes it states");
        chunk.bytes.resize(raw);
        const size_t n = ZSTD_decompress(chunk.bytes.data(), raw, body, stored);
        if (ZSTD_isError(n) || n != raw)
            refuse(at, "compressed chunk is damaged (zstd: " +
                           std::string(ZSTD_isError(n) ? ZSTD_getErrorName(n) : "short") + ")");
    }
    at_ = at + kChunkHeaderBytes + stored;
    if (chunk.kind == ChunkKind::End) {
        ended_ = true;
        if (at_ != file_.size()) refuse(at_, "bytes after the end record");
    }
    return true;
}

}  // namespace fe::gdi::capture
