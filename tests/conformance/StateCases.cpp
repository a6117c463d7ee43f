// Conformance cases for multisampling, shadow-map state (comparison samplers, depth bias,
// depth clamp) and indirect work.
#include <algorithm>
#include <array>
#include <cmath>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr TextureUsage kTarget = TextureUsage::RenderTarget | TextureUsage::CopySrc;

struct Vertex3 {
    float x, y, z;
    float r, g, b, a;
};

// position3_color.vert + color.frag, for geometry with depth.
struct DepthGeometry {
    DeviceObjects objects;
    ShaderHandle vs, fs;
    GraphicsPipelineDesc desc;
    explicit DepthGeometry(Device& d) : objects(d) {
        vs = objects.add(
            d.createShader({.stage = ShaderStage::Vertex,
                            .binary = shaders::find("conformance/position3_color.vert")}));
        fs = objects.add(d.createShader(
            {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")}));
        desc = {.vertexShader = vs,
                .fragmentShader = fs,
                .vertexBuffers = {
                    {.stride = sizeof(Vertex3),
                     .attributes = {{0, VertexFormat::Float3, 0}, {1, VertexFormat::Float4, 12}}}}};
    }
};

// Two triangles covering [x0, x1] x [y0, y1] in NDC at depth z0 (left) to z1 (right).
std::vector<Vertex3> quad(float x0, float x1, float y0, float y1, float z0, float z1, Texel c) {
    auto v = [&](float x, float y, float z) { return Vertex3{x, y, z, c[0], c[1], c[2], c[3]}; };
    return {v(x0, y0, z0), v(x1, y0, z1), v(x0, y1, z0),
            v(x0, y1, z0), v(x1, y0, z1), v(x1, y1, z1)};
}

// --- Multisampling ------------------------------------------------------------------------------

// TextureUsage::Transient attachments: a 4-sample colour and depth that live inside one pass
// (cleared, stored DontCare, the colour resolved) draw two overlapping quads with the depth test
// as ordinary ones do; a single-sample transient depth beside a stored colour likewise. Loading
// or storing one, resolving into one, reading, writing or sampling one are the same Error on
// every backend.
std::vector<CaseImage> transientAttachments(Device& d) {
    std::vector<CaseImage> out;
    DepthGeometry geo(d);
    const TextureUsage transient = TextureUsage::RenderTarget | TextureUsage::Transient;
    std::vector<Vertex3> v = quad(-1, 0.5f, -1, 1, 0.5f, 0.5f, {1, 0, 0, 1});
    const std::vector<Vertex3> behind = quad(-0.5f, 1, -1, 1, 0.75f, 0.75f, {0, 0, 1, 1});
    v.insert(v.end(), behind.begin(), behind.end());
    DeviceObjects o(d);
    const BufferHandle vb = o.add(d.createBuffer(
        {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t) -> Texel {
        return x < 48 ? Texel{1, 0, 0, 1} : Texel{0, 0, 1, 1};  // red in front up to x = 48
    });
    const uint32_t counts = d.info().limits.colorSampleCounts & d.info().limits.depthSampleCounts;
    for (uint32_t samples : {1u, 4u}) {
        if (!(counts & samples)) continue;
        GraphicsPipelineDesc pd = geo.desc;
        pd.colorFormats = {Format::RGBA8};
        pd.depthFormat = Format::D32F;
        pd.depthStencil = {.depthTest = true, .depthWrite = true};
        pd.multisample.sampleCount = samples;
        const PipelineHandle p = o.add(d.createGraphicsPipeline(pd));
        const TextureHandle depth = o.add(d.createTexture({.format = Format::D32F,
                                                           .width = kCaseSize,
                                                           .height = kCaseSize,
                                                           .sampleCount = samples,
                                                           .usage = transient,
                                                           .debugName = "transient depth"}));
        const TextureHandle result = caseTarget(o);
        ColorAttachment color{.texture = result, .clear = {0, 0, 0, 1}};
        if (samples > 1) {
            color.texture = o.add(d.createTexture({.width = kCaseSize,
                                                   .height = kCaseSize,
                                                   .sampleCount = samples,
                                                   .usage = transient,
                                                   .debugName = "transient colour"}));
            color.store = StoreOp::DontCare;
            color.resolveTexture = result;
        }
        auto cmd = d.createCommandList();
        cmd->beginRenderPass(
            {.colors = {color}, .depth = {.texture = depth, .store = StoreOp::DontCare}});
        cmd->setPipeline(p);
        cmd->setVertexBuffer(0, vb);
        cmd->draw(12);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(exact(std::to_string(samples) + " sample(s), transient depth" +
                                (samples > 1 ? " and colour" : ""),
                            d.readTexture(result), expected));

        auto list = d.createCommandList();
        expectError(
            [&] {
                list->beginRenderPass(
                    {.colors = {{.texture = result}}, .depth = {.texture = depth}});
            },
            "depth attachment is Transient: it is loaded by Clear or DontCare and stored "
            "DontCare");
        expectError(
            [&] {
                list->beginRenderPass(
                    {.colors = {{.texture = result}},
                     .depth = {
                         .texture = depth, .load = LoadOp::Load, .store = StoreOp::DontCare}});
            },
            "depth attachment is Transient");
        expectError([&] { d.readTexture(depth); }, "is Transient: its contents live only inside");
        d.wait(d.submit(*list));
    }
    const TextureHandle transientColor = o.add(d.createTexture(
        {.width = kCaseSize, .height = kCaseSize, .usage = transient, .debugName = "tc"}));
    expectError(
        [&] {
            d.createTexture({.width = 8,
                             .height = 8,
                             .usage = transient | TextureUsage::Sampled,
                             .debugName = "sampled transient"});
        },
        "a Transient texture is a RenderTarget only");
    expectError([&] { d.writeTexture(transientColor, {}, bytesOf(expected.data)); },
                "is Transient: its contents live only inside");
    if (counts & 4) {
        const TextureHandle ms = o.add(d.createTexture(
            {.width = kCaseSize, .height = kCaseSize, .sampleCount = 4, .usage = transient}));
        auto list = d.createCommandList();
        expectError(
            [&] {
                list->beginRenderPass({.colors = {{.texture = ms,
                                                   .store = StoreOp::DontCare,
                                                   .resolveTexture = transientColor}}});
            },
            "resolve target is Transient");
        d.wait(d.submit(*list));
    }
    return out;
}

// A 4-sample texture drawn with a white quad whose edge runs through the middle of column 31,
// then read per sample with texelFetch (sampler2DMS, Sampled usage): at the standard sample
// positions samples 0 and 2 of that column lie left of the middle (inside), 1 and 3 right of it.
// Every sample of the other columns is exact. The same texture bound to a sampler2D slot, or a
// single-sample one to a sampler2DMS slot, is an Error at the draw on every backend.
struct MultisampledEdge {
    DeviceObjects o;
    TextureHandle texture;
    MultisampledEdge(Device& d, DepthGeometry& geo) : o(d) {
        GraphicsPipelineDesc pd = geo.desc;
        pd.colorFormats = {Format::RGBA8};
        pd.multisample.sampleCount = 4;
        const PipelineHandle p = o.add(d.createGraphicsPipeline(pd));
        texture =
            o.add(d.createTexture({.width = kCaseSize,
                                   .height = kCaseSize,
                                   .sampleCount = 4,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::Sampled |
                                            TextureUsage::CopySrc | TextureUsage::CopyDst,
                                   .debugName = "multisampled"}));
        const std::vector<Vertex3> v =
            quad(-1, 31.5f / 32.0f - 1.0f, -1, 1, 0.5f, 0.5f, {1, 1, 1, 1});
        const BufferHandle vb = o.add(d.createBuffer(
            {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = texture, .clear = {0, 0, 0, 1}}}});
        cmd->setPipeline(p);
        cmd->setVertexBuffer(0, vb);
        cmd->draw(6);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
    }
    // Sample `s` of each pixel, when the quad covered columns [x0, x1) (31: by sample position).
    static Image expected(uint32_t s, uint32_t x0 = 0, uint32_t x1 = 32) {
        return expectImage(Format::RGBA8, [=](uint32_t x, uint32_t) -> Texel {
            const bool edge = x == x1 - 1;
            const float v = x < x0 || x >= x1 ? 0.0f : edge ? float(s % 2 == 0) : 1.0f;
            return {v, v, v, 1};
        });
    }
};

std::vector<CaseImage> msaaTexelFetch(Device& d) {
    std::vector<CaseImage> out;
    if (!(d.info().limits.colorSampleCounts & 4)) return out;
    DepthGeometry geo(d);
    MultisampledEdge edge(d, geo);
    FullscreenSampler perSample(d, "conformance/sample_ms_index.frag");
    for (uint32_t s = 0; s < 4; ++s)
        out.push_back(exact("sample " + std::to_string(s),
                            perSample.draw(d, edge.texture, Format::RGBA8, {float(s), 0, 0, 0}),
                            MultisampledEdge::expected(s)));
    FullscreenSampler plain(d, "conformance/textured.frag");
    expectError([&] { plain.draw(d, edge.texture, Format::RGBA8); },
                "is declared a Texture2D in its shader, but the texture bound there is a Texture2D "
                "(multisampled)");
    const TextureHandle single = edge.o.add(
        d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = TextureUsage::Sampled}));
    expectError([&] { perSample.draw(d, single, Format::RGBA8); },
                "sampler2DMS takes multisampled textures");
    return out;
}

// Multisampled textures copied to multisampled ones, every sample: whole, and a region (the
// left 32 columns placed at x = 16); and resolved by region (resolveTexture) into a single-sample
// one. Copies between sample counts, and to or from buffers, are the same Error everywhere.
std::vector<CaseImage> msaaCopy(Device& d) {
    std::vector<CaseImage> out;
    if (!(d.info().limits.colorSampleCounts & 4)) return out;
    DepthGeometry geo(d);
    MultisampledEdge edge(d, geo);
    DeviceObjects& o = edge.o;
    auto copyTarget = [&] {
        return o.add(d.createTexture(
            {.width = kCaseSize,
             .height = kCaseSize,
             .sampleCount = 4,
             .usage = TextureUsage::RenderTarget | TextureUsage::Sampled | TextureUsage::CopyDst}));
    };
    const TextureHandle whole = copyTarget(), moved = copyTarget();
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = moved, .clear = {0, 0, 0, 1}}}});
    cmd->endRenderPass();
    cmd->copyTexture(whole, edge.texture);
    cmd->copyTexture(moved, {.x = 16}, edge.texture, {.width = 32, .height = 64, .depth = 1});
    d.wait(d.submit(*cmd));
    FullscreenSampler perSample(d, "conformance/sample_ms_index.frag");
    for (uint32_t s : {0u, 1u}) {
        out.push_back(exact("whole, sample " + std::to_string(s),
                            perSample.draw(d, whole, Format::RGBA8, {float(s), 0, 0, 0}),
                            MultisampledEdge::expected(s)));
        out.push_back(exact("region at x = 16, sample " + std::to_string(s),
                            perSample.draw(d, moved, Format::RGBA8, {float(s), 0, 0, 0}),
                            MultisampledEdge::expected(s, 16, 48)));
    }
    // Resolved by region: the left 32 columns averaged into x = 8 of a single-sample texture.
    const TextureHandle resolved =
        o.add(d.createTexture({.width = kCaseSize,
                               .height = kCaseSize,
                               .usage = TextureUsage::CopyDst | TextureUsage::CopySrc}));
    auto resolve = d.createCommandList();
    resolve->resolveTexture(resolved, {.x = 8}, edge.texture,
                            {.width = 32, .height = 64, .depth = 1});
    d.wait(d.submit(*resolve));
    CaseImage r{"region resolved at x = 8", d.readTexture(resolved),
                expectImage(Format::RGBA8, [](uint32_t x, uint32_t) -> Texel {
                    const float v = x < 8 || x >= 40 ? 0.0f : x == 39 ? 0.5f : 1.0f;
                    return {v, v, v, x < 8 || x >= 40 ? 0.0f : 1.0f};
                })};
    r.absTolerance = 1.0 / 255.0;  // 127.5 rounds either way
    r.toleranceReason = "the half-covered edge column averages to 0.5 (127 or 128 in 8 bits)";
    out.push_back(std::move(r));
    auto list = d.createCommandList();
    expectError([&] { list->resolveTexture(resolved, {}, resolved, {}); },
                "resolves a multisampled texture");
    const TextureHandle single = o.add(
        d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = TextureUsage::CopyDst}));
    expectError([&] { list->copyTexture(single, {}, edge.texture, {}); },
                "copies keep every sample");
    const BufferHandle buffer =
        o.add(d.createBuffer({.size = 64 * 64 * 4, .usage = BufferUsage::CopyDst}));
    expectError([&] { list->copyTextureToBuffer(buffer, {}, edge.texture, {}); },
                "multisampled textures go to and from buffers only through a single-sample one");
    d.wait(d.submit(*list));
    return out;
}

