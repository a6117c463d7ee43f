// Conformance cases for sampler state (border colours, level-of-detail bias and clamps), vertex
// and index fetch (stride-0 buffers, primitive restart), zero-initialised resources, the sample
// mask, and the pipeline state a command list may change between draws (blend constant,
// stencil reference, depth bias).
#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <vector>

#include "CaseSupport.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr TextureUsage kTarget = TextureUsage::RenderTarget | TextureUsage::CopySrc;
constexpr Rect kWhole{0, 0, kCaseSize, kCaseSize};

// An 8-bit colour: k/255 survives the float-to-unorm conversion of clears, draws and samples.
Texel rgb8(uint32_t r, uint32_t g, uint32_t b) {
    return {r / 255.0f, g / 255.0f, b / 255.0f, 1.0f};
}

bool inside(uint32_t x, uint32_t y, Rect r) {
    return int32_t(x) >= r.x && x < r.x + r.width && int32_t(y) >= r.y && y < r.y + r.height;
}
// `background`, with `in` over rectangle r.
Image rectImage(Texel background, Rect r, Texel in) {
    return expectImage(Format::RGBA8,
                       [=](uint32_t x, uint32_t y) { return inside(x, y, r) ? in : background; });
}

// The uniform block of fullscreen_ubo.vert and ubo_color.frag.
struct Params {
    float color[4];
    float depth[4];  // x: the full-screen triangle's depth
};
BufferHandle params(DeviceObjects& o, Texel c, float depth = 0.5f) {
    const Params p{{c[0], c[1], c[2], c[3]}, {depth, 0, 0, 0}};
    return o.add(
        o.device().createBuffer({.size = sizeof p, .usage = BufferUsage::Uniform}, bytesOf(p)));
}

// --- Samplers -----------------------------------------------------------------------------------

// A 4x4 texture of 16 distinct opaque texels (none black or white), and its texel i = 4 row + column.
Texel tileTexel(uint32_t i) { return rgb8(i * 16, 255 - i * 16, (i % 4) * 80 + 10); }

// ClampToBorder: textured_uv.frag at uv = pixel / 32 - 0.5 shows the 4x4 texture, 8 pixels a
// texel, over pixels [16, 48) (uv in [0, 1]) and the border colour around it, for each of the
// three colours. Without ClampToBorder (clamped to the edge, repeated) the edge texels or the
// texture show outside; a border colour not passed on gives the same colour for all three.
std::vector<CaseImage> borderColor(Device& d) {
    DeviceObjects o(d);
    const TextureHandle tex =
        o.add(d.createTexture({.width = 4,
                               .height = 4,
                               .usage = TextureUsage::Sampled | TextureUsage::CopyDst,
                               .debugName = "tiles"}));
    const Image tiles = expectImage(
        Format::RGBA8, [](uint32_t x, uint32_t y) { return tileTexel(4 * y + x); }, 4, 4);
    d.writeTexture(tex, {}, bytesOf(tiles.data));
    struct Border {
        BorderColor color;
        Texel value;
        const char* name;
    };
    const Border borders[3] = {{BorderColor::TransparentBlack, {0, 0, 0, 0}, "transparent_black"},
                               {BorderColor::OpaqueBlack, {0, 0, 0, 1}, "opaque_black"},
                               {BorderColor::OpaqueWhite, {1, 1, 1, 1}, "opaque_white"}};
    std::vector<CaseImage> out;
    for (const Border& b : borders) {
        FullscreenSampler pass(d, "conformance/textured_uv.frag",
                               {.minFilter = Filter::Nearest,
                                .magFilter = Filter::Nearest,
                                .addressU = AddressMode::ClampToBorder,
                                .addressV = AddressMode::ClampToBorder,
                                .addressW = AddressMode::ClampToBorder,
                                .borderColor = b.color});
        const Image image = pass.draw(d, tex, Format::RGBA8, {2, 2, -0.5f, -0.5f});
        const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
            if (x < 16 || x >= 48 || y < 16 || y >= 48) return b.value;
            return tileTexel(4 * ((y - 16) / 8) + (x - 16) / 8);
        });
        out.push_back(within(
            b.name, image, expected, 1.0 / 255.0,
            "k/255 texels and 0/1 border colours sampled into an 8-bit target: one step of rounding"));
    }
    return out;
}

