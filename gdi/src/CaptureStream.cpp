#include "fe/gdi/CaptureStream.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>

namespace fe::gdi {

namespace {

template <class T>
void put(std::vector<std::byte>& out, T v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}

template <class T>
struct ArrayElement {
    static constexpr bool kIsArray = false;
};
template <class T>
struct ArrayElement<cmd::Array<T>> {
    static constexpr bool kIsArray = true;
    using Type = T;
};

// Every Array/String field of record `r` (of `bytes` bytes after its header) lies inside it, and
// a string ends with its NUL. Returns what is wrong, empty when nothing is.
template <class R>
std::string payloadProblem(const R& r, size_t bytes) {
    std::string problem;
    cmd::forEachField(r, [&](const char* name, const auto& field) {
        using F = std::decay_t<decltype(field)>;
        if constexpr (ArrayElement<F>::kIsArray) {
            using T = typename ArrayElement<F>::Type;
            const uint64_t end = uint64_t(field.offset) + uint64_t(field.count) * sizeof(T);
            if (field.count && (field.offset < sizeof(R) || field.offset % alignof(T) || end > bytes))
                problem = std::string("field '") + name + "' points outside the record";
            else if constexpr (std::is_same_v<F, cmd::String>)
                if (field.count && reinterpret_cast<const char*>(&r)[field.offset + field.count - 1] != '\0')
                    problem = std::string("string '") + name + "' is not terminated";
        }
    });
    return problem;
}

struct Reader {
    std::span<const std::byte> bytes;
    uint64_t base;
    size_t at = 0;
    template <class T>
    T read(const char* what) {
        if (bytes.size() - at < sizeof(T))
            throw CaptureError("capture: truncated " + std::string(what) + " at offset " + std::to_string(base + at));
        T v;
        std::memcpy(&v, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return v;
    }
};

}  // namespace

std::vector<std::byte> encodeCommandStream(const cmd::CommandStream& stream) {
    std::vector<std::byte> records;
    stream.forEachRaw([&](std::span<const std::byte> r) { records.insert(records.end(), r.begin(), r.end()); });
    // Children are reached through ExecuteSecondary's indices: count them by walking once.
    uint32_t children = 0;
    stream.forEach([&](const auto& r) {
        if constexpr (std::is_same_v<std::decay_t<decltype(r)>, cmd::ExecuteSecondary>) children = std::max(children, r.child + 1);
    });
    std::vector<std::byte> out;
    put(out, uint32_t(stream.commandCount()));
    put(out, children);
    put(out, uint64_t(records.size()));
    out.insert(out.end(), records.begin(), records.end());
    for (uint32_t c = 0; c < children; ++c) {
        const std::vector<std::byte> child = encodeCommandStream(stream.child(c));
        put(out, uint64_t(child.size()));
        out.insert(out.end(), child.begin(), child.end());
    }
    return out;
}

std::unique_ptr<cmd::CommandStream> decodeCommandStream(std::span<const std::byte> bytes, uint64_t baseOffset) {
    Reader in{bytes, baseOffset};
    const uint32_t records = in.read<uint32_t>("stream header");
    const uint32_t children = in.read<uint32_t>("stream header");
    const uint64_t recordBytes = in.read<uint64_t>("stream header");
    if (recordBytes > bytes.size() - in.at)
        throw CaptureError("capture: stream at offset " + std::to_string(baseOffset) + " states " + std::to_string(recordBytes) +
                           " bytes of records; " + std::to_string(bytes.size() - in.at) + " remain");
    auto stream = std::make_unique<cmd::CommandStream>();
    const size_t end = in.at + size_t(recordBytes);
    for (uint32_t i = 0; i < records; ++i) {
        const uint64_t offset = baseOffset + in.at;
        auto fail = [&](const std::string& why, const char* op = nullptr) {
            return CaptureError("capture: record " + std::to_string(i) + (op ? std::string(" (") + op + ")" : std::string()) +
                                " at offset " + std::to_string(offset) + ": " + why);
        };
        if (end - in.at < sizeof(cmd::CommandStream::Header)) throw fail("truncated header");
        cmd::CommandStream::Header h;
        std::memcpy(&h, bytes.data() + in.at, sizeof h);
        if (uint16_t(h.op) >= uint16_t(cmd::Op::Count)) throw fail("unknown command " + std::to_string(uint16_t(h.op)));
        if (h.size % 8 || h.size < sizeof h || h.size > end - in.at) throw fail("size " + std::to_string(h.size) + " is invalid", cmd::opName(h.op));
        // The record body is copied to aligned memory before it is looked at.
        std::vector<uint64_t> aligned((h.size + 7) / 8);
        std::memcpy(aligned.data(), bytes.data() + in.at, h.size);
        const std::byte* body = reinterpret_cast<const std::byte*>(aligned.data()) + sizeof h;
        const size_t bodyBytes = h.size - sizeof h;
        std::string problem;
        cmd::CommandStream::dispatch(h.op, body, [&](const auto& r) {
            using R = std::decay_t<decltype(r)>;
            if (bodyBytes < sizeof(R)) problem = "shorter than its fields";
            else problem = payloadProblem(r, bodyBytes);
            if constexpr (std::is_same_v<R, cmd::ExecuteSecondary>)
                if (problem.empty() && r.child >= children) problem = "secondary stream " + std::to_string(r.child) + " does not exist";
        });
        if (!problem.empty()) throw fail(problem, cmd::opName(h.op));
        stream->pushRaw(std::span(reinterpret_cast<const std::byte*>(aligned.data()), h.size));
        in.at += h.size;
    }
    if (in.at != end)
        throw CaptureError("capture: stream at offset " + std::to_string(baseOffset) + ": " + std::to_string(end - in.at) +
                           " bytes after its " + std::to_string(records) + " records");
    for (uint32_t c = 0; c < children; ++c) {
        const uint64_t size = in.read<uint64_t>("secondary stream size");
        if (size > bytes.size() - in.at)
            throw CaptureError("capture: secondary stream " + std::to_string(c) + " at offset " + std::to_string(baseOffset + in.at) +
                               " states " + std::to_string(size) + " bytes; " + std::to_string(bytes.size() - in.at) + " remain");
        stream->adopt(decodeCommandStream(bytes.subspan(in.at, size_t(size)), baseOffset + in.at));
        in.at += size_t(size);
    }
    return stream;
}

}  // namespace fe::gdi
