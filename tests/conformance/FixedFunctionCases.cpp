// Conformance cases for fixed-function behaviour where Vulkan and GL differ by default and the
// device makes them agree: firstInstance, point sprites, depth writes without the
// depth test, MipFilter::None minification, textures that are only copied.
#include <cstring>

#include "CaseSupport.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// Flat outputs take the first vertex's value (Vulkan's provoking vertex; GL's default is the
// last, which the device changes). Left half: a triangle list of two triangles whose first
// vertices are red and green; right half: a strip of two triangles (the first vertex of
// triangle i is vertex i: blue, then white). Each triangle's other vertices are black.
std::vector<CaseImage> flatFirstVertex(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = caseTarget(o);
    GraphicsPipelineDesc desc{
        .vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/flat_color.vert"),
        .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/flat_color.frag"),
        .vertexBuffers = {{.stride = 24,
                           .attributes = {{0, VertexFormat::Float2, 0},
                                          {1, VertexFormat::Float4, 8}}}},
        .colorFormats = {Format::RGBA8},
        .debugName = "flat list"};
    const PipelineHandle list = o.add(d.createGraphicsPipeline(desc));
    desc.topology = PrimitiveTopology::TriangleStrip;
    desc.debugName = "flat strip";
    const PipelineHandle strip = o.add(d.createGraphicsPipeline(desc));
    struct V {
        float x, y, r, g, b, a;
    };
    const V black = {0, 0, 0, 0, 0, 1};
    auto at = [](V v, float x, float y) { return V{x, y, v.r, v.g, v.b, v.a}; };
    const V red{0, 0, 1, 0, 0, 1}, green{0, 0, 0, 1, 0, 1}, blue{0, 0, 0, 0, 1, 1},
        white{0, 0, 1, 1, 1, 1};
    const std::vector<V> v = {// list: top-left triangle, then bottom-right, of the left half
                              at(red, -1, -1), at(black, 0, -1), at(black, -1, 1), at(green, 0, 1),
                              at(black, -1, 1), at(black, 0, -1),
                              // strip over the right half: (v0 v1 v2) then (v1 v2 v3)
                              at(blue, 0, -1), at(white, 0, 1), at(black, 1, -1), at(black, 1, 1)};
    const BufferHandle vb = o.add(
        d.createBuffer({.size = v.size() * sizeof(V), .usage = BufferUsage::Vertex}, bytesOf(v)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 0}}}});
    cmd->setVertexBuffer(0, vb);
    cmd->setPipeline(list);
    cmd->draw(6);
    cmd->setPipeline(strip);
    cmd->draw(4, 1, 6, 0);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    // Pixel centres off the diagonals: which triangle covers (x, y) in each half.
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        const float u = (float(x % (kCaseSize / 2)) + 0.5f) / float(kCaseSize / 2),
                    w = (float(y) + 0.5f) / float(kCaseSize);
        if (x < kCaseSize / 2) return u + w < 1.0f ? Texel{1, 0, 0, 1} : Texel{0, 1, 0, 1};
        return u + w < 1.0f ? Texel{0, 0, 1, 1} : Texel{1, 1, 1, 1};
    });
    return {drawn8("first_vertex", d.readTexture(t), expected)};
}

// A pipeline with two colour targets whose fragment shader writes only location 0: target 1
// keeps what the pass cleared it to (the device masks its writes; Vulkan had stored stale bytes
// there, GL zeros).
std::vector<CaseImage> unwrittenTargetKeepsContents(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t0 = caseTarget(o), t1 = caseTarget(o);
    const float params[8] = {1, 0, 1, 1, 0.5f, 0, 0, 0};  // fullscreen_ubo.vert's colour and depth
    const BufferHandle colour = o.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag"),
         .colorFormats = {Format::RGBA8, Format::RGBA8},
         .debugName = "one output, two targets"}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t0, .clear = {0, 0, 0, 1}},
                                     {.texture = t1, .clear = {0, 0.5f, 0, 1}}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, colour);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return {
        exact("written", d.readTexture(t0), solid(Format::RGBA8, {1, 0, 1, 1})),
        drawn8("unwritten_keeps_clear", d.readTexture(t1), solid(Format::RGBA8, {0, 0.5f, 0, 1}))};
}

