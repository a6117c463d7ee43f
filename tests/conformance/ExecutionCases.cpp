// Conformance cases for command execution: recording is not executing, on every backend.
// A CommandList only records. Its commands run at Device::submit, in submission order, and
// read buffers and textures as they are when the work runs. So a list never submitted changes
// nothing, data written after recording and before submit is what a draw sees, lists may be
// recorded on several threads at once while another thread creates and uploads, objects may be
// destroyed while the GPU still uses them (but a list that uses a destroyed object cannot be
// submitted), mapped Upload and Readback memory is paced by fences, and explicit buffer and
// subresource barriers order the work. A backend that runs commands as they are recorded fails
// these cases.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <exception>
#include <latch>
#include <memory>
#include <random>
#include <thread>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr TextureUsage kTarget =
    TextureUsage::RenderTarget | TextureUsage::CopySrc | TextureUsage::Sampled;
constexpr Rect kWhole{0, 0, kCaseSize, kCaseSize};

// The uniform block of fullscreen_ubo.vert, ubo_color.frag and textured_uv.frag.
struct Params {
    float color[4];  // ubo_color.frag: the colour; textured_uv.frag: uv scale (xy) and offset (zw)
    float depth[4];  // x: the triangle's depth; y: textured_uv.frag's level of detail
};
Params paramsOf(Texel color, float lod = 0) {
    return {{color[0], color[1], color[2], color[3]}, {0.5f, lod, 0, 0}};
}

// An 8-bit colour: k/255 survives the float-to-unorm conversion of clears and draws.
Texel rgb8(uint32_t r, uint32_t g, uint32_t b) {
    return {r / 255.0f, g / 255.0f, b / 255.0f, 1.0f};
}
const Texel kBlack = rgb8(0, 0, 0);

TextureHandle target(DeviceObjects& objects) {
    return objects.add(objects.device().createTexture({.width = kCaseSize,
                                                       .height = kCaseSize,
                                                       .usage = kTarget,
                                                       .debugName = "execution target"}));
}

void beginPass(CommandList& cmd, TextureHandle t, Texel clear, LoadOp load = LoadOp::Clear) {
    cmd.beginRenderPass(
        {.colors = {
             {.texture = t, .load = load, .clear = {clear[0], clear[1], clear[2], clear[3]}}}});
}

// `background`, with `inside` over rectangle r.
Image rectImage(Texel background, Rect r, Texel inside) {
    return expectImage(Format::RGBA8, [=](uint32_t x, uint32_t y) {
        const bool in =
            int32_t(x) >= r.x && x < r.x + r.width && int32_t(y) >= r.y && y < r.y + r.height;
        return in ? inside : background;
    });
}

// Eight 8-pixel columns, column f in bandColor(f): one per frame of the multi-frame cases.
Texel bandColor(uint32_t f) { return rgb8(30 * f + 20, 240 - 25 * f, 100 + 15 * f); }
Image bandsImage() {
    return expectImage(Format::RGBA8, [](uint32_t x, uint32_t) { return bandColor(x / 8); });
}
Rect band(uint32_t f) { return {int32_t(8 * f), 0, 8, kCaseSize}; }

CaseImage rendered(const std::string& name, Image image, Image expected) {
    return within(
        name, std::move(image), std::move(expected), 1.0 / 255.0,
        "k/255 colours cleared or drawn into an 8-bit target: one step of float-to-unorm rounding");
}

template <class T>
std::vector<uint8_t> bytesVector(const T& value) {
    const ByteSpan b = bytesOf(value);
    return {reinterpret_cast<const uint8_t*>(b.data()),
            reinterpret_cast<const uint8_t*>(b.data() + b.size())};
}