// A white quad whose edge runs through the middle of pixel column 31: at the standard sample
// positions of 2, 4 and 8 samples exactly half of that column's samples are inside, so the
// colour resolve (the average) is 0.5 there. The depth resolve is sample 0, which lies left of
// the middle for 4 samples (0.375, 0.125) and right of it for 2 (0.75, 0.75) and 8 (0.5625,
// 0.3125): drawn once on each side of the edge, sample 0 is inside exactly once, so a resolve
// taking the minimum or maximum of the samples fails one of the two.
std::vector<CaseImage> msaaResolve(Device& d) {
    std::vector<CaseImage> out;
    DepthGeometry geo(d);
    const float edge = 31.5f / 32.0f - 1.0f;
    const uint32_t counts = d.info().limits.colorSampleCounts & d.info().limits.depthSampleCounts;
    FE_CONFORMANCE_CHECK(counts & 1, "one sample is always supported");
    for (uint32_t samples : {2u, 4u, 8u}) {
        if (!(counts & samples)) {
            FE_CONFORMANCE_CHECK(
                throws([&] {  // (freed at once, should it be made)
                    DeviceObjects(d).add(d.createTexture(
                        {.width = 8, .height = 8, .sampleCount = samples, .usage = kTarget}));
                }),
                "an unsupported sample count is an error");
            continue;
        }
        DeviceObjects iteration(d);
        GraphicsPipelineDesc pd = geo.desc;
        pd.colorFormats = {Format::RGBA8};
        pd.depthFormat = Format::D32F;
        pd.depthStencil = {.depthTest = true, .depthWrite = true};
        pd.multisample.sampleCount = samples;
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(pd));
        TextureHandle ms = iteration.add(d.createTexture(
            {.width = kCaseSize, .height = kCaseSize, .sampleCount = samples, .usage = kTarget}));
        TextureHandle msDepth = iteration.add(d.createTexture({.format = Format::D32F,
                                                               .width = kCaseSize,
                                                               .height = kCaseSize,
                                                               .sampleCount = samples,
                                                               .usage = kTarget}));
        TextureHandle color = iteration.add(d.createTexture(
            {.width = kCaseSize, .height = kCaseSize, .usage = kTarget | TextureUsage::Sampled}));
        TextureHandle depth =
            iteration.add(d.createTexture({.format = Format::D32F,
                                           .width = kCaseSize,
                                           .height = kCaseSize,
                                           .usage = kTarget | TextureUsage::Sampled}));
        for (bool left : {true, false}) {
            std::vector<Vertex3> v = left ? quad(-1, edge, -1, 1, 0.25f, 0.25f, {1, 1, 1, 1})
                                          : quad(edge, 1, -1, 1, 0.25f, 0.25f, {1, 1, 1, 1});
            DeviceObjects side(d);
            BufferHandle vb = side.add(d.createBuffer(
                {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
            auto cmd = d.createCommandList();
            cmd->beginRenderPass(
                {.colors = {{.texture = ms,
                             .store = StoreOp::DontCare,
                             .clear = {0, 0, 0, 1},
                             .resolveTexture = color}},
                 .depth = {
                     .texture = msDepth, .store = StoreOp::DontCare, .resolveTexture = depth}});
            cmd->setPipeline(p);
            cmd->setVertexBuffer(0, vb);
            cmd->draw(6);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            auto inside = [left](uint32_t x) { return left ? x < 31 : x > 31; };
            const std::string n =
                std::string(left ? "left_" : "right_") + std::to_string(samples) + "x";
            CaseImage c{"colour_" + n, d.readTexture(color),
                        expectImage(Format::RGBA8, [&](uint32_t x, uint32_t) -> Texel {
                            const float v = x == 31 ? 0.5f : inside(x) ? 1.0f : 0.0f;
                            return {v, v, v, 1};
                        })};
            c.absTolerance = 1.0 / 255.0;  // 127.5 rounds either way
            c.maxFractionOver = 0;
            c.toleranceReason = "half-covered edge column averages to 0.5 (127 or 128 in 8 bits)";
            out.push_back(std::move(c));
            const bool sample0Left = samples == 4;
            const float edgeDepth = sample0Left == left ? 0.25f : 1.0f;
            out.push_back(
                exact("depth_sample0_" + n, d.readTexture(depth),
                      expectImage(Format::D32F, [&](uint32_t x, uint32_t) -> Texel {
                          return {x == 31 ? edgeDepth : inside(x) ? 0.25f : 1.0f, 0, 0, 1};
                      })));
        }
        {  // sRGB: the same edge into an RGBA8_SRGB target resolves in linear space, as Vulkan's
            // AVERAGE does: half of white is linear 0.5, stored encoded as 0.735. (GL's blit with
            // GL_FRAMEBUFFER_SRGB off averaged the encoded bytes instead, storing 0.502: caught here.)
            GraphicsPipelineDesc ps = pd;
            ps.colorFormats = {Format::RGBA8_SRGB};
            ps.depthFormat = Format::Undefined;
            ps.depthStencil = {};
            DeviceObjects srgb(d);
            PipelineHandle psrgb = srgb.add(d.createGraphicsPipeline(ps));
            TextureHandle msS = srgb.add(d.createTexture({.format = Format::RGBA8_SRGB,
                                                          .width = kCaseSize,
                                                          .height = kCaseSize,
                                                          .sampleCount = samples,
                                                          .usage = kTarget}));
            TextureHandle resS = srgb.add(d.createTexture({.format = Format::RGBA8_SRGB,
                                                           .width = kCaseSize,
                                                           .height = kCaseSize,
                                                           .usage = kTarget}));
            std::vector<Vertex3> v = quad(-1, edge, -1, 1, 0.25f, 0.25f, {1, 1, 1, 1});
            BufferHandle vb = srgb.add(d.createBuffer(
                {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
            auto cmd = d.createCommandList();
            cmd->beginRenderPass({.colors = {{.texture = msS,
                                              .store = StoreOp::DontCare,
                                              .clear = {0, 0, 0, 1},
                                              .resolveTexture = resS}}});
            cmd->setPipeline(psrgb);
            cmd->setVertexBuffer(0, vb);
            cmd->draw(6);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            const float half =
                1.055f * std::pow(0.5f, 1.0f / 2.4f) - 0.055f;  // sRGB encoding of linear 0.5
            auto expected = [&](uint32_t x, uint32_t) -> Texel {
                const float v = x < 31 ? 1.0f : x == 31 ? half : 0.0f;
                return {v, v, v, 1};
            };
            out.push_back(within("colour_srgb_" + std::to_string(samples) + "x",
                                 d.readTexture(resS), expectImage(Format::RGBA8_SRGB, expected),
                                 1.0 / 255.0,
                                 "linear average of the edge's samples, encoded: one 8-bit step"));
        }
        // A single-sample pipeline in a multisampled pass, and reading a multisampled texture, are errors.
        GraphicsPipelineDesc single = pd;
        single.multisample.sampleCount = 1;
        PipelineHandle p1 = iteration.add(d.createGraphicsPipeline(single));
        auto bad = d.createCommandList();
        bad->beginRenderPass({.colors = {{.texture = ms}}, .depth = {.texture = msDepth}});
        FE_CONFORMANCE_CHECK(throws([&] { bad->setPipeline(p1); }),
                             "a pipeline's sample count must match the pass");
        bad->endRenderPass();
        d.wait(d.submit(*bad));
        FE_CONFORMANCE_CHECK(throws([&] { d.readTexture(ms); }),
                             "a multisampled texture cannot be read back");
    }
    return out;
}

// Four targets of mixed formats and a depth/stencil target, all multisampled, each resolved
// into its own texture at the end of one pass: the half-covered column averages each target's
// value with its clear (0), and depth takes sample 0 (inside, for 4 samples).
std::vector<CaseImage> msaaMultipleTargets(Device& d) {
    std::vector<CaseImage> out;
    const uint32_t counts = d.info().limits.colorSampleCounts & d.info().limits.depthSampleCounts;
    if (!(counts & 4)) return out;
    const std::vector<Format> formats = {Format::RGBA8, Format::RGBA16F, Format::RG16F,
                                         Format::R32F};
    const Texel values[4] = {{0.2f, 0.4f, 0.6f, 0.8f},
                             {1.5f, -2.0f, 3.25f, 1.0f},
                             {0.125f, 4.5f, 0, 1},
                             {-7.75f, 0, 0, 1}};
    DepthGeometry geo(d);
    DeviceObjects objects(d);
    ShaderHandle mrt = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/mrt.frag")}));
    GraphicsPipelineDesc pd = geo.desc;
    pd.fragmentShader = mrt;
    pd.colorFormats = formats;
    pd.depthFormat = Format::D24S8;
    pd.depthStencil = {.depthTest = true, .depthWrite = true};
    pd.multisample.sampleCount = 4;
    PipelineHandle p = objects.add(d.createGraphicsPipeline(pd));
    std::vector<Vertex3> v = quad(-1, 31.5f / 32.0f - 1.0f, -1, 1, 0.25f, 0.25f, {1, 1, 1, 1});
    BufferHandle vb = objects.add(d.createBuffer(
        {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
    auto make = [&](Format f, uint32_t samples) {
        return objects.add(d.createTexture({.format = f,
                                            .width = kCaseSize,
                                            .height = kCaseSize,
                                            .sampleCount = samples,
                                            .usage = kTarget}));
    };
    RenderPassDesc rp;
    std::vector<TextureHandle> resolved;
    for (Format f : formats) {
        resolved.push_back(make(f, 1));
        rp.colors.push_back(
            {.texture = make(f, 4), .store = StoreOp::DontCare, .resolveTexture = resolved.back()});
    }
    TextureHandle depth = make(Format::D24S8, 1);
    rp.depth = {
        .texture = make(Format::D24S8, 4), .store = StoreOp::DontCare, .resolveTexture = depth};
    auto cmd = d.createCommandList();
    cmd->beginRenderPass(rp);
    cmd->setPipeline(p);
    cmd->setVertexBuffer(0, vb);
    cmd->draw(6);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    for (size_t i = 0; i < formats.size(); ++i) {
        auto expected = [&](uint32_t x, uint32_t) -> Texel {
            const float k = x < 31 ? 1.0f : x == 31 ? 0.5f : 0.0f;
            return {values[i][0] * k, values[i][1] * k, values[i][2] * k, values[i][3] * k};
        };
        out.push_back(
            within("target" + std::to_string(i) + "_" + std::string(formatInfo(formats[i]).name),
                   d.readTexture(resolved[i]), expectImage(formats[i], expected),
                   formatInfo(formats[i]).isFloat ? 1e-3 : 1.0 / 255.0,
                   "averages of values exact in the format (8-bit: one step of rounding)"));
    }
    auto depthExpected = [](uint32_t x, uint32_t) -> Texel {
        return {x <= 31 ? 0.25f : 1.0f, 0, 0, 1};
    };
    out.push_back(within("depth_D24S8_sample0", d.readTexture(depth),
                         expectImage(Format::D24S8, depthExpected), std::ldexp(1.0, -23),
                         "24-bit depth: one step"));
    return out;
}

// Alpha to coverage: alpha 0 covers no sample, alpha 1 all of them, alpha 0.5 about half (the
// exact mask, dithered or not, is the implementation's; its mean is checked, and the image is
// compared across backends).
std::vector<CaseImage> msaaAlphaToCoverage(Device& d) {
    std::vector<CaseImage> out;
    const uint32_t counts = d.info().limits.colorSampleCounts;
    const uint32_t samples = (counts & 4) ? 4 : (counts & 8) ? 8 : (counts & 2) ? 2 : 0;
    if (!samples) return out;
    DeviceObjects objects(d);
    ShaderHandle vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    ShaderHandle fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    PipelineHandle p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .multisample = {.sampleCount = samples, .alphaToCoverage = true},
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}}));
    for (float alpha : {0.0f, 0.5f, 1.0f}) {
        DeviceObjects iteration(d);
        const std::array<float, 8> params = {1, 1, 1, alpha, 0, 0, 0, 0};
        BufferHandle ubo = iteration.add(d.createBuffer(
            {.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
        TextureHandle ms = iteration.add(d.createTexture(
            {.width = kCaseSize, .height = kCaseSize, .sampleCount = samples, .usage = kTarget}));
        TextureHandle color = iteration.add(
            d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = kTarget}));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass(
            {.colors = {{.texture = ms, .clear = {0, 0, 0, 0}, .resolveTexture = color}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        Image img = d.readTexture(color);
        double mean = 0;
        for (uint32_t y = 0; y < kCaseSize; ++y)
            for (uint32_t x = 0; x < kCaseSize; ++x)
                mean += img.texel(x, y)[0] / double(kCaseSize * kCaseSize);
        const std::string n = "alpha_" + std::to_string(int(alpha * 100));
        if (alpha == 0.5f) {
            FE_CONFORMANCE_CHECK(std::abs(mean - 0.5) <= 0.5 / samples + 0.01,
                                 "alpha 0.5 covers about half the samples");
            out.push_back({n, img, {}});
        } else {
            CaseImage ci{n, img, solid(Format::RGBA8, {alpha, alpha, alpha, alpha})};
            ci.absTolerance = 1.0 / 255.0;
            ci.maxFractionOver = 0;
            out.push_back(std::move(ci));
        }
    }
    return out;
}

// --- Shadow-map state ---------------------------------------------------------------------------

// An 8x8 D32F texture, owned by `objects`: depth 0.25 in columns 0-3, 0.75 in columns 4-7 (a
// known depth step).
TextureHandle depthStep(DeviceObjects& objects) {
    Device& d = objects.device();
    TextureHandle t = objects.add(d.createTexture(
        {.format = Format::D32F,
         .width = 8,
         .height = 8,
         .usage = TextureUsage::RenderTarget | TextureUsage::Sampled | TextureUsage::CopySrc}));
    DeviceObjects drawing(d);
    ShaderHandle vs =
        drawing.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    PipelineHandle p = drawing.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .depthStencil = {.depthTest = true, .depthWrite = true, .depthCompare = CompareOp::Always},
         .depthFormat = Format::D32F,
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::Vertex}}}));
    const std::array<float, 8> params = {0, 0, 0, 0, 0.25f, 0, 0, 0};
    BufferHandle ubo = drawing.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.depth = {.texture = t, .clearDepth = 0.75f}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->setScissor({0, 0, 4, 8});
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return t;
}

bool compareResult(CompareOp op, float ref, float depth) {
    switch (op) {
        case CompareOp::Never:
            return false;
        case CompareOp::Less:
            return ref < depth;
        case CompareOp::Equal:
            return ref == depth;
        case CompareOp::LessOrEqual:
            return ref <= depth;
        case CompareOp::Greater:
            return ref > depth;
        case CompareOp::NotEqual:
            return ref != depth;
        case CompareOp::GreaterOrEqual:
            return ref >= depth;
        case CompareOp::Always:
            return true;
    }
    return false;
}

SamplerDesc compareSampler(CompareOp op, Filter filter) {
    return {.minFilter = filter,
            .magFilter = filter,
            .addressU = AddressMode::ClampToEdge,
            .addressV = AddressMode::ClampToEdge,
            .addressW = AddressMode::ClampToEdge,
            .compareEnable = true,
            .compare = op};
}

// Every compare op with the reference equal to the near side of the step: 0 or 1 per side.
std::vector<CaseImage> shadowCompareOps(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects objects(d);
    TextureHandle step = depthStep(objects);
    out.push_back(exact("depth_step", d.readTexture(step),
                        expectImage(
                            Format::D32F,
                            [](uint32_t x, uint32_t) -> Texel {
                                return {x < 4 ? 0.25f : 0.75f, 0, 0, 1};
                            },
                            8, 8)));
    static const char* names[] = {
        "never", "less", "equal", "less_or_equal", "greater", "not_equal", "greater_or_equal",
        "always"};
    for (int i = 0; i < 8; ++i) {
        const CompareOp op = CompareOp(i);
        FullscreenSampler fs(d, "conformance/shadow_2d.frag", compareSampler(op, Filter::Nearest));
        out.push_back(exact(names[i], fs.draw(d, step, Format::RGBA8, {0.25f}),
                            expectImage(Format::RGBA8, [&](uint32_t x, uint32_t) -> Texel {
                                const float v =
                                    compareResult(op, 0.25f, x < 32 ? 0.25f : 0.75f) ? 1.0f : 0.0f;
                                return {v, v, v, v};
                            })));
    }
    return out;
}

// Linear filtering of comparison results (hardware PCF) across the step: each pixel is the
// bilinear weight of the taps on the far side, where the reference 0.5 passes LessOrEqual.
std::vector<CaseImage> shadowComparePcf(Device& d) {
    DeviceObjects objects(d);
    TextureHandle step = depthStep(objects);
    FullscreenSampler fs(d, "conformance/shadow_2d.frag",
                         compareSampler(CompareOp::LessOrEqual, Filter::Linear));
    auto pcf = [](uint32_t x, uint32_t) -> Texel {
        const double u = (x + 0.5) / 64.0 * 8.0 - 0.5;
        const double i0 = std::floor(u), w = u - i0;
        auto pass = [](double i) { return std::clamp(i, 0.0, 7.0) >= 4 ? 1.0 : 0.0; };
        const float v = float((1 - w) * pass(i0) + w * pass(i0 + 1));
        return {v, v, v, v};
    };
    CaseImage ci =
        within("pcf_across_step", fs.draw(d, step, Format::RGBA16F, {0.5f}),
               expectImage(Format::RGBA16F, pcf), 1.0 / 64.0,
               "filter weights have 8 sub-texel bits on Mesa (1/256) and fewer elsewhere: 1/64");
    return {ci};
}

// sampler2DArrayShadow reads the layer it is given; samplerCubeShadow the face its direction
// addresses.
std::vector<CaseImage> shadowArrayCube(Device& d) {
    std::vector<CaseImage> out;
    const TextureUsage usage = TextureUsage::RenderTarget | TextureUsage::Sampled;
    DeviceObjects objects(d);
    TextureHandle arr = objects.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                                     .format = Format::D32F,
                                                     .width = 8,
                                                     .height = 8,
                                                     .depthOrLayers = 2,
                                                     .usage = usage}));
    TextureHandle cube = objects.add(d.createTexture({.dimension = TextureDimension::TextureCube,
                                                      .format = Format::D32F,
                                                      .width = 8,
                                                      .height = 8,
                                                      .depthOrLayers = 6,
                                                      .usage = usage}));
    auto cmd = d.createCommandList();
    for (uint32_t l = 0; l < 2; ++l) {
        cmd->beginRenderPass(
            {.depth = {.texture = arr, .layer = l, .clearDepth = l ? 0.75f : 0.25f}});
        cmd->endRenderPass();
    }
    for (uint32_t f = 0; f < 6; ++f) {
        cmd->beginRenderPass(
            {.depth = {.texture = cube, .layer = f, .clearDepth = 0.1f * float(f + 1) + 0.05f}});
        cmd->endRenderPass();
    }
    d.wait(d.submit(*cmd));
    FullscreenSampler fa(d, "conformance/shadow_array.frag",
                         compareSampler(CompareOp::LessOrEqual, Filter::Nearest));
    for (uint32_t l = 0; l < 2; ++l)
        out.push_back(exact("array_layer" + std::to_string(l),
                            fa.draw(d, arr, Format::RGBA8, {0.5f, float(l)}),
                            solid(Format::RGBA8, l ? Texel{1, 1, 1, 1} : Texel{0, 0, 0, 0})));
    FullscreenSampler fc(d, "conformance/shadow_cube.frag",
                         compareSampler(CompareOp::LessOrEqual, Filter::Nearest));
    out.push_back(exact("cube_faces", fc.draw(d, cube, Format::RGBA8, {0.4f}),
                        expectImage(Format::RGBA8, [](uint32_t x, uint32_t) -> Texel {
                            const uint32_t face = uint32_t((x + 0.5) * 6.0 / 64.0);
                            const float v = 0.4f <= 0.1f * float(face + 1) + 0.05f ? 1.0f : 0.0f;
                            return {v, v, v, v};
                        })));
    return out;
}

