// Mistakes in descriptions, uploads, copies and handles: clear errors, the same on every
// backend, never crashes. The DeviceErrors and DamagedSpirv suites are instantiated here; their
// tests are spread by topic over *ErrorTests.cpp (DeviceErrors.h).
#include "DeviceErrors.h"

using namespace fe::gdi;
using fe::testing::errorOf;

FE_INSTANTIATE_FOR_EVERY_BACKEND(DeviceErrors);
FE_INSTANTIATE_FOR_EVERY_BACKEND(DamagedSpirv);

TEST_P(DeviceErrors, ZeroSizes) {
    EXPECT_NE(errorOf([&] { device->createBuffer({.size = 0}); }).find("size is 0"),
              std::string::npos);
    EXPECT_NE(
        errorOf([&] { device->createTexture({.width = 0, .height = 4}); }).find("zero dimension"),
        std::string::npos);
    EXPECT_NE(errorOf([&] {
                  device->createTexture({.width = 1u << 20, .height = 4});
              }).find("exceeds the device limit"),
              std::string::npos);
}

TEST_P(DeviceErrors, UnsupportedUsage) {
    EXPECT_NE(
        errorOf([&] {
            device->createTexture(
                {.format = Format::D24S8, .width = 4, .height = 4, .usage = TextureUsage::Storage});
        }).find("cannot be a storage texture"),
        std::string::npos);
}

// Texture kinds: each rule of TextureDesc gives its own message.
TEST_P(DeviceErrors, TextureKinds) {
    using D = TextureDimension;
    auto err = [&](const TextureDesc& d) {
        return errorOf([&] { device->destroy(device->createTexture(d)); });
    };
    const TextureUsage rt = TextureUsage::RenderTarget;
    EXPECT_NE(err({.dimension = D::Texture2D, .width = 4, .height = 4, .depthOrLayers = 2})
                  .find("a Texture2D has depthOrLayers 1"),
              std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCube, .width = 4, .height = 8, .depthOrLayers = 6})
                  .find("faces must be square"),
              std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCube, .width = 4, .height = 4, .depthOrLayers = 12})
                  .find("a TextureCube has 6 layers"),
              std::string::npos);
    EXPECT_NE(err({.dimension = D::TextureCubeArray, .width = 4, .height = 4, .depthOrLayers = 8})
                  .find("6 layers per cube"),
              std::string::npos);
    EXPECT_NE(err({.dimension = D::Texture3D,
                   .format = Format::D32F,
                   .width = 4,
                   .height = 4,
                   .depthOrLayers = 4})
                  .find("cannot have a depth format"),
              std::string::npos);
    EXPECT_NE(err({.dimension = D::Texture3D,
                   .width = 4,
                   .height = 4,
                   .depthOrLayers = 16,
                   .mipLevels = 6})
                  .find("mipLevels 6 not in [1, 5]"),
              std::string::npos);
    EXPECT_NE(
        err({.dimension = D::Texture2DArray, .width = 4, .height = 4, .depthOrLayers = 1u << 20})
            .find("exceed the device limit"),
        std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .sampleCount = 3, .usage = rt})
                  .find("sampleCount 3 is not 1, 2, 4 or 8"),
              std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .mipLevels = 2, .sampleCount = 4, .usage = rt})
                  .find("one mip level"),
              std::string::npos);
    EXPECT_NE(err({.width = 4, .height = 4, .sampleCount = 4, .usage = rt | TextureUsage::Storage})
                  .find("a multisampled texture is a render target"),
              std::string::npos);
    EXPECT_NE(err({.format = Format::BC7, .width = 4, .height = 4, .usage = rt})
                  .find("can only be sampled and copied"),
              std::string::npos);
    // Every supported kind creates, with the layer count its kind implies.
    for (TextureDesc d :
         {TextureDesc{.dimension = D::Texture2DArray, .width = 4, .height = 4, .depthOrLayers = 3},
          TextureDesc{.dimension = D::TextureCube, .width = 4, .height = 4, .depthOrLayers = 6},
          TextureDesc{.dimension = D::Texture3D,
          .width = 4,
          .height = 4,
          .depthOrLayers = 4,
          .mipLevels = 3}})
        EXPECT_EQ(err(d), "(no error)");
}