// fullscreen_ubo.vert + ubo_color.frag into RGBA8: a full-screen triangle in its uniform
// block's colour, cut to a rectangle by the scissor.
struct ColorDraw {
    DeviceObjects objects;
    ShaderHandle vs, fs;
    PipelineHandle pipeline;
    explicit ColorDraw(Device& d) : objects(d) {
        vs = objects.add(
            d.createShader({.stage = ShaderStage::Vertex,
                            .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
        fs = objects.add(d.createShader({.stage = ShaderStage::Fragment,
                                         .binary = shaders::find("conformance/ubo_color.frag")}));
        pipeline = objects.add(d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .colorFormats = {Format::RGBA8},
             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
             .debugName = "execution colour"}));
    }
    // A GpuOnly uniform block of colour c, owned by `owner`.
    BufferHandle params(DeviceObjects& owner, Texel c) const {
        const Params p = paramsOf(c);
        return owner.add(
            owner.device().createBuffer({.size = sizeof p,
                                         .usage = BufferUsage::Uniform | BufferUsage::CopyDst,
                                         .debugName = "colour"},
                                        bytesOf(p)));
    }
    // Inside a pass: the block at `offset` of `ubo` over `rect`.
    void draw(CommandList& cmd, BufferHandle ubo, Rect rect, uint64_t offset = 0) const {
        cmd.setPipeline(pipeline);
        cmd.setUniformBuffer(0, ubo, offset, sizeof(Params));
        cmd.setScissor(rect);
        cmd.draw(3);
    }
};

// fullscreen_ubo.vert + textured_uv.frag into RGBA8: the texture at uv = pixel / 64 (scale 1,
// offset 0) and the block's level of detail.
struct TexturedDraw {
    DeviceObjects objects;
    ShaderHandle vs, fs;
    SamplerHandle nearest;  // base level only (MipFilter::None), clamped
    explicit TexturedDraw(Device& d) : objects(d) {
        vs = objects.add(
            d.createShader({.stage = ShaderStage::Vertex,
                            .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
        fs = objects.add(d.createShader({.stage = ShaderStage::Fragment,
                                         .binary = shaders::find("conformance/textured_uv.frag")}));
        nearest = objects.add(d.createSampler({.minFilter = Filter::Nearest,
                                               .magFilter = Filter::Nearest,
                                               .addressU = AddressMode::ClampToEdge,
                                               .addressV = AddressMode::ClampToEdge}));
    }
    GraphicsPipelineDesc desc() const {
        return {.vertexShader = vs,
                .fragmentShader = fs,
                .colorFormats = {Format::RGBA8},
                .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                             {1, BindingType::SampledTexture, ShaderStage::Fragment}},
                .debugName = "execution textured"};
    }
    BufferHandle params(DeviceObjects& owner, float lod) const {
        const Params p = paramsOf({1, 1, 0, 0}, lod);
        return owner.add(owner.device().createBuffer(
            {.size = sizeof p, .usage = BufferUsage::Uniform}, bytesOf(p)));
    }
    // One full-screen draw of `texture` through `sampler` (default: nearest) in an open pass.
    void draw(CommandList& cmd, PipelineHandle pipeline, BufferHandle ubo, TextureHandle texture,
              SamplerHandle sampler = {}) const {
        cmd.setPipeline(pipeline);
        cmd.setUniformBuffer(0, ubo);
        cmd.setTexture(1, texture, sampler ? sampler : nearest);
        cmd.draw(3);
    }
};

// A 4x4 texture of 16 distinct texels, and how textured_uv.frag shows it (16x magnified).
Texel tileTexel(uint32_t i) { return rgb8(i * 16, 255 - i * 16, (i % 4) * 80); }
Image tiles() {
    return expectImage(
        Format::RGBA8, [](uint32_t x, uint32_t y) { return tileTexel(y * 4 + x); }, 4, 4);
}
Image tilesMagnified() {
    return expectImage(Format::RGBA8,
                       [](uint32_t x, uint32_t y) { return tileTexel((y / 16) * 4 + x / 16); });
}
TextureHandle tileTexture(DeviceObjects& owner) {
    TextureHandle t = owner.add(
        owner.device().createTexture({.width = 4,
                                      .height = 4,
                                      .usage = TextureUsage::Sampled | TextureUsage::CopyDst,
                                      .debugName = "tiles"}));
    owner.device().writeTexture(t, {}, bytesOf(tiles().data));
    return t;
}

// Threads that keep what they throw, for the case to rethrow once every one is joined (an
// exception leaving a thread would end the program). Joined at destruction too.
class Threads {
public:
    template <class Fn>
    void start(Fn fn) {
        auto error = std::make_shared<std::exception_ptr>();
        errors_.push_back(error);
        threads_.emplace_back([error, fn = std::move(fn)]() mutable {
            try {
                fn();
            } catch (...) {
                *error = std::current_exception();
            }
        });
    }
    void joinAndRethrow() {
        for (std::jthread& t : threads_)
            if (t.joinable()) t.join();
        for (const auto& e : errors_)
            if (*e) std::rethrow_exception(*e);
    }

private:
    std::vector<std::shared_ptr<std::exception_ptr>> errors_;
    std::vector<std::jthread> threads_;
};

// --- Cases --------------------------------------------------------------------------------------

// Lists run in the order they are submitted, not the order they were recorded: A and B each
// clear the same target and draw a rectangle; A is always recorded first, and whichever runs
// last decides the image, as two submissions or as one submission of both.
std::vector<CaseImage> submissionOrder(Device& d) {
    ColorDraw draw(d);
    DeviceObjects objects(d);
    TextureHandle t = target(objects);
    const Texel clearA = rgb8(200, 40, 40), rectA = rgb8(250, 220, 30), clearB = rgb8(30, 60, 210),
                rectB = rgb8(40, 230, 90);
    const Rect areaA{8, 8, 24, 24}, areaB{32, 32, 24, 24};
    BufferHandle uboA = draw.params(objects, rectA), uboB = draw.params(objects, rectB);
    auto a = d.createCommandList(), b = d.createCommandList();
    auto record = [&] {
        beginPass(*a, t, clearA);
        draw.draw(*a, uboA, areaA);
        a->endRenderPass();
        beginPass(*b, t, clearB);
        draw.draw(*b, uboB, areaB);
        b->endRenderPass();
    };
    const Image imageA = rectImage(clearA, areaA, rectA), imageB = rectImage(clearB, areaB, rectB);
    std::vector<CaseImage> out;
    record();
    d.submit(*b);
    d.wait(d.submit(*a));
    out.push_back(rendered("submit_b_then_a", d.readTexture(t), imageA));
    record();  // submitted lists are empty: recorded anew
    CommandList* bThenA[] = {b.get(), a.get()};
    d.wait(d.submit(bThenA));
    out.push_back(rendered("one_submission_b_a", d.readTexture(t), imageA));
    record();
    CommandList* aThenB[] = {a.get(), b.get()};
    d.wait(d.submit(aThenB));
    out.push_back(rendered("one_submission_a_b", d.readTexture(t), imageB));
    return out;
}

// A list that is recorded but never submitted changes nothing: not while other work is
// submitted and completed, and not when the list is destroyed.
std::vector<CaseImage> unsubmittedListHasNoEffect(Device& d) {
    ColorDraw draw(d);
    DeviceObjects objects(d);
    TextureHandle t = target(objects), other = target(objects);
    const Texel red = rgb8(255, 0, 0), green = rgb8(0, 255, 0);
    BufferHandle greenUbo = draw.params(objects, green);
    const std::array<uint32_t, 4> kept = {1, 2, 3, 4}, copied = {9, 9, 9, 9};
    BufferHandle data = objects.add(
        d.createBuffer({.size = sizeof kept, .usage = BufferUsage::CopySrc | BufferUsage::CopyDst},
                       bytesOf(kept)));
    BufferHandle source = objects.add(
        d.createBuffer({.size = sizeof copied, .usage = BufferUsage::CopySrc}, bytesOf(copied)));
    auto cmd = d.createCommandList();
    beginPass(*cmd, t, red);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    auto never = d.createCommandList();
    beginPass(*never, t, green);
    draw.draw(*never, greenUbo, kWhole);
    never->endRenderPass();
    never->copyBuffer(data, 0, source, 0, sizeof copied);
    // Other work submitted and completed meanwhile does not carry the unsubmitted list along.
    beginPass(*cmd, other, green);
    draw.draw(*cmd, greenUbo, kWhole);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    std::vector<CaseImage> out;
    out.push_back(rendered("recorded_not_submitted", d.readTexture(t), solid(Format::RGBA8, red)));
    out.push_back(
        rendered("other_work_submitted", d.readTexture(other), solid(Format::RGBA8, green)));
    FE_CONFORMANCE_CHECK(d.readBuffer(data, 0, sizeof kept) == bytesVector(kept),
                         "an unsubmitted copy leaves its destination as it was");

    never.reset();
    d.waitIdle();
    out.push_back(rendered("list_destroyed", d.readTexture(t), solid(Format::RGBA8, red)));
    FE_CONFORMANCE_CHECK(d.readBuffer(data, 0, sizeof kept) == bytesVector(kept),
                         "destroying an unsubmitted list does not run its copy");
    return out;
}

// Commands read buffers and textures when they run: what is written after recording and before
// submit is what the draw sees (writeBuffer into GpuOnly memory, a write through an Upload
// buffer's mapping, writeTexture), and writeBuffer between two submissions lands between them.
std::vector<CaseImage> dataReadAtExecution(Device& d) {
    ColorDraw draw(d);
    TexturedDraw textured(d);
    DeviceObjects objects(d);
    const Texel x = rgb8(220, 30, 30), y = rgb8(20, 200, 120);
    std::vector<CaseImage> out;
    auto recordColour = [&](CommandList& cmd, TextureHandle t, BufferHandle ubo) {
        beginPass(cmd, t, kBlack);
        draw.draw(cmd, ubo, kWhole);
        cmd.endRenderPass();
    };
    {
        TextureHandle t = target(objects);
        BufferHandle ubo = objects.add(d.createBuffer(
            {.size = sizeof(Params), .usage = BufferUsage::Uniform | BufferUsage::CopyDst}));
        d.writeBuffer(ubo, 0, bytesOf(paramsOf(x)));
        auto cmd = d.createCommandList();
        recordColour(*cmd, t, ubo);
        d.writeBuffer(ubo, 0, bytesOf(paramsOf(y)));
        d.wait(d.submit(*cmd));
        out.push_back(rendered("gpu_only_uniform", d.readTexture(t), solid(Format::RGBA8, y)));
    }
    {
        TextureHandle t = target(objects);
        BufferHandle ubo = objects.add(d.createBuffer({.size = sizeof(Params),
                                                       .usage = BufferUsage::Uniform,
                                                       .access = MemoryAccess::Upload}));
        void* mapped = d.map(ubo);
        FE_CONFORMANCE_CHECK(mapped != nullptr, "an Upload buffer maps");
        const Params px = paramsOf(x), py = paramsOf(y);
        std::memcpy(mapped, &px, sizeof px);
        auto cmd = d.createCommandList();
        recordColour(*cmd, t, ubo);
        std::memcpy(mapped, &py, sizeof py);
        d.wait(d.submit(*cmd));
        out.push_back(rendered("upload_uniform_mapped", d.readTexture(t), solid(Format::RGBA8, y)));
    }
    {
        TextureHandle t = target(objects);
        TextureHandle tex = objects.add(d.createTexture(
            {.width = 4, .height = 4, .usage = TextureUsage::Sampled | TextureUsage::CopyDst}));
        d.writeTexture(tex, {}, bytesOf(solid(Format::RGBA8, x, 4, 4).data));
        PipelineHandle p = objects.add(d.createGraphicsPipeline(textured.desc()));
        BufferHandle ubo = textured.params(objects, 0);
        auto cmd = d.createCommandList();
        beginPass(*cmd, t, kBlack);
        textured.draw(*cmd, p, ubo, tex);
        cmd->endRenderPass();
        d.writeTexture(tex, {}, bytesOf(tiles().data));
        d.wait(d.submit(*cmd));
        out.push_back(rendered("texture", d.readTexture(t), tilesMagnified()));
    }
    {  // Both lists recorded first; each sees the write made just before its own submit.
        TextureHandle first = target(objects), second = target(objects);
        BufferHandle ubo = objects.add(d.createBuffer(
            {.size = sizeof(Params), .usage = BufferUsage::Uniform | BufferUsage::CopyDst}));
        auto a = d.createCommandList(), b = d.createCommandList();
        recordColour(*a, first, ubo);
        recordColour(*b, second, ubo);
        d.writeBuffer(ubo, 0, bytesOf(paramsOf(x)));
        d.submit(*a);
        d.writeBuffer(ubo, 0, bytesOf(paramsOf(y)));
        d.wait(d.submit(*b));
        out.push_back(
            rendered("write_between_submits_first", d.readTexture(first), solid(Format::RGBA8, x)));
        out.push_back(rendered("write_between_submits_second", d.readTexture(second),
                               solid(Format::RGBA8, y)));
    }
    return out;
}

// Eight lists recorded on four threads at once (two each, with draws), each into its own target,
// then submitted together in a shuffled order: each target shows its own list's work.
std::vector<CaseImage> recordOnThreads(Device& d) {
    constexpr uint32_t kThreads = 4, kListsPerThread = 2, kLists = kThreads * kListsPerThread;
    ColorDraw draw(d);
    DeviceObjects objects(d);
    auto clearOf = [](uint32_t i) { return rgb8(20 + 28 * i, 200 - 24 * i, 40 + 20 * i); };
    auto drawnOf = [](uint32_t i) { return rgb8(250 - 30 * i, 16 + 30 * i, 128 + (i % 2) * 100); };
    const Rect leftHalf{0, 0, kCaseSize / 2, kCaseSize};
    std::array<TextureHandle, kLists> targets;
    std::array<BufferHandle, kLists> ubos;
    for (uint32_t i = 0; i < kLists; ++i) {
        targets[i] = target(objects);
        ubos[i] = draw.params(objects, drawnOf(i));
    }
    std::array<std::unique_ptr<CommandList>, kLists> lists;
    std::latch start(kThreads);  // all four record at the same time
    Threads threads;
    for (uint32_t th = 0; th < kThreads; ++th)
        threads.start([&, th] {
            start.arrive_and_wait();
            for (uint32_t k = 0; k < kListsPerThread; ++k) {
                const uint32_t i = th * kListsPerThread + k;
                lists[i] = d.createCommandList();
                beginPass(*lists[i], targets[i], clearOf(i));
                for (uint32_t strip = 0; strip < 8; ++strip)  // the left half in eight draws
                    draw.draw(*lists[i], ubos[i], {0, int32_t(strip * 8), leftHalf.width, 8});
                lists[i]->endRenderPass();
            }
        });
    threads.joinAndRethrow();

    std::vector<CommandList*> order;
    for (auto& l : lists) order.push_back(l.get());
    std::mt19937 rng(20240601);  // a fixed seed: the same order on every run and backend
    for (size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng() % (i + 1)]);
    d.wait(d.submit(order));
    std::vector<CaseImage> out;
    for (uint32_t i = 0; i < kLists; ++i)
        out.push_back(rendered("list" + std::to_string(i), d.readTexture(targets[i]),
                               rectImage(clearOf(i), leftHalf, drawnOf(i))));
    return out;
}

// Reusable secondary lists (bundles): two lists recorded once on two threads draw constant-
// coloured quads; they run in two passes of two frames, one of them twice in one pass with the
// primary's own draws before, between and after (which set their pipeline again after each
// executeSecondary); the lists start from the render area as viewport whatever the primary set.
// A list recorded anew while a submission that ran the old recording is in flight leaves that
// submission's image as it was; reset() makes a secondary list a primary one again.
std::vector<CaseImage> reusableSecondaryLists(Device& d) {
    DeviceObjects o(d);
    const PipelineHandle quads = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
         .fragmentShader =
             registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
         .topology = PrimitiveTopology::TriangleStrip,
         .colorFormats = {Format::RGBA8},
         .debugName = "quads"}));
    const TextureHandle first = caseTarget(o), second = caseTarget(o), third = caseTarget(o);
    const RenderPassDesc pass{.colors = {{.texture = first, .clear = {0, 0, 0, 1}}},
                              .secondaryLists = true};
    auto record = [&](CommandList& list, QuadConstants q) {
        list.beginSecondary(pass);
        list.setPipeline(quads);
        list.setConstants(q);
        list.draw(4);
        list.endSecondary();
    };
    const Texel red{1, 0, 0, 1}, green{0, 1, 0, 1}, blue{0, 0, 1, 1}, white{1, 1, 1, 1};
    auto left = d.createCommandList(), right = d.createCommandList();
    std::thread a([&] { record(*left, pixelQuad(0, 0, 16, 64, red)); });
    std::thread b([&] { record(*right, pixelQuad(48, 0, 64, 64, green)); });
    a.join();
    b.join();
    auto direct = [&](CommandList& cmd, uint32_t x0, uint32_t x1, Texel c) {
        cmd.setPipeline(quads);
        cmd.setConstants(pixelQuad(x0, 0, x1, 64, c));
        cmd.draw(4);
    };
    // Frame 1: primary, left, primary, left again (over the primary's quad), right, primary.
    auto frame = d.createCommandList();
    frame->beginRenderPass(pass);
    direct(*frame, 0, 24, blue);
    frame->setViewport({0, 0, 8, 8});  // the lists draw in the render area regardless
    frame->executeSecondary(*left);
    direct(*frame, 20, 28, white);
    std::array<CommandList*, 2> both = {left.get(), right.get()};
    frame->executeSecondary(both);
    direct(*frame, 30, 34, blue);
    frame->endRenderPass();
    d.wait(d.submit(*frame));
    // Frame 2: the same lists in another target of the same kind; then the right one is
    // recorded anew (yellow) before that frame completes, and runs in frame 3.
    RenderPassDesc pass2 = pass;
    pass2.colors[0].texture = second;
    frame->beginRenderPass(pass2);
    frame->executeSecondary(both);
    frame->endRenderPass();
    const FenceValue frame2 = d.submit(*frame);
    record(*right, pixelQuad(40, 0, 64, 64, {1, 1, 0, 1}));
    RenderPassDesc pass3 = pass;
    pass3.colors[0].texture = third;
    frame->beginRenderPass(pass3);
    frame->executeSecondary(*right);
    frame->endRenderPass();
    d.wait(d.submit(*frame));
    d.wait(frame2);
    // reset(): the secondary list is as new, and records as a primary one.
    FE_CONFORMANCE_CHECK(throws([&] { right->draw(4); }),
                         "an ended secondary list records no more");
    right->reset();
    const TextureHandle fourth = caseTarget(o);
    right->beginRenderPass({.colors = {{.texture = fourth, .clear = {0, 0, 0, 1}}}});
    direct(*right, 8, 12, green);
    right->endRenderPass();
    d.wait(d.submit(*right));
    auto columns = [](std::initializer_list<std::tuple<uint32_t, uint32_t, Texel>> spans) {
        return expectImage(Format::RGBA8, [=](uint32_t x, uint32_t) -> Texel {
            Texel c{0, 0, 0, 1};
            for (const auto& [x0, x1, t] : spans)
                if (x >= x0 && x < x1) c = t;
            return c;
        });
    };
    return {exact("frame 1: the primary's draws between the lists", d.readTexture(first),
                  columns({{0, 24, blue},
                           {0, 16, red},
                           {20, 28, white},
                           {0, 16, red},
                           {48, 64, green},
                           {30, 34, blue}})),
            exact("frame 2: the same lists in another pass", d.readTexture(second),
                  columns({{0, 16, red}, {48, 64, green}})),
            exact("frame 3: the right list recorded anew", d.readTexture(third),
                  columns({{40, 64, {1, 1, 0, 1}}})),
            exact("after reset, a primary list", d.readTexture(fourth), columns({{8, 12, green}}))};
}

