// Layer 5 frame plumbing on every backend: the headless swap chain's ring of images, the
// command queue's frames in flight with their upload regions, and pass timing.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <thread>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "frame/CommandQueue.h"
#include "frame/SwapChain.h"
#include "assets/BuiltinScenes.h"
#include "integration/SceneRenderer.h"

using namespace fe;

class Frames : public fe::testing::BackendTest {};

TEST_P(Frames, SwapChainCyclesItsImagesAndReadsBackTheLastPresented) {
    render::CommandQueue queue(*device, 2);
    render::SwapChain chain(
        *device, {.width = 32, .height = 16, .format = gdi::Format::RGBA8, .imageCount = 3});
    std::set<uint32_t> seen;
    for (int frame = 0; frame < 7; ++frame) {
        gdi::TextureHandle image = chain.acquire();
        seen.insert(image.id);
        gdi::CommandList& cmd = queue.beginFrame();
        const float v = float(frame) / 8.0f;
        cmd.beginRenderPass({.colors = {{.texture = image, .clear = {v, 0.25f, 1.0f - v, 1.0f}}}});
        cmd.endRenderPass();
        chain.present(queue.endFrame());
        gdi::Image shown = chain.readLastPresented();
        ASSERT_EQ(shown.width, 32u);
        ASSERT_EQ(shown.height, 16u);
        EXPECT_NEAR(shown.texel(5, 7)[0], v, 1.0 / 255.0) << "frame " << frame;
        EXPECT_NEAR(shown.texel(31, 15)[2], 1.0f - v, 1.0 / 255.0) << "frame " << frame;
    }
    EXPECT_EQ(seen.size(), 3u);  // a ring of three distinct images
}

TEST_P(Frames, UploadsAreAlignedFramesInFlightKeepTheirRegionsAndRegionsGrow) {
    render::CommandQueue queue(*device, 2, 4096);
    const uint64_t align =
        std::max<uint64_t>(1, device->info().limits.uniformBufferOffsetAlignment);
    std::vector<render::UploadAllocation> first;
    for (int frame = 0; frame < 2; ++frame) {
        queue.beginFrame();
        render::UploadAllocation a = queue.upload(uint32_t(1)), b = queue.upload(uint64_t(2));
        EXPECT_EQ(a.offset % align, 0u);
        EXPECT_EQ(b.offset % align, 0u);
        EXPECT_GE(b.offset, a.offset + a.size);
        first.push_back(a);
        queue.endFrame();
    }
    EXPECT_NE(first[0].offset, first[1].offset);  // two frames in flight, two regions
    // A frame that asks for more than its region moves to a buffer of larger regions: what it
    // uploaded before stays where it was, each upload holds its bytes, the outgrown buffer goes
    // once the frame is submitted, and the next frames fit without growing again.
    const uint32_t buffersBefore = device->liveObjects().buffers;
    queue.beginFrame();
    std::vector<uint8_t> small(1000, 0x5a), big(8192);
    for (size_t i = 0; i < big.size(); ++i) big[i] = uint8_t(i * 7 + 1);
    const render::UploadAllocation a = queue.upload(gdi::bytesOf(small));
    const render::UploadAllocation b = queue.upload(gdi::bytesOf(big));
    EXPECT_NE(a.buffer.id, b.buffer.id);
    EXPECT_EQ(b.offset % align, 0u);
    EXPECT_EQ(device->readBuffer(a.buffer, a.offset, a.size), small);
    EXPECT_EQ(device->readBuffer(b.buffer, b.offset, b.size), big);
    EXPECT_EQ(device->liveObjects().buffers, buffersBefore + 1);
    queue.endFrame();
    for (int frame = 0; frame < 3; ++frame) {
        queue.beginFrame();
        const render::UploadAllocation c = queue.upload(gdi::bytesOf(big));
        EXPECT_EQ(c.buffer.id, b.buffer.id) << "frame " << frame;
        EXPECT_EQ(device->readBuffer(c.buffer, c.offset, c.size), big);
        queue.endFrame();
    }
    queue.waitIdle();
    EXPECT_EQ(device->liveObjects().buffers, buffersBefore);  // the outgrown one is gone
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Frames);

