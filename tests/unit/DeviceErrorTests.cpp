// Invalid descriptions give clear errors, never crashes, on every backend.
#include <array>
#include <atomic>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <thread>
#include <gtest/gtest.h>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/ShaderReflection.h"
#include "fe/gdi/ShaderRegistry.h"
#include "fe/gdi/Validation.h"

using namespace fe::gdi;
using fe::testing::errorOf;

class DeviceErrors : public fe::testing::BackendTest {};


TEST_P(DeviceErrors, ZeroSizes) {
    EXPECT_NE(errorOf([&] { device->createBuffer({.size = 0}); }).find("size is 0"), std::string::npos);
    EXPECT_NE(errorOf([&] { device->createTexture({.width = 0, .height = 4}); }).find("zero dimension"), std::string::npos);
    EXPECT_NE(errorOf([&] { device->createTexture({.width = 1u << 20, .height = 4}); }).find("exceeds the device limit"),
              std::string::npos);
}

TEST_P(DeviceErrors, UnsupportedUsage) {
    EXPECT_NE(errorOf([&] {
                  device->createTexture({.format = Format::D24S8, .width = 4, .height = 4, .usage = TextureUsage::Storage});
              }).find("cannot be a storage texture"),
              std::string::npos);
}

// Texture kinds: each rule of TextureDesc gives its own message.
TEST_P(DeviceErrors, TextureKinds) {
    using D = TextureDimension;
    auto err = [&](const TextureDesc& d) { return errorOf([&] { device->destroy(device->createTexture(d)); }); };
    const TextureUsage rt = TextureUsage::RenderTarget;
    EXPECT_NE(err({.dimension = D::Texture2D, .width = 4, .height = 4, .depthOrLayers = 2}).find("a Texture2D has depthOrLayers 1"), std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCube, .width = 4, .height = 8, .depthOrLayers = 6}).find("faces must be square"), std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCube, .width = 4, .height = 4, .depthOrLayers = 12}).find("a TextureCube has 6 layers"), std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCubeArray, .width = 4, .height = 4, .depthOrLayers = 8}).find("6 layers per cube"), std::string::npos);
    EXPECT_NE(err({.dimension = D::Texture3D, .format = Format::D32F, .width = 4, .height = 4, .depthOrLayers = 4}).find("cannot have a depth format"), std::string::npos);
    EXPECT_NE(err({.dimension = D::Texture3D, .width = 4, .height = 4, .depthOrLayers = 16, .mipLevels = 6}).find("mipLevels 6 not in [1, 5]"), std::string::npos);
    EXPECT_NE(err({.dimension = D::Texture2DArray, .width = 4, .height = 4, .depthOrLayers = 1u << 20}).find("exceed the device limit"), std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .sampleCount = 3, .usage = rt}).find("sampleCount 3 is not 1, 2, 4 or 8"), std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .mipLevels = 2, .sampleCount = 4, .usage = rt}).find("one mip level"), std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .sampleCount = 4, .usage = rt | TextureUsage::Sampled}).find("resolved (not sampled)"), std::string::npos);
    EXPECT_NE(err({.format = Format::BC7, .width = 4, .height = 4, .usage = rt}).find("can only be sampled and copied"), std::string::npos);
    // Every supported kind creates, with the layer count its kind implies.
    for (TextureDesc d : {TextureDesc{.dimension = D::Texture2DArray, .width = 4, .height = 4, .depthOrLayers = 3},
                          TextureDesc{.dimension = D::TextureCube, .width = 4, .height = 4, .depthOrLayers = 6},
                          TextureDesc{.dimension = D::Texture3D, .width = 4, .height = 4, .depthOrLayers = 4, .mipLevels = 3}})
        EXPECT_EQ(err(d), "(no error)");
}

// Subresources that do not exist, resolves that do not fit, and readback of what cannot be read.
TEST_P(DeviceErrors, SubresourcesAndResolves) {
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::CopySrc;
    auto arr = device->createTexture({.dimension = TextureDimension::Texture2DArray, .width = 8, .height = 8,
                                      .depthOrLayers = 2, .mipLevels = 2, .usage = rt, .debugName = "arr"});
    auto vol = device->createTexture({.dimension = TextureDimension::Texture3D, .width = 8, .height = 8, .depthOrLayers = 4,
                                      .mipLevels = 2, .usage = TextureUsage::Sampled | TextureUsage::CopySrc | TextureUsage::CopyDst});
    EXPECT_NE(errorOf([&] { device->readTexture(arr, {.layer = 2}); }).find("layer 2 out of range (2 at mip 0)"), std::string::npos);
    EXPECT_NE(errorOf([&] { device->readTexture(arr, {.mipLevel = 2}); }).find("mip level 2 out of range"), std::string::npos);
    EXPECT_NE(errorOf([&] { device->readTexture(vol, {.mipLevel = 1, .layer = 2}); }).find("slice 2 out of range (2 at mip 1)"),
              std::string::npos);
    EXPECT_EQ(device->readTexture(vol, {.mipLevel = 1, .layer = 1}).width, 4u);
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = arr, .layer = 5}}}); }).find("layer 5 out of range"),
              std::string::npos);
    const uint32_t counts = device->info().limits.colorSampleCounts;
    if (counts & 4) {
        auto ms = device->createTexture({.width = 8, .height = 8, .sampleCount = 4, .usage = rt});
        auto small = device->createTexture({.width = 4, .height = 4, .usage = rt});
        auto other = device->createTexture({.format = Format::RGBA16F, .width = 8, .height = 8, .usage = rt});
        auto single = device->createTexture({.width = 8, .height = 8, .usage = rt});
        EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = ms, .resolveTexture = small}}}); }).find("resolve target size differs"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = ms, .resolveTexture = other}}}); }).find("resolve target format RGBA16F differs"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = single, .resolveTexture = single}}}); }).find("nothing to resolve"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = ms}, {.texture = single}}}); }).find("mismatched sample counts"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] { device->readTexture(ms); }).find("is multisampled"), std::string::npos);
        for (auto t : {ms, small, other, single}) device->destroy(t);
    }
    device->destroy(arr);
    device->destroy(vol);
}

// Indirect arguments are checked before the API sees them.
TEST_P(DeviceErrors, IndirectArguments) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    const DrawIndirectArgs rec{3, 1, 0, 0};
    auto args = device->createBuffer({.size = sizeof rec, .usage = BufferUsage::Indirect, .debugName = "args"}, bytesOf(rec));
    auto plain = device->createBuffer({.size = 64, .usage = BufferUsage::Storage, .debugName = "plain"});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 0); }).find("outside a render pass"), std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(plain, 0); }).find("buffer 'plain': lacks Indirect usage"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 2); }).find("not a multiple of 4"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 4); }).find("exceed its size 16"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndexedIndirect(args, 0); }).find("without an index buffer"), std::string::npos);
    if (!device->info().features.drawIndirectCount) {
        EXPECT_NE(errorOf([&] { cmd->drawIndirectCount(args, 0, args, 0, 1); }).find("not supported"), std::string::npos);
    }
    cmd->drawIndirect(args, 0);  // a valid one still records
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    for (auto b : {args, plain}) device->destroy(b);
    device->destroy(t);
    device->destroy(p);
    device->destroy(vs);
    device->destroy(fs);
}

TEST_P(DeviceErrors, MismatchedAttachments) {
    auto a = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto b = device->createTexture({.width = 16, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = a}, {.texture = b}}}); }).find("mismatched attachments"),
              std::string::npos);
}

TEST_P(DeviceErrors, MissingBinding) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
                                             .debugName = "needs slot 0"});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("missing binding for slot(s) 0"), std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Buffer binding arguments: every invalid one is an error naming the problem (the Vulkan
// setters have a separate fast path, so each way to leave it is exercised), and a valid bind
// after the errors still draws.
TEST_P(DeviceErrors, BufferBindingArguments) {
    const std::array<float, 64> params = {0.25f, 0.5f, 0.75f, 1.0f};  // the whole 256-byte buffer
    auto ubo = device->createBuffer({.size = 256, .usage = BufferUsage::Uniform | BufferUsage::Storage, .debugName = "params"},
                                    bytesOf(params));
    auto gone = device->createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    device->destroy(gone);
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, ubo, 256); }).find("empty range"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, ubo, 200, 100); }).find("exceeds its size 256"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(0, ubo, 300, 16); }).find("exceeds its size 256"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, ubo, ~uint64_t(0) - 8, 16); }).find("exceeds its size 256"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(64, ubo); }).find("slot 64 out of range"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(70, ubo); }).find("slot 70 out of range"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, gone); }).find("invalid or destroyed"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(0, BufferHandle{}); }).find("invalid or destroyed"), std::string::npos);

    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, ubo, 0, 32); }), "(no error)");
    cmd->draw(3);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    const Image img = device->readTexture(t);
    const auto texel = img.texel(4, 4);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(texel[c], params[c], 1.0 / 255) << "channel " << c;
}

