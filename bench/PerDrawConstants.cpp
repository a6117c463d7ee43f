// Per-draw data two ways (issue 26), per backend, medians over repeated rounds: 20,000 draws of
// a small triangle, each with 80 bytes of its own data, either
//   - uniform offsets: the data in one uniform buffer, setUniformBuffer(slot, buffer, i * 256, 80)
//     per draw (the way ports did it before setConstants), or
//   - constants: setConstants(0, 80 bytes) per draw (push constants on Vulkan, the GL ring).
// Timed: recording alone (CPU per draw on the recording thread), and record + submit + wait (on
// GL this includes the context thread's replay, where the constants are uploaded). Prints a
// markdown table; on lavapipe/llvmpipe these are software-rasterizer figures.
//   fe_bench_constants [--backend NAME|all] [--rounds N]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

namespace {

constexpr uint32_t kDraws = 20000;
constexpr uint32_t kStride = 256;  // >= every device's uniform offset alignment
using Clock = std::chrono::steady_clock;

struct Object {
    float offsetScale[4];
    float color[4];
    float extra[12];
};
static_assert(sizeof(Object) == 80);

double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

struct Row {
    std::string backend;
    double recordUbo = 0, recordConstants = 0, totalUbo = 0, totalConstants = 0;  // ns per draw
};

Row measure(const std::string& backend, uint32_t rounds) {
    auto device = createDevice({.backend = backend, .validation = false, .verbose = false});
    Device& d = *device;
    DeviceObjects o(d);
    std::vector<Object> objects(kDraws);
    std::vector<std::byte> packed(size_t(kDraws) * kStride);
    for (uint32_t i = 0; i < kDraws; ++i) {
        objects[i] = {
            {-1 + 2 * float(i % 100) / 100, -1 + 2 * float(i / 100 % 100) / 100, 0.03f, 0.03f},
            {1, 1, 1, 1},
            {}};
        std::memcpy(&packed[size_t(i) * kStride], &objects[i], sizeof(Object));
    }
    const TextureHandle target =
        o.add(d.createTexture({.width = 100, .height = 100, .usage = TextureUsage::RenderTarget}));
    const float tri[] = {0, 0, 1, 0, 0, 1};
    const BufferHandle vertices =
        o.add(d.createBuffer({.size = sizeof(tri), .usage = BufferUsage::Vertex}, bytesOf(tri)));
    const BufferHandle ubo = o.add(
        d.createBuffer({.size = packed.size(), .usage = BufferUsage::Uniform}, bytesOf(packed)));
    auto shader = [&](ShaderStage stage, const char* path) {
        return o.add(d.createShader({.stage = stage, .binary = fe::shaders::find(path)}));
    };
    const ShaderHandle fs = shader(ShaderStage::Fragment, "bench/draw.frag");
    auto pipeline = [&](const char* vs) {
        return o.add(d.createGraphicsPipeline(
            {.vertexShader = shader(ShaderStage::Vertex, vs),
             .fragmentShader = fs,
             .vertexBuffers = {{.stride = 8,
                                .attributes = {{.location = 0, .format = VertexFormat::Float2}}}},
             .colorFormats = {Format::RGBA8}}));
    };
    const PipelineHandle withUbo = pipeline("bench/object_ubo.vert");
    const PipelineHandle withConstants = pipeline("bench/object_constants.vert");
    auto cmd = d.createCommandList();
    auto run = [&](bool constants, std::vector<double>& record, std::vector<double>& total) {
        const auto t0 = Clock::now();
        cmd->beginRenderPass({.colors = {{.texture = target}}});
        cmd->setPipeline(constants ? withConstants : withUbo);
        cmd->setVertexBuffer(0, vertices);
        for (uint32_t i = 0; i < kDraws; ++i) {
            if (constants)
                cmd->setConstants(objects[i]);
            else
                cmd->setUniformBuffer(0, ubo, uint64_t(i) * kStride, sizeof(Object));
            cmd->draw(3);
        }
        cmd->endRenderPass();
        record.push_back(msSince(t0) * 1e6 / kDraws);
        d.wait(d.submit(*cmd));
        total.push_back(msSince(t0) * 1e6 / kDraws);
    };
    std::vector<double> recordUbo, recordConstants, totalUbo, totalConstants;
    for (uint32_t r = 0; r < rounds + 1;
         ++r) {  // alternating, so drift affects both; round 0 warms up
        run(false, recordUbo, totalUbo);
        run(true, recordConstants, totalConstants);
        if (r == 0)
            recordUbo.clear(), totalUbo.clear(), recordConstants.clear(), totalConstants.clear();
    }
    return {backend, median(recordUbo), median(recordConstants), median(totalUbo),
            median(totalConstants)};
}

}  // namespace

int main(int argc, char** argv) {
    std::string backend = "all";
    uint32_t rounds = 11;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--backend")
            backend = argv[i + 1];
        else if (a == "--rounds")
            rounds = uint32_t(std::max(1, std::atoi(argv[i + 1])));
        else
            return std::fprintf(stderr,
                                "usage: fe_bench_constants [--backend NAME|all] [--rounds N]\n"),
                   2;
    }
    try {
        std::printf(
            "| backend | record, uniform offsets (ns/draw) | record, constants | ratio | record+submit+wait, offsets | "
            "record+submit+wait, constants | ratio |\n|---|---|---|---|---|---|---|\n");
        for (const std::string& b : expandBackendList(backend)) {
            const Row r = measure(b, rounds);
            std::printf("| %s | %.0f | %.0f | %.2f | %.0f | %.0f | %.2f |\n", r.backend.c_str(),
                        r.recordUbo, r.recordConstants, r.recordConstants / r.recordUbo, r.totalUbo,
                        r.totalConstants, r.totalConstants / r.totalUbo);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_bench_constants: %s\n", e.what());
        return 1;
    }
    return 0;
}