// Subresources that do not exist, resolves that do not fit, and readback of what cannot be read.
TEST_P(DeviceErrors, SubresourcesAndResolves) {
    const TextureUsage rt = TextureUsage::RenderTarget | TextureUsage::CopySrc;
    auto arr = device->createTexture({.dimension = TextureDimension::Texture2DArray,
                                      .width = 8,
                                      .height = 8,
                                      .depthOrLayers = 2,
                                      .mipLevels = 2,
                                      .usage = rt,
                                      .debugName = "arr"});
    auto vol = device->createTexture(
        {.dimension = TextureDimension::Texture3D,
         .width = 8,
         .height = 8,
         .depthOrLayers = 4,
         .mipLevels = 2,
         .usage = TextureUsage::Sampled | TextureUsage::CopySrc | TextureUsage::CopyDst});
    EXPECT_NE(errorOf([&] {
                  device->readTexture(arr, {.layer = 2});
              }).find("layer 2 out of range (2 at mip 0)"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  device->readTexture(arr, {.mipLevel = 2});
              }).find("mip level 2 out of range"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  device->readTexture(vol, {.mipLevel = 1, .layer = 2});
              }).find("slice 2 out of range (2 at mip 1)"),
              std::string::npos);
    EXPECT_EQ(device->readTexture(vol, {.mipLevel = 1, .layer = 1}).width, 4u);
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = arr, .layer = 5}}});
              }).find("layer 5 out of range"),
              std::string::npos);
    const uint32_t counts = device->info().limits.colorSampleCounts;
    if (counts & 4) {
        auto ms = device->createTexture({.width = 8, .height = 8, .sampleCount = 4, .usage = rt});
        auto small = device->createTexture({.width = 4, .height = 4, .usage = rt});
        auto other = device->createTexture(
            {.format = Format::RGBA16F, .width = 8, .height = 8, .usage = rt});
        auto single = device->createTexture({.width = 8, .height = 8, .usage = rt});
        EXPECT_NE(errorOf([&] {
                      cmd->beginRenderPass({.colors = {{.texture = ms, .resolveTexture = small}}});
                  }).find("resolve target size differs"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] {
                      cmd->beginRenderPass({.colors = {{.texture = ms, .resolveTexture = other}}});
                  }).find("resolve target format RGBA16F differs"),
                  std::string::npos);
        EXPECT_NE(
            errorOf([&] {
                cmd->beginRenderPass({.colors = {{.texture = single, .resolveTexture = single}}});
            }).find("nothing to resolve"),
            std::string::npos);
        EXPECT_NE(errorOf([&] {
                      cmd->beginRenderPass({.colors = {{.texture = ms}, {.texture = single}}});
                  }).find("mismatched sample counts"),
                  std::string::npos);
        EXPECT_NE(errorOf([&] { device->readTexture(ms); }).find("is multisampled"),
                  std::string::npos);
        for (auto t : {ms, small, other, single}) device->destroy(t);
    }
    device->destroy(arr);
    device->destroy(vol);
}

// Indirect arguments are checked before the API sees them.
TEST_P(DeviceErrors, IndirectArguments) {
    auto vs = device->createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    const DrawIndirectArgs rec{3, 1, 0, 0};
    auto args = device->createBuffer(
        {.size = sizeof rec, .usage = BufferUsage::Indirect, .debugName = "args"}, bytesOf(rec));
    auto plain =
        device->createBuffer({.size = 64, .usage = BufferUsage::Storage, .debugName = "plain"});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 0); }).find("outside a render pass"),
              std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_NE(
        errorOf([&] { cmd->drawIndirect(plain, 0); }).find("buffer 'plain': lacks Indirect usage"),
        std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 2); }).find("not a multiple of 4"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndirect(args, 4); }).find("exceed its size 16"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->drawIndexedIndirect(args, 0); }).find("without an index buffer"),
              std::string::npos);
    if (!device->info().features.drawIndirectCount) {
        EXPECT_NE(
            errorOf([&] { cmd->drawIndirectCount(args, 0, args, 0, 1); }).find("not supported"),
            std::string::npos);
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
    auto depth = device->createTexture(
        {.format = Format::D32F, .width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = rt, .clear = {0, nan, 0, 1}}}});
              }),
              "render pass: colour attachment 0: clear colour is not finite");
    EXPECT_EQ(errorOf([&] {
                  cmd->beginRenderPass(
                      {.colors = {{.texture = rt,
                                   .clear = {0, std::numeric_limits<float>::infinity(), 0, 1}}}});
              }),
              "render pass: colour attachment 0: clear colour is not finite");
    EXPECT_EQ(
        errorOf([&] { cmd->beginRenderPass({.depth = {.texture = depth, .clearDepth = 2.0f}}); }),
        "render pass: depth attachment: clearDepth 2.000000 is not in [0, 1]");
    EXPECT_EQ(
        errorOf([&] { cmd->beginRenderPass({.depth = {.texture = depth, .clearDepth = nan}}); }),
        "render pass: depth attachment: clearDepth nan is not in [0, 1]");
    // Loaded, not cleared: the clear values are not used and not checked.
    cmd->beginRenderPass(
        {.colors = {{.texture = rt, .load = LoadOp::Load, .clear = {nan, 0, 0, 1}}},
         .depth = {.texture = depth, .load = LoadOp::Load, .clearDepth = 2.0f}});
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    EXPECT_EQ(
        errorOf([&] {
            device->createShader({.stage = ShaderStage::Vertex, .binary = {.name = "none"}});
        }),
        "shader 'none': the binary is empty (no SPIR-V for Vulkan or for OpenGL: fe_add_shaders and shaders::find make "
        "both)");
    device->destroy(rt);
    device->destroy(depth);
}