// The draws of one pass recorded on four threads as secondary lists, executed by the primary in
// a shuffled order over two executeSecondary calls, for two frames (the lists record anew after
// being executed). Secondary list t fills column quarter t and then the middle band: each column
// shows its list, the band the list executed last.
std::vector<CaseImage> secondaryListsInOnePass(Device& d) {
    constexpr uint32_t kThreads = 4;
    ColorDraw draw(d);
    DeviceObjects objects(d);
    const TextureHandle t = target(objects);
    auto colorOf = [](uint32_t frame, uint32_t i) {
        return rgb8(40 + 50 * i, 220 - 40 * i - 20 * frame, 60 + 90 * frame);
    };
    const Rect middle{8, 28, 48, 8};
    const Texel clear = rgb8(10, 20, 30);
    std::array<std::unique_ptr<CommandList>, kThreads> parts;
    for (auto& p : parts) p = d.createCommandList();
    auto primary = d.createCommandList();
    const std::array<std::array<uint32_t, kThreads>, 2> orders{{{2, 0, 3, 1}, {1, 3, 0, 2}}};
    std::vector<CaseImage> out;
    for (uint32_t frame = 0; frame < 2; ++frame) {
        std::array<BufferHandle, kThreads> ubos;
        for (uint32_t i = 0; i < kThreads; ++i) ubos[i] = draw.params(objects, colorOf(frame, i));
        const RenderPassDesc pass{
            .colors = {{.texture = t, .clear = {clear[0], clear[1], clear[2], clear[3]}}},
            .debugName = "secondary lists",
            .secondaryLists = true};
        primary->beginRenderPass(pass);  // before the workers record: order does not matter
        std::latch start(kThreads);
        Threads threads;
        for (uint32_t th = 0; th < kThreads; ++th)
            threads.start([&, th] {
                start.arrive_and_wait();
                CommandList& part = *parts[th];
                part.beginSecondary(pass);
                part.pushDebugGroup("part");
                for (uint32_t strip = 0; strip < 4; ++strip)  // the quarter in four draws
                    draw.draw(part, ubos[th], {int32_t(16 * th), int32_t(16 * strip), 16, 16});
                draw.draw(part, ubos[th], middle);
                part.popDebugGroup();
                part.endSecondary();
            });
        threads.joinAndRethrow();
        const auto& order = orders[frame];
        primary->executeSecondary(
            std::vector<CommandList*>{parts[order[0]].get(), parts[order[1]].get()});
        primary->executeSecondary(
            std::vector<CommandList*>{parts[order[2]].get(), parts[order[3]].get()});
        primary->endRenderPass();
        d.wait(d.submit(*primary));
        const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) {
            const bool inMiddle = int32_t(x) >= middle.x && x < middle.x + middle.width &&
                                  int32_t(y) >= middle.y && y < middle.y + middle.height;
            return colorOf(frame, inMiddle ? order[kThreads - 1] : x / 16);
        });
        out.push_back(rendered("frame" + std::to_string(frame), d.readTexture(t), expected));
    }
    return out;
}

