// Conformance cases for texture kinds (arrays, cubes, cube arrays, 3D), subresource upload,
// readback and rendering, GPU mip generation, block compression and upload lengths.
#include <array>
#include <cmath>
#include <functional>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// A texel pattern unique to (x, y, layer): every readback and sample names its source.
Texel patternTexel(uint32_t x, uint32_t y, uint32_t layer) {
    return {float(x * 32) / 255.0f, float(y * 32) / 255.0f, float(layer * 40 + 15) / 255.0f, 1.0f};
}

Image patternImage(uint32_t w, uint32_t h, uint32_t layer) {
    std::vector<Texel> t;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) t.push_back(patternTexel(x, y, layer));
    return Image::fromTexels(w, h, Format::RGBA8, t);
}

// Uploads patternImage to every layer of mip 0 and reads each back by index.
void uploadLayers(Device& d, TextureHandle t, uint32_t w, uint32_t h, uint32_t layers,
                  std::vector<CaseImage>& out, const std::string& prefix) {
    for (uint32_t l = 0; l < layers; ++l)
        d.writeTexture(t, {.layer = l}, bytesOf(patternImage(w, h, l).data));
    for (uint32_t l = 0; l < layers; ++l)
        out.push_back(exact(prefix + "_readback_layer" + std::to_string(l),
                            d.readTexture(t, {.layer = l}), patternImage(w, h, l)));
}

std::vector<CaseImage> textureArrayLayers(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects objects(d);
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                                   .width = 8,
                                                   .height = 8,
                                                   .depthOrLayers = 4,
                                                   .debugName = "array"}));
    uploadLayers(d, t, 8, 8, 4, out, "array");
    FullscreenSampler fs(d, "conformance/sample_array.frag");
    Image img = fs.draw(d, t, Format::RGBA8);
    out.push_back({"sampled_quadrants", img, expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) {
                       return patternTexel((x % 32) / 4, (y % 32) / 4, x / 32 + 2 * (y / 32));
                   })});
    return out;
}

// Face f: a 2x2 image whose texels say (face, s, t).
Texel faceTexel(uint32_t cube, uint32_t face, uint32_t x, uint32_t y) {
    return {float(face * 40 + cube * 20 + 15) / 255.0f, float(x * 200 + 20) / 255.0f,
            float(y * 200 + 30) / 255.0f, 1.0f};
}

void uploadFaces(Device& d, TextureHandle t, uint32_t cubes, std::vector<CaseImage>& out) {
    for (uint32_t c = 0; c < cubes; ++c)
        for (uint32_t f = 0; f < 6; ++f) {
            std::vector<Texel> texels;
            for (uint32_t y = 0; y < 2; ++y)
                for (uint32_t x = 0; x < 2; ++x) texels.push_back(faceTexel(c, f, x, y));
            Image face = Image::fromTexels(2, 2, Format::RGBA8, texels);
            d.writeTexture(t, {.layer = c * 6 + f}, bytesOf(face.data));
            out.push_back(exact("readback_cube" + std::to_string(c) + "_face" + std::to_string(f),
                                d.readTexture(t, {.layer = c * 6 + f}), face));
        }
}

// What cube_direction.glsl addresses at pixel (x, y): face band, then s and t halves.
Texel expectedCube(uint32_t cube, uint32_t x, uint32_t y) {
    const double u = (x + 0.5) * 6.0 / 64.0;
    const uint32_t face = uint32_t(u);
    return faceTexel(cube, face, (u - face) < 0.5 ? 0 : 1, y < 32 ? 0 : 1);
}

std::vector<CaseImage> cubeFaces(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects objects(d);
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::TextureCube,
                                                   .width = 2,
                                                   .height = 2,
                                                   .depthOrLayers = 6,
                                                   .debugName = "cube"}));
    uploadFaces(d, t, 1, out);
    FullscreenSampler fs(d, "conformance/sample_cube.frag");
    out.push_back(
        {"faces_by_direction", fs.draw(d, t, Format::RGBA8),
         expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) { return expectedCube(0, x, y); })});
    return out;
}