TEST_P(DeviceErrors, OutOfRangeBufferWrite) {
    auto b = device->createBuffer({.size = 16});
    uint8_t data[32] = {};
    EXPECT_NE(
        errorOf([&] { device->writeBuffer(b, 8, bytesOf(data)); }).find("exceeds its size 16"),
        std::string::npos);
}

// A handle is its own device's: given to another device of the same backend, where an object
// of the same kind sits at the same index, it is refused as invalid instead of naming that
// object (it did, before handles were salted per device).
TEST_P(DeviceErrors, HandlesOfAnotherDeviceAreRefused) {
    BackendProbe second = probeBackend(GetParam(), true);
    ASSERT_TRUE(second.available) << second.reason;
    Device& other = *second.device;
    const std::array<uint8_t, 16> bytes{};
    auto mine = device->createBuffer(
        {.size = 16, .usage = BufferUsage::Uniform | BufferUsage::CopySrc | BufferUsage::CopyDst});
    auto theirs = other.createBuffer(
        {.size = 16, .usage = BufferUsage::Uniform | BufferUsage::CopySrc | BufferUsage::CopyDst});
    auto myTexture =
        device->createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    auto theirTexture =
        other.createTexture({.width = 4, .height = 4, .usage = TextureUsage::RenderTarget});
    EXPECT_EQ(errorOf([&] { other.writeBuffer(theirs, 0, bytesOf(bytes)); }), "(no error)");
    EXPECT_NE(errorOf([&] {
                  other.writeBuffer(mine, 0, bytesOf(bytes));
              }).find("invalid or destroyed buffer handle"),
              std::string::npos);
    EXPECT_NE(
        errorOf([&] { other.readBuffer(mine, 0, 16); }).find("invalid or destroyed buffer handle"),
        std::string::npos);
    auto cmd = other.createCommandList();
    EXPECT_NE(
        errorOf([&] { cmd->setUniformBuffer(0, mine); }).find("invalid or destroyed buffer handle"),
        std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = myTexture}}});
              }).find("invalid or destroyed texture handle"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->beginRenderPass({.colors = {{.texture = theirTexture}}}); }),
              "(no error)");
    cmd->endRenderPass();
    other.wait(other.submit(*cmd));
    EXPECT_EQ(other.validationErrorCount(), 0u);
}

