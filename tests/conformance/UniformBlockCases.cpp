// Conformance case for uniform blocks written by name: the reflection's block members
// (ShaderInterface::Binding::members) and gdi::UniformBlock, on every backend.
#include "CaseSupport.h"
#include "fe/gdi/UniformBlock.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// A std140 block with every member a C++ struct would pad by hand (vec3 after a float, arrays
// of vec2 and of structs, mat3, a row-major mat2x3, int, uint, bool, ivec2), written by name
// from the fragment shader's reflection; the shader turns each group of members it reads back
// into a green column. Then the helper's mistakes, the same Error everywhere.
std::vector<CaseImage> uniformBlockLayout(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/fullscreen.vert");
    const ShaderHandle fs =
        registryShader(o, ShaderStage::Fragment, "conformance/uniform_block_layout.frag");
    const ShaderInterface& reflected = d.shaderInterface(fs);
    UniformBlock block(reflected, "Material");
    std::string layout;
    for (const BlockMember& m : block.block().members)
        layout += " " + m.name + "@" + std::to_string(m.offset);
    FE_CONFORMANCE_CHECK(block.bytes().size() == 264,
                         ("the block's std140 size is 264 bytes (ivec2 counts at 256), got " +
                          std::to_string(block.bytes().size()) + ":" + layout)
                             .c_str());
    FE_CONFORMANCE_CHECK(block.member("tint").offset == 16 && block.member("rotation").offset == 80,
                         "a vec3 after a float starts at 16; mat3 at 80");
    FE_CONFORMANCE_CHECK(
        block.member("offsets").arrayStride == 16 && block.member("offsets").arrayCount == 3,
        "vec2 offsets[3]: std140's stride of 16");
    FE_CONFORMANCE_CHECK(block.member("lights[1].colour").offset == 176 &&
                             block.member("skew").rowMajor &&
                             block.member("skew").matrixStride == 16,
                         "structs by element, row-major matrices by row");
    block.set("scale", 0.25f);
    block.set("tint", {0.5f, 0.75f, 1.0f});
    block.set("offsets", {1.0f, 0.0f}, 0);
    block.set("offsets", {0.0f, -2.0f}, 1);
    block.set("offsets", {3.5f, 0.0f}, 2);
    block.set("rotation", {1, 2, 3, 4, 5, 6, 7, 8, 9});  // column by column
    block.set("mode", -7);
    block.set("flags", 0x80000001u);
    block.set("enabled", 1);
    block.set("lights[0].colour", {0.1f, 0.2f, 0.3f});
    block.set("lights[0].weight", 0.5f);
    block.set("lights[1].colour", {0.9f, 0.8f, 0.7f});
    block.set("lights[1].direction", {0.0f, -1.0f});
    block.set("skew", {1, 3, 5, 2, 4, 6});  // columns (1 3 5) and (2 4 6): rows (1 2) (3 4) (5 6)
    const int32_t counts[] = {3, -4};
    block.set("counts", std::span<const int32_t>(counts));

    const BufferHandle ubo = o.add(d.createBuffer(
        {.size = block.bytes().size(), .usage = BufferUsage::Uniform, .debugName = "Material"},
        block.bytes()));
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}));
    const TextureHandle target = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    expectError(
        [&] {
            block.set("tnit", {0.0f, 0.0f, 0.0f});
        },
        "UniformBlock 'Material': no member 'tnit' (members: scale, tint, offsets,");
    expectError([&] { block.set("mode", 1.0f); },
                "UniformBlock 'Material' member 'mode' is int, given float values");
    expectError([&] { block.set("flags", -1); },
                "UniformBlock 'Material' member 'flags' is uint: the int value -1 is not the same "
                "there");
    expectError(
        [&] {
            block.set("tint", {1.0f, 2.0f});
        },
        "UniformBlock 'Material' member 'tint' takes 3 value(s), given 2");
    expectError(
        [&] {
            block.set("offsets", {1.0f, 2.0f}, 3);
        },
        "member 'offsets' has 3 element(s); element 3 is past its end");
    expectError([&] { UniformBlock(reflected, "Missing"); },
                "the fragment shader has no uniform or storage block named 'Missing' (its blocks: "
                "Material (slot 0))");
    return {
        exact("every member in place", d.readTexture(target), solid(Format::RGBA8, {0, 1, 0, 1}))};
}

}  // namespace

std::vector<Case> uniformBlockCases() { return {{"uniform_block_layout", uniformBlockLayout}}; }

}  // namespace fe::conformance
