// Example (d): what a port of a Vulkan or GL sample uses, from the installed package: per-draw
// constants and a specialization constant in shaders of its own (fe_common.glsl's FE_CONSTANTS),
// a texture view drawn into (one layer of an array), a region read back with a row pitch, an
// occlusion query, two lists recorded on two threads and submitted together, shaders given as
// GLSL source (compiled on two threads) with a uniform block set by member name, and six
// mistakes made on purpose that must be the same gdi::Error on every backend
// (tests/package_consumer.sh compares the output).
//   fe_example_ported [--backend NAME] [--validation]
// Prints the query count, the texels read back and the mistakes; exit 1 when something differs
// from what the program expects.
#include <array>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/ShaderRegistry.h"
#include "fe/gdi/UniformBlock.h"

using namespace fe::gdi;

namespace {
struct Quad {
    float rect[4];
    float color[4];
};
bool reported(const char* what, const std::function<void()>& mistake) {
    try {
        mistake();
    } catch (const Error& e) {
        std::printf("error: %s: %s\n", what, e.what());
        return true;
    }
    std::printf("NOT REPORTED: %s\n", what);
    return false;
}
}  // namespace

// A GL port's shaders given as source (glShaderSource), compiled on two threads at once, and its
// uniform block set by member name (glUniform*) rather than padded by hand; then two mistakes.
bool sourceShadersAndBlocks(Device& d) {
    DeviceObjects o(d);
    const char* vertex = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
void main() {
    vec2 p = vec2((FE_VERTEX_ID << 1) & 2, FE_VERTEX_ID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
    const char* fragment = R"(#version 450
layout(binding = 0, std140) uniform Tint { float scale; vec3 colour; } tint;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(tint.colour * tint.scale, 1.0); }
)";
    std::array<ShaderHandle, 2> shaders{};
    std::thread vsThread([&] {
        shaders[0] = o.add(d.createShader(
            {.stage = ShaderStage::Vertex, .source = {.text = vertex, .name = "port.vert"}}));
    });
    shaders[1] = o.add(d.createShader(
        {.stage = ShaderStage::Fragment, .source = {.text = fragment, .name = "port.frag"}}));
    vsThread.join();
    UniformBlock tint(d.shaderInterface(shaders[1]), "Tint");
    tint.set("scale", 0.5f);
    tint.set("colour", {1.0f, 0.5f, 0.0f});  // at offset 16, where std140 puts a vec3
    const BufferHandle ubo = o.add(
        d.createBuffer({.size = tint.bytes().size(), .usage = BufferUsage::Uniform}, tint.bytes()));
    const PipelineHandle p = o.add(d.createGraphicsPipeline({.vertexShader = shaders[0],
                                                             .fragmentShader = shaders[1],
                                                             .colorFormats = {Format::RGBA8}}));
    const TextureHandle target = o.add(d.createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image image = d.readTexture(target);
    const auto t = image.texel(4, 4);
    std::printf("source shaders, block by name: %.2f %.2f %.2f\n", t[0], t[1], t[2]);
    bool ok = t[0] > 0.49f && t[0] < 0.51f && t[1] > 0.24f && t[1] < 0.26f && t[2] < 0.01f;
    ok &= reported("a uniform block member that is not there", [&] {
        tint.set("color", {1.0f, 1.0f, 1.0f});
    });
    ok &= reported("a shader source that does not compile", [&] {
        d.createShader({.stage = ShaderStage::Fragment,
                        .source = {.text = "#version 450\nvoid main() { undeclared = 1; }\n",
                                   .name = "broken.frag"}});
    });
    return ok;
}

int main(int argc, char** argv) {
    std::string backend = "auto";
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            backend = argv[++i];
        else if (a == "--validation")
            validation = true;
        else
            return std::fprintf(stderr, "usage: %s [--backend NAME] [--validation]\n", argv[0]), 2;
    }
    try {
        auto device =
            createDevice({.backend = backend, .validation = validation, .verbose = false});
        Device& d = *device;
        DeviceObjects o(d);
        const ShaderHandle vs = o.add(d.createShader(
            {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("ported/ported.vert")}));
        const ShaderHandle fs = o.add(d.createShader(
            {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("ported/ported.frag")}));
        auto pipeline = [&](float brightness) {
            return o.add(d.createGraphicsPipeline(
                {.vertexShader = vs,
                 .fragmentShader = fs,
                 .topology = PrimitiveTopology::TriangleStrip,
                 .colorFormats = {Format::RGBA8},
                 .specialization = {SpecializationConstant::of(0, brightness)}}));
        };
        const PipelineHandle full = pipeline(1.0f), half = pipeline(0.5f);
        // A 2-layer array; layer 1 is drawn through a Texture2D view of it.
        const TextureHandle layers =
            o.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                   .width = 32,
                                   .height = 32,
                                   .depthOrLayers = 2,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
        const TextureHandle layer1 = o.add(d.createTextureView(
            layers, {.dimension = TextureDimension::Texture2D, .baseLayer = 1, .layerCount = 1}));
        const QuerySetHandle occlusion =
            o.add(d.createQuerySet({.type = QueryType::Occlusion, .count = 1}));
        const BufferHandle readback = o.add(d.createBuffer(
            {.size = 256, .usage = BufferUsage::CopyDst, .access = MemoryAccess::Readback}));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = layer1}}});
        cmd->beginQuery(occlusion, 0);
        cmd->setPipeline(full);
        cmd->setConstants(Quad{{-1, -1, 0, 0}, {1, 0.5f, 0, 1}});  // the top-left 16x16 quarter
        cmd->draw(4);
        cmd->setPipeline(half);  // constants persist across setPipeline; only the rect changes
        cmd->setConstants(0, bytesOf(std::array<float, 4>{0, 0, 1, 1}));
        cmd->draw(4);
        cmd->endQuery(occlusion, 0);
        cmd->endRenderPass();
        // Texels (14..17, 15) and (14..17, 16) of layer 1: two rows of 4, with 64-byte rows.
        cmd->copyTextureToBuffer(readback, {.bytesPerRow = 64}, layers,
                                 {.x = 14, .y = 15, .z = 1, .width = 4, .height = 2, .depth = 1});
        d.wait(d.submit(*cmd));
        std::array<uint64_t, 1> samples{};
        const bool ready = d.queryResults(occlusion, 0, 1, samples);
        std::printf("occlusion: %s, %llu samples passed\n", ready ? "ready" : "not ready",
                    (unsigned long long)samples[0]);
        const auto* texels = static_cast<const uint8_t*>(d.map(readback));
        for (int row = 0; row < 2; ++row) {
            std::printf("row %d:", row);
            for (int x = 0; x < 4; ++x)
                std::printf(" %02x%02x%02x%02x", texels[row * 64 + x * 4],
                            texels[row * 64 + x * 4 + 1], texels[row * 64 + x * 4 + 2],
                            texels[row * 64 + x * 4 + 3]);
            std::printf("\n");
        }
        bool ok = ready && samples[0] == 2 * 16 * 16 && texels[0] == 255 && texels[64 + 12] == 128;

        // Two threads record a list each (constants per draw, a query each), submitted together.
        const std::array<TextureHandle, 2> halves = {
            o.add(d.createTexture({.width = 16,
                                   .height = 16,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc})),
            o.add(d.createTexture({.width = 16,
                                   .height = 16,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}))};
        const QuerySetHandle counts =
            o.add(d.createQuerySet({.type = QueryType::Occlusion, .count = 2}));
        std::array<std::unique_ptr<CommandList>, 2> lists = {d.createCommandList(),
                                                             d.createCommandList()};
        auto record = [&](uint32_t k, uint32_t query) {
            CommandList& l = *lists[k];
            l.beginRenderPass({.colors = {{.texture = halves[k]}}});
            l.setPipeline(full);
            l.beginQuery(counts, query);
            l.setConstants(
                Quad{{-1, -1, k ? 1.0f : 0.0f, 1}, {float(k), 1, 0, 1}});  // all, or the left half
            l.draw(4);
            l.endQuery(counts, query);
            l.endRenderPass();
        };
        std::array<std::thread, 2> workers = {std::thread(record, 0u, 0u),
                                              std::thread(record, 1u, 0u)};
        for (std::thread& t : workers) t.join();
        std::array<CommandList*, 2> both = {lists[0].get(), lists[1].get()};
        ok &= reported("one query written by both lists of a submission", [&] { d.submit(both); });
        for (auto& l : lists) l = d.createCommandList();  // record again, a query each
        workers = {std::thread(record, 0u, 0u), std::thread(record, 1u, 1u)};
        for (std::thread& t : workers) t.join();
        both = {lists[0].get(), lists[1].get()};
        d.wait(d.submit(both));
        std::array<uint64_t, 2> covered{};
        ok &=
            d.queryResults(counts, 0, 2, covered) && covered[0] == 8 * 16 && covered[1] == 16 * 16;
        std::printf("two threads: %llu and %llu samples\n", (unsigned long long)covered[0],
                    (unsigned long long)covered[1]);
        ok &= reported("constants at an offset that is not a multiple of 4",
                       [&] { cmd->setConstants(2, bytesOf(1.0f)); });
        ok &= reported("a view drawn into, then copied from", [&] {
            cmd->copyTextureToBuffer(readback, {}, layer1, {.width = 4, .height = 4, .depth = 1});
        });
        ok &= reported("a specialization constant the shaders do not declare", [&] {
            d.createGraphicsPipeline({.vertexShader = vs,
                                      .fragmentShader = fs,
                                      .colorFormats = {Format::RGBA8},
                                      .specialization = {SpecializationConstant::of(7, 1.0f)}});
        });
        ok &= sourceShadersAndBlocks(d);
        if (validation && d.validationErrorCount())
            ok = false, std::printf("the validation layer reported errors\n");
        return ok ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_ported: %s\n", e.what());
        return 1;
    }
}
