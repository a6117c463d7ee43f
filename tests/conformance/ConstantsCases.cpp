// Conformance cases for per-draw constants, specialization constants and the pipeline cache
// file, with analytic expectations and the same errors on every backend.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "CaseSupport.h"
#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/CommandRecorder.h"
#include "fe/gdi/PipelineCacheFile.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// 64 quads of 8x8 pixels, one draw each, placed and coloured only by per-draw constants read
// in both stages. Even draws write all 128 bytes; odd draws write only the first 32 (rect and
// colour), so their tail is the previous draw's: values persist, also across a setPipeline in
// the middle. Then a compute pipeline reads 128 bytes set before it was bound.
std::vector<CaseImage> constantsPerDraw(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert");
    const ShaderHandle fs =
        registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag");
    const ShaderHandle cs =
        registryShader(o, ShaderStage::Compute, "conformance/constants_copy.comp");
    const GraphicsPipelineDesc quadDesc{.vertexShader = vs,
                                        .fragmentShader = fs,
                                        .topology = PrimitiveTopology::TriangleStrip,
                                        .colorFormats = {Format::RGBA8},
                                        .debugName = "constants A"};
    GraphicsPipelineDesc otherDesc = quadDesc;
    otherDesc.blend = {
        {.enable = true}};  // One * src + Zero * dst: the same colours, another pipeline
    otherDesc.debugName = "constants B";
    const PipelineHandle a = o.add(d.createGraphicsPipeline(quadDesc));
    const PipelineHandle b = o.add(d.createGraphicsPipeline(otherDesc));
    const PipelineHandle copy =
        o.add(d.createComputePipeline({.computeShader = cs, .debugName = "constants copy"}));
    const BufferHandle out =
        o.add(d.createBuffer({.size = kMaxConstantBytes, .usage = BufferUsage::Storage}));
    const TextureHandle target = caseTarget(o);

    auto blueOf = [](uint32_t i) { return (i % 2 ? i - 1 : i) % 4 == 0 ? 128.0f : 64.0f; };
    auto cell = [](uint32_t i) {
        QuadConstants q{};
        const float x0 = -1.0f + 0.25f * float(i % 8), y0 = -1.0f + 0.25f * float(i / 8);
        q.rect[0] = x0, q.rect[1] = y0, q.rect[2] = x0 + 0.25f, q.rect[3] = y0 + 0.25f;
        q.color[0] = float(32 * (i % 8)) / 255.0f, q.color[1] = float(32 * (i / 8)) / 255.0f,
        q.color[3] = 1.0f;
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
        if (i == 0) cmd->setPipeline(a);   // constants set before the pipeline are read too
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
    FE_CONFORMANCE_CHECK(
        std::memcmp(got.data(), words.data(), kMaxConstantBytes) == 0,
        "the compute shader reads the 128 bytes of constants set before its pipeline");
    const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
        const uint32_t i = (y / 8) * 8 + x / 8;
        return {float(32 * (i % 8)) / 255.0f, float(32 * (i / 8)) / 255.0f, blueOf(i) / 255.0f,
                1.0f};
    });
    return {drawn8("64 quads placed and coloured by constants", d.readTexture(target), expected)};
}

// Mistakes with constants: a misaligned or oversized write, a block over 128 bytes.
std::vector<CaseImage> constantsErrors(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert");
    const ShaderHandle big =
        registryShader(o, ShaderStage::Fragment, "conformance/constants_too_big.frag");
    expectError(
        [&] {
            d.destroy(d.createGraphicsPipeline({.vertexShader = vs,
                                                .fragmentShader = big,
                                                .colorFormats = {Format::RGBA8},
                                                .debugName = "big"}));
        },
        "the fragment shader's constants block is 144 bytes; at most 128");
    auto cmd = d.createCommandList();
    const uint32_t four[4] = {1, 2, 3, 4};
    expectError([&] { cmd->setConstants(2, bytesOf(four)); },
                "setConstants: offset 2 and size 16 must be multiples of 4");
    expectError([&] { cmd->setConstants(120, bytesOf(four)); }, "offset + size at most 128");
    expectError([&] { cmd->setConstants(0, ByteSpan{}); }, "the size not 0");
    return {};
}