// Draws a full-screen quad from depth z0 (left) to z1 (right) into a cleared D32F target with
// the given raster state and reads the depth back.
Image biasedDepth(Device& d, float z0, float z1, RasterState raster) {
    DepthGeometry geo(d);
    GraphicsPipelineDesc pd = geo.desc;
    pd.fragmentShader = {};
    pd.raster = raster;
    pd.depthFormat = Format::D32F;
    pd.depthStencil = {.depthTest = true, .depthWrite = true, .depthCompare = CompareOp::Always};
    DeviceObjects objects(d);
    PipelineHandle p = objects.add(d.createGraphicsPipeline(pd));
    std::vector<Vertex3> v = quad(-1, 1, -1, 1, z0, z1, {1, 1, 1, 1});
    BufferHandle vb = objects.add(d.createBuffer(
        {.size = v.size() * sizeof(Vertex3), .usage = BufferUsage::Vertex}, bytesOf(v)));
    TextureHandle t = objects.add(d.createTexture(
        {.format = Format::D32F, .width = kCaseSize, .height = kCaseSize, .usage = kTarget}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.depth = {.texture = t, .clearDepth = 1.0f}});
    cmd->setPipeline(p);
    cmd->setVertexBuffer(0, vb);
    cmd->draw(6);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return d.readTexture(t);
}

