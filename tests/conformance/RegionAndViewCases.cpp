// Conformance cases for texture regions and views: uploads and read-backs with a row pitch,
// copies between regions, mips, layers and faces, and views of mips, layers, faces, formats and
// swizzles, sampled and drawn into; plus a recorded list replayed from capture bytes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "CaseSupport.h"
#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/CommandRecorder.h"
#include "fe/gdi/PipelineCacheFile.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// RGBA8 test texel of texture coordinate (x, y) and a tag (layer or source): exact in 8 bits.
std::array<uint8_t, 4> patternTexel(uint32_t x, uint32_t y, uint32_t tag) {
    return {uint8_t(x * 4), uint8_t(y * 4), uint8_t(64 + 32 * tag), 255};
}
// A CPU image of `w` x `h` RGBA8 texels: the pattern inside [x0, x0 + rw) x [y0, y0 + rh), 0 elsewhere.
Image patternImage(uint32_t w, uint32_t h, uint32_t x0, uint32_t y0, uint32_t rw, uint32_t rh,
                   uint32_t tag, int32_t dx = 0, int32_t dy = 0) {
    Image img{w, h, Format::RGBA8, std::vector<uint8_t>(size_t(w) * h * 4, 0)};
    for (uint32_t y = y0; y < y0 + rh; ++y)
        for (uint32_t x = x0; x < x0 + rw; ++x) {
            const auto t = patternTexel(uint32_t(int32_t(x) + dx), uint32_t(int32_t(y) + dy), tag);
            std::memcpy(&img.data[(size_t(y) * w + x) * 4], t.data(), 4);
        }
    return img;
}
// Bytes of a padded layout holding the pattern of the box, padding bytes 0xEE (they must not land).
std::vector<uint8_t> paddedPattern(const TextureRegion& r, const TexelLayout& l,
                                   uint32_t firstTag) {
    std::vector<uint8_t> bytes(l.offset + size_t(l.rowsPerImage) * l.bytesPerRow * r.depth, 0xEE);
    for (uint32_t z = 0; z < r.depth; ++z)
        for (uint32_t y = 0; y < r.height; ++y)
            for (uint32_t x = 0; x < r.width; ++x) {
                const auto t = patternTexel(r.x + x, r.y + y, firstTag + z);
                std::memcpy(
                    &bytes[l.offset + (size_t(z) * l.rowsPerImage + y) * l.bytesPerRow + x * 4],
                    t.data(), 4);
            }
    return bytes;
}

// Padded rows land where stated: a writeTextureRegion with 20-texel rows for a 16-texel box at
// an offset, and a buffer copy into two layers of an array with 16-texel rows and 10 rows per
// layer; the padding never reaches the texture, and nothing outside the boxes changes.
std::vector<CaseImage> regionUploadRowPitch(Device& d) {
    DeviceObjects o(d);
    const TextureHandle flat =
        o.add(d.createTexture({.width = 64, .height = 64, .debugName = "flat"}));
    const TextureRegion box{.x = 8, .y = 4, .width = 16, .height = 8, .depth = 1};
    const TexelLayout rows{.offset = 12, .bytesPerRow = 20 * 4};
    TexelLayout full = rows;
    full.rowsPerImage = box.height;
    d.writeTextureRegion(flat, box, bytesOf(paddedPattern(box, full, 0)), rows);

    const TextureHandle array =
        o.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                               .width = 64,
                               .height = 64,
                               .depthOrLayers = 3,
                               .debugName = "array"}));
    const TextureRegion layers{.x = 32, .y = 40, .z = 1, .width = 8, .height = 8, .depth = 2};
    const TexelLayout pitch{.offset = 256, .bytesPerRow = 16 * 4, .rowsPerImage = 10};
    const std::vector<uint8_t> staged = paddedPattern(layers, pitch, 1);
    const BufferHandle buffer = o.add(
        d.createBuffer({.size = staged.size(), .usage = BufferUsage::CopySrc}, bytesOf(staged)));
    auto cmd = d.createCommandList();
    cmd->copyBufferToTexture(array, layers, buffer, pitch);
    d.wait(d.submit(*cmd));
    return {
        exact("writeTextureRegion, 80-byte rows", d.readTexture(flat),
              patternImage(64, 64, 8, 4, 16, 8, 0)),
        exact("array layer 0 untouched", d.readTexture(array, {0, 0}),
              patternImage(64, 64, 0, 0, 0, 0, 0)),
        exact("array layer 1", d.readTexture(array, {0, 1}), patternImage(64, 64, 32, 40, 8, 8, 1)),
        exact("array layer 2", d.readTexture(array, {0, 2}),
              patternImage(64, 64, 32, 40, 8, 8, 2))};
}