// Level of detail = computed + lodBias, clamped to [minLod, maxLod]: a 64x64 texture with a
// solid colour per mip, drawn by textured.frag at one texel per pixel (computed level 0)
// through Nearest/MipFilter::Nearest samplers. No bias shows level 0; lodBias 2 level 2;
// minLod 1 level 1; lodBias 3 capped by maxLod 1 level 1. Ignoring the bias or either clamp
// shows another level's colour.
std::vector<CaseImage> lodBiasAndClamp(Device& d) {
    constexpr uint32_t kLevels = 4;
    const Texel levelColor[kLevels] = {rgb8(240, 16, 16), rgb8(16, 240, 16), rgb8(16, 16, 240),
                                       rgb8(240, 240, 16)};
    DeviceObjects o(d);
    const TextureHandle tex =
        o.add(d.createTexture({.width = kCaseSize,
                               .height = kCaseSize,
                               .mipLevels = kLevels,
                               .usage = TextureUsage::Sampled | TextureUsage::CopyDst,
                               .debugName = "level colours"}));
    for (uint32_t m = 0; m < kLevels; ++m) {
        const Image level = solid(Format::RGBA8, levelColor[m], kCaseSize >> m, kCaseSize >> m);
        d.writeTexture(tex, {.mipLevel = m}, bytesOf(level.data));
    }
    struct Lod {
        float bias, minLod, maxLod;
        uint32_t level;
        const char* name;
    };
    const Lod lods[4] = {{0, 0, 1000, 0, "no_bias_level0"},
                         {2, 0, 1000, 2, "bias2_level2"},
                         {0, 1, 1000, 1, "min_lod1_level1"},
                         {3, 0, 1, 1, "bias3_max_lod1_level1"}};
    std::vector<CaseImage> out;
    for (const Lod& l : lods) {
        FullscreenSampler pass(d, "conformance/textured.frag",
                               {.minFilter = Filter::Nearest,
                                .magFilter = Filter::Nearest,
                                .mipFilter = MipFilter::Nearest,
                                .addressU = AddressMode::ClampToEdge,
                                .addressV = AddressMode::ClampToEdge,
                                .addressW = AddressMode::ClampToEdge,
                                .lodBias = l.bias,
                                .minLod = l.minLod,
                                .maxLod = l.maxLod});
        out.push_back(within(l.name, pass.draw(d, tex, Format::RGBA8),
                             solid(Format::RGBA8, levelColor[l.level]), 1.0 / 255.0,
                             "k/255 texels sampled into an 8-bit target: one step of rounding"));
    }
    return out;
}

// --- Vertex and index fetch ---------------------------------------------------------------------

// A vertex buffer of stride 0: every vertex reads its first element. vertex_attr.vert takes
// positions from buffer 0 (stride 8) and the colour from buffer 1 (stride 0), whose first
// colour is the one expected and the rest red: a stride taken as tightly packed (GL's
// glVertexAttribPointer reading of 0) shows red on vertices 1-5.
std::vector<CaseImage> strideZeroVertex(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = caseTarget(o);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/vertex_attr.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/value.frag"),
         .vertexBuffers = {{.stride = 8, .attributes = {{0, VertexFormat::Float2, 0}}},
                           {.stride = 0, .attributes = {{1, VertexFormat::Float4, 0}}}},
         .colorFormats = {Format::RGBA8},
         .debugName = "stride 0 colour"}));
    // Pixels [16, 48) x [8, 40): NDC x in [-0.5, 0.5], y in [-0.75, 0.25].
    const float positions[12] = {-0.5f, -0.75f, 0.5f, -0.75f, -0.5f, 0.25f,
                                 -0.5f, 0.25f,  0.5f, -0.75f, 0.5f,  0.25f};
    const Texel color = rgb8(51, 153, 204), red = rgb8(255, 0, 0);
    const std::array<Texel, 6> colors = {color, red, red, red, red, red};
    const BufferHandle pb = o.add(d.createBuffer(
        {.size = sizeof positions, .usage = BufferUsage::Vertex}, bytesOf(positions)));
    const BufferHandle cb = o.add(
        d.createBuffer({.size = sizeof colors, .usage = BufferUsage::Vertex}, bytesOf(colors)));
    const Texel clear = rgb8(0, 0, 0);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass(
        {.colors = {{.texture = t, .clear = {clear[0], clear[1], clear[2], clear[3]}}}});
    cmd->setPipeline(p);
    cmd->setVertexBuffer(0, pb);
    cmd->setVertexBuffer(1, cb);
    cmd->draw(6);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return {drawn8("constant_colour", d.readTexture(t), rectImage(clear, {16, 8, 32, 32}, color))};
}