// draw(6, 2, 0, 3) and drawIndexed(6, 1, 0, 0, 6): the instances are 3, 4 and 6 (FE_INSTANCE_ID
// counts from firstInstance on both backends; GL adds gl_BaseInstance to gl_InstanceID).
std::vector<CaseImage> firstInstance(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = caseTarget(o);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/instance_band.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/value.frag"),
         .colorFormats = {Format::RGBA8},
         .debugName = "instance bands"}));
    const uint16_t indices[6] = {0, 1, 2, 3, 4, 5};
    const BufferHandle ib = o.add(
        d.createBuffer({.size = sizeof indices, .usage = BufferUsage::Index}, bytesOf(indices)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 1, 1}}}});
    cmd->setPipeline(p);
    cmd->draw(6, 2, 0, 3);
    cmd->setIndexBuffer(ib, IndexType::U16);
    cmd->drawIndexed(6, 1, 0, 0, 6);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t) -> Texel {
        const uint32_t band = x / 8;
        if (band == 3 || band == 4 || band == 6) return {float(band) / 16.0f, 0.5f, 0, 1};
        return {0, 0, 1, 1};
    });
    return {drawn8("instances", d.readTexture(t), expected)};
}

// Two points, 8 and 4 pixels wide (gl_PointSize), each showing gl_PointCoord: (0, 0) at its top
// left, the centre of pixel (i, j) of the point at ((i + 0.5) / size, (j + 0.5) / size).
std::vector<CaseImage> pointSizeAndCoord(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = caseTarget(o);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/point_sprite.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/point_coord.frag"),
         .topology = PrimitiveTopology::PointList,
         .colorFormats = {Format::RGBA8},
         .debugName = "points"}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 1, 1}}}});
    cmd->setPipeline(p);
    cmd->draw(2);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    struct Point {
        uint32_t x0, y0, size;
    };
    const Point points[2] = {{12, 12, 8}, {38, 22, 4}};
    const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
        for (const Point& pt : points)
            if (x >= pt.x0 && x < pt.x0 + pt.size && y >= pt.y0 && y < pt.y0 + pt.size)
                return {(float(x - pt.x0) + 0.5f) / float(pt.size),
                        (float(y - pt.y0) + 0.5f) / float(pt.size), 0, 1};
        return {0, 0, 1, 1};
    });
    return {drawn8("points", d.readTexture(t), expected, 1.5)};
}

// depthWrite without depthTest writes every fragment's depth on both backends (Device.h): a
// triangle at depth 0.25 over the left half of a depth target cleared to 1, then one at 0.75
// over all of it, which passes too (no test) and writes 0.75 everywhere it covers.
std::vector<CaseImage> depthWriteWithoutTest(Device& d) {
    DeviceObjects o(d);
    const TextureHandle color = caseTarget(o);
    const TextureHandle depth = caseTarget(o, Format::D32F);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag"),
         .depthStencil = {.depthTest = false, .depthWrite = true},
         .colorFormats = {Format::RGBA8},
         .depthFormat = Format::D32F,
         .debugName = "depth write, no test"}));
    const float near[8] = {1, 0, 0, 1, 0.25f, 0, 0, 0}, far[8] = {0, 1, 0, 1, 0.75f, 0, 0, 0};
    const BufferHandle nearUbo =
        o.add(d.createBuffer({.size = sizeof near, .usage = BufferUsage::Uniform}, bytesOf(near)));
    const BufferHandle farUbo =
        o.add(d.createBuffer({.size = sizeof far, .usage = BufferUsage::Uniform}, bytesOf(far)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = color, .clear = {0, 0, 1, 1}}},
                          .depth = {.texture = depth, .clearDepth = 1.0f}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, nearUbo);
    cmd->setScissor({0, 0, 32, 64});
    cmd->draw(3);
    cmd->setUniformBuffer(0, farUbo);
    cmd->setScissor({0, 0, 64, 16});
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    auto region = [](uint32_t x, uint32_t y) { return y < 16 ? 2 : x < 32 ? 1 : 0; };
    const Image expectedDepth = expectImage(Format::D32F, [&](uint32_t x, uint32_t y) -> Texel {
        const float z[3] = {1.0f, 0.25f, 0.75f};
        return {z[region(x, y)], 0, 0, 0};
    });
    const Image expectedColor = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
        const Texel c[3] = {{0, 0, 1, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}};
        return c[region(x, y)];
    });
    return {exact("depth", d.readTexture(depth), expectedDepth),
            drawn8("colour", d.readTexture(color), expectedColor)};
}