// The per-object bind path remembers the buffer it bound last (Vulkan skips the handle lookup
// for it): a buffer bound, destroyed and bound again is still "invalid or destroyed", and a
// buffer bound only with Storage usage is refused as a uniform buffer after it was bound as
// storage, on every backend.
TEST_P(DeviceErrors, RebindingABufferChecksItAgain) {
    auto ubo = device->createBuffer({.size = 512, .usage = BufferUsage::Uniform});
    auto ssbo = device->createBuffer({.size = 512, .usage = BufferUsage::Storage});
    auto other = device->createBuffer({.size = 16, .usage = BufferUsage::Uniform});
    auto cmd = device->createCommandList();
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, ubo, 0, 64); }), "(no error)");
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(1, ubo, 256, 64); }), "(no error)");
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(1, ubo, 480, 64); }).find("exceeds its size 512"), std::string::npos);
    device->destroy(other);  // another object's destroy: the same buffer still binds
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(1, ubo, 256, 64); }), "(no error)");
    device->destroy(ubo);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(1, ubo, 256, 64); }).find("invalid or destroyed"), std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setStorageBuffer(2, ssbo); }), "(no error)");
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(2, ssbo); }).find("Uniform"), std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setStorageBuffer(3, ssbo, 256); }), "(no error)");
    device->destroy(ssbo);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(3, ssbo, 256); }).find("invalid or destroyed"), std::string::npos);
}

// Binding needs no recording: a buffer bound before a list's first command, destroyed, then
// drawn with. The draw records (recording may go on after a destroy), the submit is refused
// with the same message on every backend, and no native command names a freed object (on
// Vulkan the buffer's release waits for the list; without that the validation layer reports
// the destroyed VkBuffer and TearDown fails). Once the list is gone, so is the buffer.
TEST_P(DeviceErrors, StateBoundBeforeRecordingOutlivesItsDestroy) {
    const std::array<float, 64> params = {0.25f, 0.5f, 0.75f, 1.0f};
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    const LiveObjects before = device->liveObjects();
    {
        auto ubo = device->createBuffer({.size = 256, .usage = BufferUsage::Uniform}, bytesOf(params));
        auto cmd = device->createCommandList();
        cmd->setUniformBuffer(0, ubo);  // state only: nothing recorded yet
        device->destroy(ubo);
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
        cmd->endRenderPass();
        EXPECT_NE(errorOf([&] { device->submit(*cmd); }).find("destroyed after it was recorded"), std::string::npos);
    }
    device->waitIdle();
    EXPECT_TRUE(device->liveObjects() == before);
}

// A draw that samples what its own pass renders into (a feedback loop, undefined on both
// APIs) and a pass naming one subresource twice are Errors, the same on every backend; other
// mips and layers of the same texture, and a depth attachment that the pipeline only tests,
// may be read.
TEST_P(DeviceErrors, FeedbackLoopsAreRefused) {
    Device& d = *device;
    auto vs = d.createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto sampleFs = d.createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/textured.frag")});
    auto colorFs = d.createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto shadowFs = d.createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/shadow_2d.frag")});
    auto sampling = d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = sampleFs,
                                              .colorFormats = {Format::RGBA8}, .debugName = "sampling"});
    auto plain = d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = colorFs, .colorFormats = {Format::RGBA8}});
    auto depthReader = [&](bool depthWrite, const char* name) {
        return d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = shadowFs,
                                         .depthStencil = {.depthTest = true, .depthWrite = depthWrite},
                                         .colorFormats = {Format::RGBA8}, .depthFormat = Format::D32F, .debugName = name});
    };
    auto testsDepth = depthReader(false, "tests depth"), writesDepth = depthReader(true, "writes depth");
    auto rt = d.createTexture({.width = 64, .height = 64, .mipLevels = 2,
                               .usage = TextureUsage::RenderTarget | TextureUsage::Sampled, .debugName = "rt"});
    auto other = d.createTexture({.width = 64, .height = 64, .usage = TextureUsage::RenderTarget});
    auto mip1 = d.createTextureView(rt, {.baseMip = 1, .mipCount = 1});
    auto depth = d.createTexture({.format = Format::D32F, .width = 64, .height = 64,
                                  .usage = TextureUsage::RenderTarget | TextureUsage::Sampled, .debugName = "depth"});
    auto sampler = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    auto mipmapped = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest, .mipFilter = MipFilter::Nearest});
    auto compare = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest, .compareEnable = true});
    const std::array<float, 8> params{0.5f};
    auto ubo = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    d.writeBuffer(ubo, 0, bytesOf(params));

    auto cmd = d.createCommandList();
    // Bound before the pass: it persists into it, and the draw that reads it is refused.
    cmd->setTexture(1, rt, sampler);
    cmd->beginRenderPass({.colors = {{.texture = rt}}, .debugName = "loop"});
    cmd->setPipeline(plain);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)") << "a pipeline that does not read slot 1";
    cmd->setPipeline(sampling);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }),
              "draw with pipeline 'sampling': slot 1 samples texture 'rt' (mip 0, layer 0), which colour attachment 0 "
              "of render pass 'loop' writes: a feedback loop, undefined on every API. Read another mip or layer, or a copy");
    cmd->setTexture(1, mip1, sampler);  // mip 1 while mip 0 is rendered: allowed
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(1, rt, sampler);  // bound inside the pass
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 0, layer 0)"), std::string::npos);
    cmd->endRenderPass();
    // The next pass renders elsewhere: the same binding is fine again.
    cmd->beginRenderPass({.colors = {{.texture = other}}});
    cmd->setPipeline(sampling);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    // Rendering into mip 1 of rt while sampling the view of mip 1: refused; sampling mip 0 is fine.
    auto mip0 = d.createTextureView(rt, {.baseMip = 0, .mipCount = 1});
    cmd->setTexture(1, mip1, sampler);
    cmd->beginRenderPass({.colors = {{.texture = rt, .mipLevel = 1}}});
    cmd->setPipeline(sampling);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 1, layer 0)"), std::string::npos);
    cmd->setTexture(1, mip0, sampler);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    // The whole texture: a sampler without a mip filter reads its base mip only (GL's rule too);
    // one with a mip filter may read mip 1.
    cmd->setTexture(1, rt, sampler);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(1, rt, mipmapped);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 1, layer 0)"), std::string::npos);
    cmd->endRenderPass();

    // The depth attachment: a pipeline that only tests depth may sample it, one that writes may not,
    // also when it replaces the reading pipeline without a new binding.
    cmd->setUniformBuffer(0, ubo);
    cmd->setTexture(1, depth, compare);
    cmd->beginRenderPass({.colors = {{.texture = other}}, .depth = {.texture = depth, .load = LoadOp::Load}});
    cmd->setTexture(0, depth, compare);  // a loop for a moment: the uniform buffer replaces it
    cmd->setUniformBuffer(0, ubo);
    cmd->setPipeline(testsDepth);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setPipeline(writesDepth);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }),
              "draw with pipeline 'writes depth': slot 1 samples texture 'depth' (mip 0, layer 0), which the depth "
              "attachment of render pass writes: a feedback loop, undefined on every API. Read another mip or layer, or "
              "a copy (a pipeline that writes neither depth nor stencil may sample the depth attachment)");
    cmd->setPipeline(testsDepth);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    // One subresource as two attachments, and a secondary list reading its pass's target.
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = rt}, {.texture = mip0}}, .debugName = "twice"}); }),
              "render pass 'twice': colour attachment 0 and colour attachment 1 are the same subresource (texture 'rt', "
              "mip 0, layer 0): each attachment needs its own");
    // The refused pass leaves nothing behind: storage textures bound after it are not checked
    // against the attachments it never began with.
    auto img = d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::Storage | TextureUsage::RenderTarget});
    auto img2 = d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::Storage});
    EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = img}, {.texture = img}}}); }).find("same subresource"),
              std::string::npos);
    auto cs = d.createShader({.stage = ShaderStage::Compute, .binary = fe::shaders::find("conformance/storage_high_slots.comp")});
    auto fill = d.createComputePipeline({.computeShader = cs});
    auto scale = d.createBuffer({.size = 16, .usage = BufferUsage::Storage});
    cmd->setPipeline(fill);
    cmd->setStorageTexture(9, img);
    cmd->setStorageTexture(40, img2);
    cmd->setStorageBuffer(3, scale);
    EXPECT_EQ(errorOf([&] { cmd->dispatch(1, 1); }), "(no error)");
    auto part = d.createCommandList();
    const RenderPassDesc pass{.colors = {{.texture = rt}}, .secondaryLists = true};
    part->beginSecondary(pass);
    part->setPipeline(sampling);
    part->setTexture(1, rt, sampler);
    EXPECT_NE(errorOf([&] { part->draw(3); }).find("slot 1 samples texture 'rt' (mip 0, layer 0)"), std::string::npos);
    part->setTexture(1, mip1, sampler);
    EXPECT_EQ(errorOf([&] { part->draw(3); }), "(no error)");
    part->endSecondary();
    cmd->beginRenderPass(pass);
    cmd->executeSecondary(*part);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    for (auto v : {mip0, mip1}) d.destroy(v);
    for (auto t : {rt, other, depth, img, img2}) d.destroy(t);
}