// One thread creates sixteen textures and uploads them while this one creates uniform buffers
// and records and submits eight lists, one band of a target each: every upload reads back
// as written and every band is drawn.
std::vector<CaseImage> createWhileRecording(Device& d) {
    constexpr uint32_t kTextures = 16, kTextureSize = 16, kFrames = 8;
    ColorDraw draw(d);
    DeviceObjects objects(d);
    DeviceObjects uploads(d);  // the uploading thread's alone until it is joined
    std::array<TextureHandle, kTextures> uploaded{};
    auto uploadTexel = [](uint32_t i, uint32_t x, uint32_t y) {
        return rgb8(i * 15 + 10, x * 16, y * 16);
    };
    std::latch start(2);
    Threads threads;
    threads.start([&] {
        start.arrive_and_wait();
        for (uint32_t i = 0; i < kTextures; ++i) {
            uploaded[i] = uploads.add(d.createTexture(
                {.width = kTextureSize,
                 .height = kTextureSize,
                 .usage = TextureUsage::Sampled | TextureUsage::CopyDst | TextureUsage::CopySrc,
                 .debugName = "uploaded on a thread"}));
            const Image texels = expectImage(
                Format::RGBA8, [&](uint32_t x, uint32_t y) { return uploadTexel(i, x, y); },
                kTextureSize, kTextureSize);
            d.writeTexture(uploaded[i], {}, bytesOf(texels.data));
        }
    });
    start.arrive_and_wait();
    TextureHandle bands = target(objects);
    std::vector<std::unique_ptr<CommandList>> lists;
    FenceValue last = 0;
    for (uint32_t f = 0; f < kFrames; ++f) {
        BufferHandle ubo =
            draw.params(objects, bandColor(f));  // created while the other thread creates
        lists.push_back(d.createCommandList());
        beginPass(*lists.back(), bands, kBlack, f == 0 ? LoadOp::Clear : LoadOp::Load);
        draw.draw(*lists.back(), ubo, band(f));
        lists.back()->endRenderPass();
        last = d.submit(*lists.back());
    }
    d.wait(last);
    threads.joinAndRethrow();

    std::vector<CaseImage> out;
    out.push_back(rendered("bands_drawn_meanwhile", d.readTexture(bands), bandsImage()));
    // The uploads read back, laid out 4 x 4 in one image.
    Image mosaic{kCaseSize, kCaseSize, Format::RGBA8,
                 std::vector<uint8_t>(size_t(kCaseSize) * kCaseSize * 4)};
    for (uint32_t i = 0; i < kTextures; ++i) {
        const Image img = d.readTexture(uploaded[i]);
        FE_CONFORMANCE_CHECK(
            img.width == kTextureSize && img.height == kTextureSize && img.format == Format::RGBA8,
            "an uploaded texture reads back at its size and format");
        for (uint32_t y = 0; y < kTextureSize; ++y)
            std::memcpy(
                &mosaic.data[((i / 4 * kTextureSize + y) * kCaseSize + i % 4 * kTextureSize) * 4],
                &img.data[y * kTextureSize * 4], kTextureSize * 4);
    }
    out.push_back(
        exact("uploaded_on_thread", mosaic, expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) {
                  return uploadTexel((y / kTextureSize) * 4 + x / kTextureSize, x % kTextureSize,
                                     y % kTextureSize);
              })));
    return out;
}