// Primitive restart: indices {0, 1, 2, 3, restart, 4, 5, 6, 7} of a triangle strip draw two
// separate quads, pixels [8, 24) and [40, 56) x [16, 48), and nothing between them, with U16
// (restart 0xFFFF) and U32 (0xFFFFFFFF) indices. For U16 the buffer holds 65536 vertices and
// vertex 0xFFFF sits in the gap, so a strip that ran on through it would cover gap pixels.
std::vector<CaseImage> primitiveRestart(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/position.vert"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag");
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .vertexBuffers = {{.stride = 8, .attributes = {{0, VertexFormat::Float2, 0}}}},
         .topology = PrimitiveTopology::TriangleStrip,
         .primitiveRestart = true,
         .colorFormats = {Format::RGBA8},
         .debugName = "restarted strips"}));
    // Unused vertices lie outside the target; each quad is a strip of four corners.
    std::vector<std::array<float, 2>> positions(65536, {5, 5});
    auto strip = [&](uint32_t first, float x0, float x1) {
        positions[first] = {x0, -0.5f};
        positions[first + 1] = {x1, -0.5f};
        positions[first + 2] = {x0, 0.5f};
        positions[first + 3] = {x1, 0.5f};
    };
    strip(0, -0.75f, -0.25f);
    strip(4, 0.25f, 0.75f);
    positions[0xFFFF] = {0.0f, 0.25f};
    const BufferHandle vb = o.add(d.createBuffer({.size = positions.size() * sizeof positions[0],
                                                  .usage = BufferUsage::Vertex,
                                                  .debugName = "strip corners"},
                                                 bytesOf(positions)));
    const uint16_t indices16[9] = {0, 1, 2, 3, 0xFFFF, 4, 5, 6, 7};
    const uint32_t indices32[9] = {0, 1, 2, 3, 0xFFFFFFFFu, 4, 5, 6, 7};
    const BufferHandle ib16 = o.add(d.createBuffer(
        {.size = sizeof indices16, .usage = BufferUsage::Index}, bytesOf(indices16)));
    const BufferHandle ib32 = o.add(d.createBuffer(
        {.size = sizeof indices32, .usage = BufferUsage::Index}, bytesOf(indices32)));
    const Texel color = rgb8(255, 204, 51), clear = rgb8(0, 0, 0);
    const BufferHandle ubo = params(o, color);
    const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) {
        return inside(x, y, {8, 16, 16, 32}) || inside(x, y, {40, 16, 16, 32}) ? color : clear;
    });
    std::vector<CaseImage> out;
    for (IndexType type : {IndexType::U16, IndexType::U32}) {
        const TextureHandle t = caseTarget(o);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass(
            {.colors = {{.texture = t, .clear = {clear[0], clear[1], clear[2], clear[3]}}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->setVertexBuffer(0, vb);
        cmd->setIndexBuffer(type == IndexType::U16 ? ib16 : ib32, type);
        cmd->drawIndexed(9);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(drawn8(type == IndexType::U16 ? "u16_two_strips" : "u32_two_strips",
                             d.readTexture(t), expected));
    }
    return out;
}

// --- Zero-initialised resources -----------------------------------------------------------------

// Makes an object like the one under test, fills it with non-zero bytes and frees it once the
// GPU is done, so that the next one of that size likely takes the same memory: the zero fill is
// then seen, not merely inherited from memory that happened to be fresh.
void dirtyBuffer(Device& d, BufferDesc desc) {
    DeviceObjects o(d);
    desc.debugName = "dirty";
    o.add(d.createBuffer(desc, bytesOf(std::vector<uint8_t>(desc.size, 0xAB))));
    o.clear();
    d.waitIdle();
}
void dirtyTexture(Device& d, TextureDesc desc) {
    DeviceObjects o(d);
    desc.usage = desc.usage | TextureUsage::RenderTarget;
    desc.debugName = "dirty";
    const TextureHandle t = o.add(d.createTexture(desc));
    auto cmd = d.createCommandList();
    for (uint32_t m = 0; m < desc.mipLevels; ++m) {
        if (isDepthFormat(desc.format))
            cmd->beginRenderPass(
                {.depth = {.texture = t, .mipLevel = m, .clearDepth = 0.5f, .clearStencil = 0x5A}});
        else
            cmd->beginRenderPass(
                {.colors = {{.texture = t, .mipLevel = m, .clear = {0.25f, 0.5f, 0.75f, 1}}}});
        cmd->endRenderPass();
    }
    d.wait(d.submit(*cmd));
    o.clear();
    d.waitIdle();
}
bool allZero(const uint8_t* bytes, size_t size) {
    return std::all_of(bytes, bytes + size, [](uint8_t b) { return b == 0; });
}

// New buffers and textures read as zeros (Device.h), each made where a freed one of non-zero
// bytes was: a GpuOnly buffer read back, Upload and Readback buffers through map() (and read
// back), an RGBA8 texture never written (both mips), an RGBA16F render target never drawn and
// a D32F depth target never cleared. A backend that leaves new memory as it finds it shows the
// freed object's bytes.
std::vector<CaseImage> zeroInitialised(Device& d) {
    DeviceObjects o(d);
    {
        const BufferDesc desc{.size = 4096,
                              .usage = BufferUsage::Storage | BufferUsage::CopySrc,
                              .debugName = "new gpu-only"};
        dirtyBuffer(d, desc);
        const BufferHandle b = o.add(d.createBuffer(desc));
        const std::vector<uint8_t> bytes = d.readBuffer(b, 0, desc.size);
        FE_CONFORMANCE_CHECK(bytes.size() == desc.size, "readBuffer returns the bytes asked for");
        FE_CONFORMANCE_CHECK(allZero(bytes.data(), bytes.size()),
                             "a new GpuOnly buffer reads as zeros");
    }
    {
        const BufferDesc desc{.size = 256,
                              .usage = BufferUsage::Uniform | BufferUsage::CopySrc,
                              .access = MemoryAccess::Upload,
                              .debugName = "new upload"};
        dirtyBuffer(d, desc);
        const BufferHandle b = o.add(d.createBuffer(desc));
        const auto* mapped = static_cast<const uint8_t*>(d.map(b));
        FE_CONFORMANCE_CHECK(mapped != nullptr, "an Upload buffer maps");
        FE_CONFORMANCE_CHECK(allZero(mapped, desc.size),
                             "a new Upload buffer's mapped bytes are zeros");
        const std::vector<uint8_t> bytes = d.readBuffer(b, 0, desc.size);
        FE_CONFORMANCE_CHECK(allZero(bytes.data(), bytes.size()),
                             "a new Upload buffer reads back as zeros");
    }
    {
        const BufferDesc desc{.size = 256,
                              .usage = BufferUsage::CopyDst | BufferUsage::CopySrc,
                              .access = MemoryAccess::Readback,
                              .debugName = "new readback"};
        dirtyBuffer(d, desc);
        const BufferHandle b = o.add(d.createBuffer(desc));
        d.waitIdle();  // Readback bytes are valid once the work before them has completed
        const auto* mapped = static_cast<const uint8_t*>(d.map(b));
        FE_CONFORMANCE_CHECK(mapped != nullptr, "a Readback buffer maps");
        FE_CONFORMANCE_CHECK(allZero(mapped, desc.size),
                             "a new Readback buffer's mapped bytes are zeros");
    }
    std::vector<CaseImage> out;
    {
        const TextureDesc desc{.width = kCaseSize,
                               .height = kCaseSize,
                               .mipLevels = 2,
                               .usage = TextureUsage::Sampled | TextureUsage::CopySrc,
                               .debugName = "new sampled"};
        dirtyTexture(d, desc);
        const TextureHandle t = o.add(d.createTexture(desc));
        out.push_back(exact("rgba8_mip0", d.readTexture(t), solid(Format::RGBA8, {0, 0, 0, 0})));
        out.push_back(exact("rgba8_mip1", d.readTexture(t, {.mipLevel = 1}),
                            solid(Format::RGBA8, {0, 0, 0, 0}, kCaseSize / 2, kCaseSize / 2)));
    }
    for (Format f : {Format::RGBA16F, Format::D32F}) {
        const TextureDesc desc{.format = f,
                               .width = kCaseSize,
                               .height = kCaseSize,
                               .usage = kTarget,
                               .debugName = "new target"};
        dirtyTexture(d, desc);
        const TextureHandle t = o.add(d.createTexture(desc));
        out.push_back(exact(f == Format::D32F ? "d32f_target" : "rgba16f_target", d.readTexture(t),
                            solid(f, {0, 0, 0, 0})));
    }
    return out;
}

// --- Sample mask --------------------------------------------------------------------------------

// MultisampleState::sampleMask: a full-screen opaque white draw over black into a 4-sample
// target writes only the samples whose mask bits are set, so the resolve averages to the
// fraction of bits set (1, 2 and 3 of 4: 0.25, 0.5, 0.75). On a single-sample target bit 0
// decides: mask 0 and 0xe draw nothing (lavapipe drew 0xe: any bit set), 1 and all ones
// everything. A mask that is ignored gives white.
std::vector<CaseImage> sampleMask(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex,
                                           "conformance/fullscreen_ubo.vert"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag");
    const BufferHandle white = params(o, {1, 1, 1, 1});
    auto pipeline = [&](uint32_t samples, uint32_t mask) {
        return o.add(
            d.createGraphicsPipeline({.vertexShader = vs,
                                      .fragmentShader = fs,
                                      .multisample = {.sampleCount = samples, .sampleMask = mask},
                                      .colorFormats = {Format::RGBA8},
                                      .debugName = "sample mask"}));
    };
    auto drawInto = [&](PipelineHandle p, const ColorAttachment& attachment) {
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {attachment}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, white);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
    };
    std::vector<CaseImage> out;
    for (uint32_t mask : {0u, 1u, 0xeu, 0xffffffffu}) {
        const TextureHandle t = caseTarget(o);
        drawInto(pipeline(1, mask), {.texture = t, .clear = {0, 0, 0, 1}});
        const float v = float(mask & 1u);
        out.push_back(exact("single_sample_mask" + std::to_string(mask), d.readTexture(t),
                            solid(Format::RGBA8, {v, v, v, 1})));
    }
    if (d.info().limits.colorSampleCounts & 4) {
        const TextureHandle ms = o.add(d.createTexture({.width = kCaseSize,
                                                        .height = kCaseSize,
                                                        .sampleCount = 4,
                                                        .usage = TextureUsage::RenderTarget}));
        for (uint32_t mask : {0b0001u, 0b0011u, 0b1110u}) {
            const TextureHandle resolved = caseTarget(o);
            drawInto(pipeline(4, mask), {.texture = ms,
                                         .store = StoreOp::DontCare,
                                         .clear = {0, 0, 0, 1},
                                         .resolveTexture = resolved});
            const float v = float(std::popcount(mask)) / 4.0f;
            out.push_back(within(
                "msaa4_mask" + std::to_string(mask), d.readTexture(resolved),
                solid(Format::RGBA8, {v, v, v, 1}), 1.5 / 255.0,
                "average of 4 samples of 0 and 1 (0.25 and 0.75 round either way in 8 bits)"));
        }
    }
    return out;
}

// gl_SampleMask written by the fragment shader (sample_mask_columns.frag: per column of four, no
// sample, sample 0, samples 1-3, every sample; the last column's lower half nothing, from a second
// return). A single-sample target keeps the fragments whose mask has bit 0 set, as Vulkan does
// (GL ignores the mask without sample buffers: the device rewrites the shader there); a 4-sample
// target resolves to the fraction of samples written.
std::vector<CaseImage> shaderSampleMask(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex,
                                           "conformance/fullscreen_ubo.vert"),
                       fs = registryShader(o, ShaderStage::Fragment,
                                           "conformance/sample_mask_columns.frag");
    const BufferHandle unused = params(o, {0, 0, 0, 0});
    auto drawInto = [&](uint32_t samples, const ColorAttachment& attachment) {
        const PipelineHandle p =
            o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = fs,
                                            .multisample = {.sampleCount = samples},
                                            .colorFormats = {Format::RGBA8},
                                            .debugName = "shader sample mask"}));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {attachment}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, unused);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
    };
    auto expected = [](const std::array<float, 4>& byColumn) {
        return expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
            const float v = x % 4 == 3 && y >= 32 ? 0.0f : byColumn[x % 4];
            return {v, v, v, 1};
        });
    };
    std::vector<CaseImage> out;
    const TextureHandle single = caseTarget(o);
    drawInto(1, {.texture = single, .clear = {0, 0, 0, 1}});
    out.push_back(
        exact("single sample: bit 0 decides", d.readTexture(single), expected({0, 1, 0, 1})));
    if (d.info().limits.colorSampleCounts & 4) {
        const TextureHandle ms = o.add(d.createTexture({.width = kCaseSize,
                                                        .height = kCaseSize,
                                                        .sampleCount = 4,
                                                        .usage = TextureUsage::RenderTarget}));
        const TextureHandle resolved = caseTarget(o);
        drawInto(4, {.texture = ms,
                     .store = StoreOp::DontCare,
                     .clear = {0, 0, 0, 1},
                     .resolveTexture = resolved});
        out.push_back(within("4 samples: the fraction written", d.readTexture(resolved),
                             expected({0, 0.25f, 0.75f, 1}), 1.5 / 255.0,
                             "average of 4 samples of 0 and 1 (0.25 and 0.75 round either way)"));
    }
    return out;
}

