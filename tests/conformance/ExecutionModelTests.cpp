// The execution-model conformance cases that use threads, as a small test program of its own:
// `tools/run-thread-sanitized-tests.sh` builds just this under ThreadSanitizer (CI), and the
// normal suite runs it too. Each case runs on every backend that starts here.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <thread>

#include "Conformance.h"
#include "fe/gdi/Backend.h"

namespace fe::conformance {
namespace {

class ExecutionModel : public ::testing::TestWithParam<std::string> {};

const Case& caseNamed(const std::string& name) {
    for (const Case& c : cases())
        if (c.name == name) return c;
    throw std::runtime_error("no conformance case " + name);
}

TEST_P(ExecutionModel, ThreadedCasesPass) {
    const std::string backend = GetParam();
    if (!gdi::probeBackend(backend, false).available)
        GTEST_SKIP() << backend << " is not available here";
    auto device = gdi::createDevice({.backend = backend, .validation = true});
    for (const char* name : {"submission_order", "record_on_threads", "create_while_recording",
                             "destroy_while_in_flight", "mapped_upload_ring", "async_readback",
                             "data_read_at_execution", "secondary_lists_in_one_pass",
                             "reusable_secondary_lists", "compute_queue"}) {
        const CaseResult r = runCase(*device, caseNamed(name));
        EXPECT_TRUE(r.passed) << backend << " " << name << ": " << r.message;
    }
    EXPECT_EQ(device->validationErrorCount(), 0u);
}

// Misuse: one list used by two threads at once. Each thread calls `call` in a loop until one of
// them is refused (or 10 s pass: on two busy cores a collision needs a preemption inside a call,
// which comes within milliseconds). Returns the first refusal's message, "" if none came; any
// other Error fails the test.
std::string collide(const std::function<void()>& first, const std::function<void()>& second) {
    std::atomic<bool> refused{false};
    std::atomic<int> ready{0};
    std::string message, unexpected;
    std::mutex m;
    auto loop = [&](const std::function<void()>& call) {
        ++ready;
        while (ready.load() < 2) std::this_thread::yield();
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (!refused.load(std::memory_order_relaxed) &&
               std::chrono::steady_clock::now() < deadline) {
            for (int i = 0; i < 256 && !refused.load(std::memory_order_relaxed); ++i) {
                try {
                    call();
                } catch (const gdi::Error& e) {
                    std::lock_guard lock(m);
                    const std::string what = e.what();
                    if (what.find("in use by another thread") == std::string::npos)
                        unexpected = what;
                    else if (message.empty())
                        message = what;
                    refused = true;
                }
            }
        }
    };
    std::thread a(loop, first), b(loop, second);
    a.join(), b.join();
    EXPECT_EQ(unexpected, "");
    return message;
}

class ListOnTwoThreads : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        const std::string backend = GetParam();
        if (!gdi::probeBackend(backend, false).available)
            GTEST_SKIP() << backend << " is not available here";
        device = gdi::createDevice({.backend = backend, .validation = true});
        target = device->createTexture(
            {.format = gdi::Format::RGBA8,
             .width = 16,
             .height = 16,
             .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::CopySrc});
        list = device->createCommandList();
    }
    // The list still works after the refusals: a cleared target reads back cleared.
    void expectListStillRecords() {
        list->beginRenderPass({.colors = {{.texture = target, .clear = {0, 1, 0, 1}}}});
        list->endRenderPass();
        device->wait(device->submit(*list));
        EXPECT_EQ(device->readTexture(target).texel(7, 7)[1], 1.0f);
        EXPECT_EQ(device->validationErrorCount(), 0u);
    }
    std::unique_ptr<gdi::Device> device;
    gdi::TextureHandle target;
    std::unique_ptr<gdi::CommandList> list;
};

