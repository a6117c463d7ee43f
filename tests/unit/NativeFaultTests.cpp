// Native API failures on every backend, made to happen by fault injection (fe/gdi/Faults.h):
// out of memory is an error naming the call and the object, leaves nothing behind and keeps the
// device usable; a lost device throws DeviceLostError from then on, while objects made before
// the loss are still destroyed normally. Leaks are counted with Device::liveObjects.
#include <algorithm>
#include <gtest/gtest.h>

#include <functional>
#include <regex>
#include <ostream>
#include <vector>

#include "BackendTest.h"
#include "fe/gdi/Faults.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe;
using namespace fe::gdi;

namespace fe::gdi {
// Readable leak-check failures.
void PrintTo(const LiveObjects& o, std::ostream* os) { *os << toString(o); }
}  // namespace fe::gdi

namespace {

class NativeFaults : public fe::testing::BackendTest {
protected:
    void TearDown() override {
        fault::arm(fault::Site::Allocation, 0);
        fault::arm(fault::Site::Submission, 0);
        BackendTest::TearDown();
    }

    // Runs `op` once per native allocation it makes, failing the first, then the second, ...
    // until it runs through. Every failure must be an Error whose message passes `check` and
    // must leave the device's objects as they were. Returns the native calls failed, in order,
    // as the errors name them.
    std::vector<std::string> failEachAllocation(
        const std::function<void()>& op, const std::function<void(const std::string&)>& check) {
        std::vector<std::string> failed;
        for (uint64_t n = 1; n <= 32; ++n) {
            fault::arm(fault::Site::Allocation, n);
            const uint64_t firedBefore = fault::fired(fault::Site::Allocation);
            const LiveObjects before = device->liveObjects();
            try {
                op();
            } catch (const Error& e) {
                EXPECT_EQ(fault::fired(fault::Site::Allocation), firedBefore + 1)
                    << "not the injected failure: " << e.what();
                check(e.what());
                EXPECT_EQ(device->liveObjects(), before)
                    << "allocation " << n << " failed and left objects behind";
                std::smatch call;
                const std::string message = e.what();
                EXPECT_TRUE(std::regex_search(message, call, std::regex(R"(\b(vk|gl)[A-Z]\w+)")))
                    << "no native call named: " << message;
                failed.push_back(call.str());
                continue;
            }
            fault::arm(fault::Site::Allocation, 0);
            EXPECT_EQ(fault::fired(fault::Site::Allocation), firedBefore)
                << "a failure was swallowed";
            return failed;
        }
        ADD_FAILURE() << "the operation still made native allocations after 32";
        return failed;
    }