// Regions read back into a buffer with a pitch (the bytes between rows keep the buffer's
// earlier contents), and copied between textures of compatible formats: RGBA8 into RGBA8_SRGB
// and R32F into R32U move the same bits. And every layout or region mistake is the same Error.
std::vector<CaseImage> regionCopies(Device& d) {
    DeviceObjects o(d);
    const TextureHandle source =
        o.add(d.createTexture({.width = 64, .height = 64, .debugName = "source"}));
    const TextureRegion whole{.width = 64, .height = 64, .depth = 1};
    d.writeTextureRegion(
        source, whole, bytesOf(paddedPattern(whole, {.bytesPerRow = 256, .rowsPerImage = 64}, 0)));
    const BufferHandle readback =
        o.add(d.createBuffer({.size = 4096, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
    const TextureRegion box{.x = 16, .y = 8, .width = 8, .height = 4, .depth = 1};
    const TexelLayout pitch{.offset = 64, .bytesPerRow = 48};
    const TextureHandle srgb = o.add(d.createTexture(
        {.format = Format::RGBA8_SRGB, .width = 64, .height = 64, .debugName = "srgb"}));
    const TextureHandle floats = o.add(d.createTexture(
        {.format = Format::R32F, .width = 64, .height = 64, .debugName = "floats"}));
    const TextureHandle uints = o.add(
        d.createTexture({.format = Format::R32U, .width = 64, .height = 64, .debugName = "uints"}));
    std::vector<float> values(64 * 64);
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) * 0.25f - 100.0f;
    d.writeTextureRegion(floats, whole, bytesOf(values));
    auto cmd = d.createCommandList();
    cmd->clearBuffer(readback, 0, 0, 0xABABABABu);
    cmd->copyTextureToBuffer(readback, pitch, source, box);
    cmd->copyTexture(srgb, {.x = 40, .y = 50}, source, box);
    cmd->copyTexture(uints, {}, floats, {.y = 32, .height = 32});
    d.wait(d.submit(*cmd));

    const std::vector<uint8_t> bytes = d.readBuffer(readback, 0, 4096);
    for (uint32_t i = 0; i < 4096; ++i) {
        const bool inBox = i >= pitch.offset && (i - pitch.offset) / 48 < box.height &&
                           (i - pitch.offset) % 48 < 32;
        uint8_t want = 0xAB;
        if (inBox) {
            const uint32_t row = (i - 64) / 48, column = (i - 64) % 48 / 4;
            want = patternTexel(box.x + column, box.y + row, 0)[(i - 64) % 4];
        }
        FE_CONFORMANCE_CHECK(bytes[i] == want,
                             ("copyTextureToBuffer byte " + std::to_string(i) + " is " +
                              std::to_string(bytes[i]) + ", expected " + std::to_string(want))
                                 .c_str());
    }
    // Compared byte by byte (as RGBA8 images of the same bytes): the copy moves bits, not values.
    Image floatBits{64, 64, Format::RGBA8, std::vector<uint8_t>(64 * 64 * 4, 0)};
    std::memcpy(floatBits.data.data(),
                reinterpret_cast<const uint8_t*>(values.data()) + 32 * 64 * 4, 32 * 64 * 4);
    auto asBytes = [](Image i) {  // 4-byte texels compared as the bytes the copy moved
        i.format = Format::RGBA8;
        return i;
    };
    Image srgbRaw = asBytes(d.readTexture(srgb));
    std::vector<CaseImage> images = {
        exact("RGBA8 box copied into RGBA8_SRGB", srgbRaw,
              patternImage(64, 64, 40, 50, 8, 4, 0, -24, -42)),
        exact("R32F rows copied into R32U", asBytes(d.readTexture(uints)), floatBits)};

    auto list = d.createCommandList();
    expectError([&] { list->copyTextureToBuffer(readback, {.bytesPerRow = 30}, source, box); },
                "bytesPerRow 30 is not a multiple of the texel size (4) of at least one row (32)");
    expectError([&] { list->copyTextureToBuffer(readback, {.offset = 2}, source, box); },
                "offset 2 is not a multiple of 4");
    expectError(
        [&] {
            list->copyBufferToTexture(source, TextureRegion{.depth = 1}, readback, TexelLayout{});
        },
        "copyBufferToTexture: range [0, 16384) exceeds its size 4096");
    expectError([&] { list->copyTexture(source, {.x = 60}, source, box); },
                "is outside mip level 0 (64x64x1)");
    expectError(
        [&] {
            list->copyTexture(
                floats, {},
                o.add(d.createTexture({.format = Format::RGBA16F, .width = 8, .height = 8})), {});
        },
        "RGBA16F texels cannot be copied into R32F");
    expectError([&] { list->copyTexture(source, {.x = 20, .y = 10}, source, box); },
                "source and destination overlap in 'source'");
    expectError([&] { d.writeTextureRegion(source, box, bytesOf(values), {.rowsPerImage = 2}); },
                "rowsPerImage 2 is less than the region's 4 rows");
    d.wait(d.submit(*list));
    return images;
}

// Mip to mip and face to face inside one texture: a 16x16 box of level 0 into level 1 at (4, 4),
// one cube face's quadrant into another face, and a 3D texture's slices moved along z.
std::vector<CaseImage> textureCopyBetweenMips(Device& d) {
    DeviceObjects o(d);
    const TextureHandle chain =
        o.add(d.createTexture({.width = 64, .height = 64, .mipLevels = 3, .debugName = "chain"}));
    const TextureRegion level0{.width = 64, .height = 64, .depth = 1};
    d.writeTextureRegion(
        chain, level0, bytesOf(paddedPattern(level0, {.bytesPerRow = 256, .rowsPerImage = 64}, 0)));
    const TextureHandle cube = o.add(d.createTexture({.dimension = TextureDimension::TextureCube,
                                                      .width = 32,
                                                      .height = 32,
                                                      .depthOrLayers = 6,
                                                      .debugName = "cube"}));
    const TextureRegion face2{.z = 2, .width = 32, .height = 32, .depth = 1};
    d.writeTextureRegion(
        cube, face2, bytesOf(paddedPattern(face2, {.bytesPerRow = 128, .rowsPerImage = 32}, 2)));
    const TextureHandle volume = o.add(d.createTexture({.dimension = TextureDimension::Texture3D,
                                                        .width = 16,
                                                        .height = 16,
                                                        .depthOrLayers = 8,
                                                        .debugName = "volume"}));
    const TextureRegion slices{.z = 0, .width = 16, .height = 16, .depth = 2};
    d.writeTextureRegion(
        volume, slices, bytesOf(paddedPattern(slices, {.bytesPerRow = 64, .rowsPerImage = 16}, 0)));
    auto cmd = d.createCommandList();
    cmd->copyTexture(chain, {.mipLevel = 1, .x = 4, .y = 4}, chain, {.width = 16, .height = 16});
    cmd->copyTexture(cube, {.x = 16, .y = 16, .z = 5}, cube,
                     {.z = 2, .width = 16, .height = 16, .depth = 1});
    cmd->copyTexture(volume, {.z = 5}, volume, slices);
    d.wait(d.submit(*cmd));
    std::vector<CaseImage> images = {
        exact("level 0 box in level 1 at (4, 4)", d.readTexture(chain, {1, 0}),
              patternImage(32, 32, 4, 4, 16, 16, 0, -4, -4)),
        exact("face 2 quadrant in face 5", d.readTexture(cube, {0, 5}),
              patternImage(32, 32, 16, 16, 16, 16, 2, -16, -16))};
    for (uint32_t z : {5u, 6u})
        images.push_back(exact("3D slice " + std::to_string(z), d.readTexture(volume, {0, z}),
                               patternImage(16, 16, 0, 0, 16, 16, z - 5)));
    return images;
}

// Solid RGBA8 colours, exact in 8 bits, one per mip level or layer.
constexpr std::array<std::array<uint8_t, 4>, 6> kSolid = {{{255, 0, 0, 255},
                                                           {0, 255, 0, 255},
                                                           {0, 0, 255, 255},
                                                           {255, 255, 255, 255},
                                                           {255, 0, 255, 255},
                                                           {0, 255, 255, 255}}};
Texel solidTexel(size_t i) {
    return {kSolid[i][0] / 255.0f, kSolid[i][1] / 255.0f, kSolid[i][2] / 255.0f,
            kSolid[i][3] / 255.0f};
}
// Fills every texel of one subresource of an RGBA8 texture with kSolid[colour].
void fillSolid(Device& d, TextureHandle t, Subresource at, size_t colour) {
    const TextureDesc& desc = d.desc(t);
    const uint32_t w = std::max(1u, desc.width >> at.mipLevel),
                   h = std::max(1u, desc.height >> at.mipLevel);
    std::vector<std::array<uint8_t, 4>> texels(size_t(w) * h, kSolid[colour]);
    d.writeTexture(t, at, bytesOf(texels));
}
Image solidImage(size_t colour, uint32_t w = kCaseSize, uint32_t h = kCaseSize) {
    return solid(Format::RGBA8, solidTexel(colour), w, h);
}

// One pass drawing a full-screen triangle into `target` (a texture or view) that samples
// `source` with textured_uv.frag at uv = pixel / 64 and level of detail `lod`.
void sampleInto(Device& d, TextureHandle target, Format format, TextureHandle source,
                float lod = 0) {
    DeviceObjects o(d);
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert"),
         .fragmentShader = registryShader(o, ShaderStage::Fragment, "conformance/textured_uv.frag"),
         .colorFormats = {format},
         .debugName = "sample into"}));
    const std::array<float, 8> params = {1, 1, 0, 0, 0, lod, 0, 0};
    const BufferHandle ubo = o.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    const SamplerHandle nearest = o.add(d.createSampler({.minFilter = Filter::Nearest,
                                                         .magFilter = Filter::Nearest,
                                                         .mipFilter = MipFilter::Nearest,
                                                         .addressU = AddressMode::ClampToEdge,
                                                         .addressV = AddressMode::ClampToEdge}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}, .debugName = "sample into"});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->setTexture(1, source, nearest);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
}