// offset = slope * m + constant * r, clamped: constant alone on a flat quad at 0.5 moves depth
// by constant * 2^-24 (D32F, exponent of 0.5 is -1); slope alone on a quad whose depth grows by
// 0.25 per 32 pixels moves it by slope / 128; a clamp caps the offset.
std::vector<CaseImage> depthBias(Device& d) {
    std::vector<CaseImage> out;
    auto ramp = [](uint32_t x) { return 0.5f + 0.25f * ((float(x) + 0.5f) / 32.0f - 1.0f); };
    auto check = [&](const std::string& name, Image img,
                     const std::function<float(uint32_t)>& expected, double tol,
                     const char* reason) {
        auto texel = [&](uint32_t x, uint32_t) -> Texel { return {expected(x), 0, 0, 1}; };
        out.push_back(within(name, img, expectImage(Format::D32F, texel), tol, reason));
    };
    const float r = std::ldexp(1.0f, -24);
    check(
        "none", biasedDepth(d, 0.5f, 0.5f, {}), [](uint32_t) { return 0.5f; }, 0, "no bias: exact");
    check(
        "constant_64", biasedDepth(d, 0.5f, 0.5f, {.depthBiasConstant = 64}),
        [&](uint32_t) { return 0.5f + 64 * r; }, 4 * r, "64 r with r = 2^-24: within 4 r");
    check(
        "slope_2", biasedDepth(d, 0.25f, 0.75f, {.depthBiasSlope = 2}),
        [&](uint32_t x) { return ramp(x) + 2.0f / 128.0f; }, 2e-4,
        "m = 1/128 per pixel from the rasterizer's plane equation: within 2e-4 of 1/64");
    if (d.info().features.depthBiasClamp)
        check(
            "slope_2_clamped",
            biasedDepth(d, 0.25f, 0.75f, {.depthBiasSlope = 2, .depthBiasClamp = 0.01f}),
            [&](uint32_t x) { return ramp(x) + 0.01f; }, 2e-4, "offset 1/64 clamped to 0.01");
    return out;
}