std::vector<CaseImage> cubeArray(Device& d) {
    std::vector<CaseImage> out;
    if (!d.info().features.textureCubeArray) {
        FE_CONFORMANCE_CHECK(throws([&] {  // (freed at once, should it be made)
                                 DeviceObjects(d).add(d.createTexture(
                                     {.dimension = TextureDimension::TextureCubeArray,
                                      .width = 2,
                                      .height = 2,
                                      .depthOrLayers = 12}));
                             }),
                             "a cube array on a device without them is an error");
        return out;
    }
    DeviceObjects objects(d);
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::TextureCubeArray,
                                                   .width = 2,
                                                   .height = 2,
                                                   .depthOrLayers = 12,
                                                   .debugName = "cube array"}));
    uploadFaces(d, t, 2, out);
    FullscreenSampler fs(d, "conformance/sample_cube_array.frag");
    for (uint32_t c = 0; c < 2; ++c)
        out.push_back({"cube" + std::to_string(c) + "_by_direction",
                       fs.draw(d, t, Format::RGBA8, {float(c)}),
                       expectImage(Format::RGBA8,
                                   [c](uint32_t x, uint32_t y) { return expectedCube(c, x, y); })});
    return out;
}

std::vector<CaseImage> texture3dSlices(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects objects(d);
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::Texture3D,
                                                   .width = 4,
                                                   .height = 4,
                                                   .depthOrLayers = 4,
                                                   .debugName = "volume"}));
    uploadLayers(d, t, 4, 4, 4, out, "slice");
    FullscreenSampler fs(d, "conformance/sample_3d.frag");
    out.push_back({"sampled_slices", fs.draw(d, t, Format::RGBA8),
                   expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) {
                       return patternTexel((x % 16) / 4, y / 16, x / 16);
                   })});
    return out;
}

// One render pass per target subresource: each is cleared to its own colour; the others keep
// what they had, so a pass that wrote the whole texture fails.
std::vector<CaseImage> renderToSubresources(Device& d) {
    std::vector<CaseImage> out;
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::CopySrc |
                            TextureUsage::CopyDst | TextureUsage::Sampled;
    struct Target {
        const char* name;
        TextureDesc desc;
        Subresource at;
    };
    const Target targets[] = {
        {"array_layer2",
         {.dimension = TextureDimension::Texture2DArray,
          .width = 16,
          .height = 16,
          .depthOrLayers = 4,
          .usage = rt},
         {0, 2}},
        {"cube_face3",
         {.dimension = TextureDimension::TextureCube,
          .width = 16,
          .height = 16,
          .depthOrLayers = 6,
          .usage = rt},
         {0, 3}},
        {"mip1", {.width = 16, .height = 16, .mipLevels = 3, .usage = rt}, {1, 0}},
        {"volume_slice1_mip1",
         {.dimension = TextureDimension::Texture3D,
          .width = 16,
          .height = 16,
          .depthOrLayers = 4,
          .mipLevels = 2,
          .usage = rt},
         {1, 1}},
    };
    const Texel before{0.2f, 0.2f, 0.2f, 1.0f}, painted{1.0f, 0.6f, 0.0f, 1.0f};
    for (const Target& tg : targets) {
        DeviceObjects iteration(d);
        TextureHandle t = iteration.add(d.createTexture(tg.desc));
        auto cmd = d.createCommandList();
        // Every subresource first gets `before`, then only tg.at gets `painted` plus a triangle.
        for (uint32_t m = 0; m < tg.desc.mipLevels; ++m) {
            const uint32_t layers = tg.desc.dimension == TextureDimension::Texture3D
                                        ? std::max(1u, tg.desc.depthOrLayers >> m)
                                        : tg.desc.depthOrLayers;
            for (uint32_t l = 0; l < layers; ++l) {
                cmd->beginRenderPass(
                    {.colors = {{.texture = t,
                                 .mipLevel = m,
                                 .layer = l,
                                 .clear = {before[0], before[1], before[2], before[3]}}}});
                cmd->endRenderPass();
            }
        }
        cmd->beginRenderPass(
            {.colors = {{.texture = t,
                         .mipLevel = tg.at.mipLevel,
                         .layer = tg.at.layer,
                         .clear = {painted[0], painted[1], painted[2], painted[3]}}}});
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        const uint32_t size = 16 >> tg.at.mipLevel;
        out.push_back(exact(std::string(tg.name), d.readTexture(t, tg.at),
                            solid(Format::RGBA8, painted, size, size)));
        // A neighbour keeps its clear: the same mip's other layer, or the other mip.
        Subresource other = tg.at.layer > 0 ? Subresource{tg.at.mipLevel, 0} : Subresource{0, 0};
        const uint32_t otherSize = 16 >> other.mipLevel;
        out.push_back(exact(std::string(tg.name) + "_neighbour_untouched", d.readTexture(t, other),
                            solid(Format::RGBA8, before, otherSize, otherSize)));
    }
    return out;
}

