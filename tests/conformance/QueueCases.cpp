// Conformance cases for the three queues (Device.h, "Queues"): work on the compute and copy
// queues, ordered against the graphics queue only by SubmitDesc::waitFor, gives the same images
// on every backend, whether the queue is a hardware queue of its own (DeviceFeatures::
// asyncCompute / asyncCopy) or shares the graphics one. What a list may record depends on its
// queue, and every mistake is the same gdi::Error everywhere, before any native call.
#include <cstring>
#include <future>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr TextureUsage kTarget = TextureUsage::RenderTarget | TextureUsage::CopySrc;

// fullscreen.vert + textured.frag: `texture` at pixel / 64, nearest, into an RGBA8 target.
struct SampledCopy {
    DeviceObjects objects;
    PipelineHandle pipeline;
    SamplerHandle nearest;
    explicit SampledCopy(Device& d) : objects(d) {
        auto shader = [&](ShaderStage stage, const char* name) {
            return objects.add(d.createShader({.stage = stage, .binary = shaders::find(name)}));
        };
        pipeline = objects.add(d.createGraphicsPipeline(
            {.vertexShader = shader(ShaderStage::Vertex, "conformance/fullscreen.vert"),
             .fragmentShader = shader(ShaderStage::Fragment, "conformance/textured.frag"),
             .colorFormats = {Format::RGBA8},
             .bindings = {{1, BindingType::SampledTexture, ShaderStage::Fragment}},
             .debugName = "queues: sampled copy"}));
        nearest = objects.add(d.createSampler({.minFilter = Filter::Nearest,
                                               .magFilter = Filter::Nearest,
                                               .addressU = AddressMode::ClampToEdge,
                                               .addressV = AddressMode::ClampToEdge}));
    }
    void record(CommandList& cmd, TextureHandle target, TextureHandle texture) const {
        cmd.beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
        cmd.setPipeline(pipeline);
        cmd.setTexture(1, texture, nearest);
        cmd.draw(3);
        cmd.endRenderPass();
    }
};

Image mappedImage(Device& d, BufferHandle readback) {
    const auto* bytes = static_cast<const uint8_t*>(d.map(readback));
    const size_t size = size_t(kCaseSize) * kCaseSize * 4;
    return {kCaseSize, kCaseSize, Format::RGBA8, std::vector<uint8_t>(bytes, bytes + size)};
}

BufferHandle readbackBuffer(DeviceObjects& o) {
    return o.add(o.device().createBuffer({.size = uint64_t(kCaseSize) * kCaseSize * 4,
                                          .usage = BufferUsage::CopyDst,
                                          .access = MemoryAccess::Readback,
                                          .debugName = "queues: readback"}));
}

// The mistakes every queue case checks: a submission mixing queues and a waitFor never issued.
void checkSubmissionErrors(Device& d, QueueKind other) {
    auto graphics = d.createCommandList();
    auto list = d.createCommandList({.queue = other});
    FE_CONFORMANCE_CHECK(list->queue() == other && graphics->queue() == QueueKind::Graphics,
                         "a list reports the queue it was made for");
    CommandList* mixed[] = {graphics.get(), list.get()};
    expectError([&] { d.submit(mixed); },
                "submit: list 0 is for the graphics queue and list 1 for the " +
                    std::string(queueKindName(other)) +
                    " queue (one submission goes to one queue)");
    const FenceValue last = d.submit(*list);
    expectError([&] { d.submit(*list, {.waitFor = last + 5}); },
                "submit: SubmitDesc::waitFor is fence " + std::to_string(last + 5) +
                    ", which was never issued");
    d.wait(d.submit(*list, {.waitFor = last}));  // a fence of the same queue: already ordered
}

