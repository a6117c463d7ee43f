// Conformance cases for the vocabulary a port needs (issue 26): per-draw constants and
// specialization constants, with analytic expectations and the same errors on every backend.
#include <cstring>

#include "CaseSupport.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// The 128-byte block of constants_quad.vert/.frag.
struct QuadConstants {
    float rect[4];   // x0, y0, x1, y1 in clip space
    float color[4];
    float unused[20];
    float tail[4];   // added to the colour: proves the last bytes arrive
};
static_assert(sizeof(QuadConstants) == kMaxConstantBytes);

// 64 quads of 8x8 pixels, one draw each, placed and coloured only by per-draw constants read
// in both stages. Even draws write all 128 bytes; odd draws write only the first 32 (rect and
// colour), so their tail is the previous draw's: values persist, also across a setPipeline in
// the middle. Then a compute pipeline reads 128 bytes set before it was bound.
std::vector<CaseImage> constantsPerDraw(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert");
    const ShaderHandle fs = registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag");
    const ShaderHandle cs = registryShader(o, ShaderStage::Compute, "conformance/constants_copy.comp");
    const GraphicsPipelineDesc quadDesc{.vertexShader = vs, .fragmentShader = fs,
                                        .topology = PrimitiveTopology::TriangleStrip, .colorFormats = {Format::RGBA8},
                                        .debugName = "constants A"};
    GraphicsPipelineDesc otherDesc = quadDesc;
    otherDesc.blend = {{.enable = true}};  // One * src + Zero * dst: the same colours, another pipeline
    otherDesc.debugName = "constants B";
    const PipelineHandle a = o.add(d.createGraphicsPipeline(quadDesc));
    const PipelineHandle b = o.add(d.createGraphicsPipeline(otherDesc));
    const PipelineHandle copy = o.add(d.createComputePipeline({.computeShader = cs, .debugName = "constants copy"}));
    const BufferHandle out = o.add(d.createBuffer({.size = kMaxConstantBytes, .usage = BufferUsage::Storage}));
    const TextureHandle target = caseTarget(o);

    auto blueOf = [](uint32_t i) { return (i % 2 ? i - 1 : i) % 4 == 0 ? 128.0f : 64.0f; };
    auto cell = [](uint32_t i) {
        QuadConstants q{};
        const float x0 = -1.0f + 0.25f * float(i % 8), y0 = -1.0f + 0.25f * float(i / 8);
        q.rect[0] = x0, q.rect[1] = y0, q.rect[2] = x0 + 0.25f, q.rect[3] = y0 + 0.25f;
        q.color[0] = float(32 * (i % 8)) / 255.0f, q.color[1] = float(32 * (i / 8)) / 255.0f, q.color[3] = 1.0f;
        return q;
    };
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}, .debugName = "constants"});
    for (uint32_t i = 0; i < 64; ++i) {
        QuadConstants q = cell(i);
        if (i % 2 == 0) {
            q.tail[2] = blueOf(i) / 255.0f;
            cmd->setConstants(q);
        } else {
            cmd->setConstants(0, std::as_bytes(std::span(&q.rect[0], 8)));  // rect and colour only
        }
        if (i == 0) cmd->setPipeline(a);  // constants set before the pipeline are read too
        if (i == 33) cmd->setPipeline(b);  // after this draw's partial write: the tail persists
        cmd->draw(4);
    }
    cmd->endRenderPass();
    std::array<uint32_t, 32> words;
    for (uint32_t k = 0; k < 32; ++k) words[k] = 0x01010101u * k + 5;
    cmd->setConstants(words);
    cmd->setPipeline(copy);
    cmd->setStorageBuffer(0, out);
    cmd->dispatch(1);
    d.wait(d.submit(*cmd));

    const std::vector<uint8_t> got = d.readBuffer(out, 0, kMaxConstantBytes);
    FE_CONFORMANCE_CHECK(std::memcmp(got.data(), words.data(), kMaxConstantBytes) == 0,
                         "the compute shader reads the 128 bytes of constants set before its pipeline");
    const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
        const uint32_t i = (y / 8) * 8 + x / 8;
        return {float(32 * (i % 8)) / 255.0f, float(32 * (i / 8)) / 255.0f, blueOf(i) / 255.0f, 1.0f};
    });
    return {drawn8("64 quads placed and coloured by constants", d.readTexture(target), expected)};
}

// Messages that must be the same gdi::Error on every backend.
void expectError(const std::function<void()>& fn, const std::string& text) {
    std::string got = "(no error)";
    try {
        fn();
    } catch (const Error& e) {
        got = e.what();
    }
    FE_CONFORMANCE_CHECK(got.find(text) != std::string::npos, ("expected \"" + text + "\", got \"" + got + "\"").c_str());
}