// Objects destroyed right after the submit of work that reads them (a texture, a sampler, a
// uniform buffer, the pipeline) live until that work is done: the image is right, and once
// the device is idle everything they held is released. A list that uses an object destroyed
// before its submit may record on (no validation message), is refused with an Error at submit,
// runs nothing, and the device carries on; what it held back is released when it is dropped.
std::vector<CaseImage> destroyWhileInFlight(Device& d) {
    TexturedDraw textured(d);
    DeviceObjects objects(d);
    TextureHandle t = target(objects);
    auto cmd = d.createCommandList();
    d.waitIdle();  // earlier destructions have been released: the count below is settled
    const LiveObjects before = d.liveObjects();
    // Made and destroyed with no submission between: their first commands (Vulkan: the
    // transition and zero clear, the zero fill) are dropped and they are released at once.
    d.destroy(d.createTexture(
        {.width = 64, .height = 64, .usage = TextureUsage::Sampled | TextureUsage::CopyDst}));
    d.destroy(d.createBuffer({.size = 4096, .usage = BufferUsage::Storage}));
    FE_CONFORMANCE_CHECK(d.liveObjects() == before,
                         "objects made and destroyed before any submission are released at once");
    {
        DeviceObjects inFlight(d);
        TextureHandle tex = tileTexture(inFlight);
        SamplerHandle sampler = inFlight.add(
            d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest}));
        BufferHandle ubo = textured.params(inFlight, 0);
        PipelineHandle p = inFlight.add(d.createGraphicsPipeline(textured.desc()));
        beginPass(*cmd, t, kBlack);
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->setTexture(1, tex, sampler);
        for (int i = 0; i < 64; ++i)
            cmd->draw(3);  // work the GPU is likely still doing when they go
        cmd->endRenderPass();
        const FenceValue fence = d.submit(*cmd);
        inFlight.clear();
        d.wait(fence);
    }
    std::vector<CaseImage> out;
    out.push_back(rendered("destroyed_after_submit", d.readTexture(t), tilesMagnified()));
    d.waitIdle();
    FE_CONFORMANCE_CHECK(d.liveObjects() == before,
                         "objects destroyed in flight are released once their work has completed");

    const Texel magenta = rgb8(255, 0, 255);
    for (bool destroyTexture : {true, false}) {
        DeviceObjects iteration(d);
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(textured.desc()));
        TextureHandle tex = tileTexture(iteration);
        BufferHandle ubo = textured.params(iteration, 0);
        auto stale = d.createCommandList();
        beginPass(*stale, t, magenta);
        textured.draw(*stale, p, ubo, tex);
        stale->endRenderPass();
        if (destroyTexture)
            iteration.destroy(tex);
        else
            iteration.destroy(ubo);
        // Recording goes on after the destroy (Vulkan: into the command buffer that names the
        // object, so its native release waits for the list); only the submit is refused.
        beginPass(*stale, t, magenta);
        if (destroyTexture)
            textured.draw(*stale, p, ubo, tileTexture(iteration));
        else
            textured.draw(*stale, p, textured.params(iteration, 0), tex);
        stale->endRenderPass();
        FE_CONFORMANCE_CHECK(throws([&] { d.submit(*stale); }),
                             destroyTexture
                                 ? "submitting a list that uses a destroyed texture is an error"
                                 : "submitting a list that uses a destroyed buffer is an error");
    }
    d.waitIdle();
    FE_CONFORMANCE_CHECK(d.liveObjects() == before,
                         "what refused lists held back is released once they are dropped");
    out.push_back(rendered("refused_submits_ran_nothing", d.readTexture(t), tilesMagnified()));
    {  // and the device carries on
        DeviceObjects again(d);
        PipelineHandle p = again.add(d.createGraphicsPipeline(textured.desc()));
        TextureHandle tex = tileTexture(again);
        BufferHandle ubo = textured.params(again, 0);
        beginPass(*cmd, t, magenta);
        textured.draw(*cmd, p, ubo, tex);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(rendered("after_refused_submits", d.readTexture(t), tilesMagnified()));
    }
    return out;
}

