// Mistakes with lists themselves: outliving the device, other threads, refused submits,
// secondary lists, lists and timers of another device.
#include "DeviceErrors.h"

using namespace fe::gdi;
using fe::testing::errorOf;

// A list destroyed after its device is safe, and recording into it is an Error, not a crash.
TEST_P(DeviceErrors, ListsMayOutliveTheirDevice) {
    auto other = createDevice({.backend = GetParam()});
    auto recorded = other->createCommandList();
    auto submitted = other->createCommandList();
    auto t = other->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    recorded->beginRenderPass({.colors = {{.texture = t}}});
    submitted->beginRenderPass({.colors = {{.texture = t}}});
    submitted->endRenderPass();
    other->submit(*submitted);
    auto empty = other->createCommandList();
    other.reset();  // lists first would be the right order
    for (auto* list : {recorded.get(), submitted.get(), empty.get()}) {
        EXPECT_NE(
            errorOf([&] { list->draw(3); }).find("the device of this command list was destroyed"),
            std::string::npos);
        EXPECT_NE(errorOf([&] {
                      list->setScissor({});
                  }).find("the device of this command list was destroyed"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] {
                      list->clearBuffer({1});
                  }).find("the device of this command list was destroyed"),
                  std::string::npos);
    }
    recorded.reset();
    submitted.reset();
    empty.reset();
}