// A slot bound with another kind of resource than the pipeline declares is an error at the
// draw, also when it is re-bound wrongly after draws that were right.
TEST_P(DeviceErrors, WrongBindingKind) {
    const std::array<float, 64> params = {1, 0, 0, 1};  // the whole 256-byte buffer
    auto buf = device->createBuffer({.size = 256, .usage = BufferUsage::Uniform | BufferUsage::Storage}, bytesOf(params));
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
                                             .debugName = "ubo at 0"});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::Sampled});
    auto s = device->createSampler({});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setStorageBuffer(0, buf);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("pipeline 'ubo at 0': slot 0 expects a uniform buffer but a storage buffer is bound"),
              std::string::npos);
    cmd->setUniformBuffer(0, buf);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    auto other = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    cmd->beginRenderPass({.colors = {{.texture = other}}});
    cmd->setPipeline(p);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(0, t, s);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 0 expects a uniform buffer but a sampled texture is bound"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Draw state errors, the same on every backend: no pass, no pipeline (also in a later pass:
// a pass starts without one), compute pipeline.
TEST_P(DeviceErrors, DrawStateErrors) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto cs = device->createShader({.stage = ShaderStage::Compute, .binary = fe::shaders::find("conformance/fill.comp")});
    auto c = device->createComputePipeline({.computeShader = cs,
                                            .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                                                         {1, BindingType::StorageTexture, ShaderStage::Compute}},
                                            .debugName = "fill"});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw outside a render pass"), std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    EXPECT_NE(errorOf([&] { cmd->drawIndexed(3); }).find("drawIndexed without a pipeline"), std::string::npos);
    cmd->setPipeline(p);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw outside a render pass"), std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t, .load = LoadOp::Load}}});
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw without a pipeline"), std::string::npos);
    cmd->setPipeline(c);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw with compute pipeline 'fill'"), std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Vertex input, viewports, scissors, dispatch sizes, copies and fences: mistakes a port makes,
// one Error on every backend before any native call (lavapipe crashed on a missing index
// buffer; GL dropped what Vulkan drew).
TEST_P(DeviceErrors, DrawInputsAreCheckedAlike) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/vertex_color.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs,
         .vertexBuffers = {{.stride = 24, .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}},
                           {.stride = 8, .perInstance = true, .attributes = {{2, VertexFormat::Float2, 0}}}},
         .colorFormats = {Format::RGBA8}, .debugName = "vc"});
    auto vertices = device->createBuffer({.size = 72, .usage = BufferUsage::Vertex});  // 3 vertices
    auto offsets = device->createBuffer({.size = 16, .usage = BufferUsage::Vertex});   // 2 instances
    auto indices = device->createBuffer({.size = 12, .usage = BufferUsage::Index, .debugName = "idx"});  // 6 U16
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto has = [](const std::string& e, const std::string& s) { return e.find(s) != std::string::npos; };
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }), "draw: pipeline 'vc' reads vertex buffer 0, which is not bound"));
    cmd->setVertexBuffer(0, vertices);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }), "reads vertex buffer 1, which is not bound"));
    cmd->setVertexBuffer(1, offsets);
    EXPECT_EQ(errorOf([&] { cmd->draw(3, 2); }), "(no error)");
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3, 1, 1); }), "vertices [1, 4) reach past the bound vertex buffers"));
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3, 2, 0, 1); }), "instances [1, 3) reach past"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setVertexBuffer(0, vertices, 24); cmd->draw(3); }), "vertices [0, 3)"));
    cmd->setVertexBuffer(0, vertices);
    EXPECT_TRUE(has(errorOf([&] { cmd->drawIndexed(3); }), "drawIndexed without an index buffer"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setIndexBuffer(indices, IndexType::U32, 2); }), "offset 2 is not a multiple of 4"));
    cmd->setIndexBuffer(indices, IndexType::U16, 2);
    EXPECT_EQ(errorOf([&] { cmd->drawIndexed(5); }), "(no error)");
    EXPECT_TRUE(has(errorOf([&] { cmd->drawIndexed(3, 1, 3); }), "indices [3, 6) reach past the index buffer, which holds 5"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setVertexBuffer(16, vertices); }), "index 16 out of range (at most 16 vertex buffers)"));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 0, nan, 8}); }), "not finite"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 8, 8, -8}); }), "a negative height (Vulkan's y flip) is not supported"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 0, 0, 8}); }), "width and height must be positive"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 0, 8, 8, 0, 2}); }), "must lie in [0, 1]"));
    EXPECT_EQ(errorOf([&] { cmd->setScissor({-4, -100, 16, 16}); }), "(no error)");  // clipped: nothing left
    cmd->draw(3, 2);
    cmd->endRenderPass();
    auto b = device->createBuffer({.size = 64, .debugName = "bytes"});
    EXPECT_TRUE(has(errorOf([&] { cmd->copyBuffer(b, 16, b, 0, 32); }), "buffer 'bytes': copyBuffer: the source [0, 32) and destination [16, 48) overlap"));
    EXPECT_EQ(errorOf([&] { cmd->copyBuffer(b, 32, b, 0, 32); }), "(no error)");
    auto cs = device->createShader({.stage = ShaderStage::Compute, .binary = fe::shaders::find("conformance/fill.comp")});
    auto c = device->createComputePipeline({.computeShader = cs});
    cmd->setPipeline(c);
    const std::array<uint32_t, 3> most = device->info().limits.maxComputeWorkGroupCount;
    EXPECT_GE(most[0], 65535u);
    if (most[0] < UINT32_MAX) {
        EXPECT_TRUE(has(errorOf([&] { cmd->dispatch(most[0] + 1); }), "beyond the device's maxComputeWorkGroupCount"));
    }
    const FenceValue f = device->submit(*cmd);
    EXPECT_TRUE(has(errorOf([&] { device->wait(f + 1000); }), "wait: fence " + std::to_string(f + 1000) + " was never issued"));
    EXPECT_TRUE(has(errorOf([&] { device->isComplete(f + 1); }), "isComplete: fence"));
    device->wait(f);
    for (auto buffer : {vertices, offsets, indices, b}) device->destroy(buffer);
}

// A texture bound where the shader declares another kind (Vulkan sampled it with a validation
// error, GL read black) is one Error; a view of the shader's kind is the way to bind it.
TEST_P(DeviceErrors, TexturesAreBoundAsTheKindTheShaderDeclares) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/sample_array.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
                                             .debugName = "layers"});
    auto flat = device->createTexture({.width = 4, .height = 4, .debugName = "flat"});
    auto asArray = device->createTextureView(flat, {.dimension = TextureDimension::Texture2DArray});
    auto sampler = device->createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setTexture(1, flat, sampler);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("pipeline 'layers': slot 1 is declared a Texture2DArray in its shader, "
                                                 "but the texture bound there is a Texture2D"),
              std::string::npos);
    cmd->setTexture(1, asArray, sampler);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    device->destroy(asArray);
    for (auto tex : {flat, t}) device->destroy(tex);
}