// fill.comp on a compute-queue list, recorded and submitted on another thread, writes a buffer
// (3i + 1) and a gradient image; a graphics list that waits for that fence samples the image,
// and a second compute-queue list that waits for the graphics fence copies the drawn target
// into a Readback buffer. Then the mistakes a compute list refuses.
std::vector<CaseImage> computeQueue(Device& d) {
    SampledCopy copy(d);
    DeviceObjects objects(d);
    PipelineHandle fill = objects.add(d.createComputePipeline(
        {.computeShader = objects.add(d.createShader(
             {.stage = ShaderStage::Compute, .binary = shaders::find("conformance/fill.comp")})),
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                      {1, BindingType::StorageTexture, ShaderStage::Compute}}}));
    BufferHandle values =
        objects.add(d.createBuffer({.size = uint64_t(kCaseSize) * kCaseSize * 4,
                                    .usage = BufferUsage::Storage | BufferUsage::CopySrc,
                                    .debugName = "queues: values"}));
    TextureHandle gradient =
        objects.add(d.createTexture({.format = Format::RGBA32F,
                                     .width = kCaseSize,
                                     .height = kCaseSize,
                                     .usage = TextureUsage::Storage | TextureUsage::Sampled,
                                     .debugName = "queues: gradient"}));
    TextureHandle target = caseTarget(objects);
    BufferHandle readback = readbackBuffer(objects);

    auto compute = d.createCommandList({.queue = QueueKind::Compute});
    std::future<FenceValue> computed = std::async(std::launch::async, [&] {
        compute->setPipeline(fill);
        compute->setStorageBuffer(0, values);
        compute->setStorageTexture(1, gradient);
        compute->dispatch(kCaseSize / 8, kCaseSize / 8);
        return d.submit(*compute);
    });
    auto graphics = d.createCommandList();
    copy.record(*graphics, target, gradient);  // recorded while the other thread submits
    const FenceValue drawn = d.submit(*graphics, {.waitFor = computed.get()});
    compute->copyTextureToBuffer(readback, 0, target, {});
    d.wait(d.submit(*compute, {.waitFor = drawn}));

    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        return {float(x) / 64, float(y) / 64, 0.5f, 1};
    });
    std::vector<CaseImage> out;
    out.push_back(drawn8("sampled_after_compute_queue", d.readTexture(target), expected));
    out.push_back(
        exact("copied_on_compute_queue", mappedImage(d, readback), d.readTexture(target)));
    const std::vector<uint8_t> bytes = d.readBuffer(values, 0, uint64_t(kCaseSize) * kCaseSize * 4);
    bool valuesRight = true;
    for (uint32_t i = 0; i < kCaseSize * kCaseSize; ++i) {
        uint32_t v;
        std::memcpy(&v, bytes.data() + 4 * i, 4);
        valuesRight = valuesRight && v == 3 * i + 1;
    }
    FE_CONFORMANCE_CHECK(valuesRight, "the compute queue's buffer writes are read back");

    auto wrong = d.createCommandList({.queue = QueueKind::Compute});
    const std::string why =
        ": this list is for the compute queue, which runs no render passes, generateMips or "
        "resolveTexture (make the list with CommandListDesc{.queue = QueueKind::Graphics})";
    expectError([&] { wrong->beginRenderPass({.colors = {{.texture = target}}}); },
                "beginRenderPass" + why);
    expectError([&] { wrong->generateMips(gradient); }, "generateMips" + why);
    expectError([&] { wrong->resolveTexture(target, {}, target, {}); }, "resolveTexture" + why);
    expectError([&] { wrong->beginSecondary({.colors = {{.texture = target}}}); },
                "beginSecondary" + why);
    checkSubmissionErrors(d, QueueKind::Compute);
    return out;
}