// A view of mips 2 and 3 sampled at its levels 0 and 1; then one mip sampled through a view of
// it while the next one is drawn through another (a downsampling chain's step).
std::vector<CaseImage> viewMipRange(Device& d) {
    DeviceObjects o(d);
    const TextureHandle chain =
        o.add(d.createTexture({.width = 64,
                               .height = 64,
                               .mipLevels = 4,
                               .usage = TextureUsage::Sampled | TextureUsage::RenderTarget |
                                        TextureUsage::CopyDst | TextureUsage::CopySrc,
                               .debugName = "chain"}));
    for (uint32_t m = 0; m < 4; ++m) fillSolid(d, chain, {m, 0}, m);
    const TextureHandle tail =
        o.add(d.createTextureView(chain, {.baseMip = 2, .mipCount = 2, .debugName = "mips 2-3"}));
    FE_CONFORMANCE_CHECK(d.desc(tail).width == 16 && d.desc(tail).mipLevels == 2,
                         "the view's desc is its base mip's size and count");
    std::vector<CaseImage> images;
    for (uint32_t level : {0u, 1u}) {
        const TextureHandle target = caseTarget(o);
        sampleInto(d, target, Format::RGBA8, tail, float(level));
        images.push_back(
            exact("view level " + std::to_string(level) + " is mip " + std::to_string(level + 2),
                  d.readTexture(target), solidImage(level + 2)));
    }
    const TextureHandle mip0 =
        o.add(d.createTextureView(chain, {.mipCount = 1, .debugName = "mip 0"}));
    const TextureHandle mip1 =
        o.add(d.createTextureView(chain, {.baseMip = 1, .mipCount = 1, .debugName = "mip 1"}));
    sampleInto(d, mip1, Format::RGBA8, mip0);
    images.push_back(
        exact("mip 1 drawn from mip 0", d.readTexture(chain, {1, 0}), solidImage(0, 32, 32)));
    images.push_back(exact("mip 2 untouched", d.readTexture(chain, {2, 0}), solidImage(2, 16, 16)));
    return images;
}

// Layers as textures: one layer of an array as a Texture2D, two layers as a smaller array, six
// layers of a square array as a cube, and one face of a cube as a Texture2D.
std::vector<CaseImage> viewLayerAndFace(Device& d) {
    DeviceObjects o(d);
    const TextureHandle array =
        o.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                               .width = 32,
                               .height = 32,
                               .depthOrLayers = 6,
                               .debugName = "array"}));
    const TextureHandle cube = o.add(d.createTexture({.dimension = TextureDimension::TextureCube,
                                                      .width = 32,
                                                      .height = 32,
                                                      .depthOrLayers = 6,
                                                      .debugName = "cube"}));
    for (uint32_t l = 0; l < 6; ++l)
        fillSolid(d, array, {0, l}, l), fillSolid(d, cube, {0, l}, 5 - l);
    std::vector<CaseImage> images;
    auto sampled = [&](const char* shader, TextureHandle view) {
        return FullscreenSampler(d, shader).draw(d, view, Format::RGBA8);
    };
    const TextureHandle layer4 = o.add(d.createTextureView(
        array, {.dimension = TextureDimension::Texture2D, .baseLayer = 4, .layerCount = 1}));
    images.push_back(exact("array layer 4 as a Texture2D",
                           sampled("conformance/textured.frag", layer4), solidImage(4)));
    const TextureHandle pair = o.add(d.createTextureView(array, {.baseLayer = 2, .layerCount = 2}));
    images.push_back(exact("layers 2-3 as an array", sampled("conformance/sample_array.frag", pair),
                           expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) {
                               return solidTexel(x < 32 && y < 32 ? 2 : 3);
                           })));
    const TextureHandle asCube =
        o.add(d.createTextureView(array, {.dimension = TextureDimension::TextureCube}));
    images.push_back(exact("six array layers as a cube",
                           sampled("conformance/sample_cube.frag", asCube),
                           expectImage(Format::RGBA8, [](uint32_t x, uint32_t) {
                               return solidTexel(size_t((x + 0.5) * 6.0 / 64.0));
                           })));
    const TextureHandle face1 = o.add(d.createTextureView(
        cube, {.dimension = TextureDimension::Texture2D, .baseLayer = 1, .layerCount = 1}));
    images.push_back(exact("cube face 1 as a Texture2D",
                           sampled("conformance/textured.frag", face1), solidImage(4)));

    expectError([&] { d.createTextureView(array, {.dimension = TextureDimension::Texture2D}); },
                "a Texture2D view has one layer, not 6");
    expectError(
        [&] {
            d.createTextureView(array,
                                {.dimension = TextureDimension::TextureCube, .baseLayer = 1});
        },
        "a TextureCube view takes 6 layers per cube, not 5");
    expectError([&] { d.createTextureView(layer4, {}); }, "a view of a view");
    expectError([&] { d.destroy(array); }, "view(s) of it are alive: destroy them first");
    expectError(
        [&] {
            auto c = d.createCommandList();
            c->generateMips(layer4);
        },
        "is for binding");
    expectError([&] { d.readTexture(face1); }, "is for binding");
    return images;
}

