// Both encodings of a graphics stage go through SPIRV-Tools' performance passes, at build time
// (cmake/fe-spirv-embed.sh) and at run time (compileShader), and reflect the same bindings and
// specialization constants, so that a pipeline is checked alike on every backend. Compute stages
// are left as glslang writes them (fe-spirv-embed.sh says why).
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <string>

#include "fe/gdi/ShaderCompiler.h"
#include "fe/gdi/ShaderReflection.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe;
using namespace fe::gdi;

namespace {

// OpFunctionCall instructions in a module: glslang writes one per helper called; the optimizer
// inlines them all.
size_t functionCalls(std::span<const uint32_t> spirv) {
    size_t calls = 0;
    for (size_t i = 5; i < spirv.size() && (spirv[i] >> 16) != 0; i += spirv[i] >> 16)
        if ((spirv[i] & 0xffffu) == 57u) ++calls;
    return calls;
}

// A helper function, a block, a texture, a specialization constant used and one not.
constexpr const char* kFragment = R"(#version 450
layout(constant_id = 3) const float kScale = 2.0;
layout(constant_id = 9) const float kUnused = 5.0;
layout(binding = 1, std140) uniform Tint { vec4 tint; };
layout(binding = 4) uniform sampler2D image;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 colour;
vec4 shade(vec2 p) { return texture(image, p) * tint * kScale; }
void main() { colour = shade(uv) + shade(uv.yx); }
)";

constexpr const char* kCompute = R"(#version 450
layout(local_size_x = 8) in;
layout(binding = 2, std430) buffer Data { float values[]; };
float twice(float v) { return 2.0 * v; }
void main() { values[gl_GlobalInvocationID.x] = twice(values[gl_GlobalInvocationID.x]); }
)";

// The Vulkan encoding's interface against the GL one's, whose FE_CONSTANTS block is a uniform
// block at slot 64 where Vulkan's is a push-constant block (fe_common.glsl).
void expectSameInterface(const ShaderInterface& vk, ShaderInterface gl) {
    if (vk.pushConstantBytes > 0)
        std::erase_if(gl.bindings, [](const ShaderInterface::Binding& b) { return b.slot == 64; });
    const ShaderInterface& a = vk;
    const ShaderInterface& b = gl;
    ASSERT_EQ(a.bindings.size(), b.bindings.size());
    for (size_t i = 0; i < a.bindings.size(); ++i) {
        EXPECT_EQ(a.bindings[i].slot, b.bindings[i].slot);
        EXPECT_EQ(a.bindings[i].type, b.bindings[i].type);
        EXPECT_EQ(a.bindings[i].dimension, b.bindings[i].dimension);
        EXPECT_EQ(a.bindings[i].members.size(), b.bindings[i].members.size());
    }
    ASSERT_EQ(a.specConstants.size(), b.specConstants.size());
    for (size_t i = 0; i < a.specConstants.size(); ++i)
        EXPECT_EQ(a.specConstants[i].id, b.specConstants[i].id);
}

}  // namespace

TEST(ShaderOptimization, RunTimeGraphicsStagesAreOptimizedWithTheirInterfaceKept) {
    const ShaderBinary bin =
        compileShader({.stage = ShaderStage::Fragment, .text = kFragment, .name = "opt.frag"});
    EXPECT_EQ(functionCalls(bin.vulkan), 0u);  // inlined
    EXPECT_EQ(functionCalls(bin.opengl), 0u);
    const ShaderInterface vk =
        reflectShader(bin.vulkan, ShaderStage::Fragment, "main", "opt.frag", SpirvRules::Vulkan12);
    const ShaderInterface gl =
        reflectShader(bin.opengl, ShaderStage::Fragment, "main", "opt.frag", SpirvRules::OpenGL45);
    expectSameInterface(vk, gl);
    EXPECT_EQ(vk.bindings.size(), 2u);
    EXPECT_EQ(vk.specConstants.size(), 2u);  // the unused one too
}

TEST(ShaderOptimization, RunTimeComputeStagesAreLeftAsGlslangWritesThem) {
    const ShaderBinary bin =
        compileShader({.stage = ShaderStage::Compute, .text = kCompute, .name = "opt.comp"});
    EXPECT_EQ(functionCalls(bin.vulkan), 1u);
    EXPECT_EQ(functionCalls(bin.opengl), 1u);
}

namespace {
ShaderStage stageOfPath(std::string path) {
    path = path.substr(0, path.find(':'));
    if (path.ends_with(".hlsl")) path.resize(path.size() - 5);
    const std::string ext = path.substr(path.rfind('.') + 1);
    if (ext == "vert") return ShaderStage::Vertex;
    if (ext == "frag") return ShaderStage::Fragment;
    if (ext == "geom") return ShaderStage::Geometry;
    if (ext == "tesc") return ShaderStage::TessControl;
    if (ext == "tese") return ShaderStage::TessEvaluation;
    return ShaderStage::Compute;
}
}  // namespace

// Every shader built into this program: the two encodings reflect the same interface.
TEST(ShaderOptimization, BuiltInShadersReflectTheSameInterfaceInBothEncodings) {
    size_t checked = 0;
    for (std::string_view name : shaders::names()) {
        const std::string path(name);
        SCOPED_TRACE(path);
        const ShaderBinary& bin = shaders::find(path);
        const ShaderStage stage = stageOfPath(path);
        expectSameInterface(reflectShader(bin.vulkan, stage, "main", path, SpirvRules::Vulkan12),
                            reflectShader(bin.opengl, stage, "main", path, SpirvRules::OpenGL45));
        ++checked;
    }
    EXPECT_GT(checked, 200u);
}

TEST(ShaderOptimization, BuildTimeGraphicsStagesAreOptimizedComputeStagesNot) {
    for (const char* path : {"scene/forward_plus.frag", "scene/gbuffer.frag"}) {
        SCOPED_TRACE(path);
        EXPECT_EQ(functionCalls(shaders::find(path).vulkan), 0u);  // glslang's calls helpers
        EXPECT_EQ(functionCalls(shaders::find(path).opengl), 0u);
    }
    const ShaderBinary& culling = shaders::find("scene/tile_light_culling.comp");
    EXPECT_GT(functionCalls(culling.vulkan), 0u);
    EXPECT_GT(functionCalls(culling.opengl), 0u);
}