    // A triangle drawn and read back: the device works.
    void expectDraws() {
        Device& d = *device;
        auto vs = d.createShader(
            {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/triangle.vert")});
        auto fs = d.createShader(
            {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")});
        auto p = d.createGraphicsPipeline(
            {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
        auto t = d.createTexture({.width = 16,
                                  .height = 16,
                                  .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 1, 1}}}});
        cmd->setPipeline(p);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        const Image img = d.readTexture(t);
        EXPECT_EQ(img.texel(0, 15), (std::array<float, 4>{0, 0, 1, 1}))
            << "corner: the clear colour";
        const auto centre = img.texel(8, 8);
        EXPECT_GT(centre[0] + centre[1], 0.5f) << "centre: the triangle";
        cmd.reset();
        for (auto h : {vs, fs}) d.destroy(h);
        d.destroy(p);
        d.destroy(t);
    }

    // f must throw DeviceLostError naming `call`.
    template <class F>
    void expectLost(const char* call, F&& f) {
        try {
            f();
            ADD_FAILURE() << call << " did not throw on a lost device";
        } catch (const DeviceLostError& e) {
            EXPECT_NE(std::string(e.what()).find(call), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("device lost"), std::string::npos) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << call << " threw another error on a lost device: " << e.what();
        }
    }
};

// The message names the native call, what failed, and the object.
void expectOutOfMemory(const std::string& message, const std::string& object) {
    EXPECT_TRUE(message.find("VK_ERROR_OUT_OF_DEVICE_MEMORY") != std::string::npos ||
                message.find("GL_OUT_OF_MEMORY") != std::string::npos)
        << message;
    EXPECT_TRUE(message.find("vk") != std::string::npos || message.find("gl") != std::string::npos)
        << message;
    EXPECT_NE(message.find(object), std::string::npos) << message;
}

}  // namespace

TEST(FaultInjection, CounterFailsOnlyTheNthCall) {
    const uint64_t fired = fault::fired(fault::Site::Allocation);
    const uint64_t calls = fault::calls(fault::Site::Allocation);
    fault::arm(fault::Site::Allocation, 3);
    EXPECT_FALSE(fault::hit(fault::Site::Allocation, "a"));
    EXPECT_FALSE(fault::hit(fault::Site::Submission, "s"));  // sites count separately
    EXPECT_FALSE(fault::hit(fault::Site::Allocation, "b"));
    EXPECT_TRUE(fault::hit(fault::Site::Allocation, "c"));
    EXPECT_FALSE(fault::hit(fault::Site::Allocation, "d"));
    EXPECT_EQ(fault::fired(fault::Site::Allocation), fired + 1);
    fault::arm(fault::Site::Allocation, 0);
    EXPECT_FALSE(fault::hit(fault::Site::Allocation, "e"));
    EXPECT_EQ(fault::calls(fault::Site::Allocation), calls + 5)
        << "every call is counted, armed or not";
}

TEST_P(NativeFaults, OutOfMemoryCreatingBuffersIsAnErrorAndTheDeviceStaysUsable) {
    const LiveObjects empty = device->liveObjects();
    // Objects made before the failures, released normally at the end.
    BufferHandle before = device->createBuffer({.size = 256, .debugName = "made before"});
    TextureHandle beforeTexture = device->createTexture({.width = 8, .height = 8});

    // Larger than half a Vulkan memory block: memory of its own (vkAllocateMemory) besides
    // vkCreateBuffer, and the initial data goes through a staging buffer that allocates too.
    std::vector<uint8_t> data(20u << 20, 7);
    BufferHandle big;
    const std::vector<std::string> failed = failEachAllocation(
        [&] {
            big = device->createBuffer({.size = data.size(), .debugName = "big vertices"},
                                       bytesOf(data));
        },
        [&](const std::string& m) { expectOutOfMemory(m, "buffer"); });
    if (GetParam() == "vulkan") {
        // The buffer and its memory, then the staging buffer, its memory and mapping, and the
        // copy's command buffer; memory is mapped where it is host-visible (the buffer's too on
        // a CPU device). Last, the command buffer that carries the first commands of the
        // texture made before (recorded at the first transfer or submission after it).
        std::vector<std::string> unmapped = failed;
        std::erase(unmapped, "vkMapMemory");
        EXPECT_EQ(unmapped,
                  (std::vector<std::string>{"vkCreateBuffer", "vkAllocateMemory", "vkCreateBuffer",
                                            "vkAllocateMemory", "vkAllocateCommandBuffers",
                                            "vkBeginCommandBuffer", "vkEndCommandBuffer",
                                            "vkAllocateCommandBuffers", "vkBeginCommandBuffer"}));
        EXPECT_GE(failed.size() - unmapped.size(), 1u) << "the staging memory's mapping";
    } else {
        EXPECT_EQ(failed, std::vector<std::string>{"glNamedBufferStorage"});
    }
    EXPECT_EQ(device->readBuffer(big, data.size() - 4, 4), std::vector<uint8_t>(4, 7));

    // The failing object itself is named.
    fault::arm(fault::Site::Allocation, 1);
    const std::string message =
        fe::testing::errorOf([&] { device->createBuffer({.size = 64, .debugName = "named one"}); });
    expectOutOfMemory(message, "buffer 'named one' (64 bytes)");

    expectDraws();
    for (BufferHandle b : {before, big}) device->destroy(b);
    device->destroy(beforeTexture);
    EXPECT_EQ(device->liveObjects(), empty);
}

TEST_P(NativeFaults, OutOfMemoryCreatingTexturesIsAnErrorAndTheDeviceStaysUsable) {
    const LiveObjects empty = device->liveObjects();
    BufferHandle before = device->createBuffer({.size = 256});
    TextureHandle beforeTexture =
        device->createTexture({.width = 8, .height = 8, .debugName = "made before"});

    TextureHandle small, big;
    EXPECT_FALSE(
        failEachAllocation(
            [&] {
                small = device->createTexture({.width = 64, .height = 64, .debugName = "albedo"});
            },
            [&](const std::string& m) { expectOutOfMemory(m, "texture 'albedo' (64x64 RGBA8)"); })
            .empty());
    // 32 MiB: memory of its own on Vulkan (vkCreateImage, then vkAllocateMemory).
    const std::vector<std::string> failed = failEachAllocation(
        [&] {
            big = device->createTexture(
                {.format = Format::RGBA8, .width = 4096, .height = 2048, .debugName = "huge"});
        },
        [&](const std::string& m) { expectOutOfMemory(m, "texture 'huge'"); });
    if (GetParam() == "vulkan") {
        // The image, its memory (mapped where host-visible) and its view. Its first layout
        // transition goes into the command buffer the texture made before already started
        // (recorded for the next submission, not submitted and waited for here).
        std::vector<std::string> unmapped = failed;
        std::erase(unmapped, "vkMapMemory");
        EXPECT_EQ(unmapped, (std::vector<std::string>{"vkCreateImage", "vkAllocateMemory",
                                                      "vkCreateImageView"}));
    } else {
        EXPECT_EQ(failed, std::vector<std::string>{"glTextureStorage2D"});
    }

    // Every texture kind, each of its allocations failed in turn.
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::Sampled;
    std::vector<TextureDesc> kinds = {{.dimension = TextureDimension::Texture2DArray,
                                       .width = 32,
                                       .height = 32,
                                       .depthOrLayers = 4,
                                       .debugName = "layers"},
                                      {.dimension = TextureDimension::TextureCube,
                                       .format = Format::RGBA16F,
                                       .width = 32,
                                       .height = 32,
                                       .depthOrLayers = 6,
                                       .mipLevels = 6,
                                       .usage = rt,
                                       .debugName = "environment"},
                                      {.dimension = TextureDimension::Texture3D,
                                       .width = 16,
                                       .height = 16,
                                       .depthOrLayers = 16,
                                       .debugName = "volume"},
                                      {.format = Format::D32F,
                                       .width = 64,
                                       .height = 64,
                                       .usage = rt,
                                       .debugName = "shadow map"}};
    if (device->info().limits.colorSampleCounts & 4)
        kinds.push_back({.width = 64,
                         .height = 64,
                         .sampleCount = 4,
                         .usage = TextureUsage::RenderTarget,
                         .debugName = "msaa"});
    std::vector<TextureHandle> made;
    for (const TextureDesc& k : kinds) {
        TextureHandle t;
        EXPECT_FALSE(failEachAllocation([&] { t = device->createTexture(k); },
                                        [&](const std::string& m) {
                                            expectOutOfMemory(
                                                m, std::string("texture '") + k.debugName + "'");
                                        })
                         .empty())
            << k.debugName;
        made.push_back(t);
    }

    expectDraws();
    for (TextureHandle t : made) device->destroy(t);
    for (TextureHandle t : {beforeTexture, small, big}) device->destroy(t);
    device->destroy(before);
    EXPECT_EQ(device->liveObjects(), empty);
}

// Transfers allocate staging memory on Vulkan; GL copies without a native allocation.
TEST_P(NativeFaults, OutOfMemoryInTransfersLeavesNothingBehind) {
    const LiveObjects empty = device->liveObjects();
    // Staging memory is host-visible: where that is another memory type than a texture's
    // (NVIDIA), the first transfer each way also makes and maps a memory block, which stays for
    // later ones. One transfer each way first makes the counted ones alike on every device.
    {
        TextureHandle warm =
            device->createTexture({.width = 16, .height = 16, .debugName = "warm-up"});
        device->writeTexture(warm, {}, bytesOf(std::vector<uint8_t>(16 * 16 * 4, 1)));
        device->readTexture(warm);
        device->destroy(warm);
    }
    TextureHandle t = device->createTexture({.width = 16, .height = 16, .debugName = "uploaded"});
    std::vector<uint8_t> texels(16 * 16 * 4, 200);
    auto staging = [](const std::string& m) {
        expectOutOfMemory(m, m.find("staging") != std::string::npos
                                 ? "staging buffer for texture 'uploaded' (1024 bytes)"
                                 : "texture 'uploaded'");  // the copy's command buffer
    };
    const std::vector<std::string> failedWrites =
        failEachAllocation([&] { device->writeTexture(t, {}, bytesOf(texels)); }, staging);
    Image img;
    const std::vector<std::string> failedReads =
        failEachAllocation([&] { img = device->readTexture(t); }, staging);
    EXPECT_EQ(img.data, texels);
    // Vulkan, each way: the staging buffer (its memory block is already mapped, made by the
    // earlier texture) and the copy's command buffer.
    const std::vector<std::string> perTransfer =
        GetParam() == "vulkan"
            ? std::vector<std::string>{"vkCreateBuffer", "vkAllocateCommandBuffers",
                                       "vkBeginCommandBuffer", "vkEndCommandBuffer"}
            : std::vector<std::string>{};
    // The first write also records the texture's first commands (transition, zero clear) into
    // a command buffer of their own, in the same submission.
    std::vector<std::string> firstWrite = perTransfer;
    if (GetParam() == "vulkan")
        firstWrite.insert(firstWrite.end(), {"vkAllocateCommandBuffers", "vkBeginCommandBuffer"});
    EXPECT_EQ(failedWrites, firstWrite);
    EXPECT_EQ(failedReads, perTransfer);
    device->destroy(t);
    EXPECT_EQ(device->liveObjects(), empty);
}

TEST_P(NativeFaults, LostDeviceThrowsFromEveryLaterCallAndStillReleasesObjects) {
    Device& d = *device;
    const LiveObjects empty = d.liveObjects();
    // Objects made before the loss.
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/triangle.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")});
    auto pipeline = d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto target = d.createTexture(
        {.width = 16, .height = 16, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    auto buffer = d.createBuffer({.size = 256, .debugName = "made before"});
    auto sampler = d.createSampler({});
    auto timer = d.createTimer();
    auto cmd = d.createCommandList();
    auto record = [&] {
        cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 1, 1}}}});
        cmd->setPipeline(pipeline);
        cmd->draw(3);
        cmd->endRenderPass();
    };