// Depth clamp keeps fragments beyond the far (near) plane at depth 1 (0); without it they are
// clipped away.
std::vector<CaseImage> depthClamp(Device& d) {
    std::vector<CaseImage> out;
    if (!d.info().features.depthClamp) return out;
    DeviceObjects objects(d);
    ShaderHandle vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    ShaderHandle fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    for (float z : {1.5f, -0.5f})
        for (bool clamp : {false, true}) {
            DeviceObjects iteration(d);
            PipelineHandle p = iteration.add(d.createGraphicsPipeline(
                {.vertexShader = vs,
                 .fragmentShader = fs,
                 .raster = {.depthClamp = clamp},
                 .depthStencil = {.depthTest = true,
                                  .depthWrite = true,
                                  .depthCompare = CompareOp::Always},
                 .colorFormats = {Format::RGBA8},
                 .depthFormat = Format::D32F,
                 .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}}));
            const std::array<float, 8> params = {1, 0.5f, 0, 1, z, 0, 0, 0};
            BufferHandle ubo = iteration.add(d.createBuffer(
                {.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
            TextureHandle c = iteration.add(
                d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = kTarget}));
            TextureHandle t = iteration.add(d.createTexture({.format = Format::D32F,
                                                             .width = kCaseSize,
                                                             .height = kCaseSize,
                                                             .usage = kTarget}));
            auto cmd = d.createCommandList();
            cmd->beginRenderPass({.colors = {{.texture = c, .clear = {0, 0, 0, 1}}},
                                  .depth = {.texture = t, .clearDepth = 0.5f}});
            cmd->setPipeline(p);
            cmd->setUniformBuffer(0, ubo);
            cmd->draw(3);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            const std::string n =
                std::string(z > 1 ? "far" : "near") + (clamp ? "_clamped" : "_clipped");
            out.push_back(
                exact(n + "_colour", d.readTexture(c),
                      solid(Format::RGBA8, clamp ? Texel{1, 0.5f, 0, 1} : Texel{0, 0, 0, 1})));
            out.back().absTolerance = 1.0 / 255.0;
            out.push_back(
                exact(n + "_depth", d.readTexture(t),
                      solid(Format::D32F, {clamp ? (z > 1 ? 1.0f : 0.0f) : 0.5f, 0, 0, 1})));
        }
    return out;
}