// Every call of a list whose device is gone is that Error, naming the call, on every backend
// (before: binding setters, beginRenderPass on GL and beginSecondary read the freed device and
// crashed; other calls named "recording" on Vulkan, or said "dispatch without a pipeline").
TEST_P(DeviceErrors, EveryCallOfAnOrphanedListNamesItself) {
    using Call = std::pair<const char*, std::function<void(CommandList&)>>;
    const BufferHandle b{1};
    const TextureHandle t{1};
    const float four[4] = {};
    const TextureBarrier tb{.texture = t};
    const BufferBarrier bb{.buffer = b};
    const std::vector<Call> calls = {
        {"beginRenderPass",
         [&](CommandList& l) { l.beginRenderPass({.colors = {{.texture = t}}}); }},
        {"endRenderPass", [](CommandList& l) { l.endRenderPass(); }},
        {"setPipeline", [](CommandList& l) { l.setPipeline({1}); }},
        {"setViewport", [](CommandList& l) { l.setViewport({.width = 4, .height = 4}); }},
        {"setScissor",
         [](CommandList& l) {
             l.setScissor({0, 0, 4, 4});
         }},
        {"setBlendConstant",
         [](CommandList& l) {
             l.setBlendConstant({0, 0, 0, 0});
         }},
        {"setStencilReference", [](CommandList& l) { l.setStencilReference(1); }},
        {"setDepthBias", [](CommandList& l) { l.setDepthBias(1, 1); }},
        {"setConstants", [&](CommandList& l) { l.setConstants(0, bytesOf(four)); }},
        {"setVertexBuffer", [&](CommandList& l) { l.setVertexBuffer(0, b); }},
        {"setIndexBuffer", [&](CommandList& l) { l.setIndexBuffer(b, IndexType::U16); }},
        {"setUniformBuffer", [&](CommandList& l) { l.setUniformBuffer(0, b); }},
        {"setStorageBuffer", [&](CommandList& l) { l.setStorageBuffer(0, b); }},
        {"setTexture", [&](CommandList& l) { l.setTexture(0, t, {1}); }},
        {"setStorageTexture", [&](CommandList& l) { l.setStorageTexture(0, t); }},
        {"draw", [](CommandList& l) { l.draw(3); }},
        {"drawIndexed", [](CommandList& l) { l.drawIndexed(3); }},
        {"dispatch", [](CommandList& l) { l.dispatch(1); }},
        {"drawIndirect", [&](CommandList& l) { l.drawIndirect(b, 0); }},
        {"drawIndexedIndirect", [&](CommandList& l) { l.drawIndexedIndirect(b, 0); }},
        {"drawIndirectCount", [&](CommandList& l) { l.drawIndirectCount(b, 0, b, 0, 1); }},
        {"drawIndexedIndirectCount",
         [&](CommandList& l) { l.drawIndexedIndirectCount(b, 0, b, 0, 1); }},
        {"dispatchIndirect", [&](CommandList& l) { l.dispatchIndirect(b, 0); }},
        {"generateMips", [&](CommandList& l) { l.generateMips(t); }},
        {"copyBuffer", [&](CommandList& l) { l.copyBuffer(b, 0, b, 4, 4); }},
        {"clearBuffer", [&](CommandList& l) { l.clearBuffer(b); }},
        {"copyTexture", [&](CommandList& l) { l.copyTexture(t, t); }},
        {"copyBufferToTexture",
         [&](CommandList& l) { l.copyBufferToTexture(t, Subresource{}, b, 0); }},
        {"copyTextureToBuffer",
         [&](CommandList& l) { l.copyTextureToBuffer(b, 0, t, Subresource{}); }},
        {"beginTimer", [](CommandList& l) { l.beginTimer({1}); }},
        {"endTimer", [](CommandList& l) { l.endTimer({1}); }},
        {"beginQuery", [](CommandList& l) { l.beginQuery({1}, 0); }},
        {"endQuery", [](CommandList& l) { l.endQuery({1}, 0); }},
        {"writeTimestamp", [](CommandList& l) { l.writeTimestamp({1}, 0); }},
        {"resolveQueries", [&](CommandList& l) { l.resolveQueries({1}, 0, 1, b, 0); }},
        {"pushDebugGroup", [](CommandList& l) { l.pushDebugGroup("g"); }},
        {"popDebugGroup", [](CommandList& l) { l.popDebugGroup(); }},
        {"insertDebugLabel", [](CommandList& l) { l.insertDebugLabel("l"); }},
        {"discardTexture", [&](CommandList& l) { l.discardTexture(t); }},
        {"setAutomaticBarriers", [](CommandList& l) { l.setAutomaticBarriers(false); }},
        {"barrier", [&](CommandList& l) { l.barrier(tb); }},
        {"barrier", [&](CommandList& l) { l.barrier(bb); }},
        {"beginSecondary", [&](CommandList& l) { l.beginSecondary({.colors = {{.texture = t}}}); }},
        {"endSecondary", [](CommandList& l) { l.endSecondary(); }},
        {"executeSecondary",
         [](CommandList& l) { l.executeSecondary(std::span<CommandList* const>()); }},
    };
    for (bool inPass : {false, true}) {
        auto other = createDevice({.backend = GetParam()});
        auto target =
            other->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
        std::vector<std::unique_ptr<CommandList>> lists;
        for (size_t i = 0; i < calls.size(); ++i) {
            lists.push_back(other->createCommandList());
            if (inPass) lists.back()->beginRenderPass({.colors = {{.texture = target}}});
        }
        other.reset();
        for (size_t i = 0; i < calls.size(); ++i)
            EXPECT_EQ(
                errorOf([&] { calls[i].second(*lists[i]); }),
                std::string(calls[i].first) +
                    ": the device of this command list was destroyed (destroy lists before their device)")
                << (inPass ? "in a pass: " : "") << calls[i].first;
    }
}