// One SPIR-V pair, four pipelines: a quadrant chosen by an int constant in the vertex shader, a
// colour from float, uint, bool and int constants in the fragment shader (one pipeline keeps
// every default), and a compute shader's uint constant, default and specialized.
using S = SpecializationConstant;
const std::array<std::vector<S>, 4> kQuadrantValues = {{
    {},
    {S::of(4, int32_t(1)), S::of(0, 1.0f), S::of(1, uint32_t(128)), S::of(2, true)},
    {S::of(4, int32_t(2)), S::of(0, 0.5f), S::of(3, int32_t(2))},
    {S::of(4, int32_t(3)), S::of(1, uint32_t(255)), S::of(2, false), S::of(3, int32_t(3))},
}};
const std::array<Texel, 4> kQuadrantColors = {
    {{0, 0, 0, 1}, {1, 128 / 255.0f, 1, 1}, {0.5f, 0, 0, 0.5f}, {0, 1, 0, 0.75f}}};

// Four pipelines of one SPIR-V pair, one per kQuadrantValues, each drawing its quadrant.
TextureHandle drawSpecializedQuadrants(Device& d, DeviceObjects& o, CommandList& cmd) {
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/specialized_quad.vert");
    const ShaderHandle fs =
        registryShader(o, ShaderStage::Fragment, "conformance/specialized_color.frag");
    const TextureHandle target = caseTarget(o);
    cmd.beginRenderPass({.colors = {{.texture = target, .clear = {0.25f, 0.25f, 0.25f, 0.25f}}}});
    for (const auto& v : kQuadrantValues) {
        cmd.setPipeline(
            o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = fs,
                                            .topology = PrimitiveTopology::TriangleStrip,
                                            .colorFormats = {Format::RGBA8},
                                            .specialization = v,
                                            .debugName = "specialized"})));
        cmd.draw(4);
    }
    cmd.endRenderPass();
    return target;
}
Image quadrantsExpected() {
    return expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) {
        return kQuadrantColors[(y / 32) * 2 + x / 32];
    });
}

std::vector<CaseImage> specialization(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/specialized_quad.vert");
    const ShaderHandle fs =
        registryShader(o, ShaderStage::Fragment, "conformance/specialized_color.frag");
    const ShaderHandle cs =
        registryShader(o, ShaderStage::Compute, "conformance/specialized_value.comp");
    auto cmd = d.createCommandList();
    const TextureHandle target = drawSpecializedQuadrants(d, o, *cmd);
    const std::array<BufferHandle, 2> out = {
        o.add(d.createBuffer({.size = 4, .usage = BufferUsage::Storage})),
        o.add(d.createBuffer({.size = 4, .usage = BufferUsage::Storage}))};
    const std::array<PipelineHandle, 2> compute = {
        o.add(d.createComputePipeline({.computeShader = cs, .debugName = "default"})),
        o.add(d.createComputePipeline(
            {.computeShader = cs, .specialization = {S::of(0, uint32_t(42))}, .debugName = "42"}))};
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
        FE_CONFORMANCE_CHECK(v == (i == 0 ? 7u : 42u),
                             "the compute constant is its default (7), then 42");
    }

    // Mistakes, refused at creation with the same message everywhere.
    auto create = [&](std::vector<S> v) {
        return [&d, vs, fs, v] {
            d.destroy(d.createGraphicsPipeline({.vertexShader = vs,
                                                .fragmentShader = fs,
                                                .colorFormats = {Format::RGBA8},
                                                .specialization = v,
                                                .debugName = "bad"}));
        };
    };
    expectError(create({S::of(9, 1.0f)}),
                "specialization constant 9 is not declared by its shaders");
    expectError(create({{.id = 2, .bits = 2}}),
                "specialization constant 2 ('kBlue') is a bool: its value is 0 or 1, not 2");
    expectError(create({S::of(0, 1.0f), S::of(0, 0.0f)}),
                "specialization constant 0 is given twice");
    return {drawn8("quadrants from specialization constants", d.readTexture(target),
                   quadrantsExpected())};
}

