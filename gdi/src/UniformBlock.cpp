#include "fe/gdi/UniformBlock.h"

#include <algorithm>
#include <cstring>

#include "fe/gdi/Device.h"

namespace fe::gdi {

namespace {

const ShaderInterface::Binding& findBlock(const ShaderInterface& shader, std::string_view name,
                                          const uint32_t* slot) {
    std::string blocks;
    for (const ShaderInterface::Binding& b : shader.bindings) {
        if (b.type != BindingType::UniformBuffer && b.type != BindingType::StorageBuffer) continue;
        if (slot ? b.slot == *slot : b.name == name) return b;
        blocks += (blocks.empty() ? "" : ", ") + b.name + " (slot " + std::to_string(b.slot) + ")";
    }
    throw Error("UniformBlock: the " + std::string(shaderStageName(shader.stage)) +
                " shader has no uniform or storage block " +
                (slot ? "at slot " + std::to_string(*slot) : "named '" + std::string(name) + "'") +
                " (its blocks: " + (blocks.empty() ? "none" : blocks) + ")");
}

}  // namespace

UniformBlock::UniformBlock(const ShaderInterface& shader, std::string_view block)
    : UniformBlock(findBlock(shader, block, nullptr)) {}

UniformBlock::UniformBlock(const ShaderInterface& shader, uint32_t slot)
    : UniformBlock(findBlock(shader, {}, &slot)) {}

UniformBlock::UniformBlock(const ShaderInterface::Binding& block)
    : block_(block), bytes_(block.blockBytes, 0) {}

const BlockMember& UniformBlock::member(std::string_view name) const {
    for (const BlockMember& m : block_.members)
        if (m.name == name) return m;
    std::string names;
    for (const BlockMember& m : block_.members) names += (names.empty() ? "" : ", ") + m.name;
    throw Error("UniformBlock '" + block_.name + "': no member '" + std::string(name) +
                "' (members: " + names + ")");
}

void UniformBlock::write(std::string_view name, ScalarKind kind, const uint32_t* words,
                         size_t count, uint32_t element) {
    const BlockMember& m = member(name);
    const std::string what = "UniformBlock '" + block_.name + "' member '" + m.name + "'";
    // Floats go to float members only. Integers cross between int and uint where the value is
    // the same in both: SPIR-V stores a block's bool as a uint, which a port sets with 0 or 1.
    const bool integers =
        (m.kind == ScalarKind::Int || m.kind == ScalarKind::Uint || m.kind == ScalarKind::Other) &&
        kind != ScalarKind::Float;
    if (m.kind != kind && !integers)
        throw Error(what + " is " +
                    (m.kind == ScalarKind::Other ? std::string("bool") : scalarKindName(m.kind)) +
                    ", given " + scalarKindName(kind) + " values");
    if (m.kind != kind && integers)
        for (size_t i = 0; i < count; ++i)
            if (words[i] & 0x80000000u)
                throw Error(what + " is " + scalarKindName(m.kind) + ": the " +
                            scalarKindName(kind) + " value " +
                            (kind == ScalarKind::Int ? std::to_string(int32_t(words[i]))
                                                     : std::to_string(words[i])) +
                            " is not the same there");
    const uint32_t components = m.vectorSize * m.columns;
    if (count != components)
        throw Error(what + " takes " + std::to_string(components) + " value(s), given " +
                    std::to_string(count));
    const uint32_t elements = m.arrayCount ? m.arrayCount : (m.arrayStride ? UINT32_MAX : 1);
    if (element >= elements)
        throw Error(what + " has " + std::to_string(elements) + " element(s); element " +
                    std::to_string(element) + " is past its end");
    const uint64_t base = uint64_t(m.offset) + uint64_t(element) * m.arrayStride;
    for (uint32_t c = 0; c < m.columns; ++c)
        for (uint32_t r = 0; r < m.vectorSize; ++r) {
            // Column-major values; row_major lays each row out contiguously instead.
            const uint64_t at = m.columns == 1 ? base + 4ull * r
                                : m.rowMajor   ? base + uint64_t(r) * m.matrixStride + 4ull * c
                                               : base + uint64_t(c) * m.matrixStride + 4ull * r;
            if (at + 4 > bytes_.size()) {
                if (m.arrayCount != 0)
                    throw Error(what + ": element " + std::to_string(element) +
                                " lies past the block's " + std::to_string(bytes_.size()) +
                                " bytes");
                bytes_.resize(size_t(at + 4), 0);  // a runtime-sized array grows
            }
            std::memcpy(bytes_.data() + at, &words[c * m.vectorSize + r], 4);
        }
}

void UniformBlock::set(std::string_view member, std::span<const float> values, uint32_t element) {
    write(member, ScalarKind::Float, reinterpret_cast<const uint32_t*>(values.data()),
          values.size(), element);
}

void UniformBlock::set(std::string_view member, std::span<const int32_t> values, uint32_t element) {
    write(member, ScalarKind::Int, reinterpret_cast<const uint32_t*>(values.data()), values.size(),
          element);
}

void UniformBlock::set(std::string_view member, std::span<const uint32_t> values,
                       uint32_t element) {
    write(member, ScalarKind::Uint, values.data(), values.size(), element);
}

}  // namespace fe::gdi