// A 64x64 depth (or depth-stencil) attachment, owned by `o`.
TextureHandle caseDepthTarget(DeviceObjects& o, Format f) {
    return o.add(o.device().createTexture({.format = f,
                                           .width = kCaseSize,
                                           .height = kCaseSize,
                                           .usage = TextureUsage::RenderTarget}));
}

// --- Dynamic pipeline state ---------------------------------------------------------------------

// Blend constant, stencil reference and depth bias set between draws stay until set again:
// setPipeline applies a pipeline's own values only to what the pass has not set (Device.h), and
// each pass starts from its pipelines' values. Three images:
//  - blend constant: colour = white x constant, four 16-pixel columns. Column 0 the pipeline's
//    (red), 1 after setBlendConstant (green), 2 after setPipeline again (still green), 3 after
//    setBlendConstant (blue); then a second pass draws the bottom 8 rows with the pipeline's
//    value again (red);
//  - stencil reference: setStencilReference(5) before a replacing pipeline (reference 0) writes
//    5 in a rectangle; an Equal pipeline (reference 0) keeps 5 and draws red there; then
//    setStencilReference(0) and the Equal pipeline bound again draw green everywhere else;
//  - depth bias: a triangle at 0.5 everywhere, then another at 0.5 with depth test Less: column
//    0 unbiased (fails), 1 after setDepthBias(-1000) (passes), 2 after setPipeline again (the
//    bias stays: passes), 3 in a second pass with a pipeline whose depthBiasConstant is -1000
//    (passes), while the unbiased pipeline bound in that pass draws nothing in column 0.
// A command ignored, or setPipeline replacing a value the pass set, changes a column.
std::vector<CaseImage> dynamicBlendStencilBias(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex,
                                           "conformance/fullscreen_ubo.vert"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag");
    const Texel red{1, 0, 0, 1}, green{0, 1, 0, 1}, blue{0, 0, 1, 1};
    const BufferHandle whiteUbo = params(o, {1, 1, 1, 1}), redUbo = params(o, red),
                       greenUbo = params(o, green), blueUbo = params(o, blue);
    auto column = [](uint32_t i) { return Rect{int32_t(16 * i), 0, 16, kCaseSize}; };
    auto columns = [](Texel c0, Texel c1, Texel c2, Texel c3) {
        return expectImage(Format::RGBA8, [=](uint32_t x, uint32_t) {
            const Texel c[4] = {c0, c1, c2, c3};
            return c[x / 16];
        });
    };
    std::vector<CaseImage> out;
    {
        const PipelineHandle p =
            o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = fs,
                                            .blend = {{.enable = true,
                                                       .srcColor = BlendFactor::ConstantColor,
                                                       .dstColor = BlendFactor::Zero,
                                                       .srcAlpha = BlendFactor::One,
                                                       .dstAlpha = BlendFactor::Zero}},
                                            .blendConstant = {1, 0, 0, 1},
                                            .colorFormats = {Format::RGBA8},
                                            .debugName = "blend constant"}));
        const TextureHandle t = caseTarget(o);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, whiteUbo);
        cmd->setScissor(column(0));
        cmd->draw(3);
        cmd->setBlendConstant({0, 1, 0, 1});
        cmd->setScissor(column(1));
        cmd->draw(3);
        cmd->setPipeline(p);
        cmd->setScissor(column(2));
        cmd->draw(3);
        cmd->setBlendConstant({0, 0, 1, 1});
        cmd->setScissor(column(3));
        cmd->draw(3);
        cmd->endRenderPass();
        cmd->beginRenderPass({.colors = {{.texture = t, .load = LoadOp::Load}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, whiteUbo);
        cmd->setScissor({0, int32_t(kCaseSize) - 8, kCaseSize, 8});
        cmd->draw(3);  // a new pass: the pipeline's constant again
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        const Texel c[4] = {red, green, green, blue};
        out.push_back(exact("blend_constant", d.readTexture(t),
                            expectImage(Format::RGBA8, [=](uint32_t x, uint32_t y) {
                                return y >= kCaseSize - 8 ? red : c[x / 16];
                            })));
    }
    {
        const TextureHandle t = caseTarget(o);
        const TextureHandle ds = caseDepthTarget(o, Format::D24S8);
        const StencilFaceState replace{.passOp = StencilOp::Replace, .compare = CompareOp::Always};
        const PipelineHandle write = o.add(d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .depthStencil =
                 {.stencilTest = true, .front = replace, .back = replace, .stencilReference = 0},
             .blend = {{.writeMask = ColorMask::None}},
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D24S8,
             .debugName = "stencil replace"}));
        const StencilFaceState equal{.compare = CompareOp::Equal};
        const PipelineHandle test = o.add(d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .depthStencil =
                 {.stencilTest = true, .front = equal, .back = equal, .stencilReference = 0},
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D24S8,
             .debugName = "stencil equal"}));
        const Rect r{8, 20, 24, 16};
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}},
                              .depth = {.texture = ds, .clearDepth = 1.0f, .clearStencil = 0}});
        cmd->setStencilReference(5);  // before the pipeline: kept
        cmd->setPipeline(write);
        cmd->setUniformBuffer(0, redUbo);
        cmd->setScissor(r);
        cmd->draw(3);  // stencil 5 in r
        cmd->setScissor(kWhole);
        cmd->setPipeline(test);
        cmd->draw(3);  // red where stencil is 5 (the reference set, not the pipeline's 0)
        cmd->setStencilReference(0);
        cmd->setPipeline(test);
        cmd->setUniformBuffer(0, greenUbo);
        cmd->draw(3);  // green where stencil is 0
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(exact("stencil_reference", d.readTexture(t), rectImage(green, r, red)));
    }
    {
        // D32F at 0.5: r = 2^-24, so a constant of -1000 moves depth by about -6e-5.
        const GraphicsPipelineDesc desc{.vertexShader = vs,
                                        .fragmentShader = fs,
                                        .depthStencil = {.depthTest = true,
                                                         .depthWrite = true,
                                                         .depthCompare = CompareOp::Less},
                                        .colorFormats = {Format::RGBA8},
                                        .depthFormat = Format::D32F,
                                        .debugName = "depth less"};
        GraphicsPipelineDesc biasedDesc = desc;
        biasedDesc.raster.depthBiasConstant = -1000.0f;
        biasedDesc.debugName = "depth less, biased";
        const PipelineHandle p = o.add(d.createGraphicsPipeline(desc)),
                             biased = o.add(d.createGraphicsPipeline(biasedDesc));
        const TextureHandle t = caseTarget(o);
        const TextureHandle depth = caseDepthTarget(o, Format::D32F);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}},
                              .depth = {.texture = depth, .clearDepth = 1.0f}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, redUbo);
        cmd->draw(3);  // red at 0.5 everywhere
        cmd->setUniformBuffer(0, greenUbo);
        cmd->setScissor(column(0));
        cmd->draw(3);  // 0.5 < 0.5: fails
        cmd->setDepthBias(-1000.0f, 0.0f);
        cmd->setScissor(column(1));
        cmd->draw(3);  // passes
        cmd->setPipeline(p);
        cmd->setScissor(column(2));
        cmd->draw(3);  // the bias set stays: passes
        cmd->endRenderPass();
        cmd->beginRenderPass({.colors = {{.texture = t, .load = LoadOp::Load}},
                              .depth = {.texture = depth, .load = LoadOp::Load}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, blueUbo);
        cmd->setScissor(column(0));
        cmd->draw(3);  // a new pass: the pipeline's bias (none) again: fails, stays red
        cmd->setPipeline(biased);
        cmd->setUniformBuffer(0, greenUbo);
        cmd->setScissor(column(3));
        cmd->draw(3);  // the pipeline's bias: passes
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(exact("depth_bias", d.readTexture(t), columns(red, green, green, green)));
    }
    return out;
}