std::vector<uint8_t> readFile(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
void writeFile(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The pipeline cache file: saved with this device's identity, loaded back (pipelines made from
// it draw what compiled ones draw), and a damaged, truncated or foreign file ignored with a
// warning naming why, the device working on.
std::vector<CaseImage> pipelineCacheRoundtrip(Device& d) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("fe-pipeline-cache-" + d.info().backend + "-" + std::to_string(::getpid()) + ".bin");
    struct Detach {  // the device must not save into the temporary file later
        Device& d;
        std::filesystem::path p;
        ~Detach() {
            d.openPipelineCache("");
            std::filesystem::remove(p);
        }
    } detach{d, path};
    std::filesystem::remove(path);
    PipelineCacheStats stats = d.openPipelineCache(path.string());
    FE_CONFORMANCE_CHECK(!stats.loaded && stats.path == path.string(),
                         "no file yet: nothing loaded");
    std::vector<CaseImage> images;
    auto drawFrame = [&](const std::string& name) {
        DeviceObjects o(d);
        auto cmd = d.createCommandList();
        const TextureHandle target = drawSpecializedQuadrants(d, o, *cmd);
        d.wait(d.submit(*cmd));
        images.push_back(drawn8(name, d.readTexture(target), quadrantsExpected()));
    };
    drawFrame("compiled");
    d.savePipelineCache();
    const std::vector<uint8_t> file = readFile(path);
    const PipelineCacheLoad parsed = parsePipelineCache(file, pipelineCacheIdentity(d.info()));
    FE_CONFORMANCE_CHECK(parsed.warning.empty(),
                         ("the saved file is this device's: " + parsed.warning).c_str());

    stats = d.openPipelineCache(path.string());
    FE_CONFORMANCE_CHECK(stats.loaded && stats.warning.find("ignored") == std::string::npos,
                         ("the saved file loads back: " + stats.warning).c_str());
    drawFrame("from the cache");
    const PipelineCacheStats used = d.pipelineCacheStats();
    FE_CONFORMANCE_CHECK(used.hits + used.misses <= 4,
                         "four pipelines made: each a hit or a miss (or unknown)");

    std::vector<uint8_t> damaged = file;
    damaged[damaged.size() - 1] ^= 0xff;
    std::vector<uint8_t> truncated(file.begin(), file.begin() + std::ptrdiff_t(file.size() / 2));
    const std::vector<uint8_t> foreign =
        encodePipelineCache("another|device", std::span(parsed.payload));
    const std::array<std::pair<const std::vector<uint8_t>*, const char*>, 3> bad = {
        {{&damaged, "checksum mismatch"},
         {&truncated, "truncated"},
         {&foreign, "made for another device"}}};
    for (const auto& [bytes, why] : bad) {
        writeFile(path, *bytes);
        stats = d.openPipelineCache(path.string());
        FE_CONFORMANCE_CHECK(!stats.loaded && stats.warning.find(why) != std::string::npos,
                             ("expected the file ignored with \"" + std::string(why) +
                              "\", got \"" + stats.warning + "\"")
                                 .c_str());
        drawFrame(std::string("after a file ignored: ") + why);
    }
    // A path that is not a file (a directory) is an Error, the same on every backend, and the
    // cache stays where it was (before, the read threw std::ios_base::failure out of the device).
    std::string refused;
    try {
        d.openPipelineCache(std::filesystem::temp_directory_path().string());
    } catch (const Error& e) {
        refused = e.what();
    }
    FE_CONFORMANCE_CHECK(
        refused.find("not a regular file") != std::string::npos,
        ("a directory as the cache path: expected an Error, got \"" + refused + "\"").c_str());
    FE_CONFORMANCE_CHECK(d.pipelineCacheStats().path == path.string(),
                         "the refused path did not replace the cache's");
    return images;
}

}  // namespace

std::vector<Case> constantsCases() {
    return {
        {"constants_per_draw", constantsPerDraw},
        {"constants_errors", constantsErrors},
        {"specialization", specialization},
        {"pipeline_cache_roundtrip", pipelineCacheRoundtrip},
    };
}

}  // namespace fe::conformance