// A per-frame constants ring: an Upload buffer of three regions (one per frame in flight,
// aligned for uniform binding), each frame waiting for the fence of its region's last use,
// writing its colour through the persistent mapping and drawing its band from that region.
// Eight frames through three regions: every band has its own frame's colour.
std::vector<CaseImage> mappedUploadRing(Device& d) {
    constexpr uint32_t kRegions = 3, kFrames = 8;
    ColorDraw draw(d);
    DeviceObjects objects(d);
    const uint64_t align = std::max<uint64_t>(1, d.info().limits.uniformBufferOffsetAlignment);
    const uint64_t stride = (sizeof(Params) + align - 1) / align * align;
    BufferHandle ring = objects.add(d.createBuffer({.size = stride * kRegions,
                                                    .usage = BufferUsage::Uniform,
                                                    .access = MemoryAccess::Upload,
                                                    .debugName = "upload ring"}));
    std::byte* mapped = static_cast<std::byte*>(d.map(ring));
    FE_CONFORMANCE_CHECK(mapped != nullptr, "an Upload buffer maps");
    TextureHandle t = target(objects);
    std::array<FenceValue, kRegions> lastUse{};
    auto cmd = d.createCommandList();
    for (uint32_t f = 0; f < kFrames; ++f) {
        const uint32_t region = f % kRegions;
        if (f >= kRegions)
            d.wait(lastUse[region]);  // the frame before that used this region is done
        FE_CONFORMANCE_CHECK(d.map(ring) == mapped, "map() returns the same pointer every time");
        const Params p = paramsOf(bandColor(f));
        std::memcpy(mapped + region * stride, &p, sizeof p);
        beginPass(*cmd, t, kBlack, f == 0 ? LoadOp::Clear : LoadOp::Load);
        draw.draw(*cmd, ring, band(f), region * stride);
        cmd->endRenderPass();
        lastUse[region] = d.submit(*cmd);  // the list is empty again, recorded anew next frame
    }
    d.waitIdle();
    FE_CONFORMANCE_CHECK(d.map(ring) == mapped, "map() returns the same pointer after the frames");
    BufferHandle gpuOnly = objects.add(
        d.createBuffer({.size = 256, .usage = BufferUsage::Uniform | BufferUsage::CopyDst}));
    FE_CONFORMANCE_CHECK(throws([&] { d.map(gpuOnly); }), "a GpuOnly buffer cannot be mapped");
    return {rendered("eight_frames_three_regions", d.readTexture(t), bandsImage())};
}

// Readback without blocking: render, copy the target into a Readback buffer, submit, poll
// isComplete as a frame loop would, then read the bytes through the mapping.
std::vector<CaseImage> asyncReadback(Device& d) {
    ColorDraw draw(d);
    DeviceObjects objects(d);
    TextureHandle t = target(objects);
    const Texel background = rgb8(20, 40, 160), inside = rgb8(240, 150, 20);
    const Rect area{16, 8, 32, 40};
    BufferHandle ubo = draw.params(objects, inside);
    const uint64_t size = uint64_t(kCaseSize) * kCaseSize * 4;
    BufferHandle readback = objects.add(d.createBuffer({.size = size,
                                                        .usage = BufferUsage::CopyDst,
                                                        .access = MemoryAccess::Readback,
                                                        .debugName = "readback"}));
    auto cmd = d.createCommandList();
    beginPass(*cmd, t, background);
    draw.draw(*cmd, ubo, area);
    cmd->endRenderPass();
    cmd->copyTextureToBuffer(readback, 0, t, {});
    const FenceValue fence = d.submit(*cmd);
    // Bounded: a backend that never reports completion fails the check below instead of hanging.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    bool polled = d.isComplete(fence);
    while (!polled && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        polled = d.isComplete(fence);
    }
    if (!polled) d.wait(fence);
    const auto* bytes = static_cast<const uint8_t*>(d.map(readback));
    FE_CONFORMANCE_CHECK(bytes != nullptr, "a Readback buffer maps");
    Image img{kCaseSize, kCaseSize, Format::RGBA8, std::vector<uint8_t>(bytes, bytes + size)};
    FE_CONFORMANCE_CHECK(
        polled,
        "isComplete reports the submission complete without a wait (polled for up to 30 s)");
    FE_CONFORMANCE_CHECK(d.isComplete(fence), "a completed fence stays complete");
    FE_CONFORMANCE_CHECK(img.data == d.readTexture(t).data, "the mapped bytes are the texture's");
    return {rendered("mapped_after_polling", img, rectImage(background, area, inside))};
}

