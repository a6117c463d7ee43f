#include "fe/gdi/CaptureStream.h"

#include <cmath>
#include <functional>

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
            if (field.count &&
                (field.offset < sizeof(R) || field.offset % alignof(T) || end > bytes))
                problem = std::string("field '") + name + "' points outside the record";
            else if constexpr (std::is_same_v<F, cmd::String>)
                if (field.count &&
                    reinterpret_cast<const char*>(&r)[field.offset + field.count - 1] != '\0')
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
            throw CaptureError("capture: truncated " + std::string(what) + " at offset " +
                               std::to_string(base + at));
        T v;
        std::memcpy(&v, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return v;
    }
};

// Field values a device could not be handed safely: a bool other than 0 or 1, an enum outside
// its values, flags outside their bits, a non-finite float. Read as raw bytes (loading a bool
// of value 3 is itself undefined behaviour). The device's own checks judge everything else.
class ValueCheck {
public:
    explicit ValueCheck(const std::byte* record) : record_(record) {}
    std::string problem;

    template <class T>
    void operator()(const char* name, const T& v) {
        check(name, v);
    }

private:
    template <class T>
    static uint64_t raw(const T& v) {
        uint64_t out = 0;
        std::memcpy(&out, &v, sizeof(T));
        return out;
    }
    void fail(const char* name, const std::string& why) {
        if (problem.empty()) problem = std::string("field '") + name + "' " + why;
    }
    void boolean(const char* name, const bool& v) {
        if (raw(v) > 1) fail(name, "is not a boolean (" + std::to_string(raw(v)) + ")");
    }
    template <class E>
    void upTo(const char* name, const E& v, E last) {
        if (raw(v) > uint64_t(last))
            fail(name, "has no such value (" + std::to_string(raw(v)) + ")");
    }
    void finite(const char* name, float v) {
        if (!std::isfinite(v)) fail(name, "is not a finite number");
    }
    void check(const char* name, const bool& v) { boolean(name, v); }
    void check(const char* name, const IndexType& v) { upTo(name, v, IndexType::U32); }
    void check(const char* name, const float& v) { finite(name, v); }
    void check(const char* name, const cmd::Rgba& v) {
        for (float f : v) finite(name, f);
    }
    void check(const char* name, const Viewport& v) {
        for (float f : {v.x, v.y, v.width, v.height, v.minDepth, v.maxDepth}) finite(name, f);
    }
    void check(const char* name, const DepthAttachment& d) {
        upTo(name, d.load, LoadOp::DontCare);
        upTo(name, d.store, StoreOp::DontCare);
        finite(name, d.clearDepth);
    }
    void check(const char* name, const ColorAttachment& c) {
        upTo(name, c.load, LoadOp::DontCare);
        upTo(name, c.store, StoreOp::DontCare);
        for (float f : c.clear) finite(name, f);
    }
    void check(const char* name, const TextureBarrier& b) {
        upTo(name, b.before, ResourceState::CopyDst);
        upTo(name, b.after, ResourceState::CopyDst);
    }
    void check(const char* name, const BufferBarrier& b) {
        for (const BufferAccess& a : {std::cref(b.before), std::cref(b.after)})
            if (raw(a) & ~uint64_t(0xff))
                fail(name, "has unknown access bits (" + std::to_string(raw(a)) + ")");
    }
    // Payload arrays: each element as its own field.
    template <class T>
    void check(const char* name, const cmd::Array<T>& a) {
        if constexpr (std::is_same_v<T, ColorAttachment> || std::is_same_v<T, TextureBarrier> ||
                      std::is_same_v<T, BufferBarrier>) {
            const auto* first = reinterpret_cast<const T*>(record_ + a.offset);
            for (uint32_t i = 0; i < a.count; ++i) check(name, first[i]);
        }
    }
    // Integers, handles, subresources, regions, layouts: any value is one the device can judge.
    template <class T>
    void check(const char*, const T&) {}

    const std::byte* record_;
};

template <class R>
std::string valueProblem(const R& r) {
    ValueCheck check(reinterpret_cast<const std::byte*>(&r));
    cmd::forEachField(r, check);
    return check.problem;
}

}  // namespace