// Draws (not clears) a different colour into each face of a cube, then samples the cube by
// direction: each face band shows the colour drawn into that face.
std::vector<CaseImage> renderCubeFacesThenSample(Device& d) {
    DeviceObjects objects(d);
    TextureHandle cube =
        objects.add(d.createTexture({.dimension = TextureDimension::TextureCube,
                                     .width = 16,
                                     .height = 16,
                                     .depthOrLayers = 6,
                                     .usage = TextureUsage::RenderTarget | TextureUsage::Sampled}));
    ShaderHandle vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    ShaderHandle fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    PipelineHandle p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}}));
    auto colour = [](uint32_t f) -> Texel {
        return {float(f * 40 + 15) / 255.0f, float(250 - f * 40) / 255.0f, 0.5f, 1};
    };
    auto cmd = d.createCommandList();
    for (uint32_t f = 0; f < 6; ++f) {
        const Texel c = colour(f);
        const std::array<float, 8> params = {c[0], c[1], c[2], c[3], 0, 0, 0, 0};
        const BufferHandle ubo = objects.add(d.createBuffer(
            {.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
        cmd->beginRenderPass({.colors = {{.texture = cube, .layer = f}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->draw(3);
        cmd->endRenderPass();
    }
    d.wait(d.submit(*cmd));
    FullscreenSampler sampler(d, "conformance/sample_cube.frag");
    CaseImage ci{"faces_drawn_then_sampled", sampler.draw(d, cube, Format::RGBA8),
                 expectImage(Format::RGBA8, [&](uint32_t x, uint32_t) {
                     return colour(uint32_t((x + 0.5) * 6.0 / 64.0));
                 })};
    ci.absTolerance = 1.0 / 255.0;
    ci.maxFractionOver = 0;
    return {ci};
}

// A compute shader stores into every layer of an array, every face of a cube and every slice
// of a 3D storage image (declared image2DArray, imageCube, image3D: the texture's own kind).
std::vector<CaseImage> storageTextureLayers(Device& d) {
    std::vector<CaseImage> out;
    struct Kind {
        const char* name;
        TextureDimension dim;
        uint32_t layers;
        const char* shader;
        float zScale;
    };
    for (Kind k :
         {Kind{"array", TextureDimension::Texture2DArray, 4, "conformance/fill_array.comp", 4},
          Kind{"cube", TextureDimension::TextureCube, 6, "conformance/fill_cube.comp", 8},
          Kind{"3d", TextureDimension::Texture3D, 4, "conformance/fill_3d.comp", 4}}) {
        DeviceObjects iteration(d);
        TextureHandle t = iteration.add(
            d.createTexture({.dimension = k.dim,
                             .width = 8,
                             .height = 8,
                             .depthOrLayers = k.layers,
                             .usage = TextureUsage::Storage | TextureUsage::CopySrc}));
        ShaderHandle cs = iteration.add(
            d.createShader({.stage = ShaderStage::Compute, .binary = shaders::find(k.shader)}));
        PipelineHandle p = iteration.add(d.createComputePipeline(
            {.computeShader = cs,
             .bindings = {{0, BindingType::StorageTexture, ShaderStage::Compute}}}));
        auto cmd = d.createCommandList();
        cmd->setPipeline(p);
        cmd->setStorageTexture(0, t);
        cmd->dispatch(1, 1, k.layers);
        d.wait(d.submit(*cmd));
        for (uint32_t l = 0; l < k.layers; ++l) {
            auto stored = [&](uint32_t x, uint32_t y) -> Texel {
                return {float(x) / 8.0f, float(y) / 8.0f, float(l) / k.zScale, 1};
            };
            out.push_back(within(std::string(k.name) + "_layer" + std::to_string(l),
                                 d.readTexture(t, {.layer = l}),
                                 expectImage(Format::RGBA8, stored, 8, 8), 1.0 / 255.0,
                                 "x/8 in 8 bits: one step of rounding"));
        }
    }
    return out;
}

// Storage textures at slots 9 and 40 (GL has as few as 8 image units: the backend numbers a
// pipeline's storage textures itself), then another compute pipeline with its own storage
// texture, then the first pipeline again with other textures: each lands in its own texture.
std::vector<CaseImage> storageTexturesAtAnySlot(Device& d) {
    DeviceObjects o(d);
    const TextureDesc small{
        .width = 8, .height = 8, .usage = TextureUsage::Storage | TextureUsage::CopySrc};
    const TextureHandle a = o.add(d.createTexture(small)), b = o.add(d.createTexture(small));
    const TextureHandle e = o.add(d.createTexture(small)), f = o.add(d.createTexture(small));
    const TextureHandle gradient =
        o.add(d.createTexture({.format = Format::RGBA32F,
                               .width = 64,
                               .height = 64,
                               .usage = TextureUsage::Storage | TextureUsage::CopySrc}));
    const float quarter = 0.25f, threeQuarters = 0.75f;
    const BufferHandle scaleA = o.add(d.createBuffer({.size = 16, .usage = BufferUsage::Storage},
                                                     bytesOf(std::array{quarter, 0.f, 0.f, 0.f})));
    const BufferHandle scaleE =
        o.add(d.createBuffer({.size = 16, .usage = BufferUsage::Storage},
                             bytesOf(std::array{threeQuarters, 0.f, 0.f, 0.f})));
    const BufferHandle values =
        o.add(d.createBuffer({.size = 64 * 64 * 4, .usage = BufferUsage::Storage}));
    const ShaderHandle highCs =
        o.add(d.createShader({.stage = ShaderStage::Compute,
                              .binary = shaders::find("conformance/storage_high_slots.comp")}));
    const ShaderHandle fillCs = o.add(d.createShader(
        {.stage = ShaderStage::Compute, .binary = shaders::find("conformance/fill.comp")}));
    const PipelineHandle high =
        o.add(d.createComputePipeline({.computeShader = highCs, .debugName = "slots 9 and 40"}));
    const PipelineHandle fill =
        o.add(d.createComputePipeline({.computeShader = fillCs, .debugName = "slot 1"}));
    auto cmd = d.createCommandList();
    cmd->setPipeline(high);
    cmd->setStorageBuffer(3, scaleA);
    cmd->setStorageTexture(9, a);
    cmd->setStorageTexture(40, b);
    cmd->dispatch(1, 1, 1);
    cmd->setPipeline(fill);
    cmd->setStorageBuffer(0, values);
    cmd->setStorageTexture(1, gradient);
    cmd->dispatch(8, 8, 1);
    cmd->setPipeline(high);
    cmd->setStorageBuffer(3, scaleE);
    cmd->setStorageTexture(9, e);
    cmd->setStorageTexture(40, f);
    cmd->dispatch(1, 1, 1);
    d.wait(d.submit(*cmd));
    auto first = [](float scale) {
        return [scale](uint32_t x, uint32_t) -> Texel { return {float(x) / 8.0f, 0, scale, 1}; };
    };
    auto second = [](float scale) {
        return [scale](uint32_t, uint32_t y) -> Texel {
            return {0, float(y) / 8.0f, 1 - scale, 1};
        };
    };
    const char* rounding = "x/8 in 8 bits: one step of rounding";
    return {within("slot9", d.readTexture(a), expectImage(Format::RGBA8, first(quarter), 8, 8),
                   1.0 / 255.0, rounding),
            within("slot40", d.readTexture(b), expectImage(Format::RGBA8, second(quarter), 8, 8),
                   1.0 / 255.0, rounding),
            within("slot1_between", d.readTexture(gradient),
                   expectImage(
                       Format::RGBA32F,
                       [](uint32_t x, uint32_t y) -> Texel {
                           return {float(x) / 64.0f, float(y) / 64.0f, 0.5f, 1};
                       },
                       64, 64),
                   0.0, "exact in 32-bit float"),
            within("slot9_again", d.readTexture(e),
                   expectImage(Format::RGBA8, first(threeQuarters), 8, 8), 1.0 / 255.0, rounding),
            within("slot40_again", d.readTexture(f),
                   expectImage(Format::RGBA8, second(threeQuarters), 8, 8), 1.0 / 255.0, rounding)};
}

// Depth written into one layer of a depth array and one face of a depth cube reads back there.
std::vector<CaseImage> depthToLayer(Device& d) {
    std::vector<CaseImage> out;
    const TextureUsage rt =
        TextureUsage::RenderTarget | TextureUsage::CopySrc | TextureUsage::Sampled;
    for (TextureDimension dim : {TextureDimension::Texture2DArray, TextureDimension::TextureCube}) {
        DeviceObjects iteration(d);
        TextureHandle t = iteration.add(d.createTexture({.dimension = dim,
                                                         .format = Format::D32F,
                                                         .width = 16,
                                                         .height = 16,
                                                         .depthOrLayers = 6,
                                                         .usage = rt}));
        auto cmd = d.createCommandList();
        for (uint32_t l = 0; l < 6; ++l) {
            cmd->beginRenderPass(
                {.depth = {.texture = t, .layer = l, .clearDepth = 0.1f * float(l + 1)}});
            cmd->endRenderPass();
        }
        d.wait(d.submit(*cmd));
        for (uint32_t l : {1u, 4u})
            out.push_back(
                exact(std::string(textureDimensionName(dim)) + "_layer" + std::to_string(l),
                      d.readTexture(t, {.layer = l}),
                      solid(Format::D32F, {0.1f * float(l + 1), 0, 0, 1}, 16, 16)));
    }
    return out;
}

// 2x2 (2x2x2 for 3D) box filter of values chosen so every average is exact in 8 bits.
std::vector<CaseImage> generateMips(Device& d) {
    std::vector<CaseImage> out;
    auto value = [](uint32_t x, uint32_t y, uint32_t z) -> Texel {
        return {float(((x & 1) * 2 + (y & 1)) * 64) / 255.0f,
                float((x / 2 + y / 2) % 2) * 200.0f / 255.0f, float((z & 1) * 128) / 255.0f, 1.0f};
    };
    struct Kind {
        const char* name;
        TextureDimension dim;
        uint32_t layers;
    };
    for (Kind k : {Kind{"2d", TextureDimension::Texture2D, 1},
                   Kind{"array", TextureDimension::Texture2DArray, 2},
                   Kind{"cube", TextureDimension::TextureCube, 6},
                   Kind{"3d", TextureDimension::Texture3D, 4}}) {
        const bool is3D = k.dim == TextureDimension::Texture3D;
        DeviceObjects iteration(d);
        TextureHandle t = iteration.add(
            d.createTexture({.dimension = k.dim,
                             .width = 8,
                             .height = 8,
                             .depthOrLayers = k.layers,
                             .mipLevels = 3,
                             .usage = TextureUsage::Sampled | TextureUsage::CopySrc |
                                      TextureUsage::CopyDst | TextureUsage::RenderTarget}));
        for (uint32_t l = 0; l < k.layers; ++l) {
            std::vector<Texel> texels;
            for (uint32_t y = 0; y < 8; ++y)
                for (uint32_t x = 0; x < 8; ++x) texels.push_back(value(x, y, is3D ? l : 0));
            d.writeTexture(t, {.layer = l},
                           bytesOf(Image::fromTexels(8, 8, Format::RGBA8, texels).data));
        }
        auto cmd = d.createCommandList();
        cmd->generateMips(t);
        d.wait(d.submit(*cmd));
        // Level m: each texel the mean of its 2^m x 2^m (x 2^m slices) footprint, computed here;
        // the first and last layer of each level.
        for (uint32_t m = 1; m < 3; ++m) {
            const uint32_t f = 1u << m, size = 8 >> m, zs = is3D ? f : 1,
                           layers = is3D ? k.layers >> m : k.layers;
            for (uint32_t l = 0; l < layers; l += std::max(1u, layers - 1)) {
                auto mean = [&](uint32_t x, uint32_t y) {
                    Texel sum{};
                    for (uint32_t z = 0; z < zs; ++z)
                        for (uint32_t j = 0; j < f; ++j)
                            for (uint32_t i = 0; i < f; ++i) {
                                const Texel v = value(f * x + i, f * y + j, is3D ? f * l + z : 0);
                                for (int c = 0; c < 4; ++c) sum[c] += v[c] / float(f * f * zs);
                            }
                    return sum;
                };
                out.push_back(within(
                    std::string(k.name) + "_mip" + std::to_string(m) + "_layer" + std::to_string(l),
                    d.readTexture(t, {.mipLevel = m, .layer = l}),
                    expectImage(Format::RGBA8, mean, size, size), 1.5 / 255.0,
                    "box filter of values whose means are exact in 8 bits: 1.5/255 for rounding"));
            }
        }
    }
    DeviceObjects objects(d);
    TextureHandle integer = objects.add(
        d.createTexture({.format = Format::R32U, .width = 8, .height = 8, .mipLevels = 2}));
    auto cmd = d.createCommandList();
    FE_CONFORMANCE_CHECK(throws([&] { cmd->generateMips(integer); }),
                         "integer formats cannot be filtered into mips");
    return out;
}

// Buffer <-> texture copies of one layer and one mip, through a buffer offset.
std::vector<CaseImage> copySubresources(Device& d) {
    std::vector<CaseImage> out;
    DeviceObjects objects(d);
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                                   .width = 8,
                                                   .height = 8,
                                                   .depthOrLayers = 3,
                                                   .mipLevels = 2}));
    const Image layer2 = patternImage(8, 8, 2), mip1 = patternImage(4, 4, 5);
    BufferHandle src =
        objects.add(d.createBuffer({.size = 512 + layer2.data.size() + mip1.data.size()}));
    d.writeBuffer(src, 512, bytesOf(layer2.data));
    d.writeBuffer(src, 512 + layer2.data.size(), bytesOf(mip1.data));
    BufferHandle dst = objects.add(d.createBuffer({.size = 1024}));
    auto cmd = d.createCommandList();
    cmd->copyBufferToTexture(t, {.layer = 2}, src, 512);
    cmd->copyBufferToTexture(t, {.mipLevel = 1, .layer = 1}, src, 512 + layer2.data.size());
    cmd->copyTextureToBuffer(dst, 256, t, {.mipLevel = 1, .layer = 1});
    d.wait(d.submit(*cmd));
    out.push_back(exact("layer2_from_buffer", d.readTexture(t, {.layer = 2}), layer2));
    out.push_back(
        exact("mip1_layer1_from_buffer", d.readTexture(t, {.mipLevel = 1, .layer = 1}), mip1));
    std::vector<uint8_t> back = d.readBuffer(dst, 256, mip1.data.size());
    out.push_back(exact("mip1_layer1_to_buffer", Image{4, 4, Format::RGBA8, back}, mip1));
    FE_CONFORMANCE_CHECK(throws([&] {
                             auto c = d.createCommandList();
                             c->copyBufferToTexture(t, {.layer = 3}, src, 0);
                         }),
                         "a copy to layer 3 of a 3-layer texture is an error");
    return out;
}

// --- Block compression ------------------------------------------------------------------------

// A 4x4 block's texels in row order, as the format's decoding rules give them (values in [0,1]).
using Block = std::array<Texel, 16>;

// BC1 (and BC3's colour half): red 5:6:5 endpoint 0, blue endpoint 1, four-colour mode
// (color0 > color1), texel i uses index i % 4: red, blue, 2/3 red + 1/3 blue, 1/3 red + 2/3 blue.
void bc1Colour(uint8_t* out, Block& texels) {
    const uint16_t c0 = 0xF800, c1 = 0x001F;
    out[0] = c0 & 0xff;
    out[1] = c0 >> 8;
    out[2] = c1 & 0xff;
    out[3] = c1 >> 8;
    uint32_t bits = 0;
    for (uint32_t i = 0; i < 16; ++i) bits |= (i % 4) << (2 * i);
    for (int k = 0; k < 4; ++k) out[4 + k] = uint8_t(bits >> (8 * k));
    const float red[4] = {1, 0, 2.0f / 3, 1.0f / 3};
    for (uint32_t i = 0; i < 16; ++i) texels[i] = {red[i % 4], 0, 1 - red[i % 4], 1};
}

// BC4 (and BC3's alpha, BC5's channels): endpoints 255 and 0 (eight-value mode), texel i uses
// index i % 8: 1, 0, 6/7, 5/7, 4/7, 3/7, 2/7, 1/7.
void bc4Channel(uint8_t* out, std::array<float, 16>& values) {
    out[0] = 255;
    out[1] = 0;
    uint64_t bits = 0;
    for (uint32_t i = 0; i < 16; ++i) bits |= uint64_t(i % 8) << (3 * i);
    for (int k = 0; k < 6; ++k) out[2 + k] = uint8_t(bits >> (8 * k));
    const float v[8] = {1, 0, 6.0f / 7, 5.0f / 7, 4.0f / 7, 3.0f / 7, 2.0f / 7, 1.0f / 7};
    for (uint32_t i = 0; i < 16; ++i) values[i] = v[i % 8];
}

// BC7 mode 6: one subset, RGBA endpoints of 7 bits plus a shared p-bit each, 4-bit indices
// (texel 0's top bit implied 0); texel i uses index i. Values from the format's weight table.
void bc7Mode6(uint8_t* out, Block& texels) {
    std::array<uint8_t, 16> bytes{};
    uint32_t pos = 0;
    auto put = [&](uint32_t value, uint32_t count) {
        for (uint32_t b = 0; b < count; ++b, ++pos)
            if (value & (1u << b)) bytes[pos / 8] |= uint8_t(1u << (pos % 8));
    };
    put(1u << 6, 7);  // mode 6
    const uint32_t e0[4] = {127, 0, 64, 127}, e1[4] = {0, 127, 32, 127}, p0 = 1, p1 = 0;
    for (int c = 0; c < 4; ++c) {
        put(e0[c], 7);
        put(e1[c], 7);
    }
    put(p0, 1);
    put(p1, 1);
    put(0, 3);  // texel 0, anchor
    for (uint32_t i = 1; i < 16; ++i) put(i, 4);
    std::copy(bytes.begin(), bytes.end(), out);
    static const uint32_t weights[16] = {0,  4,  9,  13, 17, 21, 26, 30,
                                         34, 38, 43, 47, 51, 55, 60, 64};
    for (uint32_t i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c) {
            const uint32_t a = (e0[c] << 1) | p0, b = (e1[c] << 1) | p1;
            texels[i][c] = float(((64 - weights[i]) * a + weights[i] * b + 32) >> 6) / 255.0f;
        }
}

struct CompressedFormat {
    Format format;
    std::function<void(uint8_t*, Block&)> encode;  // one block and its decoded texels
};

std::vector<CompressedFormat> compressedFormats() {
    auto bc3 = [](uint8_t* out, Block& t) {
        std::array<float, 16> alpha;
        bc4Channel(out, alpha);
        bc1Colour(out + 8, t);
        for (int i = 0; i < 16; ++i) t[i][3] = alpha[i];
    };
    auto bc4 = [](uint8_t* out, Block& t) {
        std::array<float, 16> r;
        bc4Channel(out, r);
        for (int i = 0; i < 16; ++i) t[i] = {r[i], 0, 0, 1};
    };
    auto bc5 = [](uint8_t* out, Block& t) {
        std::array<float, 16> r, g;
        bc4Channel(out, r);
        bc4Channel(out + 8, g);
        for (int i = 0; i < 16; ++i) t[i] = {r[i], g[i], 0, 1};
    };
    return {{Format::BC1, bc1Colour}, {Format::BC1_SRGB, bc1Colour},
            {Format::BC3, bc3},       {Format::BC3_SRGB, bc3},
            {Format::BC4, bc4},       {Format::BC5, bc5},
            {Format::BC7, bc7Mode6},  {Format::BC7_SRGB, bc7Mode6}};
}

float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

// An 8x8 texture of four copies of one known block, sampled (nearest) into an RGBA32F target:
// every pixel must be its texel's decoded value (sRGB formats: decoded, then to linear).
std::vector<CaseImage> compressedBc(Device& d) {
    std::vector<CaseImage> out;
    if (!d.info().features.textureCompressionBC) {
        FE_CONFORMANCE_CHECK(throws([&] {
                                 DeviceObjects(d).add(d.createTexture(
                                     {.format = Format::BC1, .width = 8, .height = 8}));
                             }),
                             "BC formats on a device without them are an error");
        return out;
    }
    FullscreenSampler fs(d, "conformance/textured.frag");
    for (const CompressedFormat& cf : compressedFormats()) {
        const uint32_t blockBytes = formatInfo(cf.format).bytesPerBlock;
        std::vector<uint8_t> data(4 * blockBytes);
        Block texels;
        for (int b = 0; b < 4; ++b) cf.encode(data.data() + b * blockBytes, texels);
        DeviceObjects iteration(d);
        TextureHandle t =
            iteration.add(d.createTexture({.format = cf.format, .width = 8, .height = 8}));
        d.writeTexture(t, {}, bytesOf(data));
        const bool srgb = formatInfo(cf.format).isSrgb;
        Image expected = expectImage(Format::RGBA32F, [&](uint32_t x, uint32_t y) {
            Texel v = texels[((y / 8) % 4) * 4 + (x / 8) % 4];
            if (srgb)
                for (int c = 0; c < 3; ++c) v[c] = srgbToLinear(v[c]);
            return v;
        });
        out.push_back(
            within(std::string(formatInfo(cf.format).name), fs.draw(d, t, Format::RGBA32F),
                   expected, 3.0 / 255.0,
                   "decoders may round interpolated endpoints differently: 3/255, no pixel over"));
    }
    FE_CONFORMANCE_CHECK(
        throws([&] {  // (freed at once, should it be made)
            DeviceObjects(d).add(d.createTexture({.format = Format::BC7,
                                                  .width = 8,
                                                  .height = 8,
                                                  .usage = TextureUsage::RenderTarget}));
        }),
        "a compressed render target is an error");
    return out;
}

// Every call that takes data checks its length against what it will read.
std::vector<CaseImage> uploadLengthsChecked(Device& d) {
    const uint8_t sixteen[16] = {};
    DeviceObjects objects(d);
    FE_CONFORMANCE_CHECK(
        throws([&] { objects.add(d.createBuffer({.size = 64}, bytesOf(sixteen))); }),
        "createBuffer with 16 bytes for a 64-byte buffer is an error");
    BufferHandle b = objects.add(d.createBuffer({.size = 16}, bytesOf(sixteen)));
    FE_CONFORMANCE_CHECK(throws([&] { d.writeBuffer(b, 8, bytesOf(sixteen)); }),
                         "writeBuffer past the end is an error");
    TextureHandle t = objects.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                                   .width = 4,
                                                   .height = 4,
                                                   .depthOrLayers = 2,
                                                   .mipLevels = 2}));
    std::vector<uint8_t> mip0(64), mip1(16);
    FE_CONFORMANCE_CHECK(throws([&] { d.writeTexture(t, {}, bytesOf(mip1)); }),
                         "a short texture upload is an error");
    FE_CONFORMANCE_CHECK(throws([&] { d.writeTexture(t, {.mipLevel = 1}, bytesOf(mip0)); }),
                         "a long texture upload is an error");
    FE_CONFORMANCE_CHECK(throws([&] { d.writeTexture(t, {.layer = 2}, bytesOf(mip0)); }),
                         "layer 2 of 2 is an error");
    FE_CONFORMANCE_CHECK(throws([&] { d.readTexture(t, {.mipLevel = 2}); }),
                         "mip 2 of 2 is an error");
    d.writeTexture(t, {.mipLevel = 1, .layer = 1}, bytesOf(mip1));
    return {};
}

}  // namespace

std::vector<Case> textureCases() {
    return {
        {"texture_array_layers", textureArrayLayers},
        {"cube_faces", cubeFaces},
        {"cube_array", cubeArray},
        {"texture_3d_slices", texture3dSlices},
        {"render_to_subresource", renderToSubresources},
        {"render_cube_faces_then_sample", renderCubeFacesThenSample},
        {"storage_texture_layers", storageTextureLayers},
        {"storage_textures_at_any_slot", storageTexturesAtAnySlot},
        {"depth_to_layer", depthToLayer},
        {"generate_mips", generateMips},
        {"copy_subresources", copySubresources},
        {"compressed_bc", compressedBc},
        {"upload_lengths_checked", uploadLengthsChecked},
    };
}

}  // namespace fe::conformance