// A copy-queue list moves texels from an Upload buffer through a GpuOnly buffer into a texture
// and clears a second buffer; a graphics list that waits for it samples the texture; a second
// copy-queue list that waits for the graphics fence copies the target into a Readback buffer.
// Then the mistakes a copy list refuses.
std::vector<CaseImage> copyQueue(Device& d) {
    SampledCopy copy(d);
    DeviceObjects objects(d);
    const Image source = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        return {float(4 * x) / 255, float(255 - 4 * y) / 255, float((x ^ y) & 31) / 31, 1};
    });
    const uint64_t size = source.data.size();
    BufferHandle upload = objects.add(d.createBuffer({.size = size,
                                                      .usage = BufferUsage::CopySrc,
                                                      .access = MemoryAccess::Upload,
                                                      .debugName = "queues: upload"}));
    std::memcpy(d.map(upload), source.data.data(), size);
    BufferHandle staging =
        objects.add(d.createBuffer({.size = size,
                                    .usage = BufferUsage::CopySrc | BufferUsage::CopyDst,
                                    .debugName = "queues: staging"}));
    const std::vector<uint32_t> ones(64, 0xFFFFFFFFu);
    BufferHandle cleared = objects.add(d.createBuffer(
        {.size = 256, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}, bytesOf(ones)));
    TextureHandle texture =
        objects.add(d.createTexture({.width = kCaseSize,
                                     .height = kCaseSize,
                                     .usage = TextureUsage::Sampled | TextureUsage::CopyDst,
                                     .debugName = "queues: uploaded"}));
    TextureHandle target = caseTarget(objects);
    BufferHandle readback = readbackBuffer(objects);

    auto transfer = d.createCommandList({.queue = QueueKind::Copy});
    transfer->pushDebugGroup("upload");
    transfer->copyBuffer(staging, 0, upload, 0, size);
    transfer->copyBufferToTexture(texture, {}, staging, 0);
    transfer->clearBuffer(cleared, 64, 128, 0x01020304u);
    transfer->popDebugGroup();
    const FenceValue uploaded = d.submit(*transfer);
    auto graphics = d.createCommandList();
    copy.record(*graphics, target, texture);
    const FenceValue drawn = d.submit(*graphics, {.waitFor = uploaded});
    transfer->copyTextureToBuffer(readback, 0, target, {});
    d.wait(d.submit(*transfer, {.waitFor = drawn}));

    std::vector<CaseImage> out;
    // Nearest sampling of 8-bit texels into an 8-bit target copies them exactly.
    out.push_back(exact("sampled_after_copy_queue", d.readTexture(target), source));
    out.push_back(exact("copied_on_copy_queue", mappedImage(d, readback), source));
    const std::vector<uint8_t> clearedBytes = d.readBuffer(cleared, 0, 256);
    bool clearRight = true;
    for (uint32_t i = 0; i < 64; ++i) {
        uint32_t v;
        std::memcpy(&v, clearedBytes.data() + 4 * i, 4);
        clearRight = clearRight && v == (i >= 16 && i < 48 ? 0x01020304u : 0xFFFFFFFFu);
    }
    FE_CONFORMANCE_CHECK(clearRight, "clearBuffer on the copy queue fills [64, 192) only");

    auto wrong = d.createCommandList({.queue = QueueKind::Copy});
    const std::string copyOnly =
        ": this list is for the copy queue, which runs copies, clearBuffer, barriers and debug "
        "groups only (make the list with CommandListDesc{.queue = QueueKind::";
    expectError([&] { wrong->dispatch(1); }, "dispatch" + copyOnly + "Compute})");
    expectError([&] { wrong->dispatchIndirect(staging, 0); },
                "dispatchIndirect" + copyOnly + "Compute})");
    if (d.info().features.timestamps) {
        TimerHandle timer = objects.add(d.createTimer());
        expectError([&] { wrong->beginTimer(timer); }, "beginTimer" + copyOnly + "Compute})");
        QuerySetHandle stamps =
            objects.add(d.createQuerySet({.type = QueryType::Timestamp, .count = 1}));
        expectError([&] { wrong->writeTimestamp(stamps, 0); },
                    "writeTimestamp" + copyOnly + "Compute})");
        expectError([&] { wrong->resolveQueries(stamps, 0, 1, staging, 0); },
                    "resolveQueries" + copyOnly + "Compute})");
    }
    expectError([&] { wrong->beginRenderPass({.colors = {{.texture = target}}}); },
                "beginRenderPass" + copyOnly + "Graphics})");
    expectError([&] { wrong->generateMips(texture); }, "generateMips" + copyOnly + "Graphics})");
    checkSubmissionErrors(d, QueueKind::Copy);
    return out;
}

}  // namespace

std::vector<Case> queueCases() {
    return {
        {"compute_queue", computeQueue},
        {"copy_queue", copyQueue},
    };
}

}  // namespace fe::conformance
