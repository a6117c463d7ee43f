// Layer 5 frame plumbing on every backend: the headless swap chain's ring of images and the
// command queue's frames in flight with their upload regions.
#include <gtest/gtest.h>

#include <set>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "frame/CommandQueue.h"
#include "frame/SwapChain.h"

using namespace fe;

class Frames : public fe::testing::BackendTest {};

TEST_P(Frames, SwapChainCyclesItsImagesAndReadsBackTheLastPresented) {
    render::CommandQueue queue(*device, 2);
    render::SwapChain chain(*device, {.width = 32, .height = 16, .format = gdi::Format::RGBA8, .imageCount = 3});
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

TEST_P(Frames, UploadsAreAlignedAndFramesInFlightKeepTheirRegions) {
    render::CommandQueue queue(*device, 2, 4096);
    const uint64_t align = std::max<uint64_t>(1, device->info().limits.uniformBufferOffsetAlignment);
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
    // A frame that asks for more than its region is an error, not an overwrite.
    queue.beginFrame();
    std::vector<uint8_t> big(8192);
    EXPECT_THROW(queue.upload(gdi::bytesOf(big)), gdi::Error);
    queue.endFrame();
    queue.waitIdle();
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Frames);