// MipFilter::None minifies with minFilter from the base level on both backends: a 128x128
// texture of one-texel black and white columns drawn at half size (level of detail 1) through
// a Linear-min, Nearest-mag sampler averages each pair to grey. Level 1 is red: it must not show.
std::vector<CaseImage> mipFilterNone(Device& d) {
    DeviceObjects o(d);
    const TextureHandle tex =
        o.add(d.createTexture({.width = 128,
                               .height = 128,
                               .mipLevels = 2,
                               .usage = TextureUsage::Sampled | TextureUsage::CopyDst,
                               .debugName = "columns"}));
    std::vector<uint8_t> level0(128 * 128 * 4), level1(64 * 64 * 4);
    for (uint32_t i = 0; i < 128 * 128; ++i) {
        const uint8_t v = (i % 128) % 2 ? 255 : 0;
        level0[4 * i] = level0[4 * i + 1] = level0[4 * i + 2] = v;
        level0[4 * i + 3] = 255;
    }
    for (uint32_t i = 0; i < 64 * 64; ++i) level1[4 * i] = level1[4 * i + 3] = 255;
    d.writeTexture(tex, {.mipLevel = 0}, bytesOf(level0));
    d.writeTexture(tex, {.mipLevel = 1}, bytesOf(level1));
    FullscreenSampler pass(d, "conformance/textured_uv.frag",
                           {.minFilter = Filter::Linear,
                            .magFilter = Filter::Nearest,
                            .mipFilter = MipFilter::None,
                            .addressU = AddressMode::ClampToEdge,
                            .addressV = AddressMode::ClampToEdge});
    // textured_uv.frag: uv = pixel / 64 * (1, 1) + 0, textureLod at level 1 (the block's b.y).
    const Image image = pass.draw(d, tex, Format::RGBA8, {1, 1, 0, 0}, {0, 1, 0, 0});
    return {drawn8("minified", image, solid(Format::RGBA8, {0.5f, 0.5f, 0.5f, 1}), 1.5)};
}

// Textures whose only usages are copies: written, copied into another, read back; on Vulkan
// they get no image view (a view of such an image is invalid), and the validation layer stays
// silent (the runner fails a case on any message).
std::vector<CaseImage> copyOnlyTextures(Device& d) {
    DeviceObjects o(d);
    const TextureUsage copies = TextureUsage::CopySrc | TextureUsage::CopyDst;
    const TextureHandle a = o.add(d.createTexture(
        {.width = kCaseSize, .height = kCaseSize, .usage = copies, .debugName = "copy a"}));
    const TextureHandle b = o.add(d.createTexture(
        {.width = kCaseSize, .height = kCaseSize, .usage = copies, .debugName = "copy b"}));
    const Image pattern = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        return {float(x * 4) / 255.0f, float(y * 4) / 255.0f, float((x ^ y) & 7) * 32.0f / 255.0f,
                1};
    });
    d.writeTexture(a, {}, bytesOf(pattern.data));
    auto cmd = d.createCommandList();
    cmd->copyTexture(b, a);
    d.wait(d.submit(*cmd));
    return {exact("copied", d.readTexture(b), pattern)};
}