// Viewports keep their fractions on every backend (GL's glViewport rounded them to whole
// pixels): the triangle of triangle.vert in viewport x = 2.75 covers pixels 3 to 5 of row 6.
TEST_P(DeviceErrors, ViewportsKeepTheirFractions) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setViewport({2.75f, 0, 4, 8});
    cmd->draw(3);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    const Image img = device->readTexture(t);
    std::string row;
    for (uint32_t x = 0; x < 8; ++x) row += img.texel(x, 6)[3] > 0.5f ? '#' : '.';
    EXPECT_EQ(row, "...###..");
    device->destroy(t);
}

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
        EXPECT_NE(errorOf([&] { list->draw(3); }).find("the device of this command list was destroyed"), std::string::npos);
        EXPECT_NE(errorOf([&] { list->setScissor({}); }).find("the device of this command list was destroyed"), std::string::npos);
        EXPECT_NE(errorOf([&] { list->clearBuffer({1}); }).find("the device of this command list was destroyed"), std::string::npos);
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
        {"beginRenderPass", [&](CommandList& l) { l.beginRenderPass({.colors = {{.texture = t}}}); }},
        {"endRenderPass", [](CommandList& l) { l.endRenderPass(); }},
        {"setPipeline", [](CommandList& l) { l.setPipeline({1}); }},
        {"setViewport", [](CommandList& l) { l.setViewport({.width = 4, .height = 4}); }},
        {"setScissor", [](CommandList& l) { l.setScissor({0, 0, 4, 4}); }},
        {"setBlendConstant", [](CommandList& l) { l.setBlendConstant({0, 0, 0, 0}); }},
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
        {"drawIndexedIndirectCount", [&](CommandList& l) { l.drawIndexedIndirectCount(b, 0, b, 0, 1); }},
        {"dispatchIndirect", [&](CommandList& l) { l.dispatchIndirect(b, 0); }},
        {"generateMips", [&](CommandList& l) { l.generateMips(t); }},
        {"copyBuffer", [&](CommandList& l) { l.copyBuffer(b, 0, b, 4, 4); }},
        {"clearBuffer", [&](CommandList& l) { l.clearBuffer(b); }},
        {"copyTexture", [&](CommandList& l) { l.copyTexture(t, t); }},
        {"copyBufferToTexture", [&](CommandList& l) { l.copyBufferToTexture(t, Subresource{}, b, 0); }},
        {"copyTextureToBuffer", [&](CommandList& l) { l.copyTextureToBuffer(b, 0, t, Subresource{}); }},
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
        {"executeSecondary", [](CommandList& l) { l.executeSecondary(std::span<CommandList* const>()); }},
    };
    for (bool inPass : {false, true}) {
        auto other = createDevice({.backend = GetParam()});
        auto target = other->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
        std::vector<std::unique_ptr<CommandList>> lists;
        for (size_t i = 0; i < calls.size(); ++i) {
            lists.push_back(other->createCommandList());
            if (inPass) lists.back()->beginRenderPass({.colors = {{.texture = target}}});
        }
        other.reset();
        for (size_t i = 0; i < calls.size(); ++i)
            EXPECT_EQ(errorOf([&] { calls[i].second(*lists[i]); }),
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
    std::atomic<uint32_t> current{0};
    std::atomic<bool> stop{false};
    std::thread destroyer([&] {
        for (int i = 0; i < 1500; ++i) {
            const BufferHandle b = device->createBuffer({.size = 256, .debugName = "a buffer with a name too long for SSO"});
            current = b.id;
            std::this_thread::yield();
            device->destroy(b);
        }
        stop = true;
    });
    auto list = device->createCommandList();
    uint32_t refused = 0;
    while (!stop) {
        try {
            for (int i = 0; i < 50; ++i) {
                const BufferHandle b{current.load()};
                list->copyBuffer(b, 0, b, 128, 64);
                list->setUniformBuffer(0, b, 0, 64);
            }
        } catch (const Error& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find("invalid or destroyed buffer handle"), std::string::npos) << e.what();
        }
        try {
            device->wait(device->submit(*list));
        } catch (const Error& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find("destroyed after it was recorded"), std::string::npos) << e.what();
            list = device->createCommandList();  // the refused one keeps its recording
        }
    }
    destroyer.join();
    EXPECT_GT(refused, 0u);
}

// Arrays, clear values and binaries that no backend can take: the same Error everywhere (a null
// barrier array crashed every backend; non-finite clears and an empty binary were taken or read
// differently).
TEST_P(DeviceErrors, NullArraysClearValuesAndEmptyBinaries) {
    auto cmd = device->createCommandList();
    EXPECT_EQ(errorOf([&] { cmd->barrier(static_cast<const TextureBarrier*>(nullptr), 2); }),
              "barrier: 2 barrier(s) from a null pointer");
    EXPECT_EQ(errorOf([&] { cmd->barrier(static_cast<const BufferBarrier*>(nullptr), 1); }),
              "barrier: 1 barrier(s) from a null pointer");
    cmd->barrier(static_cast<const TextureBarrier*>(nullptr), 0);  // no barrier: fine
    auto rt = device->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    auto depth = device->createTexture({.format = Format::D32F, .width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = rt, .clear = {0, nan, 0, 1}}}}); }),
              "render pass: colour attachment 0: clear colour is not finite");
    EXPECT_EQ(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = rt, .clear = {0, std::numeric_limits<float>::infinity(), 0, 1}}}});
              }),
              "render pass: colour attachment 0: clear colour is not finite");
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.depth = {.texture = depth, .clearDepth = 2.0f}}); }),
              "render pass: depth attachment: clearDepth 2.000000 is not in [0, 1]");
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.depth = {.texture = depth, .clearDepth = nan}}); }),
              "render pass: depth attachment: clearDepth nan is not in [0, 1]");
    // Loaded, not cleared: the clear values are not used and not checked.
    cmd->beginRenderPass({.colors = {{.texture = rt, .load = LoadOp::Load, .clear = {nan, 0, 0, 1}}},
                          .depth = {.texture = depth, .load = LoadOp::Load, .clearDepth = 2.0f}});
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    EXPECT_EQ(errorOf([&] { device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "none"}}); }),
              "shader 'none': the binary is empty (no SPIR-V for Vulkan or for OpenGL: fe_add_shaders and shaders::find make "
              "both)");
    device->destroy(rt);
    device->destroy(depth);
}

TEST_P(DeviceErrors, BrokenShaderBinary) {
    const uint32_t garbage[] = {0xdeadbeef, 1, 2, 3, 4, 5};
    ShaderBinary bin{"garbage.frag", garbage, garbage};
    EXPECT_NE(errorOf([&] { device->createShader({.stage = ShaderStage::Fragment, .binary = bin}); }).find("garbage.frag"),
              std::string::npos);
    ShaderBinary empty{"empty.frag", {}, {}};
    EXPECT_NE(errorOf([&] { device->createShader({.stage = ShaderStage::Fragment, .binary = empty}); }).find("empty.frag"),
              std::string::npos);
}

TEST_P(DeviceErrors, OutOfRangeBufferWrite) {
    auto b = device->createBuffer({.size = 16});
    uint8_t data[32] = {};
    EXPECT_NE(errorOf([&] { device->writeBuffer(b, 8, bytesOf(data)); }).find("exceeds its size 16"), std::string::npos);
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
    EXPECT_NE(errorOf([&] { d.submit(twice); }).find("the same list at 0 and 1"), std::string::npos);
    second->endRenderPass();
    d.wait(d.submit(both));
    EXPECT_EQ(d.readTexture(a).texel(0, 0)[0], 1.0f) << "the first list's recording was lost";
    EXPECT_EQ(d.readTexture(b).texel(0, 0)[1], 1.0f);
    d.destroy(a);
    d.destroy(b);
}

// Each rule of secondary lists (Device.h) gives its gdi::Error on every backend, before any
// native call: the primary draws in a pass of secondary lists, a secondary list is submitted,
// executed unended or for another pass, begun on a non-empty list, recorded after its end; and
// after a pass of secondary lists the primary's bindings are unset on every backend.
TEST_P(DeviceErrors, SecondaryListRules) {
    Device& d = *device;
    auto vs = d.createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = d.createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto ubo = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::CopySrc;
    auto t = d.createTexture({.width = 8, .height = 8, .usage = rt});
    auto wide = d.createTexture({.width = 16, .height = 8, .usage = rt});
    const RenderPassDesc pass{.colors = {{.texture = t}}, .secondaryLists = true};
    auto primary = d.createCommandList();
    auto part = d.createCommandList();
    auto has = [](const std::string& error, const char* text) {
        return error.find(text) != std::string::npos ? ::testing::AssertionSuccess()
                                                     : ::testing::AssertionFailure() << "got: " << error;
    };
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }), "outside a render pass begun with secondaryLists"));
    primary->beginRenderPass(pass);
    EXPECT_TRUE(has(errorOf([&] { primary->setPipeline(p); }), "setPipeline is not allowed in a render pass whose draws come from secondary lists"));
    EXPECT_TRUE(has(errorOf([&] { primary->draw(3); }), "draw is not allowed in a render pass whose draws"));
    EXPECT_TRUE(has(errorOf([&] { primary->setViewport({0, 0, 4, 4}); }), "setViewport is not allowed"));
    EXPECT_TRUE(has(errorOf([&] { primary->pushDebugGroup("x"); }), "pushDebugGroup is not allowed"));
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }), "list 0 is not a secondary list"));
    part->beginSecondary(pass);
    EXPECT_TRUE(has(errorOf([&] { part->beginRenderPass(pass); }), "beginRenderPass is not allowed in a secondary list"));
    EXPECT_TRUE(has(errorOf([&] { part->endRenderPass(); }), "endRenderPass is not allowed in a secondary list"));
    EXPECT_TRUE(has(errorOf([&] { part->copyBuffer(ubo, 0, ubo, 128, 4); }), "copyBuffer is not allowed inside a render pass"));
    EXPECT_TRUE(has(errorOf([&] { d.submit(*part); }), "a secondary list is executed by a primary list"));
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }), "list 0 is still recording (missing endSecondary)"));
    part->setPipeline(p);
    part->draw(3);
    part->pushDebugGroup("open");
    EXPECT_TRUE(has(errorOf([&] { part->endSecondary(); }), "endSecondary: 1 debug group(s) not popped"));
    part->popDebugGroup();
    part->endSecondary();
    EXPECT_TRUE(has(errorOf([&] { part->draw(3); }), "draw after endSecondary"));
    EXPECT_TRUE(has(errorOf([&] { part->setPipeline(p); }), "setPipeline after endSecondary"));
    EXPECT_TRUE(has(errorOf([&] { part->endSecondary(); }), "endSecondary without beginSecondary"));
    auto other = d.createCommandList();
    other->beginSecondary({.colors = {{.texture = wide}}});
    other->endSecondary();
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*other); }),
                    "list 0 was begun for another pass (RGBA8; 1 sample(s); 16x8) than the open one (RGBA8; 1 sample(s); 8x8)"));
    std::array<CommandList*, 2> twice = {part.get(), part.get()};
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(twice); }), "the same list at 0 and 1"));
    primary->executeSecondary(*part);
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*part); }), "list 0 is not a secondary list"));
    primary->endRenderPass();
    // The executed list is empty again; a list with something recorded cannot begin a secondary one.
    part->beginSecondary(pass);
    part->endSecondary();
    auto used = d.createCommandList();
    used->setUniformBuffer(0, ubo);
    EXPECT_TRUE(has(errorOf([&] { used->beginSecondary(pass); }), "beginSecondary: the list must be empty"));
    // The primary's bindings do not survive a pass of secondary lists.
    auto uboPipeline = d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8},
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
    EXPECT_TRUE(has(errorOf([&] { primary->executeSecondary(*other); }), "outside a render pass begun with secondaryLists"));
    for (auto pl : {p, uboPipeline}) d.destroy(pl);
    d.destroy(vs);
    d.destroy(fs);
    d.destroy(ubo);
    d.destroy(t);
    d.destroy(wide);
}