// The order Vulkan samples and WebGPU programs use: the blend constant and the depth bias set at
// the start of the pass, before setPipeline; the pipeline's own values (a red constant, no
// bias) must not replace them. Green where both held, red or black where one was replaced.
std::vector<CaseImage> dynamicStateBeforePipeline(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex,
                                           "conformance/fullscreen_ubo.vert"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag");
    const BufferHandle whiteUbo = params(o, {1, 1, 1, 1});
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .depthStencil = {.depthTest = true, .depthWrite = true, .depthCompare = CompareOp::Less},
         .blend = {{.enable = true,
                    .srcColor = BlendFactor::ConstantColor,
                    .dstColor = BlendFactor::Zero,
                    .srcAlpha = BlendFactor::One,
                    .dstAlpha = BlendFactor::Zero}},
         .blendConstant = {1, 0, 0, 1},
         .colorFormats = {Format::RGBA8},
         .depthFormat = Format::D32F,
         .debugName = "constant blend, depth less"}));
    const TextureHandle t = caseTarget(o);
    const TextureHandle depth = caseDepthTarget(o, Format::D32F);
    auto cmd = d.createCommandList();
    // Depth 0.5 everywhere first (the full-screen triangle's depth), in a pass of its own.
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}},
                          .depth = {.texture = depth, .clearDepth = 1.0f}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, whiteUbo);
    cmd->draw(3);  // red at 0.5
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = t, .load = LoadOp::Load}},
                          .depth = {.texture = depth, .load = LoadOp::Load}});
    cmd->setBlendConstant({0, 1, 0, 1});
    cmd->setDepthBias(-1000.0f, 0.0f);
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, whiteUbo);
    cmd->draw(3);  // passes only biased, green only with the constant set
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return {exact("before_pipeline", d.readTexture(t), solid(Format::RGBA8, {0, 1, 0, 1}))};
}

}  // namespace

std::vector<Case> samplerStateCases() {
    return {
        {"border_color", borderColor},
        {"lod_bias_and_clamp", lodBiasAndClamp},
        {"stride_zero_vertex", strideZeroVertex},
        {"zero_initialised", zeroInitialised},
        {"primitive_restart", primitiveRestart},
        {"sample_mask", sampleMask},
        {"shader_sample_mask", shaderSampleMask},
        {"dynamic_blend_stencil_bias", dynamicBlendStencilBias},
        {"dynamic_state_before_pipeline", dynamicStateBeforePipeline},
    };
}

}  // namespace fe::conformance