// Mistakes with constants: a misaligned or oversized write, a block over 128 bytes.
std::vector<CaseImage> constantsErrors(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert");
    const ShaderHandle big = registryShader(o, ShaderStage::Fragment, "conformance/constants_too_big.frag");
    expectError([&] { d.destroy(d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = big,
                                                          .colorFormats = {Format::RGBA8}, .debugName = "big"})); },
                "the fragment shader's constants block is 144 bytes; at most 128");
    auto cmd = d.createCommandList();
    const uint32_t four[4] = {1, 2, 3, 4};
    expectError([&] { cmd->setConstants(2, bytesOf(four)); }, "setConstants: offset 2 and size 16 must be multiples of 4");
    expectError([&] { cmd->setConstants(120, bytesOf(four)); }, "offset + size at most 128");
    expectError([&] { cmd->setConstants(0, ByteSpan{}); }, "the size not 0");
    return {};
}

// One SPIR-V pair, four pipelines: a quadrant chosen by an int constant in the vertex shader, a
// colour from float, uint, bool and int constants in the fragment shader (one pipeline keeps
// every default), and a compute shader's uint constant, default and specialized.
std::vector<CaseImage> specialization(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/specialized_quad.vert");
    const ShaderHandle fs = registryShader(o, ShaderStage::Fragment, "conformance/specialized_color.frag");
    const ShaderHandle cs = registryShader(o, ShaderStage::Compute, "conformance/specialized_value.comp");
    using S = SpecializationConstant;
    const std::array<std::vector<S>, 4> values = {{
        {},
        {S::of(4, int32_t(1)), S::of(0, 1.0f), S::of(1, uint32_t(128)), S::of(2, true)},
        {S::of(4, int32_t(2)), S::of(0, 0.5f), S::of(3, int32_t(2))},
        {S::of(4, int32_t(3)), S::of(1, uint32_t(255)), S::of(2, false), S::of(3, int32_t(3))},
    }};
    const std::array<Texel, 4> colors = {{{0, 0, 0, 1}, {1, 128 / 255.0f, 1, 1}, {0.5f, 0, 0, 0.5f}, {0, 1, 0, 0.75f}}};
    const TextureHandle target = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0.25f, 0.25f, 0.25f, 0.25f}}}});
    for (const auto& v : values) {
        cmd->setPipeline(o.add(d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs,
                                                         .topology = PrimitiveTopology::TriangleStrip,
                                                         .colorFormats = {Format::RGBA8}, .specialization = v,
                                                         .debugName = "specialized"})));
        cmd->draw(4);
    }
    cmd->endRenderPass();
    const std::array<BufferHandle, 2> out = {o.add(d.createBuffer({.size = 4, .usage = BufferUsage::Storage})),
                                             o.add(d.createBuffer({.size = 4, .usage = BufferUsage::Storage}))};
    const std::array<PipelineHandle, 2> compute = {
        o.add(d.createComputePipeline({.computeShader = cs, .debugName = "default"})),
        o.add(d.createComputePipeline({.computeShader = cs, .specialization = {S::of(0, uint32_t(42))}, .debugName = "42"}))};
    for (size_t i = 0; i < 2; ++i) {
        cmd->setPipeline(compute[i]);
        cmd->setStorageBuffer(0, out[i]);
        cmd->dispatch(1);
    }
    d.wait(d.submit(*cmd));
    for (size_t i = 0; i < 2; ++i) {
        const std::vector<uint8_t> bytes = d.readBuffer(out[i], 0, 4);
        uint32_t v = 0;
        std::memcpy(&v, bytes.data(), 4);
        FE_CONFORMANCE_CHECK(v == (i == 0 ? 7u : 42u), "the compute constant is its default (7), then 42");
    }

    // Mistakes, refused at creation with the same message everywhere.
    auto create = [&](std::vector<S> v) {
        return [&d, vs, fs, v] {
            d.destroy(d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                                .specialization = v, .debugName = "bad"}));
        };
    };
    expectError(create({S::of(9, 1.0f)}), "specialization constant 9 is not declared by its shaders");
    expectError(create({{.id = 2, .bits = 2}}), "specialization constant 2 ('kBlue') is a bool: its value is 0 or 1, not 2");
    expectError(create({S::of(0, 1.0f), S::of(0, 0.0f)}), "specialization constant 0 is given twice");
    return {drawn8("quadrants from specialization constants", d.readTexture(target),
                   expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) { return colors[(y / 32) * 2 + x / 32]; }))};
}

}  // namespace

std::vector<Case> portCases() {
    return {
        {"constants_per_draw", constantsPerDraw},
        {"constants_errors", constantsErrors},
        {"specialization", specialization},
    };
}

}  // namespace fe::conformance