// Usage flags mean what they say for the commands a list records: a copy reads a CopySrc
// resource and writes a CopyDst one, a barrier names only states the usage allows. Both
// backends accepted these (Vulkan's buffers and images carry the transfer bits whatever the
// usage), so a program that worked here failed on a stricter API. The device's own transfers
// (writeTexture, readBuffer) need no copy usage, as the header's examples show.
TEST_P(DeviceErrors, CopiesAndBarriersFollowUsage) {
    Device& d = *device;
    const BufferHandle storage =
        d.createBuffer({.size = 256, .usage = BufferUsage::Storage, .debugName = "storage only"});
    const BufferHandle staging =
        d.createBuffer({.size = 256,
                        .usage = BufferUsage::CopySrc | BufferUsage::CopyDst,
                        .debugName = "staging"});
    const TextureHandle sampled = d.createTexture(
        {.width = 4, .height = 4, .usage = TextureUsage::Sampled, .debugName = "sampled only"});
    const TextureHandle copyable =
        d.createTexture({.width = 4, .height = 4, .debugName = "copyable"});  // default usage
    const TextureHandle renderOnly = d.createTexture(
        {.width = 4, .height = 4, .usage = TextureUsage::RenderTarget, .debugName = "render only"});
    auto cmd = d.createCommandList();
    auto error = [&](auto&& f) { return errorOf(std::forward<decltype(f)>(f)); };
    EXPECT_NE(
        error([&] {
            cmd->copyBuffer(staging, 0, storage, 0, 16);
        }).find("copyBuffer source: buffer 'storage only' lacks CopySrc usage (it was created with Storage)"),
        std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyBuffer(storage, 0, staging, 0, 16);
              }).find("copyBuffer destination: buffer 'storage only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyTextureToBuffer(staging, 0, sampled, {});
              }).find("copyTextureToBuffer: texture 'sampled only' lacks CopySrc usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyBufferToTexture(sampled, {}, staging, 0);
              }).find("copyBufferToTexture: texture 'sampled only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyTextureToBuffer(storage, 0, copyable, {});
              }).find("copyTextureToBuffer: buffer 'storage only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyBufferToTexture(copyable, TextureRegion{}, storage, TexelLayout{});
              }).find("copyBufferToTexture: buffer 'storage only' lacks CopySrc usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyTexture(sampled, copyable);
              }).find("copyTexture destination: texture 'sampled only' lacks CopyDst usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->copyTexture(copyable, TextureRegion{}, sampled, TextureRegion{});
              }).find("copyTexture source: texture 'sampled only' lacks CopySrc usage"),
              std::string::npos);
    // Barriers: states and accesses the resource cannot be in.
    EXPECT_NE(error([&] {
                  cmd->barrier(TextureBarrier{.texture = sampled,
                                              .before = ResourceState::ShaderRead,
                                              .after = ResourceState::RenderTarget});
              }).find("texture 'sampled only' lacks RenderTarget usage"),
              std::string::npos);
    EXPECT_NE(
        error([&] {
            cmd->barrier(TextureBarrier{.texture = sampled, .before = ResourceState::Storage});
        }).find("lacks Storage usage"),
        std::string::npos);
    EXPECT_NE(
        error([&] {
            cmd->barrier(TextureBarrier{.texture = renderOnly, .before = ResourceState::Undefined});
        }).find("barrier to or from ShaderRead: texture 'render only' lacks Sampled or Storage usage"),
        std::string::npos);
    const TextureHandle colour = d.createTexture(
        {.width = 4, .height = 4, .usage = TextureUsage::RenderTarget, .debugName = "colour"});
    EXPECT_NE(error([&] {
                  cmd->barrier(TextureBarrier{.texture = colour,
                                              .before = ResourceState::Undefined,
                                              .after = ResourceState::DepthTarget});
              }).find("texture 'colour' has format RGBA8: its attachment state is RenderTarget"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->barrier(BufferBarrier{.buffer = storage,
                                             .before = BufferAccess::StorageWrite,
                                             .after = BufferAccess::Indirect});
              }).find("barrier: buffer 'storage only' lacks Indirect usage"),
              std::string::npos);
    EXPECT_NE(error([&] {
                  cmd->barrier(BufferBarrier{.buffer = staging,
                                             .before = BufferAccess::CopyDst,
                                             .after = BufferAccess::StorageRead});
              }).find("barrier: buffer 'staging' lacks Storage usage"),
              std::string::npos);
    const BufferHandle uniform =
        d.createBuffer({.size = 256, .usage = BufferUsage::Uniform, .debugName = "uniform only"});
    EXPECT_NE(error([&] {
                  cmd->clearBuffer(uniform);
              }).find("clearBuffer: buffer 'uniform only' lacks Storage or CopyDst usage"),
              std::string::npos);
    // What the usage allows is accepted, and runs: a Storage buffer may be cleared (a UAV clear on
    // D3D12), and the copy states go with any usage (writeTexture and writeBuffer copy into
    // anything, so a barrier from CopyDst after one is true).
    cmd->clearBuffer(storage);
    cmd->barrier(BufferBarrier{.buffer = storage,
                               .before = BufferAccess::StorageWrite,
                               .after = BufferAccess::StorageRead});
    cmd->barrier(BufferBarrier{
        .buffer = uniform, .before = BufferAccess::CopyDst, .after = BufferAccess::Uniform});
    cmd->barrier(TextureBarrier{
        .texture = sampled, .before = ResourceState::CopyDst, .after = ResourceState::ShaderRead});
    cmd->barrier(TextureBarrier{.texture = sampled,
                                .before = ResourceState::Undefined,
                                .after = ResourceState::ShaderRead});
    cmd->clearBuffer(staging, 0, 0, 0x01020304u);
    cmd->barrier(BufferBarrier{
        .buffer = staging, .before = BufferAccess::CopyDst, .after = BufferAccess::CopySrc});
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