// Misuse across threads: objects destroyed on one thread while another records with them. The
// recording calls get "invalid or destroyed" Errors or the submit refuses the list; nothing
// crashes and the validation layer stays silent. (Vulkan moved the object out of its slot at
// destroy: a copyBuffer that had just found the buffer recorded VK_NULL_HANDLE, and the layer
// crashed on it.) Racy by design, so not in the ThreadSanitizer program.
TEST_P(DeviceErrors, ObjectsDestroyedWhileAnotherThreadRecordsAreErrors) {
    std::atomic<uint32_t> current{0}, refused{0};
    std::atomic<bool> stop{false};
    // Up to 1500 buffers, or until 20 refusals show both threads meeting (most runs: a few
    // hundred buffers; on a software rasterizer each submit of a GL context takes a while).
    std::thread destroyer([&] {
        for (int i = 0; i < 1500 && refused < 20; ++i) {
            const BufferHandle b = device->createBuffer(
                {.size = 256, .debugName = "a buffer with a name too long for SSO"});
            current = b.id;
            std::this_thread::yield();
            device->destroy(b);
        }
        stop = true;
    });
    auto list = device->createCommandList();
    while (!stop) {
        try {
            for (int i = 0; i < 50; ++i) {
                const BufferHandle b{current.load()};
                list->copyBuffer(b, 0, b, 128, 64);
                list->setUniformBuffer(0, b, 0, 64);
            }
        } catch (const Error& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find("invalid or destroyed buffer handle"),
                      std::string::npos)
                << e.what();
        }
        try {
            device->wait(device->submit(*list));
        } catch (const Error& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find("destroyed after it was recorded"),
                      std::string::npos)
                << e.what();
            list = device->createCommandList();  // the refused one keeps its recording
        }
    }
    destroyer.join();
    EXPECT_GT(refused.load(), 0u);
}

// A refused submit runs none of its lists and leaves each as it was: here the second list's
// pass is still open, so the first list's clear must not run, and both lists are intact to be
// submitted once the mistake is mended. A list twice in one submit is refused the same way.
TEST_P(DeviceErrors, RefusedSubmitRunsNothingAndKeepsItsLists) {
    Device& d = *device;
    const TextureUsage usage = TextureUsage::RenderTarget | TextureUsage::CopySrc;
    const TextureHandle a = d.createTexture({.width = 4, .height = 4, .usage = usage});
    const TextureHandle b = d.createTexture({.width = 4, .height = 4, .usage = usage});
    auto clear = [&](TextureHandle t, float red) {
        auto c = d.createCommandList();
        c->beginRenderPass({.colors = {{.texture = t, .clear = {red, 0, 1, 1}}}});
        c->endRenderPass();
        return c;
    };
    d.wait(d.submit(*clear(a, 0)));
    auto first = clear(a, 1);
    auto second = d.createCommandList();
    second->beginRenderPass({.colors = {{.texture = b, .clear = {0, 1, 0, 1}}}});
    std::array<CommandList*, 2> both = {first.get(), second.get()};
    EXPECT_NE(errorOf([&] { d.submit(both); }).find("render pass still open"), std::string::npos);
    d.waitIdle();
    EXPECT_EQ(d.readTexture(a).texel(0, 0)[0], 0.0f) << "the refused submission ran its first list";
    std::array<CommandList*, 2> twice = {first.get(), first.get()};
    EXPECT_NE(errorOf([&] { d.submit(twice); }).find("the same list at 0 and 1"),
              std::string::npos);
    second->endRenderPass();
    d.wait(d.submit(both));
    EXPECT_EQ(d.readTexture(a).texel(0, 0)[0], 1.0f) << "the first list's recording was lost";
    EXPECT_EQ(d.readTexture(b).texel(0, 0)[1], 1.0f);
    d.destroy(a);
    d.destroy(b);
}