// Pipelines are checked against their shaders' reflection, with the same gdi::Error on every
// backend before any native call: bindings the list omits or mistypes, vertex inputs without
// attributes or of another scalar kind, fragment outputs of the wrong kind for their target,
// and at setPipeline attachment formats that are not the pass's. An empty binding list takes
// the shaders' own.
TEST_P(DeviceErrors, PipelinesAreCheckedAgainstTheirShaders) {
    Device& d = *device;
    auto has = [](const std::string& error, const char* text) {
        return error.find(text) != std::string::npos ? ::testing::AssertionSuccess()
                                                     : ::testing::AssertionFailure() << "got: " << error;
    };
    auto shader = [&](ShaderStage stage, const char* path) {
        return d.createShader({.stage = stage, .binary = fe::shaders::find(path)});
    };
    auto uboVs = shader(ShaderStage::Vertex, "conformance/fullscreen_ubo.vert");
    auto uboFs = shader(ShaderStage::Fragment, "conformance/ubo_color.frag");
    auto uintVs = shader(ShaderStage::Vertex, "conformance/vertex_uint.vert");
    auto valueFs = shader(ShaderStage::Fragment, "conformance/value.frag");
    auto err = [&](const GraphicsPipelineDesc& desc) { return errorOf([&] { d.destroy(d.createGraphicsPipeline(desc)); }); };
    const GraphicsPipelineDesc ubo{.vertexShader = uboVs, .fragmentShader = uboFs, .colorFormats = {Format::RGBA8},
                                   .debugName = "ubo"};
    GraphicsPipelineDesc omitted = ubo;
    omitted.bindings = {{1, BindingType::UniformBuffer, ShaderStage::AllGraphics}};
    EXPECT_TRUE(has(err(omitted), "pipeline 'ubo': binding slot 0 (uniform buffer) is used by the vertex and fragment shader "
                                  "but missing from the pipeline's bindings"));
    GraphicsPipelineDesc mistyped = ubo;
    mistyped.bindings = {{0, BindingType::StorageBuffer, ShaderStage::AllGraphics}};
    EXPECT_TRUE(has(err(mistyped), "binding slot 0 is declared a storage buffer, but the vertex and fragment shader uses a uniform buffer"));
    GraphicsPipelineDesc stageless = ubo;
    stageless.bindings = {{0, BindingType::UniformBuffer, ShaderStage::Fragment}};
    EXPECT_TRUE(has(err(stageless), "binding slot 0 is used by the vertex and fragment shader, which its declared stages leave out"));
    const VertexBufferLayout uintLayout{.stride = 12, .attributes = {{.location = 0, .format = VertexFormat::Float2},
                                                                     {.location = 1, .format = VertexFormat::UInt32, .offset = 8}}};
    GraphicsPipelineDesc noAttribute{.vertexShader = uintVs, .fragmentShader = valueFs,
                                     .vertexBuffers = {{.stride = 8, .attributes = {{.location = 0, .format = VertexFormat::Float2}}}},
                                     .colorFormats = {Format::RGBA8}, .debugName = "attrs"};
    EXPECT_TRUE(has(err(noAttribute), "pipeline 'attrs': vertex shader input 'inValue' (location 1) has no attribute in the vertex layout"));
    GraphicsPipelineDesc wrongKind = noAttribute;
    wrongKind.vertexBuffers = {{.stride = 12, .attributes = {{.location = 0, .format = VertexFormat::Float2},
                                                             {.location = 1, .format = VertexFormat::Float, .offset = 8}}}};
    EXPECT_TRUE(has(err(wrongKind), "vertex shader input 'inValue' (location 1) is uint, its attribute's format gives float"));
    GraphicsPipelineDesc intTarget = noAttribute;
    intTarget.vertexBuffers = {uintLayout};
    intTarget.colorFormats = {Format::R32U};
    EXPECT_TRUE(has(err(intTarget), "fragment output 'outColor' (location 0) is float, colour target 0 is R32U (uint)"));

    // Bindings taken from the shaders: the pipeline needs slot 0 bound, like a declared one.
    auto derived = d.createGraphicsPipeline(ubo);
    auto t = d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto t16 = d.createTexture({.format = Format::RGBA16F, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto depth = d.createTexture({.format = Format::D32F, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(derived);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }), "missing binding for slot(s) 0"));
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = t16}}});
    EXPECT_TRUE(has(errorOf([&] { cmd->setPipeline(derived); }),
                    "setPipeline: pipeline 'ubo': renders to colour [RGBA8], depth none but the render pass has colour [RGBA16F], depth none"));
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = t}}, .depth = {.texture = depth}});
    EXPECT_TRUE(has(errorOf([&] { cmd->setPipeline(derived); }), "but the render pass has colour [RGBA8], depth D32F"));
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    EXPECT_EQ(d.validationErrorCount(), 0u);
    d.destroy(derived);
    for (auto tex : {t, t16, depth}) d.destroy(tex);
    for (auto sh : {uboVs, uboFs, uintVs, valueFs}) d.destroy(sh);
}

// Binding ranges follow the device's rules before any native call: offsets a multiple of the
// kind's alignment, ranges at most its maximum; size 0 binds to the end, at most the maximum.
TEST_P(DeviceErrors, BindingOffsetsAndRangesFollowTheDeviceLimits) {
    Device& d = *device;
    const DeviceLimits& l = d.info().limits;
    ASSERT_GT(l.uniformBufferOffsetAlignment, 1u);
    ASSERT_GT(l.maxUniformBufferRange, 0u);
    auto big = d.createBuffer({.size = l.maxUniformBufferRange + 1024, .usage = BufferUsage::Uniform | BufferUsage::Storage});
    auto cmd = d.createCommandList();
    const uint64_t half = l.uniformBufferOffsetAlignment / 2;
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, big, half, 16); })
                  .find("setUniformBuffer: offset " + std::to_string(half) + " is not a multiple of the device's "
                        "uniformBufferOffsetAlignment (" + std::to_string(l.uniformBufferOffsetAlignment) + ")"),
              std::string::npos);
    if (l.storageBufferOffsetAlignment > 1) {
        EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(0, big, l.storageBufferOffsetAlignment / 2, 16); })
                      .find("is not a multiple of the device's storageBufferOffsetAlignment"),
                  std::string::npos);
    }
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, big, 0, l.maxUniformBufferRange + 16); })
                  .find("bytes exceed the device's maxUniformBufferRange"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, big, 0, 0); }), "(no error)");  // to the end, capped
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, big, l.uniformBufferOffsetAlignment, 16); }), "(no error)");
    d.destroy(big);
}