// Every capability Device::formatCaps reports is exercised, per uncompressed format: it agrees
// with supportsFormat; linearFilter: two texels (0 and 1) sampled halfway through a Linear
// sampler give 0.5 (a format without it refuses the Linear sampler at setTexture); renderTarget:
// a clear reads back; blend: One + One over a clear adds; each sample count in sampleCounts
// makes a target that a pass clears (and resolves, for averaging formats).
std::vector<CaseImage> formatCapsCase(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects o(d);
    const SamplerHandle linear = o.add(d.createSampler(
        {.addressU = AddressMode::ClampToEdge, .addressV = AddressMode::ClampToEdge}));
    for (uint32_t i = 1; i < uint32_t(Format::Count); ++i) {
        const Format f = Format(i);
        const FormatInfo& fi = formatInfo(f);
        if (isCompressedFormat(f)) continue;
        const FormatCaps caps = d.formatCaps(f);
        const std::string name(fi.name);
        FE_CONFORMANCE_CHECK(caps.sampled == d.supportsFormat(f, TextureUsage::Sampled),
                             ("sampled agrees: " + name).c_str());
        FE_CONFORMANCE_CHECK(caps.renderTarget == d.supportsFormat(f, TextureUsage::RenderTarget),
                             ("renderTarget agrees: " + name).c_str());
        FE_CONFORMANCE_CHECK(caps.storage == d.supportsFormat(f, TextureUsage::Storage),
                             ("storage agrees: " + name).c_str());
        FE_CONFORMANCE_CHECK(!caps.renderTarget || (caps.sampleCounts & 1),
                             ("one sample renders: " + name).c_str());
        if (!caps.sampled) continue;
        DeviceObjects per(d);
        const bool colour = !isDepthFormat(f) && !fi.isInteger;
        // Linear filtering, or its refusal.
        const TextureHandle pair =
            per.add(d.createTexture({.format = f,
                                     .width = 2,
                                     .height = 1,
                                     .usage = TextureUsage::Sampled | TextureUsage::CopyDst}));
        if (!caps.linearFilter) {
            auto cmd = d.createCommandList();
            FE_CONFORMANCE_CHECK(
                throws([&] { cmd->setTexture(1, pair, linear); }),
                ("a Linear sampler is refused on " + name + ", which cannot be filtered linearly")
                    .c_str());
        } else if (colour) {
            d.writeTexture(pair, {},
                           bytesOf(Image::fromTexels(2, 1, f, {{0, 0, 0, 0}, {1, 1, 1, 1}}).data));
            FullscreenSampler pass(
                d, "conformance/textured_uv.frag",
                {.addressU = AddressMode::ClampToEdge, .addressV = AddressMode::ClampToEdge});
            const Image image = pass.draw(d, pair, Format::RGBA16F,
                                          {0, 0, 0.5f, 0.5f});  // uv (0.5, 0.5) everywhere
            const bool alpha = fi.channels == 4;
            const Texel half{0.5f, fi.channels > 1 ? 0.5f : 0.0f, fi.channels > 2 ? 0.5f : 0.0f,
                             alpha ? 0.5f : 1.0f};
            out.push_back(
                within("linear_" + name, image, solid(Format::RGBA16F, half), 2.0 / 255.0,
                       "the average of texels 0 and 1: filtering weights of at least 8 bits"));
        }
        if (!caps.renderTarget || isDepthFormat(f))
            continue;  // depth and stencil: depth16, stencil8_and_readback
        // A clear of values exact in every format (and in sRGB encoding).
        const TextureHandle rt =
            per.add(d.createTexture({.format = f,
                                     .width = 4,
                                     .height = 4,
                                     .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = rt, .clear = {1, 0, 1, 1}}}});
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        const Texel cleared{1, 0, fi.channels > 2 ? 1.0f : 0.0f, fi.channels == 4 ? 1.0f : 1.0f};
        out.push_back(exact("clear_" + name, d.readTexture(rt), solid(f, cleared, 4, 4)));
        if (caps.blend && !fi.isSrgb) {  // sRGB blends in linear space: values checked elsewhere
            const PipelineHandle add = per.add(d.createGraphicsPipeline(
                {.vertexShader =
                     registryShader(per, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
                 .fragmentShader =
                     registryShader(per, ShaderStage::Fragment, "conformance/ubo_color.frag"),
                 .blend = {{.enable = true,
                            .srcColor = BlendFactor::One,
                            .dstColor = BlendFactor::One,
                            .srcAlpha = BlendFactor::One,
                            .dstAlpha = BlendFactor::One}},
                 .colorFormats = {f}}));
            const float params[8] = {0.5f, 0.5f, 0.5f, 0.5f, 0, 0, 0, 0};
            const BufferHandle ubo = per.add(d.createBuffer(
                {.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
            cmd->beginRenderPass(
                {.colors = {{.texture = rt, .clear = {0.25f, 0.25f, 0.25f, 0.25f}}}});
            cmd->setPipeline(add);
            cmd->setUniformBuffer(0, ubo);
            cmd->draw(3);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            const Texel sum{0.75f, fi.channels > 1 ? 0.75f : 0.0f, fi.channels > 2 ? 0.75f : 0.0f,
                            fi.channels == 4 ? 0.75f : 1.0f};
            out.push_back(
                within("blend_" + name, d.readTexture(rt), solid(f, sum, 4, 4), 2.0 / 255.0,
                       "0.25 + 0.5 in the target's precision (8-bit: two rounding steps)"));
        }
        // Each sample count it reports renders (and resolves, where samples are averaged).
        for (uint32_t n = 2; n <= 8; n *= 2) {
            if (!(caps.sampleCounts & n)) continue;
            const TextureHandle ms =
                per.add(d.createTexture({.format = f,
                                         .width = 4,
                                         .height = 4,
                                         .sampleCount = n,
                                         .usage = TextureUsage::RenderTarget}));
            ColorAttachment a{.texture = ms, .store = StoreOp::DontCare, .clear = {1, 0, 1, 1}};
            if (colour) a.resolveTexture = rt;
            cmd->beginRenderPass({.colors = {a}});
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            if (colour)
                out.push_back(exact("resolve_" + std::to_string(n) + "x_" + name, d.readTexture(rt),
                                    solid(f, cleared, 4, 4)));
        }
    }
    return out;
}

// D16 depth testing: near red at 0.25 drawn over the left half, far green at 0.75 over all of it
// with Less: green only on the right; the depth image reads 0.25 and 0.75 (16-bit unorm).
std::vector<CaseImage> depth16(Device& d) {
    if (!d.formatCaps(Format::D16).renderTarget)
        return {};  // not a depth target here: nothing to prove
    DeviceObjects o(d);
    const TextureHandle color = caseTarget(o);
    const TextureHandle depth = caseTarget(o, Format::D16);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag"),
         .depthStencil = {.depthTest = true, .depthWrite = true, .depthCompare = CompareOp::Less},
         .colorFormats = {Format::RGBA8},
         .depthFormat = Format::D16,
         .debugName = "depth16"}));
    const float near[8] = {1, 0, 0, 1, 0.25f, 0, 0, 0}, far[8] = {0, 1, 0, 1, 0.75f, 0, 0, 0};
    const BufferHandle nearUbo =
        o.add(d.createBuffer({.size = sizeof near, .usage = BufferUsage::Uniform}, bytesOf(near)));
    const BufferHandle farUbo =
        o.add(d.createBuffer({.size = sizeof far, .usage = BufferUsage::Uniform}, bytesOf(far)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass(
        {.colors = {{.texture = color, .clear = {0, 0, 1, 1}}}, .depth = {.texture = depth}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, nearUbo);
    cmd->setScissor({0, 0, 32, 64});
    cmd->draw(3);
    cmd->setUniformBuffer(0, farUbo);
    cmd->setScissor({0, 0, 64, 64});
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image expectedColor = expectImage(Format::RGBA8, [](uint32_t x, uint32_t) -> Texel {
        return x < 32 ? Texel{1, 0, 0, 1} : Texel{0, 1, 0, 1};
    });
    const Image expectedDepth = expectImage(Format::D16, [](uint32_t x, uint32_t) -> Texel {
        return {x < 32 ? 0.25f : 0.75f, 0, 0, 0};
    });
    return {drawn8("colour", d.readTexture(color), expectedColor),
            within("depth", d.readTexture(depth), expectedDepth, 1.5 / 65535.0,
                   "depth in 16-bit unorm: one rounding step")};
}

// Stencil written and read back with depth, in each depth-stencil format and S8 (where it is an
// attachment): stencil cleared to 3,
// a draw with Replace and reference 7 over a rectangle, the depth left at its clear value 1.
// readTexture gives depth in channel 0 and stencil in channel 1 on every backend; writeTexture
// takes the same layout for every depth format.
std::vector<CaseImage> stencilReadback(Device& d) {
    std::vector<CaseImage> out;
    for (Format f : {Format::D24S8, Format::D32F_S8, Format::S8}) {
        if (!d.formatCaps(f).renderTarget) continue;
        const float clearedDepth = formatInfo(f).hasDepth ? 1.0f : 0.0f;  // S8 reads 0 as its depth
        DeviceObjects o(d);
        const TextureHandle color = caseTarget(o);
        const TextureHandle depth = caseTarget(o, f);
        const PipelineHandle p = o.add(d.createGraphicsPipeline(
            {.vertexShader =
                 registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
             .fragmentShader =
                 registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag"),
             .depthStencil = {.stencilTest = true,
                              .front = {.passOp = StencilOp::Replace, .compare = CompareOp::Always},
                              .back = {.passOp = StencilOp::Replace, .compare = CompareOp::Always},
                              .stencilReference = 7},
             .colorFormats = {Format::RGBA8},
             .depthFormat = f,
             .debugName = "stencil replace"}));
        const float params[8] = {1, 1, 1, 1, 0.5f, 0, 0, 0};
        const BufferHandle ubo = o.add(d.createBuffer(
            {.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = color}},
                              .depth = {.texture = depth, .clearDepth = 1.0f, .clearStencil = 3}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->setScissor({8, 16, 40, 24});
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        const Image expected = expectImage(f, [&](uint32_t x, uint32_t y) -> Texel {
            const bool in = x >= 8 && x < 48 && y >= 16 && y < 40;
            return {clearedDepth, in ? 7.0f : 3.0f, 0, 0};
        });
        out.push_back(
            exact("stencil_" + std::string(formatInfo(f).name), d.readTexture(depth), expected));
    }
    // Uploads in the readback layout: a depth ramp and a stencil pattern, read back unchanged.
    for (Format f : {Format::D32F, Format::D16, Format::D24S8, Format::D32F_S8, Format::S8}) {
        if (!d.formatCaps(f).sampled) continue;
        DeviceObjects o(d);
        const TextureHandle t =
            o.add(d.createTexture({.format = f,
                                   .width = kCaseSize,
                                   .height = kCaseSize,
                                   .usage = TextureUsage::CopySrc | TextureUsage::CopyDst}));
        const Image pattern = expectImage(f, [](uint32_t x, uint32_t y) -> Texel {
            return {float(x) / 63.0f, float((x * 7 + y * 3) & 0xff), 0, 0};
        });
        d.writeTexture(t, {}, bytesOf(pattern.data));
        out.push_back(
            exact("upload_" + std::string(formatInfo(f).name), d.readTexture(t), pattern));
    }
    return out;
}

// clearBuffer fills a range with a 32-bit pattern, size 0 meaning to the end; ranges that are not
// multiples of 4 or leave the buffer are refused, and so is a buffer without CopyDst or Storage
// usage (a fill is a transfer write on Vulkan, a storage-view clear on D3D12). A debug label between the commands records
// without a validation message.
std::vector<CaseImage> clearBufferCase(Device& d) {
    DeviceObjects o(d);
    const BufferHandle b =
        o.add(d.createBuffer({.size = 256, .usage = BufferUsage::Storage, .debugName = "cleared"}));
    const BufferHandle uniformOnly =
        o.add(d.createBuffer({.size = 256, .usage = BufferUsage::Uniform}));
    auto cmd = d.createCommandList();
    FE_CONFORMANCE_CHECK(throws([&] { cmd->clearBuffer(uniformOnly); }),
                         "a buffer without CopyDst or Storage usage is refused");
    FE_CONFORMANCE_CHECK(throws([&] { cmd->clearBuffer(b, 2, 8, 1); }),
                         "an offset that is not a multiple of 4 is refused");
    FE_CONFORMANCE_CHECK(throws([&] { cmd->clearBuffer(b, 0, 6, 1); }),
                         "a size that is not a multiple of 4 is refused");
    FE_CONFORMANCE_CHECK(throws([&] { cmd->clearBuffer(b, 128, 256, 1); }),
                         "a range past the end is refused");
    cmd->clearBuffer(b, 0, 0, 0x01020304u);  // all of it
    cmd->insertDebugLabel("between the clears");
    cmd->clearBuffer(b, 16, 48, 0xdeadbeefu);
    cmd->clearBuffer(b, 192, 0, 0);  // from 192 to the end
    d.wait(d.submit(*cmd));
    const std::vector<uint8_t> bytes = d.readBuffer(b, 0, 256);
    for (uint32_t i = 0; i < 64; ++i) {
        uint32_t v;
        std::memcpy(&v, &bytes[4 * i], 4);
        const uint32_t want = i >= 48 ? 0u : (i >= 4 && i < 16) ? 0xdeadbeefu : 0x01020304u;
        FE_CONFORMANCE_CHECK(v == want, ("word " + std::to_string(i) + " holds its fill").c_str());
    }
    return {};
}

}  // namespace

std::vector<Case> fixedFunctionCases() {
    return {
        {"first_instance", firstInstance},
        {"flat_first_vertex", flatFirstVertex},
        {"unwritten_target_keeps_contents", unwrittenTargetKeepsContents},
        {"point_size_and_coord", pointSizeAndCoord},
        {"depth_write_without_test", depthWriteWithoutTest},
        {"mip_filter_none", mipFilterNone},
        {"copy_only_textures", copyOnlyTextures},
        {"format_caps", formatCapsCase},
        {"depth16", depth16},
        {"stencil8_and_readback", stencilReadback},
        {"clear_buffer", clearBufferCase},
    };
}

}  // namespace fe::conformance