// Each rule of secondary lists (Device.h) gives its gdi::Error on every backend, before any
// native call: a secondary list is submitted, executed unended or for another pass, begun on a
// non-empty list, recorded after its end; the primary may draw in a pass of secondary lists, and
// after each executeSecondary (and after the pass) its pipeline and bindings are unset.
TEST_P(DeviceErrors, SecondaryListRules) {
    Device& d = *device;
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto ubo = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::CopySrc;
    auto t = d.createTexture({.width = 8, .height = 8, .usage = rt});
    auto wide = d.createTexture({.width = 16, .height = 8, .usage = rt});
    const RenderPassDesc pass{.colors = {{.texture = t}}, .secondaryLists = true};
    auto primary = d.createCommandList();
    auto part = d.createCommandList();
    auto has = [](const std::string& error, const char* text) {
        return error.find(text) != std::string::npos
                   ? ::testing::AssertionSuccess()
                   : ::testing::AssertionFailure() << "got: " << error;
    };
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }),
                    "outside a render pass begun with secondaryLists"));
    primary->beginRenderPass(pass);
    primary->setPipeline(p);  // the primary's own draws, between the lists it executes
    primary->setViewport({0, 0, 4, 4});
    primary->draw(3);
    EXPECT_TRUE(
        has(errorOf([&] { primary->executeSecondary(*part); }), "list 0 is not a secondary list"));
    part->beginSecondary(pass);
    EXPECT_TRUE(has(errorOf([&] { part->beginRenderPass(pass); }),
                    "beginRenderPass is not allowed in a secondary list"));
    EXPECT_TRUE(has(errorOf([&] { part->endRenderPass(); }),
                    "endRenderPass is not allowed in a secondary list"));
    EXPECT_TRUE(has(errorOf([&] { part->copyBuffer(ubo, 0, ubo, 128, 4); }),
                    "copyBuffer is not allowed inside a render pass"));
    EXPECT_TRUE(
        has(errorOf([&] { d.submit(*part); }), "a secondary list is executed by a primary list"));
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }),
                    "list 0 is still recording (missing endSecondary)"));
    part->setPipeline(p);
    part->draw(3);
    part->pushDebugGroup("open");
    EXPECT_TRUE(
        has(errorOf([&] { part->endSecondary(); }), "endSecondary: 1 debug group(s) not popped"));
    part->popDebugGroup();
    part->endSecondary();
    EXPECT_TRUE(has(errorOf([&] { part->draw(3); }), "draw after endSecondary"));
    EXPECT_TRUE(has(errorOf([&] { part->setPipeline(p); }), "setPipeline after endSecondary"));
    EXPECT_TRUE(has(errorOf([&] { part->endSecondary(); }), "endSecondary without beginSecondary"));
    auto other = d.createCommandList();
    other->beginSecondary({.colors = {{.texture = wide}}});
    other->endSecondary();
    EXPECT_TRUE(has(
        errorOf([&] { primary->executeSecondary(*other); }),
        "list 0 was begun for another pass (RGBA8; 1 sample(s); 16x8) than the open one (RGBA8; 1 sample(s); 8x8)"));
    std::array<CommandList*, 2> twice = {part.get(), part.get()};
    EXPECT_TRUE(
        has(errorOf([&] { primary->executeSecondary(twice); }), "the same list at 0 and 1"));
    primary->executeSecondary(*part);
    const std::string unset = errorOf([&] { primary->draw(3); });
    EXPECT_FALSE(unset.empty()) << "after executeSecondary the primary has no pipeline";
    primary->executeSecondary(*part);  // a secondary list runs any number of times
    primary->setPipeline(p);
    primary->draw(3);
    primary->endRenderPass();
    // An ended list is recorded anew by beginSecondary; a list with something recorded cannot
    // begin a secondary one.
    part->beginSecondary(pass);
    part->endSecondary();
    auto used = d.createCommandList();
    used->setUniformBuffer(0, ubo);
    EXPECT_TRUE(has(errorOf([&] { used->beginSecondary(pass); }),
                    "beginSecondary: the list must be empty"));
    // The primary's bindings do not survive a pass of secondary lists.
    auto uboPipeline = d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    auto again = d.createCommandList();
    again->setUniformBuffer(0, ubo);
    again->beginRenderPass(pass);
    again->endRenderPass();
    again->beginRenderPass({.colors = {{.texture = t}}});
    again->setPipeline(uboPipeline);
    EXPECT_TRUE(has(errorOf([&] { again->draw(3); }), "missing binding for slot(s) 0"));
    again->endRenderPass();
    d.wait(d.submit(*primary));
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*other); }),
                    "outside a render pass begun with secondaryLists"));
    for (auto pl : {p, uboPipeline}) d.destroy(pl);
    d.destroy(vs);
    d.destroy(fs);
    d.destroy(ubo);
    d.destroy(t);
    d.destroy(wide);
}