// Pass times you can trust: a flush-and-wait profiling frame times every pass the
// graph executes, in order, and leaves the image as a plain frame draws it; the method is chosen
// from whether the timestamps account for the frame.
class PassTimes : public fe::testing::BackendTest {};

TEST_P(PassTimes, FlushAndWaitTimesEveryPassAndLeavesTheImage) {
    assets::BuiltinOptions o;
    o.lights = 16;
    const assets::Scene scene = assets::makeBuiltinScene("lights", o);
    const std::string technique =
        device->info().features.computeShaders ? "deferred-tiled" : "deferred";
    render::SceneRenderer r(*device, scene, {.technique = technique, .width = 64, .height = 48});
    r.renderFrame();
    const gdi::Image plain = r.readOutput();
    std::vector<std::string> executed;
    for (const graph::PassInfo& p : r.graph().passes())
        if (!p.culled) executed.push_back(p.name);
    const std::vector<graph::PassTiming> profiled = r.profilePasses();
    std::vector<std::string> timed;
    double sum = 0;
    for (const graph::PassTiming& p : profiled) {
        timed.push_back(p.name);
        EXPECT_GE(p.gpuMilliseconds, 0.0) << p.name;
        sum += p.gpuMilliseconds;
    }
    EXPECT_EQ(timed, executed);
    EXPECT_GT(sum, 0.0);
    EXPECT_EQ(r.readOutput().data, plain.data) << "a profiled frame draws what a plain one does";

    using render::SceneRenderer;
    EXPECT_FALSE(SceneRenderer::timersAccountForFrame({{"a", 1.0}}, 10.0));
    EXPECT_TRUE(SceneRenderer::timersAccountForFrame({{"a", 3.0}, {"b", 3.0}}, 10.0));
    EXPECT_FALSE(SceneRenderer::timersAccountForFrame({}, 10.0))
        << "no timestamps account for nothing";
    const SceneRenderer::PassTimes low =
        r.measurePassTimes({{"gbuffer", {0.1, 0.1}}}, {100.0, 100.0}, 2);
    EXPECT_EQ(low.method, "flush-and-wait");
    ASSERT_EQ(low.passes.size(), executed.size());
    EXPECT_EQ(low.passes.front().second.size(), 2u) << "two profiled frames";
    EXPECT_NEAR(low.timestampShare, 0.001, 1e-9);
    const SceneRenderer::PassTimes high = r.measurePassTimes({{"gbuffer", {90.0}}}, {100.0}, 2);
    EXPECT_EQ(high.method, "gpu-timestamps");
    EXPECT_EQ(high.passes, high.timestamps);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(PassTimes);

// Two more devices of the backend, made and driven by two threads at the same time (a tool
// drawing two views at once): both images are the one the fixture's device renders alone, bit
// for bit. (The llvmpipe crash GlContextThread's process-wide lock avoids came at a process's
// first GL use, which the fixture's device has made here: example_materials_* catch that one.)
TEST_P(Frames, TwoDevicesRenderOnTwoThreadsAtOnce) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    const render::RenderSettings settings{.technique = "forward", .width = 48, .height = 36};
    const gdi::Image alone = [&] {
        render::SceneRenderer r(*device, scene, settings);
        r.renderFrame();
        return r.readOutput();
    }();
    for (int round = 0; round < 3; ++round) {
        gdi::Image images[2];
        std::string errors[2];
        auto run = [&](int k) {
            try {
                auto own = gdi::createDevice({.backend = GetParam(), .validation = true});
                render::SceneRenderer r(*own, scene, settings);
                r.renderFrame();
                images[k] = r.readOutput();
                if (own->validationErrorCount()) errors[k] = "validation errors";
            } catch (const std::exception& e) {
                errors[k] = e.what();
            }
        };
        std::thread worker(run, 1);
        run(0);
        worker.join();
        for (int k = 0; k < 2; ++k) {
            ASSERT_EQ(errors[k], "") << "round " << round;
            EXPECT_EQ(images[k].data, alone.data) << "round " << round << ", thread " << k;
        }
    }
}
