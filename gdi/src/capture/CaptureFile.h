// The capture container (docs/CAPTURE.md): a header, then chunks, each a blob of bytes or a call
// record (CBOR), optionally zstd-compressed, and an end chunk that marks a complete file.
//
//   file   := "FECAPTUR" | u32 version | u32 0 | chunk* | end chunk
//   chunk  := u32 kind | u32 encoding (0 raw, 1 zstd) | u64 stored bytes | u64 raw bytes | stored bytes
//
// The writer hands chunks to a thread of its own, which compresses and writes them, so a
// capturing program does not wait for the disk (only when 256 MiB are queued). Blobs with the
// same bytes are written once: a second one gets the first one's id.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <fstream>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi::capture {

inline constexpr char kMagic[8] = {'F', 'E', 'C', 'A', 'P', 'T', 'U', 'R'};
inline constexpr uint32_t kVersion = 1;
inline constexpr uint64_t kHeaderBytes = 16, kChunkHeaderBytes = 24;
// A chunk's raw size is bounded so that a hostile header cannot ask for more memory than this.
inline constexpr uint64_t kMaxChunkBytes = uint64_t(1) << 31;

// Names, order and sizes of CommandSet.inc's records: a capture made with another command set
// cannot replay its lists, and says so instead of misreading them.
uint64_t commandSetFingerprint();

enum class ChunkKind : uint32_t { Blob = 1, Record = 2, End = 3 };
enum class Encoding : uint32_t { Raw = 0, Zstd = 1 };

struct WriterStats {
    uint64_t records = 0, blobs = 0, dedupedBlobs = 0, rawBytes = 0, fileBytes = 0;
};

class Writer {
public:
    Writer(const std::string& path, bool compress);  // throws Error when the file cannot be made
    ~Writer();
    Writer(const Writer&) = delete;
    Writer& operator=(const Writer&) = delete;

    // A blob's id (1, 2, ... in order of first appearance; 0 for no bytes). Thread-safe.
    uint64_t blob(std::span<const std::byte> bytes);
    uint64_t blob(const void* data, size_t size) {
        return blob({static_cast<const std::byte*>(data), size});
    }
    void record(std::vector<uint8_t> cbor);  // thread-safe
    // Writes the end chunk and closes the file; later calls do nothing.
    void finish();
    WriterStats stats();

private:
    struct Chunk {
        ChunkKind kind;
        std::vector<std::byte> bytes;
    };
    void enqueue(ChunkKind kind, std::vector<std::byte> bytes);
    void run();
    void write(const Chunk& c);

    std::ofstream out_;
    bool compress_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Chunk> queue_;
    uint64_t queuedBytes_ = 0;
    bool done_ = false, finished_ = false;
    std::string error_;  // the writer thread's failure, reported by finish()
    std::unordered_map<std::string, uint64_t> blobIds_;  // content key -> id
    WriterStats stats_;
    std::thread thread_;
};

struct Chunk {
    ChunkKind kind;
    uint64_t offset;  // of its header in the file
    std::vector<std::byte> bytes;
};

// Reads a whole capture file; every size is checked against the file before memory is taken.
class Reader {
public:
    explicit Reader(const std::string& path);  // throws CaptureError
    // The next chunk (false after the end chunk). Throws CaptureError naming the offset.
    bool next(Chunk& chunk);
    uint32_t version() const { return version_; }

private:
    std::vector<std::byte> file_;
    uint64_t at_ = kHeaderBytes;
    uint32_t version_ = 0;
    bool ended_ = false;
};

}  // namespace fe::gdi::capture