// An sRGB texture read through a UNORM view gives its stored bytes, not decoded values; a UNORM
// render target drawn through an sRGB view stores encoded values. Formats not listed in
// viewFormats, or not compatible, are refused.
std::vector<CaseImage> viewFormatSrgbUnorm(Device& d) {
    DeviceObjects o(d);
    const TextureHandle srgb = o.add(d.createTexture({.format = Format::RGBA8_SRGB,
                                                      .width = 64,
                                                      .height = 64,
                                                      .viewFormats = {Format::RGBA8},
                                                      .debugName = "srgb"}));
    std::vector<std::array<uint8_t, 4>> texels(64 * 64, {128, 64, 255, 255});
    d.writeTexture(srgb, {}, bytesOf(texels));
    const TextureHandle raw =
        o.add(d.createTextureView(srgb, {.format = Format::RGBA8, .debugName = "unorm view"}));
    FullscreenSampler sampler(d, "conformance/textured.frag");
    std::vector<CaseImage> images;
    images.push_back(exact("UNORM view of sRGB texels: the bytes",
                           sampler.draw(d, raw, Format::RGBA8),
                           expectImage(Format::RGBA8, [](uint32_t, uint32_t) -> Texel {
                               return {128 / 255.0f, 64 / 255.0f, 1, 1};
                           })));
    images.push_back(
        drawn8("the sRGB texture itself: decoded", sampler.draw(d, srgb, Format::RGBA8),
               expectImage(Format::RGBA8, [](uint32_t, uint32_t) -> Texel {
                   auto decode = [](float c) {
                       return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
                   };
                   return {decode(128 / 255.0f), decode(64 / 255.0f), 1, 1};
               })));
    const TextureHandle unorm =
        o.add(d.createTexture({.width = 64,
                               .height = 64,
                               .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                               .viewFormats = {Format::RGBA8_SRGB},
                               .debugName = "unorm target"}));
    const TextureHandle encoded = o.add(d.createTextureView(unorm, {.format = Format::RGBA8_SRGB}));
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
         .fragmentShader =
             registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
         .topology = PrimitiveTopology::TriangleStrip,
         .colorFormats = {Format::RGBA8_SRGB},
         .debugName = "srgb writer"}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = encoded}}});
    cmd->setPipeline(p);
    cmd->setConstants(pixelQuad(0, 0, 64, 64, {0.5f, 0.2f, 1, 1}));
    cmd->draw(4);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    auto encode = [](float c) {
        return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
    };
    images.push_back(drawn8("drawn through an sRGB view: encoded", d.readTexture(unorm),
                            expectImage(Format::RGBA8, [&](uint32_t, uint32_t) -> Texel {
                                return {encode(0.5f), encode(0.2f), 1, 1};
                            })));
    expectError([&] { d.createTextureView(unorm, {.format = Format::R32F}); },
                "is not the texture's RGBA8 nor in its TextureDesc::viewFormats");
    expectError(
        [&] {
            d.createTexture(
                {.width = 4, .height = 4, .viewFormats = {Format::RGBA16F}, .debugName = "bad"});
        },
        "view format RGBA16F is not compatible with RGBA8");
    return images;
}

// A swizzled view reorders and replaces channels when sampled (B, G, R, 1; then 0, 0, 0, A; then
// R, R, R, 1), the texture unchanged; a swizzled view cannot be drawn into.
std::vector<CaseImage> viewSwizzle(Device& d) {
    DeviceObjects o(d);
    const TextureHandle t = o.add(d.createTexture(
        {.width = 64,
         .height = 64,
         .usage = TextureUsage::Sampled | TextureUsage::RenderTarget | TextureUsage::CopyDst,
         .debugName = "rgba"}));
    std::vector<std::array<uint8_t, 4>> texels(64 * 64, {40, 80, 120, 160});
    d.writeTexture(t, {}, bytesOf(texels));
    using W = Swizzle;
    const std::array<std::pair<std::array<Swizzle, 4>, std::array<uint8_t, 4>>, 4> cases = {{
        {{W::Identity, W::Identity, W::Identity, W::Identity}, {40, 80, 120, 160}},
        {{W::B, W::G, W::R, W::One}, {120, 80, 40, 255}},
        {{W::Zero, W::Zero, W::Zero, W::A}, {0, 0, 0, 160}},
        {{W::R, W::R, W::R, W::One}, {40, 40, 40, 255}},
    }};
    FullscreenSampler sampler(d, "conformance/textured.frag");
    std::vector<CaseImage> images;
    for (const auto& [swizzle, want] : cases) {
        const TextureHandle view = o.add(d.createTextureView(t, {.swizzle = swizzle}));
        images.push_back(
            exact("swizzle " + std::to_string(want[0]) + "," + std::to_string(want[1]) + "," +
                      std::to_string(want[2]) + "," + std::to_string(want[3]),
                  sampler.draw(d, view, Format::RGBA8),
                  expectImage(Format::RGBA8, [w = want](uint32_t, uint32_t) -> Texel {
                      return {w[0] / 255.0f, w[1] / 255.0f, w[2] / 255.0f, w[3] / 255.0f};
                  })));
    }
    const TextureHandle swizzled =
        o.add(d.createTextureView(t, {.swizzle = {W::B, W::G, W::R, W::A}}));
    auto cmd = d.createCommandList();
    expectError([&] { cmd->beginRenderPass({.colors = {{.texture = swizzled}}}); }, "RenderTarget");
    return images;
}

