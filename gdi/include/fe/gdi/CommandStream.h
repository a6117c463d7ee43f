// A recorded command list as data: typed records in an arena, generated from CommandSet.inc.
//
//   cmd::Draw record{.vertexCount = 3, .instanceCount = 1};
//   stream.push(record);                                   // no heap allocation per command
//   auto* pass = stream.push(cmd::BeginRenderPass{}, payloadBytes);
//   pass->colors = stream.payload(*pass, std::span(colors)); // variable-length data after it
//   stream.forEach([&](const auto& record) { execute(record); });  // one overload per command
//
// Records are 8-byte aligned: a header (opcode, size), the record, then its payloads. Blocks are
// kept across reset(), so a list recorded every frame stops allocating after its first frames.
#pragma once
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <memory>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi::cmd {

// A run of T stored after its record; `offset` counts bytes from the record's start.
template <class T>
struct Array {
    uint32_t offset = 0, count = 0;
};
using String = Array<char>;  // NUL-terminated; count includes the NUL; empty: no string
using Rgba = std::array<float, 4>;

// How CommandList's methods take a field of each type (CommandSet.inc, FE_CALL): by value; the
// larger structs by const reference; payloads as a span or a C string.
template <class T>
struct ParamOf {
    using type = T;
};
template <class T>
struct ParamOf<Array<T>> {
    using type = std::span<const T>;
};
template <>
struct ParamOf<String> {
    using type = const char*;
};
template <class T>
struct ParamOfConstRef {
    using type = const T&;
};
template <>
struct ParamOf<Viewport> : ParamOfConstRef<Viewport> {};
template <>
struct ParamOf<Rect> : ParamOfConstRef<Rect> {};
template <>
struct ParamOf<Rgba> : ParamOfConstRef<Rgba> {};
template <>
struct ParamOf<TextureRegion> : ParamOfConstRef<TextureRegion> {};
template <>
struct ParamOf<TexelLayout> : ParamOfConstRef<TexelLayout> {};
template <class T>
using Param = typename ParamOf<T>::type;

// Generating code from the command set. FE_CMD_LIST(, a, b) drops the leading comma of a list a
// field macro built. For code that needs a call's parameters and its arguments at once, define
// FE_FIELD(Type, name) as (Type, name): the fields become a sequence of pairs, which
// FE_CMD_PARAMS(fields) turns into "Param<T1> n1, Param<T2> n2" and FE_CMD_ARGS(fields) into
// "n1, n2" (the alternating-macro walk over a sequence, as Boost.Preprocessor's SEQ does).
// FE_CMD_TYPE_NAMES, in a generating class, names the command set's own types as it does.
#define FE_CMD_TYPE_NAMES                   \
    template <class T>                      \
    using Array = ::fe::gdi::cmd::Array<T>; \
    using String = ::fe::gdi::cmd::String;  \
    using Rgba = ::fe::gdi::cmd::Rgba;
// FE_CMD_GDI_TYPE_NAMES does the same for the gdi types it names, in a class of another
// namespace (a backend's list: CommandListOverrides.inc).
#define FE_CMD_GDI_TYPE_NAMES                         \
    using BufferHandle = ::fe::gdi::BufferHandle;     \
    using TextureHandle = ::fe::gdi::TextureHandle;   \
    using SamplerHandle = ::fe::gdi::SamplerHandle;   \
    using PipelineHandle = ::fe::gdi::PipelineHandle; \
    using TimerHandle = ::fe::gdi::TimerHandle;       \
    using QuerySetHandle = ::fe::gdi::QuerySetHandle; \
    using Viewport = ::fe::gdi::Viewport;             \
    using Rect = ::fe::gdi::Rect;                     \
    using IndexType = ::fe::gdi::IndexType;           \
    using Subresource = ::fe::gdi::Subresource;       \
    using TextureRegion = ::fe::gdi::TextureRegion;   \
    using TexelLayout = ::fe::gdi::TexelLayout;
#define FE_CMD_DROP_FIRST(first, ...) __VA_ARGS__
#define FE_CMD_APPLY(macro, args) macro args
#define FE_CMD_LIST(...) FE_CMD_APPLY(FE_CMD_DROP_FIRST, (~__VA_ARGS__))
#define FE_CMD_END(...) FE_CMD_END_I(__VA_ARGS__)
#define FE_CMD_END_I(...) __VA_ARGS__##_END
#define FE_CMD_PARAMS(seq) FE_CMD_LIST(FE_CMD_END(FE_CMD_PARAM_A seq))
#define FE_CMD_PARAM_A(Type, name) , ::fe::gdi::cmd::Param<Type> name FE_CMD_PARAM_B
#define FE_CMD_PARAM_B(Type, name) , ::fe::gdi::cmd::Param<Type> name FE_CMD_PARAM_A
#define FE_CMD_PARAM_A_END
#define FE_CMD_PARAM_B_END
#define FE_CMD_ARGS(seq) FE_CMD_LIST(FE_CMD_END(FE_CMD_ARG_A seq))
#define FE_CMD_ARG_A(Type, name) , name FE_CMD_ARG_B
#define FE_CMD_ARG_B(Type, name) , name FE_CMD_ARG_A
#define FE_CMD_ARG_A_END
#define FE_CMD_ARG_B_END
// "arg(r, r.n1), arg(r, r.n2)": a record r's fields as the arguments of its call, each through
// an arg() the generating code provides (replay maps handles and views payloads there).
#define FE_CMD_RECORD_ARGS(seq) FE_CMD_LIST(FE_CMD_END(FE_CMD_RECORD_ARG_A seq))
#define FE_CMD_RECORD_ARG_A(Type, name) , arg(r, r.name) FE_CMD_RECORD_ARG_B
#define FE_CMD_RECORD_ARG_B(Type, name) , arg(r, r.name) FE_CMD_RECORD_ARG_A
#define FE_CMD_RECORD_ARG_A_END
#define FE_CMD_RECORD_ARG_B_END

enum class Op : uint16_t {
#define FE_COMMAND(Name, Fields) Name,
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
    Count
};

#define FE_FIELD(Type, name) Type name{};
#define FE_COMMAND(Name, Fields)                    \
    struct Name {                                   \
        static constexpr Op kOp = Op::Name;         \
        static constexpr const char* kName = #Name; \
        Fields                                      \
    };
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
#undef FE_FIELD

const char* opName(Op op);

// Calls f(fieldName, value) for every field of a record, in declaration order.
#define FE_FIELD(Type, name) f(#name, record.name);
#define FE_COMMAND(Name, Fields)                                                     \
    template <class F>                                                               \
    void forEachField([[maybe_unused]] const Name& record, [[maybe_unused]] F&& f) { \
        Fields                                                                       \
    }
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
#undef FE_FIELD

// A record's fields as references, in declaration order (CommandStream::record fills them).
#define FE_FIELD(Type, name) , record.name
#define FE_COMMAND(Name, ...)                              \
    inline auto fieldRefs([[maybe_unused]] Name& record) { \
        return std::tie(FE_CMD_LIST(__VA_ARGS__));         \
    }
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
#undef FE_FIELD

// The payload an Array field refers to.
template <class T, class R>
std::span<const T> view(const R& record, Array<T> a) {
    return {reinterpret_cast<const T*>(reinterpret_cast<const std::byte*>(&record) + a.offset),
            a.count};
}
template <class R>
const char* view(const R& record, String s) {
    return s.count ? reinterpret_cast<const char*>(&record) + s.offset : nullptr;
}

// Cache-line aligned: its cursor and count are written per command by the recording thread, and
// the device's pool allocates the streams of lists recorded on other threads next to each other
// (unaligned, two streams of under 100 bytes could share a line and every push would contend).
class alignas(64) CommandStream {
public:
    struct Header {
        Op op;
        uint16_t reserved = 0;
        uint32_t size;  // bytes of header, record and payloads, a multiple of 8
    };

    // Appends a record with room for `payloadBytes` of payloads; returns it for payload().
    template <class R>
    R* push(const R& record, size_t payloadBytes = 0) {
        static_assert(std::is_trivially_copyable_v<R>);
        const size_t size = align(sizeof(Header) + align(sizeof(R)) + payloadBytes);
        std::byte* at = reserve(size);
        new (at) Header{R::kOp, 0, uint32_t(size)};
        R* r = new (at + sizeof(Header)) R(record);
        if (payloadBytes) payloadAt_ = at + sizeof(Header) + align(sizeof(R));  // folded away: 0
        ++count_;
        return r;
    }
    // A caller's leaf fast path (no call, so no saved registers): whether a record of type R
    // without payloads fits the current block; if so, pushFitting appends it. Else the caller
    // takes its checked path, which calls push().
    template <class R>
    bool fits() const {
        return align(sizeof(Header) + align(sizeof(R))) <= size_t(end_ - cur_);
    }
    template <class R>
    void pushFitting(const R& record) {
        static_assert(std::is_trivially_copyable_v<R>);
        constexpr size_t size = align(sizeof(Header) + align(sizeof(R)));
        new (cur_) Header{R::kOp, 0, uint32_t(size)};
        new (cur_ + sizeof(Header)) R(record);
        cur_ += size;
        ++count_;
    }
    // Copies `data` into the room push() reserved after `record` (the last record pushed).
    template <class T, class R>
    Array<T> payload(const R& record, std::span<const T> data) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (data.empty()) return {};
        std::byte* at = payloadAt_;
        std::memcpy(at, data.data(), data.size_bytes());
        payloadAt_ += align(data.size_bytes());
        return {uint32_t(at - reinterpret_cast<const std::byte*>(&record)), uint32_t(data.size())};
    }
    template <class R>
    String payload(const R& record, const char* text) {
        if (!text) return {};
        return payload(record, std::span<const char>(text, std::strlen(text) + 1));
    }
    // Appends record R with its fields set from `args` in order (CommandList's parameters, as
    // cmd::Param gives them): payloads are copied after the record; a null String is stored as "".
    template <class R, class... A>
    R* record(const A&... args) {
        auto* r = push(R{}, (size_t(0) + ... + payloadBytes(args)));
        auto fields = fieldRefs(*r);
        static_assert(std::tuple_size_v<decltype(fields)> == sizeof...(A),
                      "one argument per field");
        [&]<size_t... I>(std::index_sequence<I...>) { (store(*r, std::get<I>(fields), args), ...); }
        (std::index_sequence_for<A...>{});
        return r;
    }
    static size_t payloadSize(size_t bytes) { return align(bytes); }
    static size_t payloadSize(const char* text) { return text ? align(std::strlen(text) + 1) : 0; }

    // Calls f(record) for each record in recording order; f has an overload per record type.
    template <class F>
    void forEach(F&& f) const {
        forEachRaw([&](std::span<const std::byte> r) {
            dispatch(reinterpret_cast<const Header*>(r.data())->op, r.data() + sizeof(Header), f);
        });
    }
    template <class F>
    static void dispatch(Op op, const std::byte* record, F&& f) {
        switch (op) {
#define FE_COMMAND(Name, Fields)                   \
    case Op::Name:                                 \
        f(*reinterpret_cast<const Name*>(record)); \
        break;
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
            default:
                break;
        }
    }

    // Raw form, for capture files (CaptureStream.h): f(bytes) for each record, its header included,
    // exactly as push() laid it out (payload offsets are relative, so the bytes move as they are).
    template <class F>
    void forEachRaw(F&& f) const {
        for (size_t i = 0; i < blocks_.size(); ++i) {
            const Block& b = blocks_[i];
            const std::byte* end = i == current_ ? cur_ : b.data.get() + b.used;
            for (const std::byte* p = b.data.get(); p < end;) {
                const auto* h = reinterpret_cast<const Header*>(p);
                f(std::span<const std::byte>(p, h->size));
                p += h->size;
            }
        }
    }
    // Appends a record given as forEachRaw's bytes (checked by the caller: CaptureStream.cpp).
    void pushRaw(std::span<const std::byte> bytes) {
        std::memcpy(reserve(bytes.size()), bytes.data(), bytes.size());
        ++count_;
    }

    // Secondary lists: a stream shares the streams its ExecuteSecondary records name (by
    // index) with the secondary list that recorded them, which may be executed again (no copy).
    uint32_t adopt(std::shared_ptr<const CommandStream> child) {
        children_.push_back(std::move(child));
        return uint32_t(children_.size() - 1);
    }
    const CommandStream& child(uint32_t index) const { return *children_.at(index); }
    // Lets go of the adopted streams, leaving none.
    std::vector<std::shared_ptr<const CommandStream>> takeChildren() {
        return std::exchange(children_, {});
    }

    size_t commandCount() const { return count_; }
    bool empty() const { return count_ == 0; }
    // Drops the records and adopted streams, keeping the blocks for the next recording.
    void reset() {
        children_.clear();
        for (auto& b : blocks_) b.used = 0;
        current_ = 0;
        count_ = 0;
        cur_ = blocks_.empty() ? nullptr : blocks_[0].data.get();
        end_ = blocks_.empty() ? nullptr : cur_ + blocks_[0].size;
    }

private:
    template <class T>
    static size_t payloadBytes(const T&) {
        return 0;
    }
    template <class T>
    static size_t payloadBytes(const std::span<const T>& data) {
        return align(data.size_bytes());
    }
    static size_t payloadBytes(const char* text) {
        return align(std::strlen(text ? text : "") + 1);
    }
    template <class R, class T, class V>
    void store(const R&, T& field, const V& value) {
        field = value;
    }
    template <class R, class T>
    void store(const R& record, Array<T>& field, const std::span<const T>& data) {
        field = payload(record, data);
    }
    template <class R>
    void store(const R& record, String& field, const char* text) {
        field = payload(record, text ? text : "");
    }
    static constexpr size_t kBlockSize = 64 * 1024;
    static constexpr size_t align(size_t n) { return (n + 7) & ~size_t(7); }
    struct Block {
        std::unique_ptr<std::byte[]> data;
        size_t size = 0, used = 0;
    };
    // The per-command path: a bump of the current block's cursor.
    std::byte* reserve(size_t size) {
        if (size <= size_t(end_ - cur_)) [[likely]] {
            std::byte* at = cur_;
            cur_ += size;
            return at;
        }
        return reserveInNextBlock(size);
    }
    [[gnu::noinline]] std::byte* reserveInNextBlock(size_t size) {
        if (cur_) {
            blocks_[current_].used = size_t(cur_ - blocks_[current_].data.get());
            ++current_;
        }
        // The next kept block, replaced when too small for one large record; or a new one.
        if (current_ == blocks_.size()) blocks_.push_back({});
        Block& b = blocks_[current_];
        if (b.size < size) {
            const size_t n = std::max(kBlockSize, size);
            b.data.reset(new std::byte[n]);
            b.size = n;
        }
        b.used = 0;
        cur_ = b.data.get() + size;
        end_ = b.data.get() + b.size;
        return b.data.get();
    }
    std::vector<Block> blocks_;
    size_t current_ = 0;                         // the block being written
    std::byte *cur_ = nullptr, *end_ = nullptr;  // its free space
    size_t count_ = 0;
    std::byte* payloadAt_ = nullptr;
    std::vector<std::shared_ptr<const CommandStream>> children_;
};

}  // namespace fe::gdi::cmd
