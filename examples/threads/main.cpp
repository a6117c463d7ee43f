// Example (c): command lists recorded on two threads at once and submitted together, three
// frames in flight, one pass whose draws are two secondary lists recorded on two threads (and
// executed again in a second pass, as recorded), and
// five mistakes made on purpose, each of which must be the same gdi::Error on every backend
// (tests/package_consumer.sh compares the messages).
//   fe_example_threads [--backend NAME] [--validation]
// Prints one line per mistake ("error: ..."), then whether both halves were drawn; exit 1 when
// a mistake was not reported, a half is missing or the validation layer spoke.
#include <array>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

namespace {
// Runs `mistake`, which must throw gdi::Error; prints its message.
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

int main(int argc, char** argv) {
    std::string backend = "auto";
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            backend = argv[++i];
        else if (a == "--validation")
            validation = true;
        else {
            std::fprintf(stderr, "usage: %s [--backend NAME] [--validation]\n", argv[0]);
            return 2;
        }
    }
    try {
        auto device =
            createDevice({.backend = backend, .validation = validation, .verbose = false});
        Device& d = *device;
        const ShaderHandle vs = d.createShader(
            {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("triangle/triangle.vert")});
        const ShaderHandle fs =
            d.createShader({.stage = ShaderStage::Fragment,
                            .binary = fe::shaders::find("triangle/triangle.frag")});
        const PipelineHandle pipeline = d.createGraphicsPipeline(
            {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
        auto target = [&](const char* name) {
            return d.createTexture({.width = 64,
                                    .height = 64,
                                    .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                                    .debugName = name});
        };
        const std::array<TextureHandle, 2> halves = {target("left"), target("right")};
        std::array<std::unique_ptr<CommandList>, 2> lists = {d.createCommandList(),
                                                             d.createCommandList()};
        std::array<FenceValue, 3>
            inFlight{};  // three frames in flight: frame f waits for frame f - 3

        for (uint32_t frame = 0; frame < 6; ++frame) {
            d.wait(inFlight[frame % 3]);
            // Each thread records its own list; neither touches the device's lock.
            std::array<std::thread, 2> recorders;
            for (size_t i = 0; i < 2; ++i)
                recorders[i] = std::thread([&, i] {
                    CommandList& c = *lists[i];
                    c.beginRenderPass(
                        {.colors = {{.texture = halves[i], .clear = {0.1f * float(i), 0, 0, 1}}}});
                    c.setPipeline(pipeline);
                    c.draw(3);
                    c.endRenderPass();
                });
            for (auto& t : recorders) t.join();
            std::array<CommandList*, 2> order = {lists[1].get(), lists[0].get()};
            inFlight[frame % 3] = d.submit(order);
        }
        d.waitIdle();

        // One pass, its draws recorded on two threads as secondary lists (left and right half).
        const TextureHandle whole = target("whole");
        const RenderPassDesc pass{.colors = {{.texture = whole, .clear = {0, 0, 0, 1}}},
                                  .secondaryLists = true};
        auto primary = d.createCommandList();
        primary->beginRenderPass(pass);
        std::array<std::thread, 2> recorders;
        for (size_t i = 0; i < 2; ++i)
            recorders[i] = std::thread([&, i] {
                CommandList& c = *lists[i];
                c.beginSecondary(pass);
                c.setPipeline(pipeline);
                c.setScissor({int32_t(32 * i), 0, 32, 64});
                c.draw(3);
                c.endSecondary();
            });
        for (auto& t : recorders) t.join();
        primary->executeSecondary(std::array<CommandList*, 2>{lists[0].get(), lists[1].get()});
        primary->endRenderPass();
        d.wait(d.submit(*primary));
        // The lists keep their recordings: the same pass again into another target (as a frame
        // would every frame), then reset() makes them plain lists for the mistakes below.
        const TextureHandle again = target("again");
        RenderPassDesc againPass = pass;
        againPass.colors[0].texture = again;
        primary->beginRenderPass(againPass);
        primary->executeSecondary(std::array<CommandList*, 2>{lists[0].get(), lists[1].get()});
        primary->endRenderPass();
        d.wait(d.submit(*primary));
        for (auto& l : lists) l->reset();

        bool ok = true;
        // Mistake 1: a draw outside a render pass, recorded on a worker thread.
        std::thread([&] {
            ok &= reported("draw outside a pass",
                           [&] { lists[0]->setPipeline(pipeline), lists[0]->draw(3); });
        }).join();
        // Mistake 2: a list whose target is destroyed between recording and submit.
        const TextureHandle doomed = target("doomed");
        auto late = d.createCommandList();
        late->beginRenderPass({.colors = {{.texture = doomed}}});
        late->endRenderPass();
        d.destroy(doomed);
        ok &= reported("submit after destroy", [&] { d.submit(*late); });
        // Mistake 3: mapping GPU-only memory.
        const BufferHandle gpuOnly = d.createBuffer({.size = 256, .debugName = "gpu only"});
        ok &= reported("map GpuOnly", [&] { d.map(gpuOnly); });
        // Mistake 4: a pipeline whose colour format is not the pass's (Vulkan's validation layer
        // would report it at the draw; GL would draw).
        ok &= reported("pipeline formats against the pass", [&] {
            const TextureHandle hdr = d.createTexture({.format = Format::RGBA16F,
                                                       .width = 64,
                                                       .height = 64,
                                                       .usage = TextureUsage::RenderTarget,
                                                       .debugName = "hdr"});
            auto c = d.createCommandList();
            c->beginRenderPass({.colors = {{.texture = hdr}}});
            try {
                c->setPipeline(pipeline);  // an RGBA8 pipeline in an RGBA16F pass
            } catch (...) {
                c->endRenderPass();
                d.destroy(hdr);
                throw;
            }
        });
        // Mistake 5: executing a secondary list outside a pass of secondary lists (the lists
        // keep their recordings: they could run again in another pass like `pass`).
        ok &= reported("executeSecondary outside a pass of secondary lists",
                       [&] { primary->executeSecondary(*lists[0]); });

        for (size_t i = 0; i < 2; ++i) {
            const auto mid = d.readTexture(halves[i]).texel(32, 40);
            const bool drawn = mid[1] > 0.15f || mid[2] > 0.15f;
            std::printf("%s half: %s\n", i ? "right" : "left", drawn ? "drawn" : "MISSING");
            ok &= drawn;
        }
        for (TextureHandle t : {whole, again}) {
            const Image all = d.readTexture(t);
            for (uint32_t x : {24u, 40u}) {  // either side of the split, inside the triangle
                const auto texel = all.texel(x, 40);
                const bool drawn = texel[1] > 0.15f || texel[2] > 0.15f;
                std::printf("secondary list %s%s: %s\n", x < 32 ? "left" : "right",
                            t == again ? ", executed again" : "", drawn ? "drawn" : "MISSING");
                ok &= drawn;
            }
        }
        lists = {};
        primary.reset();
        late.reset();
        d.destroy(whole);
        d.destroy(again);
        d.destroy(gpuOnly);
        for (TextureHandle t : halves) d.destroy(t);
        d.destroy(pipeline);
        d.destroy(vs);
        d.destroy(fs);
        if (d.validationErrorCount())
            std::printf("%u validation error(s)\n", unsigned(d.validationErrorCount()));
        return ok && d.validationErrorCount() == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_threads: %s\n", e.what());
        return 1;
    }
}
