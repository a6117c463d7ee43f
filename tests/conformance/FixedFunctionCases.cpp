// Conformance cases for fixed-function behaviour where Vulkan and GL differ by default and the
// device makes them agree (issue 25): firstInstance, point sprites, depth writes without the
// depth test, MipFilter::None minification, textures that are only copied.
#include <cstring>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr TextureUsage kTarget = TextureUsage::RenderTarget | TextureUsage::CopySrc;

ShaderHandle shader(DeviceObjects& o, ShaderStage stage, const char* path) {
    return o.add(o.device().createShader({.stage = stage, .binary = shaders::find(path)}));
}
TextureHandle target(DeviceObjects& o, Format f = Format::RGBA8) {
    return o.add(o.device().createTexture({.format = f, .width = kCaseSize, .height = kCaseSize, .usage = kTarget}));
}
// One step of float-to-unorm rounding, for values drawn into an 8-bit target.
CaseImage drawn(const std::string& name, Image image, Image expected, double steps = 1.0) {
    return within(name, std::move(image), std::move(expected), steps / 255.0,
                  "values drawn into an 8-bit target: float-to-unorm rounding");
}

// draw(6, 2, 0, 3) and drawIndexed(6, 1, 0, 0, 6): the instances are 3, 4 and 6 (FE_INSTANCE_ID
// counts from firstInstance on both backends; GL adds gl_BaseInstance to gl_InstanceID).
std::vector<CaseImage> firstInstance(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = target(o);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = shader(o, ShaderStage::Vertex, "conformance/instance_band.vert"),
         .fragmentShader = shader(o, ShaderStage::Fragment, "conformance/value.frag"),
         .colorFormats = {Format::RGBA8}, .debugName = "instance bands"}));
    const uint16_t indices[6] = {0, 1, 2, 3, 4, 5};
    const BufferHandle ib = o.add(d.createBuffer({.size = sizeof indices, .usage = BufferUsage::Index}, bytesOf(indices)));
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
    return {drawn("instances", d.readTexture(t), expected)};
}

// Two points, 8 and 4 pixels wide (gl_PointSize), each showing gl_PointCoord: (0, 0) at its top
// left, the centre of pixel (i, j) of the point at ((i + 0.5) / size, (j + 0.5) / size).
std::vector<CaseImage> pointSizeAndCoord(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = target(o);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = shader(o, ShaderStage::Vertex, "conformance/point_sprite.vert"),
         .fragmentShader = shader(o, ShaderStage::Fragment, "conformance/point_coord.frag"),
         .topology = PrimitiveTopology::PointList, .colorFormats = {Format::RGBA8}, .debugName = "points"}));
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
                return {(float(x - pt.x0) + 0.5f) / float(pt.size), (float(y - pt.y0) + 0.5f) / float(pt.size), 0, 1};
        return {0, 0, 1, 1};
    });
    return {drawn("points", d.readTexture(t), expected, 1.5)};
}

// depthWrite without depthTest writes every fragment's depth on both backends (Device.h): a
// triangle at depth 0.25 over the left half of a depth target cleared to 1, then one at 0.75
// over all of it, which passes too (no test) and writes 0.75 everywhere it covers.
std::vector<CaseImage> depthWriteWithoutTest(Device& d) {
    DeviceObjects o(d);
    const TextureHandle color = target(o);
    const TextureHandle depth = target(o, Format::D32F);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = shader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
         .fragmentShader = shader(o, ShaderStage::Fragment, "conformance/ubo_color.frag"),
         .depthStencil = {.depthTest = false, .depthWrite = true},
         .colorFormats = {Format::RGBA8}, .depthFormat = Format::D32F, .debugName = "depth write, no test"}));
    const float near[8] = {1, 0, 0, 1, 0.25f, 0, 0, 0}, far[8] = {0, 1, 0, 1, 0.75f, 0, 0, 0};
    const BufferHandle nearUbo = o.add(d.createBuffer({.size = sizeof near, .usage = BufferUsage::Uniform}, bytesOf(near)));
    const BufferHandle farUbo = o.add(d.createBuffer({.size = sizeof far, .usage = BufferUsage::Uniform}, bytesOf(far)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = color, .clear = {0, 0, 1, 1}}}, .depth = {.texture = depth, .clearDepth = 1.0f}});
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
    return {exact("depth", d.readTexture(depth), expectedDepth), drawn("colour", d.readTexture(color), expectedColor)};
}

// MipFilter::None minifies with minFilter from the base level on both backends: a 128x128
// texture of one-texel black and white columns drawn at half size (level of detail 1) through
// a Linear-min, Nearest-mag sampler averages each pair to grey. Level 1 is red: it must not show.
std::vector<CaseImage> mipFilterNone(Device& d) {
    DeviceObjects o(d);
    const TextureHandle tex = o.add(d.createTexture({.width = 128, .height = 128, .mipLevels = 2,
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
                           {.minFilter = Filter::Linear, .magFilter = Filter::Nearest, .mipFilter = MipFilter::None,
                            .addressU = AddressMode::ClampToEdge, .addressV = AddressMode::ClampToEdge});
    // textured_uv.frag: uv = pixel / 64 * (1, 1) + 0, textureLod at level 1 (the block's b.y).
    const Image image = pass.draw(d, tex, Format::RGBA8, {1, 1, 0, 0}, {0, 1, 0, 0});
    return {drawn("minified", image, solid(Format::RGBA8, {0.5f, 0.5f, 0.5f, 1}), 1.5)};
}

// Textures whose only usages are copies: written, copied into another, read back; on Vulkan
// they get no image view (a view of such an image is invalid), and the validation layer stays
// silent (the runner fails a case on any message).
std::vector<CaseImage> copyOnlyTextures(Device& d) {
    DeviceObjects o(d);
    const TextureUsage copies = TextureUsage::CopySrc | TextureUsage::CopyDst;
    const TextureHandle a = o.add(d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = copies, .debugName = "copy a"}));
    const TextureHandle b = o.add(d.createTexture({.width = kCaseSize, .height = kCaseSize, .usage = copies, .debugName = "copy b"}));
    const Image pattern = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        return {float(x * 4) / 255.0f, float(y * 4) / 255.0f, float((x ^ y) & 7) * 32.0f / 255.0f, 1};
    });
    d.writeTexture(a, {}, bytesOf(pattern.data));
    auto cmd = d.createCommandList();
    cmd->copyTexture(b, a);
    d.wait(d.submit(*cmd));
    return {exact("copied", d.readTexture(b), pattern)};
}

}  // namespace

std::vector<Case> fixedFunctionCases() {
    return {
        {"first_instance", firstInstance},
        {"point_size_and_coord", pointSizeAndCoord},
        {"depth_write_without_test", depthWriteWithoutTest},
        {"mip_filter_none", mipFilterNone},
        {"copy_only_textures", copyOnlyTextures},
    };
}

}  // namespace fe::conformance