struct Vertex2 {
    float x, y;
    float r, g, b, a;
};
using Corners = std::array<std::array<float, 2>, 6>;
// Two triangles covering [x0, x1] x [y0, y1] in NDC.
Corners quadCorners(float x0, float x1, float y0, float y1) {
    return {{{x0, y0}, {x1, y0}, {x0, y1}, {x0, y1}, {x1, y0}, {x1, y1}}};
}

// With automatic barriers off, compute writes what draws then read: indirect_args.comp the
// argument records, fill.comp a buffer of uints (3i + 1) used both as the index buffer and as a
// vertex attribute. Only the explicit barriers (StorageWrite -> Indirect, StorageWrite ->
// Index | Vertex) order them. The draws:
//  - drawIndirect record 0 (6 vertices from 0, one instance): quad A, red, upper left;
//  - drawIndexedIndirect record at 128 (6 indices, 2 instances from 4, base vertex 12): the
//    indices 1, 4, ... 16 pick vertices 13, 16, ... 28, quad C, blue, upper and (instance 5)
//    lower centre;
//  - draw(6, 1, 333) of vertex_uint.vert: vertex v's value is 3v + 1 >= 1000, red 1 (clamped):
//    quad D, red, lower right.
std::vector<CaseImage> bufferBarrierComputeToIndirect(Device& d) {
    DeviceObjects objects(d);
    auto shader = [&](ShaderStage stage, const char* name) {
        return objects.add(d.createShader({.stage = stage, .binary = shaders::find(name)}));
    };
    const ShaderHandle argsCs = shader(ShaderStage::Compute, "conformance/indirect_args.comp"),
                       fillCs = shader(ShaderStage::Compute, "conformance/fill.comp"),
                       colorVs = shader(ShaderStage::Vertex, "conformance/vertex_color.vert"),
                       colorFs = shader(ShaderStage::Fragment, "conformance/color.frag"),
                       uintVs = shader(ShaderStage::Vertex, "conformance/vertex_uint.vert"),
                       valueFs = shader(ShaderStage::Fragment, "conformance/value.frag");
    PipelineHandle writeArgs = objects.add(d.createComputePipeline(
        {.computeShader = argsCs,
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute}}}));
    PipelineHandle writeValues = objects.add(d.createComputePipeline(
        {.computeShader = fillCs,
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                      {1, BindingType::StorageTexture, ShaderStage::Compute}}}));
    PipelineHandle coloured = objects.add(d.createGraphicsPipeline(
        {.vertexShader = colorVs,
         .fragmentShader = colorFs,
         .vertexBuffers =
             {{.stride = sizeof(Vertex2),
               .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}},
              {.stride = 8, .perInstance = true, .attributes = {{2, VertexFormat::Float2, 0}}}},
         .colorFormats = {Format::RGBA8}}));
    PipelineHandle valued = objects.add(d.createGraphicsPipeline(
        {.vertexShader = uintVs,
         .fragmentShader = valueFs,
         .vertexBuffers = {{.stride = 8, .attributes = {{0, VertexFormat::Float2, 0}}},
                           {.stride = 4, .attributes = {{1, VertexFormat::UInt32, 0}}}},
         .colorFormats = {Format::RGBA8}}));

    // Vertices nothing should draw sit outside the target.
    std::vector<Vertex2> vertices(29, Vertex2{5, 5, 1, 1, 1, 1});
    const Corners a = quadCorners(-0.75f, -0.5f, -0.75f, -0.25f),
                  c = quadCorners(-0.25f, 0.25f, -0.75f, -0.25f);
    for (uint32_t k = 0; k < 6; ++k) {
        vertices[k] = {a[k][0], a[k][1], 1, 0, 0, 1};
        vertices[12 + 3 * k + 1] = {c[k][0], c[k][1], 0, 0, 1, 1};
    }
    const float instanceOffsets[12] = {0, 0, 0, 0, 0, 0, 0,
                                       0, 0, 0, 0, 1};  // instance 5 moves down by half the target
    constexpr uint32_t kFirstValued = 333;              // 3 * 333 + 1 = 1000
    std::vector<std::array<float, 2>> positions(kFirstValued + 6, {5, 5});
    const Corners dq = quadCorners(0.5f, 0.75f, 0.25f, 0.75f);
    std::copy(dq.begin(), dq.end(), positions.begin() + kFirstValued);
    auto vertexBuffer = [&](ByteSpan data) {
        return objects.add(
            d.createBuffer({.size = data.size(), .usage = BufferUsage::Vertex}, data));
    };
    BufferHandle vb = vertexBuffer(bytesOf(vertices)),
                 instances = vertexBuffer(bytesOf(instanceOffsets)),
                 pb = vertexBuffer(bytesOf(positions));
    BufferHandle args =
        objects.add(d.createBuffer({.size = 256,
                                    .usage = BufferUsage::Storage | BufferUsage::Indirect,
                                    .debugName = "args from compute"}));
    BufferHandle values = objects.add(
        d.createBuffer({.size = size_t(kCaseSize) * kCaseSize * 4,
                        .usage = BufferUsage::Storage | BufferUsage::Index | BufferUsage::Vertex,
                        .debugName = "indices and vertices from compute"}));
    TextureHandle image =
        objects.add(d.createTexture({.format = Format::RGBA32F,
                                     .width = kCaseSize,
                                     .height = kCaseSize,
                                     .usage = TextureUsage::Storage}));  // fill.comp writes one too
    TextureHandle t = target(objects);

    auto cmd = d.createCommandList();
    cmd->setAutomaticBarriers(false);
    const TextureBarrier firstUse[] = {
        {.texture = image, .before = ResourceState::Undefined, .after = ResourceState::Storage},
        {.texture = t, .before = ResourceState::Undefined, .after = ResourceState::RenderTarget}};
    cmd->barrier(firstUse, 2);
    cmd->setPipeline(writeArgs);
    cmd->setStorageBuffer(0, args);
    cmd->dispatch(1);
    cmd->setPipeline(writeValues);
    cmd->setStorageBuffer(0, values);
    cmd->setStorageTexture(1, image);
    cmd->dispatch(kCaseSize / 8, kCaseSize / 8);
    const BufferBarrier written[] = {
        {.buffer = args, .before = BufferAccess::StorageWrite, .after = BufferAccess::Indirect},
        {.buffer = values,
         .before = BufferAccess::StorageWrite,
         .after = BufferAccess::Index | BufferAccess::Vertex}};
    cmd->barrier(written, 2);
    beginPass(*cmd, t, kBlack);
    cmd->setPipeline(coloured);
    cmd->setVertexBuffer(0, vb);
    cmd->setVertexBuffer(1, instances);
    cmd->setIndexBuffer(values, IndexType::U32);
    cmd->drawIndirect(args, 0);
    cmd->drawIndexedIndirect(args, 128);
    cmd->setPipeline(valued);
    cmd->setVertexBuffer(0, pb);
    cmd->setVertexBuffer(1, values);
    cmd->draw(6, 1, kFirstValued);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    // NDC -0.75..-0.5 is pixels 8..15, -0.25..0.25 is 24..39, 0.5..0.75 is 48..55; rows alike.
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        const bool up = y >= 8 && y < 24, down = y >= 40 && y < 56;
        if (up && x >= 8 && x < 16) return {1, 0, 0, 1};
        if ((up || down) && x >= 24 && x < 40) return {0, 0, 1, 1};
        if (down && x >= 48 && x < 56) return {1, 0, 0, 1};
        return {0, 0, 0, 1};
    });
    return {exact("drawn_from_compute_output", d.readTexture(t), expected)};
}

