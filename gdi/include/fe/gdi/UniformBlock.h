// A uniform (or storage) block's bytes written by member name, as a port from OpenGL sets
// uniforms (glUniform*): the layout comes from the shader's reflection (BlockMember), so no C++
// struct is padded by hand to std140.
//   const ShaderInterface& vs = device->shaderInterface(vertexShader);
//   UniformBlock frame(vs, "Frame");                      // the block named Frame (or its slot)
//   frame.set("viewProjection", matrix);                  // 16 floats, column by column
//   frame.set("lights[1].colour", {1.0f, 0.5f, 0.0f});    // a member of an array of structs
//   frame.set("tint", {0.5f, 0.5f, 0.5f, 1.0f}, 2);       // element 2 of an array of vec4
//   device->writeBuffer(buffer, 0, frame.bytes());
// Mistakes are gdi::Errors naming the block and the member: no such member (the members are
// listed), a value of another kind (float to an int), too many or too few values, an element past
// the array's end.
#pragma once
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fe/gdi/ShaderReflection.h"

namespace fe::gdi {

class UniformBlock {
public:
    // The uniform or storage block named `block` (its block name, as in the shader), or bound at
    // `slot`, of a shader's interface; its bytes start zeroed.
    UniformBlock(const ShaderInterface& shader, std::string_view block);
    UniformBlock(const ShaderInterface& shader, uint32_t slot);
    explicit UniformBlock(const ShaderInterface::Binding& block);

    // Writes a float, vector or matrix member (matrices column by column, as GLSL and glm store
    // them; written row-major where the shader says row_major), at array element `element`.
    // values.size() must be the member's components (vectorSize x columns).
    void set(std::string_view member, std::span<const float> values, uint32_t element = 0);
    void set(std::string_view member, std::initializer_list<float> values, uint32_t element = 0) {
        set(member, std::span<const float>(values.begin(), values.size()), element);
    }
    void set(std::string_view member, float value, uint32_t element = 0) {
        set(member, std::span<const float>(&value, 1), element);
    }
    // Integer, unsigned and bool members. An int member takes uint values and a uint member int
    // values when the value is the same in both (a block's bool is a uint in SPIR-V: 0 or 1).
    void set(std::string_view member, std::span<const int32_t> values, uint32_t element = 0);
    void set(std::string_view member, std::span<const uint32_t> values, uint32_t element = 0);
    void set(std::string_view member, int32_t value, uint32_t element = 0) {
        set(member, std::span<const int32_t>(&value, 1), element);
    }
    void set(std::string_view member, uint32_t value, uint32_t element = 0) {
        set(member, std::span<const uint32_t>(&value, 1), element);
    }

    const BlockMember& member(std::string_view name) const;  // throws Error listing the names
    // The block's bytes, for writeBuffer or createBuffer (a runtime-sized array's as far as set).
    ByteSpan bytes() const { return std::as_bytes(std::span(bytes_)); }
    const ShaderInterface::Binding& block() const { return block_; }

private:
    void write(std::string_view member, ScalarKind kind, const uint32_t* words, size_t count,
               uint32_t element);
    ShaderInterface::Binding block_;
    std::vector<uint8_t> bytes_;
};

}  // namespace fe::gdi