    fault::arm(fault::Site::Submission,
               2);  // the first submission runs, the second loses the device
    record();
    const FenceValue first = d.submit(*cmd);
    d.wait(first);
    record();
    expectLost("device lost", [&] { d.submit(*cmd); });

    // Every later create, transfer, submit and wait throws DeviceLostError.
    uint8_t bytes[64] = {};
    expectLost("createBuffer", [&] { d.createBuffer({.size = 64}); });
    expectLost("createTexture", [&] { d.createTexture({.width = 4, .height = 4}); });
    expectLost("createSampler", [&] { d.createSampler({}); });
    expectLost("createShader", [&] {
        d.createShader(
            {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/triangle.vert")});
    });
    expectLost("createGraphicsPipeline", [&] {
        d.createGraphicsPipeline({.vertexShader = vs, .colorFormats = {Format::RGBA8}});
    });
    expectLost("createTimer", [&] { d.createTimer(); });
    expectLost("createCommandList", [&] { d.createCommandList(); });
    expectLost("writeBuffer", [&] { d.writeBuffer(buffer, 0, bytesOf(bytes)); });
    expectLost("readBuffer", [&] { d.readBuffer(buffer, 0, 64); });
    expectLost("readTexture", [&] { d.readTexture(target); });
    expectLost("timerNanoseconds", [&] { d.timerNanoseconds(timer); });
    expectLost("wait", [&] { d.wait(first); });
    expectLost("waitIdle", [&] { d.waitIdle(); });
    // Recording is not checked (the per-draw path stays cheap) and is harmless; its submit throws.
    record();
    expectLost("submit", [&] { d.submit(*cmd); });
    EXPECT_NO_THROW(d.waitIdleOrLost());

    // Queries still answer, and objects made before the loss are released normally.
    EXPECT_EQ(d.desc(buffer).size, 256u);
    EXPECT_FALSE(d.info().deviceName.empty());
    cmd.reset();
    d.destroy(pipeline);
    for (auto s : {vs, fs}) d.destroy(s);
    d.destroy(target);
    d.destroy(buffer);
    d.destroy(sampler);
    d.destroy(timer);
    EXPECT_EQ(d.liveObjects(), empty);
}

// Vulkan's blocking transfers submit work of their own: losing the device there throws
// DeviceLostError and leaves no staging buffer behind. GL makes no submission in them, so the
// same calls succeed there. Texture creation submits nothing on either.
TEST_P(NativeFaults, LossInsideBlockingTransfersLeavesNothingBehind) {
    const bool submits = GetParam() == "vulkan";
    {
        TextureHandle t = device->createTexture({.width = 8, .height = 8});
        const LiveObjects before = device->liveObjects();
        fault::arm(fault::Site::Submission, 1);
        if (submits) {
            expectLost("device lost", [&] { device->readTexture(t); });
            EXPECT_EQ(device->liveObjects(), before) << "the staging buffer was left behind";
        } else {
            EXPECT_EQ(device->readTexture(t).data.size(), 8u * 8 * 4);
        }
        device->destroy(t);
    }
    // Texture creation, on a new device (this one may be lost now; GL runs one device at a time).
    EXPECT_EQ(device->validationErrorCount(), 0u);
    device.reset();
    BackendProbe other = probeBackend(GetParam(), true);
    ASSERT_TRUE(other.available) << other.reason;
    device = std::move(other.device);  // TearDown checks it
    Device& d = *device;
    const uint64_t firedAtStart = fault::fired(fault::Site::Submission);
    const LiveObjects empty = d.liveObjects();
    // Creating a texture submits nothing on any backend (Vulkan records its first layout
    // transition for the next submission), so an armed submission failure does not fire.
    fault::arm(fault::Site::Submission, 1);
    d.destroy(d.createTexture({.width = 8, .height = 8}));
    EXPECT_EQ(fault::fired(fault::Site::Submission), firedAtStart)
        << "texture creation submitted work";
    fault::arm(fault::Site::Submission, 0);
    d.waitIdle();
    EXPECT_EQ(d.liveObjects(), empty) << "the texture was left behind";
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(NativeFaults);

// A buffer or texture larger than limits.maxAllocationSize is refused by the shared validation
// before any native call, with the same message on every backend, and the device stays usable.
// Drivers are not trusted with it: NVIDIA's GL accepted a 1 TiB buffer and then spent minutes
// zeroing it (an H200, 2026-11-27); lavapipe refuses at vkCreateBuffer, NVIDIA's Vulkan at
// vkAllocateMemory. The injected failures above stand in for what a driver reports within it.
TEST_P(NativeFaults, AllocationBeyondTheDeviceIsRefusedBeforeAnyNativeCall) {
    const DeviceLimits& l = device->info().limits;
    ASSERT_GT(l.maxAllocationSize, 0u);
    const LiveObjects before = device->liveObjects();
    const uint64_t calls = fault::calls(fault::Site::Allocation);
    const std::string limit =
        "exceed the device's maxAllocationSize (" + std::to_string(l.maxAllocationSize) + " bytes)";
    if (l.maxAllocationSize < (uint64_t(1) << 40)) {  // larger buffers are out of range anyway
        const uint64_t size = l.maxAllocationSize + 1;
        EXPECT_EQ(fe::testing::errorOf([&] {
                      device->createBuffer(
                          {.size = size, .usage = BufferUsage::Storage, .debugName = "huge"});
                  }),
                  "buffer 'huge': " + std::to_string(size) + " bytes " + limit);
    }
    // Layers of the widest RGBA32F texture, one more than fits.
    const uint32_t edge = std::min(l.maxTextureSize2D, 16384u);
    const uint64_t layerBytes = uint64_t(edge) * edge * 16;
    const uint32_t layers = uint32_t(l.maxAllocationSize / layerBytes + 1);
    ASSERT_LE(layers, l.maxTextureArrayLayers);
    const TextureDesc huge{.dimension = TextureDimension::Texture2DArray,
                           .format = Format::RGBA32F,
                           .width = edge,
                           .height = edge,
                           .depthOrLayers = layers,
                           .usage = TextureUsage::Sampled,
                           .debugName = "huge"};
    EXPECT_EQ(fe::testing::errorOf([&] { device->createTexture(huge); }),
              "texture 'huge': " + std::to_string(layerBytes * layers) + " bytes " + limit);
    EXPECT_EQ(fault::calls(fault::Site::Allocation), calls) << "a native allocation was tried";
    EXPECT_EQ(device->liveObjects(), before);
    BufferHandle b = device->createBuffer({.size = 64}, bytesOf(std::vector<uint8_t>(64, 9)));
    EXPECT_EQ(device->readBuffer(b, 0, 64), std::vector<uint8_t>(64, 9));
    device->destroy(b);
}