std::vector<std::byte> encodeCommandStream(const cmd::CommandStream& stream) {
    std::vector<std::byte> records;
    stream.forEachRaw(
        [&](std::span<const std::byte> r) { records.insert(records.end(), r.begin(), r.end()); });
    // Children are reached through ExecuteSecondary's indices: count them by walking once.
    uint32_t children = 0;
    stream.forEach([&](const auto& r) {
        if constexpr (std::is_same_v<std::decay_t<decltype(r)>, cmd::ExecuteSecondary>)
            children = std::max(children, r.child + 1);
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

std::unique_ptr<cmd::CommandStream> decodeCommandStream(std::span<const std::byte> bytes,
                                                        uint64_t baseOffset) {
    Reader in{bytes, baseOffset};
    const uint32_t records = in.read<uint32_t>("stream header");
    const uint32_t children = in.read<uint32_t>("stream header");
    const uint64_t recordBytes = in.read<uint64_t>("stream header");
    if (recordBytes > bytes.size() - in.at)
        throw CaptureError("capture: stream at offset " + std::to_string(baseOffset) + " states " +
                           std::to_string(recordBytes) + " bytes of records; " +
                           std::to_string(bytes.size() - in.at) + " remain");
    auto stream = std::make_unique<cmd::CommandStream>();
    const size_t end = in.at + size_t(recordBytes);
    for (uint32_t i = 0; i < records; ++i) {
        const uint64_t offset = baseOffset + in.at;
        auto fail = [&](const std::string& why, const char* op = nullptr) {
            return CaptureError("capture: record " + std::to_string(i) +
                                (op ? std::string(" (") + op + ")" : std::string()) +
                                " at offset " + std::to_string(offset) + ": " + why);
        };
        if (end - in.at < sizeof(cmd::CommandStream::Header)) throw fail("truncated header");
        cmd::CommandStream::Header h;
        std::memcpy(&h, bytes.data() + in.at, sizeof h);
        if (uint16_t(h.op) >= uint16_t(cmd::Op::Count))
            throw fail("unknown command " + std::to_string(uint16_t(h.op)));
        if (h.size % 8 || h.size < sizeof h || h.size > end - in.at)
            throw fail("size " + std::to_string(h.size) + " is invalid", cmd::opName(h.op));
        // The record body is copied to aligned memory before it is looked at.
        std::vector<uint64_t> aligned((h.size + 7) / 8);
        std::memcpy(aligned.data(), bytes.data() + in.at, h.size);
        const std::byte* body = reinterpret_cast<const std::byte*>(aligned.data()) + sizeof h;
        const size_t bodyBytes = h.size - sizeof h;
        std::string problem;
        cmd::CommandStream::dispatch(h.op, body, [&](const auto& r) {
            using R = std::decay_t<decltype(r)>;
            if (bodyBytes < sizeof(R))
                problem = "shorter than its fields";
            else
                problem = payloadProblem(r, bodyBytes);
            if (problem.empty()) problem = valueProblem(r);
            if constexpr (std::is_same_v<R, cmd::ExecuteSecondary>)
                if (problem.empty() && r.child >= children)
                    problem = "secondary stream " + std::to_string(r.child) + " does not exist";
            if constexpr (std::is_same_v<R, cmd::DrawOneInstance> ||
                          std::is_same_v<R, cmd::SetUniformOffset>)
                problem = "the GL backend's own form of a command, never recorded in a capture";
        });
        if (!problem.empty()) throw fail(problem, cmd::opName(h.op));
        stream->pushRaw(std::span(reinterpret_cast<const std::byte*>(aligned.data()), h.size));
        in.at += h.size;
    }
    if (in.at != end)
        throw CaptureError("capture: stream at offset " + std::to_string(baseOffset) + ": " +
                           std::to_string(end - in.at) + " bytes after its " +
                           std::to_string(records) + " records");
    for (uint32_t c = 0; c < children; ++c) {
        const uint64_t size = in.read<uint64_t>("secondary stream size");
        if (size > bytes.size() - in.at)
            throw CaptureError("capture: secondary stream " + std::to_string(c) + " at offset " +
                               std::to_string(baseOffset + in.at) + " states " +
                               std::to_string(size) + " bytes; " +
                               std::to_string(bytes.size() - in.at) + " remain");
        stream->adopt(decodeCommandStream(bytes.subspan(in.at, size_t(size)), baseOffset + in.at));
        in.at += size_t(size);
    }
    return stream;
}

}  // namespace fe::gdi