// Views as attachments and storage: layer 2 of an array drawn through a Texture2D view (its
// neighbours untouched), and mip 1 of a texture written by a compute shader through a view bound
// as a storage image.
std::vector<CaseImage> viewAsAttachment(Device& d) {
    DeviceObjects o(d);
    const TextureHandle array =
        o.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                               .width = 64,
                               .height = 64,
                               .depthOrLayers = 4,
                               .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                               .debugName = "layers"}));
    const TextureHandle layer2 = o.add(d.createTextureView(
        array, {.dimension = TextureDimension::Texture2D, .baseLayer = 2, .layerCount = 1}));
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
         .fragmentShader =
             registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
         .topology = PrimitiveTopology::TriangleStrip,
         .colorFormats = {Format::RGBA8},
         .debugName = "layer writer"}));
    const TextureHandle image =
        o.add(d.createTexture({.format = Format::RGBA32F,
                               .width = 128,
                               .height = 128,
                               .mipLevels = 2,
                               .usage = TextureUsage::Storage | TextureUsage::CopySrc,
                               .debugName = "mips"}));
    const TextureHandle level1 =
        o.add(d.createTextureView(image, {.baseMip = 1, .mipCount = 1, .debugName = "mip 1"}));
    const PipelineHandle fill = o.add(d.createComputePipeline(
        {.computeShader = registryShader(o, ShaderStage::Compute, "conformance/fill.comp"),
         .debugName = "fill"}));
    const BufferHandle values =
        o.add(d.createBuffer({.size = 64 * 64 * 4, .usage = BufferUsage::Storage}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = layer2, .clear = {0.25f, 0.5f, 0.75f, 1}}}});
    cmd->setPipeline(p);
    cmd->setConstants(pixelQuad(16, 16, 48, 48, solidTexel(1)));
    cmd->draw(4);
    cmd->endRenderPass();
    cmd->setPipeline(fill);
    cmd->setStorageBuffer(0, values);
    cmd->setStorageTexture(1, level1);
    cmd->dispatch(8, 8);
    d.wait(d.submit(*cmd));
    const Texel clear = {0.25f, 0.5f, 0.75f, 1};
    std::vector<CaseImage> images = {
        drawn8("layer 2 drawn through its view", d.readTexture(array, {0, 2}),
               expectImage(Format::RGBA8,
                           [&](uint32_t x, uint32_t y) {
                               return x >= 16 && x < 48 && y >= 16 && y < 48 ? solidTexel(1)
                                                                             : clear;
                           })),
        exact("layer 1 untouched", d.readTexture(array, {0, 1}),
              solid(Format::RGBA8, {0, 0, 0, 0})),
        within("mip 1 stored through a view", d.readTexture(image, {1, 0}),
               expectImage(Format::RGBA32F,
                           [](uint32_t x, uint32_t y) -> Texel {
                               return {float(x) / 64.0f, float(y) / 64.0f, 0.5f, 1};
                           }),
               0.0, "exact float stores")};
    return images;
}