// --- Indirect work ------------------------------------------------------------------------------

struct Vertex2 {
    float x, y;
    float r, g, b, a;
};

// Quads A (red, left), B (green, right) and C (blue, centre, indexed: 4 corners at vertex 12),
// all in the upper half; instances 2, 3 and 5 move theirs into the lower half.
struct IndirectScene {
    DeviceObjects objects;
    ShaderHandle vs, fs, cs;
    PipelineHandle draw, compute;
    BufferHandle vertices, instances, indices, args;
    explicit IndirectScene(Device& d) : objects(d) {
        vs =
            objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                        .binary = shaders::find("conformance/vertex_color.vert")}));
        fs = objects.add(d.createShader(
            {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")}));
        cs = objects.add(
            d.createShader({.stage = ShaderStage::Compute,
                            .binary = shaders::find("conformance/indirect_args.comp")}));
        draw = objects.add(d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .vertexBuffers =
                 {{.stride = sizeof(Vertex2),
                   .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}},
                  {.stride = 8, .perInstance = true, .attributes = {{2, VertexFormat::Float2, 0}}}},
             .colorFormats = {Format::RGBA8}}));
        compute = objects.add(d.createComputePipeline(
            {.computeShader = cs,
             .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute}}}));
        std::vector<Vertex2> v;
        auto addQuad = [&](float x0, float x1, Texel c) {
            for (auto [x, y] :
                 {std::pair{x0, -0.75f}, std::pair{x1, -0.75f}, std::pair{x0, -0.25f},
                  std::pair{x0, -0.25f}, std::pair{x1, -0.75f}, std::pair{x1, -0.25f}})
                v.push_back({x, y, c[0], c[1], c[2], c[3]});
        };
        addQuad(-0.75f, -0.5f, {1, 0, 0, 1});
        addQuad(0.5f, 0.75f, {0, 1, 0, 1});
        for (auto [x, y] : {std::pair{-0.25f, -0.75f}, std::pair{0.25f, -0.75f},
                            std::pair{-0.25f, -0.25f}, std::pair{0.25f, -0.25f}})
            v.push_back({x, y, 0, 0, 1, 1});
        vertices = objects.add(d.createBuffer(
            {.size = v.size() * sizeof(Vertex2), .usage = BufferUsage::Vertex}, bytesOf(v)));
        const float offsets[12] = {0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
        instances = objects.add(d.createBuffer(
            {.size = sizeof offsets, .usage = BufferUsage::Vertex}, bytesOf(offsets)));
        const uint16_t idx[6] = {0, 1, 2, 2, 1, 3};
        indices = objects.add(
            d.createBuffer({.size = sizeof idx, .usage = BufferUsage::Index}, bytesOf(idx)));
        args = objects.add(d.createBuffer({.size = 256,
                                           .usage = BufferUsage::Storage | BufferUsage::Indirect,
                                           .debugName = "indirect args"}));
    }
    // The compute pass writes the argument records, then `record` draws from them.
    Image run(Device& d, const std::function<void(CommandList&)>& record) {
        DeviceObjects running(d);
        TextureHandle t = running.add(
            d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = kTarget}));
        auto cmd = d.createCommandList();
        cmd->setPipeline(compute);
        cmd->setStorageBuffer(0, args);
        cmd->dispatch(1);
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
        cmd->setPipeline(draw);
        cmd->setVertexBuffer(0, vertices);
        cmd->setVertexBuffer(1, instances);
        cmd->setIndexBuffer(indices, IndexType::U16);
        record(*cmd);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        return d.readTexture(t);
    }
};