// A list made by one device submitted to another: GL replayed it on the wrong context (whose
// objects share the names), Vulkan's validation layer objected.
TEST_P(DeviceErrors, ListOfAnotherDeviceIsRefused) {
    auto other = createDevice({.backend = GetParam(), .validation = true});
    const BufferHandle mine = device->createBuffer({.size = 16});
    const BufferHandle theirs = other->createBuffer({.size = 16});
    auto list = other->createCommandList();
    list->clearBuffer(theirs, 0, 16, 0x5555u);
    EXPECT_NE(errorOf([&] { device->submit(*list); }).find("a command list of another device"),
              std::string::npos);
    const std::vector<uint8_t> bytes = device->readBuffer(mine, 0, 16);
    EXPECT_EQ(bytes, std::vector<uint8_t>(16, 0));  // untouched
    other->wait(other->submit(*list));
    other->destroy(theirs);
    device->destroy(mine);
}

// executeSecondary refuses, the same on every backend, a secondary list of another device and a
// list executing itself (the checks both backends share: validate::executedLists).
TEST_P(DeviceErrors, SecondaryListOfAnotherDeviceOrItselfIsRefused) {
    auto other = createDevice({.backend = GetParam(), .validation = true});
    const TextureHandle target = device->createTexture(
        {.format = Format::RGBA8, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    const TextureHandle theirs = other->createTexture(
        {.format = Format::RGBA8, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    const RenderPassDesc pass{.colors = {{.texture = target}}, .secondaryLists = true};
    auto foreign = other->createCommandList();
    foreign->beginSecondary({.colors = {{.texture = theirs}}, .secondaryLists = true});
    foreign->endSecondary();
    auto list = device->createCommandList();
    list->beginRenderPass(pass);
    EXPECT_EQ(errorOf([&] { list->executeSecondary(*foreign); }),
              "executeSecondary: list 0 belongs to another device");
    EXPECT_EQ(errorOf([&] { list->executeSecondary(*list); }),
              "executeSecondary: a list cannot execute itself");
    list->endRenderPass();
    device->wait(device->submit(*list));
    EXPECT_EQ(device->validationErrorCount(), 0u);
    other->destroy(theirs);
    device->destroy(target);
}

// Timers: one span per recording. Ended without a begin, GL read a negative time and Vulkan's
// layer objected; begun twice or left open, the backends measured different spans.
TEST_P(DeviceErrors, TimerMisuse) {
    const TimerHandle timer = device->createTimer();
    {
        auto cmd = device->createCommandList();
        EXPECT_NE(errorOf([&] {
                      cmd->endTimer(timer);
                  }).find("endTimer: the timer was not begun in this recording"),
                  std::string::npos);
        cmd->beginTimer(timer);
        EXPECT_NE(errorOf([&] {
                      cmd->beginTimer(timer);
                  }).find("beginTimer: the timer was already begun"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] {
                      device->submit(*cmd);
                  }).find("a timer begun in this recording was not ended"),
                  std::string::npos);
        cmd->endTimer(timer);
        EXPECT_NE(
            errorOf([&] { cmd->endTimer(timer); }).find("endTimer: the timer was already ended"),
            std::string::npos);
        EXPECT_FALSE(device->timerNanoseconds(timer).has_value());  // never submitted
        const FenceValue f = device->submit(*cmd);
        device->wait(f);
        if (device->info().features.timestamps) {
            const std::optional<double> ns = device->timerNanoseconds(timer);
            ASSERT_TRUE(ns.has_value());
            EXPECT_GE(*ns, 0.0);
        }
    }
    {
        auto cmd = device->createCommandList();  // a new recording: the timer may be used again
        cmd->beginTimer(timer);
        cmd->endTimer(timer);
        device->wait(device->submit(*cmd));
    }
    device->destroy(timer);
}