// Capture groundwork: a list recorded through RecordingCommandList (constants, a
// debug group and label, a pass of two secondary lists, a region copy, an occlusion query) is
// turned into capture bytes and back, then applied to a fresh list: the same picture, the same
// copy and the same query count as the live submission.
std::vector<CaseImage> recordedListReplays(Device& d) {
    DeviceObjects o(d);
    const PipelineHandle quad = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
         .fragmentShader =
             registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
         .topology = PrimitiveTopology::TriangleStrip,
         .colorFormats = {Format::RGBA8},
         .debugName = "recorded quads"}));
    const TextureHandle target =
        o.add(d.createTexture({.width = 64,
                               .height = 64,
                               .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                               .debugName = "target"}));
    const BufferHandle copy = o.add(d.createBuffer(
        {.size = 16 * 16 * 4, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
    const QuerySetHandle occlusion =
        o.add(d.createQuerySet({.type = QueryType::Occlusion, .count = 1}));
    auto frame = [&](CommandList& list, auto&& secondary) {
        list.pushDebugGroup("recorded frame");
        list.beginRenderPass({.colors = {{.texture = target, .clear = {0.1f, 0.2f, 0.3f, 1}}},
                              .debugName = "quads"});
        list.setPipeline(quad);
        list.beginQuery(occlusion, 0);
        for (uint32_t i = 0; i < 8; ++i) {
            list.setConstants(pixelQuad(8 * i, 8 * i, 8 * i + 8, 64, solidTexel(i % 6)));
            list.draw(4);
        }
        list.endQuery(occlusion, 0);
        list.insertDebugLabel("quads drawn");
        list.endRenderPass();
        const RenderPassDesc pass{.colors = {{.texture = target, .load = LoadOp::Load}},
                                  .secondaryLists = true};
        list.beginRenderPass(pass);
        std::array<std::unique_ptr<CommandList>, 2> parts = {secondary(), secondary()};
        for (uint32_t k = 0; k < 2; ++k) {
            parts[k]->beginSecondary(pass);
            parts[k]->setPipeline(quad);
            parts[k]->setConstants(pixelQuad(40 + 8 * k, 0, 48 + 8 * k, 16, solidTexel(5 - k)));
            parts[k]->draw(4);
            parts[k]->endSecondary();
        }
        list.executeSecondary(std::array<CommandList*, 2>{parts[0].get(), parts[1].get()});
        list.endRenderPass();
        list.copyTextureToBuffer(copy, {}, target,
                                 {.x = 40, .width = 16, .height = 16, .depth = 1});
        list.popDebugGroup();
    };
    RecordingCommandList recorder(d, d.createCommandList());
    frame(recorder,
          [&] { return std::make_unique<RecordingCommandList>(d, d.createCommandList()); });
    d.wait(d.submit(recorder.inner()));
    const Image live = d.readTexture(target);
    const std::vector<uint8_t> liveCopy = d.readBuffer(copy, 0, 16 * 16 * 4);
    std::array<uint64_t, 1> liveSamples{};
    FE_CONFORMANCE_CHECK(d.queryResults(occlusion, 0, 1, liveSamples),
                         "the live query has its result");

    const std::vector<std::byte> bytes = encodeCommandStream(*recorder.takeStream());
    const auto decoded = decodeCommandStream(bytes);
    {  // clear what the live frame left, so the replay has to draw everything again
        auto wipe = d.createCommandList();
        wipe->beginRenderPass({.colors = {{.texture = target}}});
        wipe->endRenderPass();
        wipe->clearBuffer(copy);
        d.wait(d.submit(*wipe));
    }
    auto replay = d.createCommandList();
    applyStream(*decoded, d, *replay);
    d.wait(d.submit(*replay));
    std::array<uint64_t, 1> replayedSamples{};
    FE_CONFORMANCE_CHECK(
        d.queryResults(occlusion, 0, 1, replayedSamples) && replayedSamples == liveSamples,
        "the replayed occlusion query counts what the live one did");
    FE_CONFORMANCE_CHECK(d.readBuffer(copy, 0, 16 * 16 * 4) == liveCopy,
                         "the replayed region copy holds the live copy's bytes");
    return {
        exact("replayed from capture bytes, against the live frame", d.readTexture(target), live)};
}

// Where one aspect of a depth/stencil texel lies in readTexture's layout (Device.h), and how many
// of its bytes are defined after a copy to a buffer (D24S8's depth word has 8 undefined bits).
struct AspectInTexel {
    uint32_t at, defined;
};
AspectInTexel aspectInTexel(Format f, TextureAspect a) {
    if (a == TextureAspect::Stencil)
        return {f == Format::D24S8 ? 3u : f == Format::D32F_S8 ? 4u : 0u, 1};
    return {0, f == Format::D16 ? 2u : f == Format::D24S8 ? 3u : 4u};
}
TextureAspect soleAspect(Format f) {
    return formatInfo(f).hasDepth ? TextureAspect::Depth : TextureAspect::Stencil;
}

// One aspect at a time through a buffer, both ways, for every depth/stencil format: a box of
// layer 1 of `source` into a pitched buffer (the bytes between rows keep their contents), the
// same bytes into another box of `target`, whose other aspect must keep its values; for two-
// aspect formats the stencil box overlaps the depth box and writeTextureRegion writes a third.
// Formats of one aspect also round-trip through the whole-subresource calls.
std::vector<CaseImage> depthStencilBufferCopies(Device& d) {
    std::vector<CaseImage> out;
    for (Format f : {Format::D16, Format::D32F, Format::D24S8, Format::D32F_S8, Format::S8}) {
        if (!d.formatCaps(f).sampled) continue;
        const std::string name(formatInfo(f).name);
        const uint32_t texel = formatInfo(f).bytesPerPixel;
        DeviceObjects o(d);
        auto make = [&](const char* debugName) {
            return o.add(d.createTexture({.dimension = TextureDimension::Texture2DArray,
                                          .format = f,
                                          .width = kCaseSize,
                                          .height = kCaseSize,
                                          .depthOrLayers = 2,
                                          .usage = TextureUsage::CopySrc | TextureUsage::CopyDst,
                                          .debugName = debugName}));
        };
        const TextureHandle source = make("source"), target = make("target");
        const Image a = expectImage(f, [](uint32_t x, uint32_t y) -> Texel {
            return {float(x) / 63.0f, float((x * 7 + y * 13) & 0xff), 0, 0};
        });
        Image expected = expectImage(f, [](uint32_t x, uint32_t y) -> Texel {
            return {float(y) / 63.0f, float(((x + 2 * y) & 0xff) ^ 0x55), 0, 0};
        });
        d.writeTexture(source, {0, 1}, bytesOf(a.data));
        d.writeTexture(target, {0, 1}, bytesOf(expected.data));
        const Image layer0 = expected;  // copies into layer 1 leave layer 0 as it is
        d.writeTexture(target, {0, 0}, bytesOf(layer0.data));
        const BufferHandle staging = o.add(
            d.createBuffer({.size = 4096, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));

        std::vector<TextureAspect> aspects;
        if (formatInfo(f).hasDepth) aspects.push_back(TextureAspect::Depth);
        if (formatInfo(f).hasStencil) aspects.push_back(TextureAspect::Stencil);
        uint32_t shift = 0;  // the stencil box lies 4 texels right of the depth box
        for (TextureAspect aspect : aspects) {
            const uint32_t bytes = aspectTexelBytes(f, aspect);
            const AspectInTexel in = aspectInTexel(f, aspect);
            const TextureRegion box{
                .x = 16, .y = 8, .z = 1, .width = 8, .height = 4, .depth = 1, .aspect = aspect};
            const TexelLayout pitch{.offset = 64, .bytesPerRow = 8 * bytes + 2 * bytes};
            TextureRegion into = box;
            into.x = 40 + shift, into.y = 50 + shift / 2;
            auto cmd = d.createCommandList();
            cmd->clearBuffer(staging, 0, 0, 0xABABABABu);
            cmd->copyTextureToBuffer(staging, pitch, source, box);
            cmd->copyBufferToTexture(target, into, staging, pitch);
            d.wait(d.submit(*cmd));
            const std::vector<uint8_t> got = d.readBuffer(staging, 0, 4096);
            for (uint32_t i = 0; i < 4096; ++i) {
                const uint32_t rel = i - 64, row = rel / pitch.bytesPerRow,
                               column = rel % pitch.bytesPerRow / bytes, byte = rel % bytes;
                const bool inBox = i >= 64 && row < 4 && column < 8;
                if (inBox && byte >= in.defined) continue;  // D24S8 depth's high byte
                const uint8_t want =
                    inBox ? a.data[((8 + row) * kCaseSize + 16 + column) * texel + in.at + byte]
                          : 0xAB;
                FE_CONFORMANCE_CHECK(
                    got[i] == want,
                    (name + " copyTextureToBuffer byte " + std::to_string(i) + " is " +
                     std::to_string(got[i]) + ", expected " + std::to_string(want))
                        .c_str());
            }
            for (uint32_t y = 0; y < 4; ++y)
                for (uint32_t x = 0; x < 8; ++x)
                    std::memcpy(
                        &expected.data[((into.y + y) * kCaseSize + into.x + x) * texel + in.at],
                        &a.data[((8 + y) * kCaseSize + 16 + x) * texel + in.at], in.defined);
            shift += 4;
        }
        if (hasTwoAspects(f)) {  // the device's own upload of one aspect: stencil 0xC3 in a 4x4 box
            const std::vector<uint8_t> stencil(16, 0xC3);
            d.writeTextureRegion(target,
                                 {.x = 2,
                                  .y = 2,
                                  .z = 1,
                                  .width = 4,
                                  .height = 4,
                                  .depth = 1,
                                  .aspect = TextureAspect::Stencil},
                                 bytesOf(stencil));
            const uint32_t at = aspectInTexel(f, TextureAspect::Stencil).at;
            for (uint32_t y = 2; y < 6; ++y)
                for (uint32_t x = 2; x < 6; ++x)
                    expected.data[(y * kCaseSize + x) * texel + at] = 0xC3;
        }
        out.push_back(
            exact(name + " boxes copied per aspect", d.readTexture(target, {0, 1}), expected));
        out.push_back(exact(name + " layer 0 untouched", d.readTexture(target, {0, 0}), layer0));

        auto list = d.createCommandList();
        if (hasTwoAspects(f)) {
            expectError(
                [&] {
                    list->copyTextureToBuffer(staging, 0, source, {0, 1});
                },
                name +
                    " has depth and stencil: copy each with a TextureRegion naming its "
                    "aspect");
            expectError(
                [&] {
                    list->copyTextureToBuffer(staging, {}, source,
                                              {.width = 4, .height = 4, .depth = 1});
                },
                name + " has depth and stencil: a region names one");
        } else {  // the whole subresource, both ways, in the aspect's layout
            const TextureHandle whole = make("whole");
            const BufferHandle big = o.add(d.createBuffer(
                {.size = 64 * 64 * 4, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
            auto cmd = d.createCommandList();
            cmd->copyTextureToBuffer(big, 0, source, {0, 1});
            cmd->copyBufferToTexture(whole, {0, 0}, big, 0);
            d.wait(d.submit(*cmd));
            out.push_back(exact(name + " whole subresource through a buffer",
                                d.readTexture(whole, {0, 0}), a));
            const TextureAspect other = soleAspect(f) == TextureAspect::Depth
                                            ? TextureAspect::Stencil
                                            : TextureAspect::Depth;
            expectError(
                [&] {
                    list->copyTextureToBuffer(
                        staging, {}, source,
                        {.width = 4, .height = 4, .depth = 1, .aspect = other});
                },
                name + " has no " + (other == TextureAspect::Depth ? "depth" : "stencil") +
                    " aspect");
        }
        expectError([&] { list->copyTexture(target, {}, source, {.width = 4, .height = 4}); },
                    "regions of depth/stencil textures are copied through a buffer");
        d.wait(d.submit(*list));
    }
    return out;
}

// BGRA8 and BGRA8_SRGB: texels written in blue, green, red, alpha byte order are sampled as RGBA
// (into an RGBA8 or RGBA8_SRGB target), drawn into (the read-back bytes are BGRA), copied to a
// buffer in that order and between the two BGRA formats bit for bit. Copies or views between
// BGRA and RGBA, and BGRA storage textures, are the same Error everywhere (GL stores BGRA8 as RGBA).
// Views across the channel orders (RGBA8 <-> BGRA8, each with its sRGB twin): the texels' red
// and blue read swapped, as Vulkan reads the other byte order (GL swaps them by the view's
// swizzle), a swizzle composes with that, and such a view is sampled only, the same Error
// everywhere when rendered into. `bytes`: BGRA bytes of blue x*4, green y*4, red 200.
void crossOrderViews(Device& d, DeviceObjects& o, FullscreenSampler& sampler, Format bgraFormat,
                     const std::vector<uint8_t>& bytes, std::vector<CaseImage>& out) {
    const Format rgbaFormat = bgraFormat == Format::BGRA8_SRGB ? Format::RGBA8_SRGB : Format::RGBA8;
    const TextureUsage all = TextureUsage::Sampled | TextureUsage::RenderTarget |
                             TextureUsage::CopySrc | TextureUsage::CopyDst;
    // The same bytes in a BGRA texture and an RGBA one: a cross-order view of each reads them in
    // the other order (from the BGRA texture red = x*4, blue = 200; from the RGBA one the reverse).
    for (const bool bgraTexture : {true, false}) {
        const Format texFormat = bgraTexture ? bgraFormat : rgbaFormat,
                     viewFormat = bgraTexture ? rgbaFormat : bgraFormat;
        const TextureHandle tex = o.add(d.createTexture({.format = texFormat,
                                                         .width = kCaseSize,
                                                         .height = kCaseSize,
                                                         .usage = all,
                                                         .viewFormats = {viewFormat},
                                                         .debugName = "cross-order"}));
        d.writeTexture(tex, {}, bytesOf(bytes));
        const std::string what = std::string(formatInfo(texFormat).name) + " seen as " +
                                 std::string(formatInfo(viewFormat).name);
        const TextureHandle view = o.add(d.createTextureView(tex, {.format = viewFormat}));
        auto expected = [&](bool swapped) {
            return expectImage(rgbaFormat, [=](uint32_t x, uint32_t y) -> Texel {
                const float ramp = float(x * 4) / 255.0f, flat = 200 / 255.0f;
                const bool rampRed = bgraTexture != swapped;
                return {rampRed ? ramp : flat, float(y * 4) / 255.0f, rampRed ? flat : ramp, 1};
            });
        };
        out.push_back(drawn8(what, sampler.draw(d, view, rgbaFormat), expected(false)));
        using S = Swizzle;
        const TextureHandle swizzled = o.add(d.createTextureView(
            tex, {.format = viewFormat, .swizzle = {S::B, S::G, S::R, S::One}}));
        out.push_back(drawn8(what + ", swizzled back", sampler.draw(d, swizzled, rgbaFormat),
                             expected(true)));
        FE_CONFORMANCE_CHECK(d.desc(view).usage == TextureUsage::Sampled,
                             "a cross-order view is sampled only");
        auto cmd = d.createCommandList();
        expectError([&] { cmd->beginRenderPass({.colors = {{.texture = view}}}); },
                    "lacks RenderTarget usage");
        d.wait(d.submit(*cmd));
    }
    expectError(
        [&] {
            const TextureHandle noSampling =
                o.add(d.createTexture({.format = bgraFormat,
                                       .width = 8,
                                       .height = 8,
                                       .usage = TextureUsage::RenderTarget,
                                       .viewFormats = {rgbaFormat}}));
            d.createTextureView(noSampling, {.format = rgbaFormat});
        },
        "a view between RGBA and BGRA channel orders is sampled only, and the texture has no "
        "Sampled usage");
}

std::vector<CaseImage> bgra8Formats(Device& d) {
    std::vector<CaseImage> out;
    FullscreenSampler sampler(d, "conformance/textured.frag");
    DeviceObjects o(d);
    const TextureUsage all = TextureUsage::Sampled | TextureUsage::RenderTarget |
                             TextureUsage::CopySrc | TextureUsage::CopyDst;
    for (Format f : {Format::BGRA8, Format::BGRA8_SRGB}) {
        const std::string name(formatInfo(f).name);
        if (!d.formatCaps(f).sampled || !d.formatCaps(f).renderTarget) {
            FE_CONFORMANCE_CHECK(false,
                                 (name + " is sampled and rendered on every backend").c_str());
            continue;
        }
        const bool srgb = f == Format::BGRA8_SRGB;
        const TextureHandle bgra = o.add(d.createTexture({.format = f,
                                                          .width = kCaseSize,
                                                          .height = kCaseSize,
                                                          .usage = all,
                                                          .viewFormats = {srgbPair(f)},
                                                          .debugName = "bgra"}));
        std::vector<uint8_t> bytes(kCaseSize * kCaseSize * 4);
        for (uint32_t i = 0; i < kCaseSize * kCaseSize; ++i) {
            const uint32_t x = i % kCaseSize, y = i / kCaseSize;
            bytes[4 * i + 0] = uint8_t(x * 4);  // blue
            bytes[4 * i + 1] = uint8_t(y * 4);  // green
            bytes[4 * i + 2] = 200;             // red
            bytes[4 * i + 3] = 255;
        }
        d.writeTexture(bgra, {}, bytesOf(bytes));
        // Sampled: RGBA in the shader (an sRGB source into an sRGB target: decoded, encoded back).
        const Format rgbaTarget = srgb ? Format::RGBA8_SRGB : Format::RGBA8;
        out.push_back(
            drawn8(name + " sampled as RGBA", sampler.draw(d, bgra, rgbaTarget),
                   expectImage(rgbaTarget, [](uint32_t x, uint32_t y) -> Texel {
                       return {200 / 255.0f, float(y * 4) / 255.0f, float(x * 4) / 255.0f, 1};
                   })));
        // Drawn into: the same RGBA values land as BGRA bytes.
        const TextureHandle rgba = o.add(d.createTexture(
            {.format = rgbaTarget, .width = kCaseSize, .height = kCaseSize, .usage = all}));
        std::vector<uint8_t> swapped = bytes;
        for (size_t i = 0; i < swapped.size(); i += 4) std::swap(swapped[i], swapped[i + 2]);
        d.writeTexture(rgba, {}, bytesOf(swapped));
        Image drawn = sampler.draw(d, rgba, f);
        out.push_back(
            drawn8(name + " drawn into", drawn, expectImage(f, [](uint32_t x, uint32_t y) -> Texel {
                       return {200 / 255.0f, float(y * 4) / 255.0f, float(x * 4) / 255.0f, 1};
                   })));
        FE_CONFORMANCE_CHECK(std::abs(int(drawn.data[4 * 70 + 0]) - 6 * 4) <= 1 &&
                                 std::abs(int(drawn.data[4 * 70 + 2]) - 200) <= 1,
                             "read back in blue, green, red, alpha byte order");
        // To a buffer and to the other BGRA format: the bytes as written.
        const BufferHandle buffer = o.add(d.createBuffer(
            {.size = bytes.size(), .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
        const TextureHandle twin = o.add(d.createTexture(
            {.format = srgbPair(f), .width = kCaseSize, .height = kCaseSize, .usage = all}));
        auto cmd = d.createCommandList();
        cmd->copyTextureToBuffer(buffer, 0, bgra, {});
        cmd->copyTexture(twin, {}, bgra, {});
        d.wait(d.submit(*cmd));
        FE_CONFORMANCE_CHECK(d.readBuffer(buffer, 0, bytes.size()) == bytes,
                             "copyTextureToBuffer gives the BGRA bytes");
        FE_CONFORMANCE_CHECK(d.readTexture(twin).data == bytes,
                             "copyTexture into the sRGB/UNORM twin moves the bytes");
        out.push_back(
            drawn8(name + " through its twin view",
                   sampler.draw(d, o.add(d.createTextureView(bgra, {.format = srgbPair(f)})),
                                srgbPair(rgbaTarget)),
                   expectImage(srgbPair(rgbaTarget), [](uint32_t x, uint32_t y) -> Texel {
                       return {200 / 255.0f, float(y * 4) / 255.0f, float(x * 4) / 255.0f, 1};
                   })));
        auto list = d.createCommandList();
        expectError(
            [&] { list->copyTexture(rgba, {}, bgra, {}); },
            name + " texels cannot be copied into " + std::string(formatInfo(rgbaTarget).name));
        d.wait(d.submit(*list));
        crossOrderViews(d, o, sampler, f, bytes, out);
        expectError(
            [&] {
                d.createTexture({.format = f,
                                 .width = 8,
                                 .height = 8,
                                 .usage = TextureUsage::Sampled,
                                 .viewFormats = {Format::R32F}});
            },
            "view format R32F is not compatible with " + name);
        expectError(
            [&] {
                d.createTexture(
                    {.format = f, .width = 8, .height = 8, .usage = TextureUsage::Storage});
            },
            name + " cannot be a storage texture");
    }
    return out;
}
}  // namespace

std::vector<Case> regionAndViewCases() {
    return {
        {"region_upload_row_pitch", regionUploadRowPitch},
        {"region_copies", regionCopies},
        {"depth_stencil_buffer_copies", depthStencilBufferCopies},
        {"bgra8_formats", bgra8Formats},
        {"texture_copy_between_mips", textureCopyBetweenMips},
        {"view_mip_range", viewMipRange},
        {"view_layer_and_face", viewLayerAndFace},
        {"view_format_srgb_unorm", viewFormatSrgbUnorm},
        {"view_swizzle", viewSwizzle},
        {"view_as_attachment", viewAsAttachment},
        {"recorded_list_replays", recordedListReplays},
    };
}

}  // namespace fe::conformance