// Which quads an image should show: pixel rows 8-15 are the upper half's quads (NDC y -0.75 to
// -0.25 -> rows 8..23), rows 40-55 the lower half's.
Image expectQuads(bool aUp, bool bUp, bool aDown, bool bDown, bool cUp = false,
                  bool cDown = false) {
    return expectImage(Format::RGBA8, [=](uint32_t x, uint32_t y) -> Texel {
        const bool up = y >= 8 && y < 24, down = y >= 40 && y < 56;
        if (x >= 8 && x < 16 && ((up && aUp) || (down && aDown))) return {1, 0, 0, 1};
        if (x >= 48 && x < 56 && ((up && bUp) || (down && bDown))) return {0, 1, 0, 1};
        if (x >= 24 && x < 40 && ((up && cUp) || (down && cDown))) return {0, 0, 1, 1};
        return {0, 0, 0, 1};
    });
}

// Arguments written by a compute shader draw exactly what they say.
std::vector<CaseImage> drawIndirect(Device& d) {
    std::vector<CaseImage> out;
    IndirectScene s(d);
    out.push_back(exact("one_record", s.run(d, [&](CommandList& c) { c.drawIndirect(s.args, 0); }),
                        expectQuads(true, false, false, false)));
    out.push_back(exact("second_record",
                        s.run(d, [&](CommandList& c) { c.drawIndirect(s.args, 16); }),
                        expectQuads(false, true, false, false)));
    if (d.info().features.multiDrawIndirect)
        out.push_back(exact("four_records",
                            s.run(d, [&](CommandList& c) { c.drawIndirect(s.args, 0, 4); }),
                            expectQuads(true, true, true, true)));
    FE_CONFORMANCE_CHECK(
        throws([&] { s.run(d, [&](CommandList& c) { c.drawIndirect(s.args, 248); }); }),
        "a record past the end of the buffer is an error");
    DeviceObjects objects(d);
    BufferHandle plain = objects.add(d.createBuffer({.size = 64, .usage = BufferUsage::Storage}));
    FE_CONFORMANCE_CHECK(
        throws([&] { s.run(d, [&](CommandList& c) { c.drawIndirect(plain, 0); }); }),
        "an argument buffer without Indirect usage is an error");
    return out;
}