// A buffer bound as what it was not created for is the same gdi::Error on every backend (the
// Vulkan validation layer would report it; GL would bind it silently).
TEST_P(DeviceErrors, BuffersAreBoundOnlyAsTheirUsage) {
    Device& d = *device;
    auto uniformOnly = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform, .debugName = "uniform only"});
    auto storageOnly = d.createBuffer({.size = 256, .usage = BufferUsage::Storage, .debugName = "storage only"});
    auto cmd = d.createCommandList();
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(0, uniformOnly); }).find("setStorageBuffer: buffer 'uniform only' lacks Storage usage"),
              std::string::npos);
    cmd->setUniformBuffer(0, uniformOnly);  // the same buffer as what it is: accepted, and again on the fast path
    cmd->setUniformBuffer(1, uniformOnly, 0, 16);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(1, uniformOnly, 0, 16); }).find("lacks Storage usage"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, storageOnly); }).find("lacks Uniform usage"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setVertexBuffer(0, storageOnly); }).find("setVertexBuffer: buffer 'storage only' lacks Vertex usage"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setIndexBuffer(storageOnly, IndexType::U16); }).find("lacks Index usage"), std::string::npos);
    d.destroy(uniformOnly);
    d.destroy(storageOnly);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(DeviceErrors);

// Damaged SPIR-V is refused by createShader with an Error naming the shader, on every backend;
// before SPIR-V was validated, SPIRV-Cross's reflection crashed on some such modules (found by
// the capture-file fuzzer).
class DamagedSpirv : public fe::testing::BackendTest {};
TEST_P(DamagedSpirv, IsAnErrorNeverACrash) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    std::mt19937 random(26);
    uint32_t refused = 0;
    for (int i = 0; i < 300; ++i) {
        std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()), opengl(good.opengl.begin(), good.opengl.end());
        for (auto* words : {&vulkan, &opengl}) {
            // Header words kept (a wrong magic is refused early anyway): damage the instructions.
            for (int k = 0; k < 1 + i % 4; ++k) {
                const size_t at = 5 + random() % (words->size() - 5);
                (*words)[at] = (i % 3 == 0) ? uint32_t(random()) : (*words)[at] ^ (1u << (random() % 32));
            }
        }
        const std::string e = fe::testing::errorOf([&] {
            const ShaderHandle s = device->createShader(
                {.stage = ShaderStage::Vertex, .binary = {.name = "damaged", .vulkan = vulkan, .opengl = opengl}});
            device->destroy(s);
        });
        if (e != "(no error)") {
            ++refused;
            EXPECT_NE(e.find("shader 'damaged'"), std::string::npos) << e;
        }
    }
    EXPECT_GT(refused, 250u);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(DamagedSpirv);

// A damaged binary is the same Error on every backend: each validates both halves of the binary,
// the Vulkan one first, so which backend reads which half does not change the message.
TEST(DamagedSpirvAcrossBackends, SameErrorOnEveryBackend) {
    std::vector<std::unique_ptr<Device>> devices;
    for (const char* name : {"vulkan", "gl-egl", "gl-osmesa"})
        if (BackendProbe p = probeBackend(name, true); p.available) devices.push_back(std::move(p.device));
    if (devices.size() < 2) GTEST_SKIP() << "fewer than two backends";
    const ShaderBinary& good = fe::shaders::find("conformance/ubo_color.frag");
    std::mt19937 random(27);
    uint32_t refused = 0;
    for (int i = 0; i < 200; ++i) {
        std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()), opengl(good.opengl.begin(), good.opengl.end());
        auto* words = (i % 2) ? &vulkan : &opengl;  // one half damaged: the other backend must notice too
        const size_t at = 5 + random() % (words->size() - 5);
        (*words)[at] ^= 1u << (random() % 32);
        std::vector<std::string> errors;
        for (const auto& device : devices)
            errors.push_back(errorOf([&] {
                device->destroy(device->createShader(
                    {.stage = ShaderStage::Fragment, .binary = {.name = "damaged", .vulkan = vulkan, .opengl = opengl}}));
            }));
        refused += errors[0] != "(no error)";
        for (size_t d = 1; d < devices.size(); ++d)
            EXPECT_EQ(errors[d], errors[0]) << "damage " << i << ": " << devices[d]->info().backend << " vs "
                                            << devices[0]->info().backend;
    }
    EXPECT_GT(refused, 100u);
    for (const auto& device : devices) EXPECT_EQ(device->validationErrorCount(), 0u);
}

// A handle is its own device's: given to another device of the same backend, where an object
// of the same kind sits at the same index, it is refused as invalid instead of naming that
// object (it did, before handles were salted per device).
TEST_P(DeviceErrors, HandlesOfAnotherDeviceAreRefused) {
    BackendProbe second = probeBackend(GetParam(), true);
    ASSERT_TRUE(second.available) << second.reason;
    Device& other = *second.device;
    const std::array<uint8_t, 16> bytes{};
    auto mine = device->createBuffer({.size = 16, .usage = BufferUsage::Uniform | BufferUsage::CopySrc | BufferUsage::CopyDst});
    auto theirs = other.createBuffer({.size = 16, .usage = BufferUsage::Uniform | BufferUsage::CopySrc | BufferUsage::CopyDst});
    auto myTexture = device->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    auto theirTexture = other.createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    EXPECT_EQ(errorOf([&] { other.writeBuffer(theirs, 0, bytesOf(bytes)); }), "(no error)");
    EXPECT_NE(errorOf([&] { other.writeBuffer(mine, 0, bytesOf(bytes)); }).find("invalid or destroyed buffer handle"), std::string::npos);
    EXPECT_NE(errorOf([&] { other.readBuffer(mine, 0, 16); }).find("invalid or destroyed buffer handle"), std::string::npos);
    auto cmd = other.createCommandList();
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, mine); }).find("invalid or destroyed buffer handle"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = myTexture}}}); }).find("invalid or destroyed texture handle"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = theirTexture}}}); }), "(no error)");
    cmd->endRenderPass();
    other.wait(other.submit(*cmd));
    EXPECT_EQ(other.validationErrorCount(), 0u);
}

// An output at a location beyond the 16 every device has is refused before the driver sees it
// (the Vulkan validation layer reported it, found by the capture-file fuzzer).
TEST_P(DamagedSpirv, LocationsBeyondSixteenAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        // OpDecorate (opcode 71): word count 4, target, Location (30), the location.
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 71 && (w[i] >> 16) == 4 && w[i + 2] == 30) w[i + 3] = 40;
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "far", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("location 40; every device has 16 (0 to 15)"), std::string::npos) << e;
}

// gl_ClipDistance longer than the 8 distances every device has is refused before the driver sees
// it (the capture-file fuzzer made one of 14337; the validation layer reported it).
TEST_P(DamagedSpirv, ClipDistancesBeyondEightAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    // The array length constant of gl_PerVertex's gl_ClipDistance: OpTypeArray (28) whose
    // element is the float type and whose length is the constant 1, made 14337.
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        std::map<uint32_t, size_t> constantAt;  // id -> word index of its value
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16)) {
            const uint32_t op = w[i] & 0xffffu, n = w[i] >> 16;
            if (op == 43 && n == 4 && w[i + 3] == 1) constantAt[w[i + 2]] = i + 3;  // OpConstant ... 1
            if (op == 28 && n == 4 && constantAt.count(w[i + 3])) w[constantAt[w[i + 3]]] = 14337;
        }
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "clip", .vulkan = vulkan, .opengl = opengl}});
    });
    // gl_ClipDistance and gl_CullDistance share the array type: 2 x 14337.
    EXPECT_NE(e.find("gl_ClipDistance and gl_CullDistance hold 28674 distances; every device has 8"), std::string::npos) << e;
}

// A uniform block member that straddles a 16-byte boundary is valid SPIR-V but not a layout any
// device reads (Vulkan's relaxed block layout, GL's std140): refused, not left to the validation
// layer or the GLSL compiler (found by the capture-file fuzzer).
TEST_P(DamagedSpirv, StraddlingBlockMembersAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/ubo_color.frag");
    // OpMemberDecorate (72): struct, member 1, Offset (35), 16 -> 24: the second vec4 straddles.
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 72 && (w[i] >> 16) == 5 && w[i + 2] == 1 && w[i + 3] == 35 && w[i + 4] == 16) w[i + 4] = 24;
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    ASSERT_NE(opengl, std::vector<uint32_t>(good.opengl.begin(), good.opengl.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Fragment, .binary = {.name = "straddle", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("shader 'straddle': not a valid SPIR-V module for Vulkan:"), std::string::npos) << e;
    EXPECT_NE(e.find("improperly straddling vector at offset 24"), std::string::npos) << e;
}

// A capability the device does not enable is refused by name before the driver sees it (the
// capture-file fuzzer made a module declaring CullDistance: a validation-layer error on Vulkan).
TEST_P(DamagedSpirv, CapabilitiesTheDeviceLacksAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        // After the first OpCapability (opcode 17): OpCapability CullDistance (33).
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 17) {
                w.insert(w.begin() + std::ptrdiff_t(i + 2), {(2u << 16) | 17u, 33u});
                break;
            }
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_EQ(vulkan.size(), good.vulkan.size() + 2);
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "cull", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("shader 'cull': its Vulkan SPIR-V declares capability 33 (CullDistance), which the device does not offer"),
              std::string::npos) << e;
    // The GL half alone: refused the same way on every backend.
    const std::string gl = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "cull", .vulkan = good.vulkan, .opengl = opengl}});
    });
    EXPECT_NE(gl.find("shader 'cull': its OpenGL SPIR-V declares capability 33 (CullDistance)"), std::string::npos) << gl;
}