// Subresources change state separately: with automatic barriers off, mip 0 of a two-mip
// texture goes to ShaderRead and mip 1 to RenderTarget, and a pass renders mip 0 (sampled at
// level 0) into mip 1 of the same texture. Then mip 1 goes to ShaderRead and is sampled at
// level 1 into another target. Mip 0 is 128x128 so that mip 1 is the suite's 64x64; each 2x2
// block of mip 0 is one value, so the sample between two of its texels reads that value.
std::vector<CaseImage> subresourceBarrier(Device& d) {
    constexpr uint32_t kMip0 = 2 * kCaseSize;
    TexturedDraw textured(d);
    DeviceObjects objects(d);
    auto source = [](uint32_t x, uint32_t y) { return rgb8(4 * x, 4 * y, 255 - 2 * (x + y)); };
    const Image mip0 = expectImage(
        Format::RGBA8, [&](uint32_t x, uint32_t y) { return source(x / 2, y / 2); }, kMip0, kMip0);
    TextureHandle tex =
        objects.add(d.createTexture({.width = kMip0,
                                     .height = kMip0,
                                     .mipLevels = 2,
                                     .usage = TextureUsage::Sampled | TextureUsage::RenderTarget |
                                              TextureUsage::CopySrc | TextureUsage::CopyDst,
                                     .debugName = "two mips"}));
    d.writeTexture(tex, {.mipLevel = 0}, bytesOf(mip0.data));
    // Mip 1 gets a colour the pass replaces: both mips were last written by an upload (CopyDst).
    d.writeTexture(tex, {.mipLevel = 1}, bytesOf(solid(Format::RGBA8, rgb8(255, 0, 255)).data));
    SamplerHandle levels = objects.add(d.createSampler({.minFilter = Filter::Nearest,
                                                        .magFilter = Filter::Nearest,
                                                        .mipFilter = MipFilter::Nearest,
                                                        .addressU = AddressMode::ClampToEdge,
                                                        .addressV = AddressMode::ClampToEdge}));
    BufferHandle level0 = textured.params(objects, 0), level1 = textured.params(objects, 1);
    PipelineHandle p = objects.add(d.createGraphicsPipeline(textured.desc()));
    TextureHandle copy = target(objects);

    auto cmd = d.createCommandList();
    cmd->setAutomaticBarriers(false);
    const TextureBarrier split[] = {{.texture = tex,
                                     .before = ResourceState::CopyDst,
                                     .after = ResourceState::ShaderRead,
                                     .baseMip = 0,
                                     .mipCount = 1},
                                    {.texture = tex,
                                     .before = ResourceState::CopyDst,
                                     .after = ResourceState::RenderTarget,
                                     .baseMip = 1,
                                     .mipCount = 1},
                                    {.texture = copy,
                                     .before = ResourceState::Undefined,
                                     .after = ResourceState::RenderTarget}};
    cmd->barrier(split, 3);
    // Sampled through textured.nearest, which reads the base level only: on GL an attached level
    // within the sampler's mip range is a feedback loop even where the shader never reads it.
    cmd->beginRenderPass({.colors = {{.texture = tex, .mipLevel = 1, .clear = {0, 0, 0, 1}}}});
    textured.draw(*cmd, p, level0, tex);
    cmd->endRenderPass();
    const TextureBarrier renderedMip{.texture = tex,
                                     .before = ResourceState::RenderTarget,
                                     .after = ResourceState::ShaderRead,
                                     .baseMip = 1,
                                     .mipCount = 1};
    cmd->barrier(renderedMip);
    cmd->beginRenderPass({.colors = {{.texture = copy, .clear = {0, 0, 0, 1}}}});
    textured.draw(*cmd, p, level1, tex, levels);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    // Nearest sampling of 8-bit texels into an 8-bit target copies them exactly.
    const Image expected = expectImage(Format::RGBA8, source);
    std::vector<CaseImage> out;
    out.push_back(exact("mip1_rendered_from_mip0", d.readTexture(tex, {.mipLevel = 1}), expected));
    out.push_back(exact("mip1_sampled_at_level1", d.readTexture(copy), expected));
    FE_CONFORMANCE_CHECK(d.readTexture(tex, {.mipLevel = 0}).data == mip0.data,
                         "rendering into mip 1 leaves mip 0 as uploaded");
    return out;
}

}  // namespace

std::vector<Case> executionCases() {
    return {
        {"submission_order", submissionOrder},
        {"unsubmitted_list_has_no_effect", unsubmittedListHasNoEffect},
        {"data_read_at_execution", dataReadAtExecution},
        {"record_on_threads", recordOnThreads},
        {"secondary_lists_in_one_pass", secondaryListsInOnePass},
        {"reusable_secondary_lists", reusableSecondaryLists},
        {"create_while_recording", createWhileRecording},
        {"destroy_while_in_flight", destroyWhileInFlight},
        {"mapped_upload_ring", mappedUploadRing},
        {"async_readback", asyncReadback},
        {"buffer_barrier_compute_to_indirect", bufferBarrierComputeToIndirect},
        {"subresource_barrier", subresourceBarrier},
    };
}

}  // namespace fe::conformance