// Two threads recording one list: the one that arrives second gets the Error, on every backend
// (before the check, GL crashed and Vulkan's layer reported UNASSIGNED-Threading-MultipleThreads).
TEST_P(ListOnTwoThreads, RecordingIsRefused) {
    list->beginRenderPass({.colors = {{.texture = target}}});
    auto scissor = [this] { list->setScissor({0, 0, 8, 8}); };
    const std::string message = collide(scissor, scissor);
    EXPECT_EQ(message.rfind("setScissor: the command list is in use by another thread", 0), 0u)
        << message;
    auto label = [this] { list->insertDebugLabel("label"); };
    EXPECT_EQ(collide(label, label).rfind("insertDebugLabel: ", 0), 0u);
    list->endRenderPass();
    device->wait(device->submit(*list));
    expectListStillRecords();
}

// Submitting a list while another thread records it is refused too (on whichever side comes second).
TEST_P(ListOnTwoThreads, SubmitWhileRecordingIsRefused) {
    const uint32_t value = 1;
    const std::string message =
        collide([this, &value] { list->setConstants(0, gdi::bytesOf(value)); },
                [this] { (void)device->submit(*list); });
    EXPECT_NE(message, "");
    device->waitIdle();
    expectListStillRecords();
}

// Devices made and destroyed on one thread while another thread works on its own device, with
// validation on (what examples/materials does with two renderers). Vulkan's validation layer
// (1.3.239, Debian 12) keeps its per-device data in one process-wide map that it changes when a
// device or instance is made or destroyed and reads in every call, unlocked; the backend
// excludes the two (gdi::NativeLayerLock); without that, this crashed inside the layer. On
// gl-egl every device shares one EGLDisplay, which one device's eglTerminate took from the other
// (eglMakeCurrent failed) until the display was counted (GlPlatform.cpp).
TEST_P(ExecutionModel, DevicesComeAndGoWhileAnotherWorks) {
    const std::string backend = GetParam();
    if (!gdi::probeBackend(backend, false).available)
        GTEST_SKIP() << backend << " is not available here";
    std::atomic<bool> done{false};
    std::string failure;
    std::mutex m;
    auto fail = [&](const std::string& what) {
        std::lock_guard lock(m);
        if (failure.empty()) failure = what;
    };
    std::thread worker([&] {
        try {
            auto device = gdi::createDevice({.backend = backend, .validation = true});
            const std::vector<uint32_t> words(256, 7u);
            uint64_t rounds = 0;
            while (!done.load() || rounds < 8) {
                const gdi::BufferHandle b = device->createBuffer(
                    {.size = 1024,
                     .usage = gdi::BufferUsage::Storage | gdi::BufferUsage::CopySrc |
                              gdi::BufferUsage::CopyDst});
                device->writeBuffer(b, 0, gdi::bytesOf(words));
                auto list = device->createCommandList();
                const gdi::TextureHandle t =
                    device->createTexture({.format = gdi::Format::RGBA8,
                                           .width = 8,
                                           .height = 8,
                                           .usage = gdi::TextureUsage::RenderTarget});
                list->beginRenderPass({.colors = {{.texture = t, .clear = {0, 1, 0, 1}}}});
                list->endRenderPass();
                device->wait(device->submit(*list));
                if (device->readBuffer(b, 4, 4)[0] != 7) fail("buffer read back wrong");
                device->destroy(t);
                device->destroy(b);
                ++rounds;
            }
            if (device->validationErrorCount() != 0)
                fail("validation errors on the working device");
        } catch (const std::exception& e) {
            fail(e.what());
        }
    });
    for (int i = 0; i < 60; ++i) {
        try {
            auto device = gdi::createDevice({.backend = backend, .validation = true});
            (void)device->createBuffer({.size = 256, .usage = gdi::BufferUsage::Storage});
        } catch (const std::exception& e) {
            fail(e.what());
        }
    }
    done = true;
    worker.join();
    EXPECT_EQ(failure, "");
}

INSTANTIATE_TEST_SUITE_P(Backends, ListOnTwoThreads,
                         ::testing::Values("vulkan", "gl-egl", "gl-osmesa"), [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n) c = c == '-' ? '_' : c;
                             return n;
                         });

INSTANTIATE_TEST_SUITE_P(Backends, ExecutionModel,
                         ::testing::Values("vulkan", "gl-egl", "gl-osmesa"), [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n) c = c == '-' ? '_' : c;
                             return n;
                         });

}  // namespace
}  // namespace fe::conformance