// The SPIR-V header's schema word must be 0: SPIRV-Tools lets other values through, Mesa's
// Vulkan driver refuses them with a validation error (found by the capture-file fuzzer).
TEST_P(DamagedSpirv, HeaderSchemaWordIsChecked) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()), opengl(good.opengl.begin(), good.opengl.end());
    vulkan[4] = opengl[4] = 40;
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "schema", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("shader 'schema': not a valid SPIR-V module for Vulkan: header word 4 (schema) is 40, not 0"), std::string::npos) << e;
}

// An image write whose texel has fewer components than the image's format is refused at
// createShader on every backend alike (the validator lets it through, Vulkan's layer does not:
// the capture-file fuzzer found one). conformance/fill.comp writes a vec4 to an rgba32f image;
// here its texel becomes a float constant.
TEST(DamagedSpirvAcrossBackends, ImageWriteWithTooFewComponentsIsRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/fill.comp");
    auto narrowed = [](std::span<const uint32_t> in) {
        std::vector<uint32_t> w(in.begin(), in.end());
        uint32_t floatType = 0, scalar = 0;
        for (size_t i = 5; i < w.size(); i += w[i] >> 16) {
            const uint32_t op = w[i] & 0xffffu;
            if (op == 22 && w[i + 2] == 32) floatType = w[i + 1];                         // OpTypeFloat 32
            if (op == 43 && floatType && w[i + 1] == floatType && !scalar) scalar = w[i + 2];  // OpConstant
            if (op == 99 && scalar) w[i + 3] = scalar;                                     // OpImageWrite's texel
        }
        return w;
    };
    const std::vector<uint32_t> vulkan = narrowed(good.vulkan), opengl = narrowed(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    for (const std::string& backend : backendNames()) {
        BackendProbe p = probeBackend(backend, true);
        if (!p.available) continue;
        EXPECT_EQ(errorOf([&] {
                      p.device->createShader({.stage = ShaderStage::Compute, .binary = {.name = "narrow", .vulkan = vulkan, .opengl = opengl}});
                  }),
                  "shader 'narrow': an image write gives 1 component(s) to an image whose format has 4")
            << backend;
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << backend;
    }
}

// GL has as few as 8 image units (NVIDIA): a pipeline's storage textures are counted against
// limits.maxStorageTextures by the shared validation, so every backend refuses alike. Checked on
// the validation itself, since no device here has a limit a shader of the suite reaches.
TEST(StorageTextureLimit, MoreThanTheDeviceBindsIsRefusedAndSlotNumbersDoNotCount) {
    ShaderInterface cs;
    cs.stage = ShaderStage::Compute;
    cs.bindings = {{9, BindingType::StorageTexture, "a"}, {40, BindingType::StorageTexture, "b"}, {3, BindingType::StorageBuffer, "s"}};
    const DeviceLimits two{.maxStorageTextures = 2}, one{.maxStorageTextures = 1};
    EXPECT_EQ(validate::pipelineBindings({}, {&cs}, "images", two).size(), 3u);  // slots 9 and 40 with 2 units
    EXPECT_EQ(errorOf([&] { validate::pipelineBindings({}, {&cs}, "images", one); }),
              "pipeline 'images': the shaders use 2 storage textures; this device binds at most 1 to one pipeline "
              "(limits.maxStorageTextures)");
}

// The GL backend renumbers storage textures to image units in the SPIR-V it hands the driver.
TEST(StorageTextureLimit, RenumberingChangesOnlyTheStorageTextureBindings) {
    const ShaderBinary& b = fe::shaders::find("conformance/storage_high_slots.comp");
    std::array<uint8_t, 64> units;
    units.fill(0xff);
    units[9] = 0, units[40] = 1;
    const std::vector<uint32_t> renumbered = withStorageTextureSlots(b.opengl, units);
    const ShaderInterface before = reflectShader(b.opengl, ShaderStage::Compute, "main", "before");
    const ShaderInterface after = reflectShader(renumbered, ShaderStage::Compute, "main", "after");
    std::map<std::string, uint32_t> slots;
    for (const auto& x : after.bindings) slots[x.name] = x.slot;
    ASSERT_EQ(before.bindings.size(), after.bindings.size());
    EXPECT_EQ(slots["first"], 0u);
    EXPECT_EQ(slots["second"], 1u);
    EXPECT_EQ(slots["Scale"], 3u);  // the storage buffer keeps its slot
    // Names get the stage's prefix, so two stages' blocks of one name stay apart on NVIDIA's GL.
    const std::vector<uint32_t> prefixed = withNamesPrefixed(b.opengl, "compute.");
    const ShaderInterface named = reflectShader(prefixed, ShaderStage::Compute, "main", "prefixed", SpirvRules::OpenGL45);
    std::set<std::string> names;
    for (const auto& x : named.bindings) names.insert(x.name);
    EXPECT_EQ(names, (std::set<std::string>{"compute.first", "compute.second", "compute.Scale"}));
}

// Mistakes a port makes with pipelines and dynamic state (found porting samples): each is the
// same Error on every backend before any native call.
TEST_P(DeviceErrors, PortingMistakesOfState) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/ubo_color.frag")});
    // Blending an integer target: Vulkan's validation layer objected, GL ignored it.
    EXPECT_NE(errorOf([&] {
                  device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs,
                                                  .blend = {{.enable = true}}, .colorFormats = {Format::R32U}});
              }).find("colour target 0 (R32U) is blended"),
              std::string::npos);
    GraphicsPipelineDesc nanConstant{.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}};
    nanConstant.blendConstant[1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(errorOf([&] { device->createGraphicsPipeline(nanConstant); }).find("blend constant values must be finite"),
              std::string::npos);
    // A sampler2DMS: no texture of the device can be bound to it.
    EXPECT_NE(errorOf([&] {
                  device->createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/sample_ms.frag")});
              }).find("'tex' is a multisampled texture, which the device has none of"),
              std::string::npos);
    auto target = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}});  // dynamic state is set inside a pass
    const DeviceLimits& l = device->info().limits;
    ASSERT_GT(l.maxViewportSize, 0u);
    ASSERT_LT(l.viewportBounds[0], 0.0f);
    EXPECT_NE(errorOf([&] { cmd->setViewport({0, 0, float(l.maxViewportSize) * 2, 64}); }).find("at most the device's maxViewportSize"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setViewport({l.viewportBounds[0] * 2, 0, 16, 16}); }).find("within the device's viewportBounds"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setViewport({0, 0, 1e30f, 64}); }).find("maxViewportSize"), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setBlendConstant({0, 0, std::numeric_limits<float>::infinity(), 1}); }).find("must be finite"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    device->destroy(target);
    device->destroy(fs);
    device->destroy(vs);
}