std::vector<CaseImage> drawIndexedIndirect(Device& d) {
    IndirectScene s(d);
    std::vector<CaseImage> out;
    out.push_back(exact("two_instances_base_vertex",
                        s.run(d, [&](CommandList& c) { c.drawIndexedIndirect(s.args, 128); }),
                        expectQuads(false, false, false, false, true, true)));
    FE_CONFORMANCE_CHECK(throws([&] {
                             s.run(d, [&](CommandList& c) {
                                 c.setIndexBuffer(s.indices, IndexType::U16, 2);
                                 c.drawIndexedIndirect(s.args, 128);
                             });
                         }),
                         "indexed indirect draws need the index buffer at offset 0");
    return out;
}

// The draw count comes from the GPU: 2 of at most 4 records.
std::vector<CaseImage> drawIndirectCount(Device& d) {
    IndirectScene s(d);
    std::vector<CaseImage> out;
    if (d.info().features.drawIndirectCount) {
        out.push_back(
            exact("gpu_count_2_of_4",
                  s.run(d, [&](CommandList& c) { c.drawIndirectCount(s.args, 0, s.args, 64, 4); }),
                  expectQuads(true, true, false, false)));
        out.push_back(
            exact("capped_at_1",
                  s.run(d, [&](CommandList& c) { c.drawIndirectCount(s.args, 0, s.args, 64, 1); }),
                  expectQuads(true, false, false, false)));
    } else {
        FE_CONFORMANCE_CHECK(
            throws([&] {
                s.run(d, [&](CommandList& c) { c.drawIndirectCount(s.args, 0, s.args, 64, 4); });
            }),
            "drawIndirectCount where the device lacks it is a clear error");
    }
    return out;
}

// fill.comp dispatched with group counts a compute shader wrote (8x8x1) fills the whole
// 64x64 buffer, as the direct dispatch in compute_buffer_and_image does.
std::vector<CaseImage> dispatchIndirect(Device& d) {
    IndirectScene s(d);
    DeviceObjects objects(d);
    auto fillShader = objects.add(d.createShader(
        {.stage = ShaderStage::Compute, .binary = shaders::find("conformance/fill.comp")}));
    PipelineHandle fill = objects.add(d.createComputePipeline(
        {.computeShader = fillShader,
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                      {1, BindingType::StorageTexture, ShaderStage::Compute}}}));
    BufferHandle buf = objects.add(
        d.createBuffer({.size = kCaseSize * kCaseSize * 4, .usage = BufferUsage::Storage}));
    TextureHandle img =
        objects.add(d.createTexture({.format = Format::RGBA32F,
                                     .width = kCaseSize,
                                     .height = kCaseSize,
                                     .usage = TextureUsage::Storage | TextureUsage::CopySrc}));
    auto cmd = d.createCommandList();
    cmd->setPipeline(s.compute);
    cmd->setStorageBuffer(0, s.args);
    cmd->dispatch(1);
    cmd->setPipeline(fill);
    cmd->setStorageBuffer(0, buf);
    cmd->setStorageTexture(1, img);
    cmd->dispatchIndirect(s.args, 192);
    d.wait(d.submit(*cmd));
    Image values{kCaseSize, kCaseSize, Format::R32U,
                 d.readBuffer(buf, 0, kCaseSize * kCaseSize * 4)};
    CaseImage a =
        exact("buffer", values, expectImage(Format::R32U, [](uint32_t x, uint32_t y) -> Texel {
                  return {float(3 * (y * kCaseSize + x) + 1), 0, 0, 1};
              }));
    return {a};
}

}  // namespace

std::vector<Case> stateCases() {
    return {
        {"msaa_resolve", msaaResolve},
        {"transient_attachments", transientAttachments},
        {"msaa_texel_fetch", msaaTexelFetch},
        {"msaa_copy", msaaCopy},
        {"msaa_multiple_targets", msaaMultipleTargets},
        {"msaa_alpha_to_coverage", msaaAlphaToCoverage},
        {"shadow_compare_ops", shadowCompareOps},
        {"shadow_compare_pcf", shadowComparePcf},
        {"shadow_array_cube", shadowArrayCube},
        {"depth_bias", depthBias},
        {"depth_clamp", depthClamp},
        {"draw_indirect", drawIndirect},
        {"draw_indexed_indirect", drawIndexedIndirect},
        {"draw_indirect_count", drawIndirectCount},
        {"dispatch_indirect", dispatchIndirect},
    };
}

}  // namespace fe::conformance