// Usage flags mean what they say for the commands a list records: a copy reads a CopySrc
// resource and writes a CopyDst one, a barrier names only states the usage allows. Both
// backends accepted these (Vulkan's buffers and images carry the transfer bits whatever the
// usage), so a program that worked here failed on a stricter API. The device's own transfers
// (writeTexture, readBuffer) need no copy usage, as the header's examples show.
TEST_P(DeviceErrors, CopiesAndBarriersFollowUsage) {
    Device& d = *device;
    const BufferHandle storage = d.createBuffer({.size = 256, .usage = BufferUsage::Storage, .debugName = "storage only"});
    const BufferHandle staging =
        d.createBuffer({.size = 256, .usage = BufferUsage::CopySrc | BufferUsage::CopyDst, .debugName = "staging"});
    const TextureHandle sampled = d.createTexture({.width = 4, .height = 4, .usage = TextureUsage::Sampled, .debugName = "sampled only"});
    const TextureHandle copyable = d.createTexture({.width = 4, .height = 4, .debugName = "copyable"});  // default usage
    const TextureHandle renderOnly = d.createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget, .debugName = "render only"});
    auto cmd = d.createCommandList();
    auto error = [&](auto&& f) { return errorOf(std::forward<decltype(f)>(f)); };
    EXPECT_NE(error([&] { cmd->copyBuffer(staging, 0, storage, 0, 16); }).find("copyBuffer source: buffer 'storage only' lacks CopySrc usage (it was created with Storage)"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyBuffer(storage, 0, staging, 0, 16); }).find("copyBuffer destination: buffer 'storage only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyTextureToBuffer(staging, 0, sampled, {}); }).find("copyTextureToBuffer: texture 'sampled only' lacks CopySrc usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyBufferToTexture(sampled, {}, staging, 0); }).find("copyBufferToTexture: texture 'sampled only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyTextureToBuffer(storage, 0, copyable, {}); }).find("copyTextureToBuffer: buffer 'storage only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyBufferToTexture(copyable, TextureRegion{}, storage, TexelLayout{}); })
                  .find("copyBufferToTexture: buffer 'storage only' lacks CopySrc usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyTexture(sampled, copyable); }).find("copyTexture destination: texture 'sampled only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->copyTexture(copyable, TextureRegion{}, sampled, TextureRegion{}); })
                  .find("copyTexture source: texture 'sampled only' lacks CopySrc usage"),
              std::string::npos);
    // Barriers: states and accesses the resource cannot be in.
    EXPECT_NE(error([&] { cmd->barrier(TextureBarrier{.texture = sampled, .before = ResourceState::ShaderRead, .after = ResourceState::RenderTarget}); })
                  .find("texture 'sampled only' lacks RenderTarget usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->barrier(TextureBarrier{.texture = sampled, .before = ResourceState::Storage}); }).find("lacks Storage usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->barrier(TextureBarrier{.texture = renderOnly, .before = ResourceState::Undefined}); })
                  .find("barrier to or from ShaderRead: texture 'render only' lacks Sampled or Storage usage"),
              std::string::npos);
    const TextureHandle colour = d.createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget, .debugName = "colour"});
    EXPECT_NE(error([&] { cmd->barrier(TextureBarrier{.texture = colour, .before = ResourceState::Undefined, .after = ResourceState::DepthTarget}); })
                  .find("texture 'colour' has format RGBA8: its attachment state is RenderTarget"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->barrier(BufferBarrier{.buffer = storage, .before = BufferAccess::StorageWrite, .after = BufferAccess::Indirect}); })
                  .find("barrier: buffer 'storage only' lacks Indirect usage"),
              std::string::npos);
    EXPECT_NE(error([&] { cmd->barrier(BufferBarrier{.buffer = staging, .before = BufferAccess::CopyDst, .after = BufferAccess::StorageRead}); })
                  .find("barrier: buffer 'staging' lacks Storage usage"),
              std::string::npos);
    const BufferHandle uniform = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform, .debugName = "uniform only"});
    EXPECT_NE(error([&] { cmd->clearBuffer(uniform); }).find("clearBuffer: buffer 'uniform only' lacks Storage or CopyDst usage"),
              std::string::npos);
    // What the usage allows is accepted, and runs: a Storage buffer may be cleared (a UAV clear on
    // D3D12), and the copy states go with any usage (writeTexture and writeBuffer copy into
    // anything, so a barrier from CopyDst after one is true).
    cmd->clearBuffer(storage);
    cmd->barrier(BufferBarrier{.buffer = storage, .before = BufferAccess::StorageWrite, .after = BufferAccess::StorageRead});
    cmd->barrier(BufferBarrier{.buffer = uniform, .before = BufferAccess::CopyDst, .after = BufferAccess::Uniform});
    cmd->barrier(TextureBarrier{.texture = sampled, .before = ResourceState::CopyDst, .after = ResourceState::ShaderRead});
    cmd->barrier(TextureBarrier{.texture = sampled, .before = ResourceState::Undefined, .after = ResourceState::ShaderRead});
    cmd->clearBuffer(staging, 0, 0, 0x01020304u);
    cmd->barrier(BufferBarrier{.buffer = staging, .before = BufferAccess::CopyDst, .after = BufferAccess::CopySrc});
    cmd->copyBufferToTexture(copyable, {}, staging, 0);
    d.wait(d.submit(*cmd));
    EXPECT_EQ(d.readTexture(copyable).data[5], 0x03);
    // Device transfers need no copy usage.
    const std::array<uint8_t, 64> texels{};
    d.writeTexture(sampled, {}, bytesOf(texels));
    EXPECT_EQ(d.readBuffer(storage, 0, 4).size(), 4u);
    for (TextureHandle t : {sampled, copyable, colour}) d.destroy(t);
    d.destroy(storage);
    d.destroy(staging);
    d.destroy(uniform);
    d.destroy(renderOnly);
}

// Dynamic state set outside a pass changed nothing (each pass starts from its pipeline's
// values), silently on both backends; destroying a handle twice was a silent no-op. Both are
// Errors now, the same on every backend; destroying the null handle stays a no-op.
TEST_P(DeviceErrors, StateOutsideAPassAndDoubleDestroy) {
    Device& d = *device;
    auto cmd = d.createCommandList();
    const std::string outside = "outside a render pass";
    EXPECT_NE(errorOf([&] { cmd->setViewport({0, 0, 8, 8}); }).find("setViewport " + outside), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setScissor({0, 0, 8, 8}); }).find("setScissor " + outside), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setBlendConstant({1, 1, 1, 1}); }).find("setBlendConstant " + outside), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStencilReference(1); }).find("setStencilReference " + outside), std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setDepthBias(1, 1, 0); }).find("setDepthBias " + outside), std::string::npos);

    auto twice = [&](auto handle, const char* kind) {
        d.destroy(handle);
        const std::string e = errorOf([&] { d.destroy(handle); });
        EXPECT_NE(e.find(std::string("destroy: ") + kind + " handle " + std::to_string(handle.id) + " is not live"),
                  std::string::npos)
            << kind << ": " << e;
        d.destroy(decltype(handle){});  // null: a no-op
    };
    twice(d.createBuffer({.size = 16}), "buffer");
    twice(d.createTexture({.width = 4, .height = 4}), "texture");
    twice(d.createSampler({}), "sampler");
    const ShaderHandle vs = d.createShader({.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    const ShaderHandle fs = d.createShader({.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    twice(d.createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}), "pipeline");
    d.destroy(fs);
    twice(vs, "shader");
    twice(d.createTimer(), "timer");
    if (d.info().features.occlusionQueries) twice(d.createQuerySet({.type = QueryType::Occlusion, .count = 2}), "query set");
    EXPECT_NE(errorOf([&] { d.destroy(HeapHandle{0x00100001u}); }).find("destroy: heap handle"), std::string::npos);
    // The device is still whole: a list records and runs.
    const BufferHandle b = d.createBuffer({.size = 16});
    cmd->clearBuffer(b, 0, 16, 7);
    d.wait(d.submit(*cmd));
    EXPECT_EQ(d.readBuffer(b, 0, 4)[0], 7);
    d.destroy(b);
}

// A list made by one device submitted to another: GL replayed it on the wrong context (whose
// objects share the names), Vulkan's validation layer objected.
TEST_P(DeviceErrors, ListOfAnotherDeviceIsRefused) {
    auto other = createDevice({.backend = GetParam(), .validation = true});
    const BufferHandle mine = device->createBuffer({.size = 16});
    const BufferHandle theirs = other->createBuffer({.size = 16});
    auto list = other->createCommandList();
    list->clearBuffer(theirs, 0, 16, 0x5555u);
    EXPECT_NE(errorOf([&] { device->submit(*list); }).find("a command list of another device"), std::string::npos);
    const std::vector<uint8_t> bytes = device->readBuffer(mine, 0, 16);
    EXPECT_EQ(bytes, std::vector<uint8_t>(16, 0));  // untouched
    other->wait(other->submit(*list));
    other->destroy(theirs);
    device->destroy(mine);
}

// Timers: one span per recording. Ended without a begin, GL read a negative time and Vulkan's
// layer objected; begun twice or left open, the backends measured different spans.
TEST_P(DeviceErrors, TimerMisuse) {
    const TimerHandle timer = device->createTimer();
    {
        auto cmd = device->createCommandList();
        EXPECT_NE(errorOf([&] { cmd->endTimer(timer); }).find("endTimer: the timer was not begun in this recording"),
                  std::string::npos);
        cmd->beginTimer(timer);
        EXPECT_NE(errorOf([&] { cmd->beginTimer(timer); }).find("beginTimer: the timer was already begun"), std::string::npos);
        EXPECT_NE(errorOf([&] { device->submit(*cmd); }).find("a timer begun in this recording was not ended"),
                  std::string::npos);
        cmd->endTimer(timer);
        EXPECT_NE(errorOf([&] { cmd->endTimer(timer); }).find("endTimer: the timer was already ended"), std::string::npos);
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
