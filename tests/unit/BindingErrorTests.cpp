// Mistakes in what a list binds and draws with: buffers, textures, vertex inputs, attachments,
// feedback loops, viewports and dynamic state; each the same error on every backend.
#include "DeviceErrors.h"

using namespace fe::gdi;
using fe::testing::errorOf;

TEST_P(DeviceErrors, MismatchedAttachments) {
    auto a = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto b = device->createTexture({.width = 16, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = a}, {.texture = b}}});
              }).find("mismatched attachments"),
              std::string::npos);
}

TEST_P(DeviceErrors, MissingBinding) {
    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
         .debugName = "needs slot 0"});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("missing binding for slot(s) 0"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Buffer binding arguments: every invalid one is an error naming the problem (the Vulkan
// setters have a separate fast path, so each way to leave it is exercised), and a valid bind
// after the errors still draws.
TEST_P(DeviceErrors, BufferBindingArguments) {
    const std::array<float, 64> params = {0.25f, 0.5f, 0.75f, 1.0f};  // the whole 256-byte buffer
    auto ubo = device->createBuffer(
        {.size = 256, .usage = BufferUsage::Uniform | BufferUsage::Storage, .debugName = "params"},
        bytesOf(params));
    auto gone = device->createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    device->destroy(gone);
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, ubo, 256); }).find("empty range"),
              std::string::npos);
    EXPECT_NE(
        errorOf([&] { cmd->setUniformBuffer(0, ubo, 200, 100); }).find("exceeds its size 256"),
        std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(0, ubo, 300, 16); }).find("exceeds its size 256"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setUniformBuffer(0, ubo, ~uint64_t(0) - 8, 16);
              }).find("exceeds its size 256"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(64, ubo); }).find("slot 64 out of range"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(70, ubo); }).find("slot 70 out of range"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, gone); }).find("invalid or destroyed"),
              std::string::npos);
    EXPECT_NE(
        errorOf([&] { cmd->setStorageBuffer(0, BufferHandle{}); }).find("invalid or destroyed"),
        std::string::npos);

    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    auto t = device->createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
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
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(1, ubo, 480, 64); }).find("exceeds its size 512"),
              std::string::npos);
    device->destroy(other);  // another object's destroy: the same buffer still binds
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(1, ubo, 256, 64); }), "(no error)");
    device->destroy(ubo);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(1, ubo, 256, 64); }).find("invalid or destroyed"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setStorageBuffer(2, ssbo); }), "(no error)");
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(2, ssbo); }).find("Uniform"), std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setStorageBuffer(3, ssbo, 256); }), "(no error)");
    device->destroy(ssbo);
    EXPECT_NE(errorOf([&] { cmd->setStorageBuffer(3, ssbo, 256); }).find("invalid or destroyed"),
              std::string::npos);
}

// Binding needs no recording: a buffer bound before a list's first command, destroyed, then
// drawn with. The draw records (recording may go on after a destroy), the submit is refused
// with the same message on every backend, and no native command names a freed object (on
// Vulkan the buffer's release waits for the list; without that the validation layer reports
// the destroyed VkBuffer and TearDown fails). Once the list is gone, so is the buffer.
TEST_P(DeviceErrors, StateBoundBeforeRecordingOutlivesItsDestroy) {
    const std::array<float, 64> params = {0.25f, 0.5f, 0.75f, 1.0f};
    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    auto t = device->createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    const LiveObjects before = device->liveObjects();
    {
        auto ubo =
            device->createBuffer({.size = 256, .usage = BufferUsage::Uniform}, bytesOf(params));
        auto cmd = device->createCommandList();
        cmd->setUniformBuffer(0, ubo);  // state only: nothing recorded yet
        device->destroy(ubo);
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
        cmd->endRenderPass();
        EXPECT_NE(errorOf([&] { device->submit(*cmd); }).find("destroyed after it was recorded"),
                  std::string::npos);
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
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto sampleFs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/textured.frag")});
    auto colorFs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto shadowFs = d.createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/shadow_2d.frag")});
    auto sampling = d.createGraphicsPipeline({.vertexShader = vs,
                                              .fragmentShader = sampleFs,
                                              .colorFormats = {Format::RGBA8},
                                              .debugName = "sampling"});
    auto plain = d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = colorFs, .colorFormats = {Format::RGBA8}});
    auto depthReader = [&](bool depthWrite, const char* name) {
        return d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = shadowFs,
             .depthStencil = {.depthTest = true, .depthWrite = depthWrite},
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D32F,
             .debugName = name});
    };
    auto testsDepth = depthReader(false, "tests depth"),
         writesDepth = depthReader(true, "writes depth");
    auto rt = d.createTexture({.width = 64,
                               .height = 64,
                               .mipLevels = 2,
                               .usage = TextureUsage::RenderTarget | TextureUsage::Sampled,
                               .debugName = "rt"});
    auto other = d.createTexture({.width = 64, .height = 64, .usage = TextureUsage::RenderTarget});
    auto mip1 = d.createTextureView(rt, {.baseMip = 1, .mipCount = 1});
    auto depth = d.createTexture({.format = Format::D32F,
                                  .width = 64,
                                  .height = 64,
                                  .usage = TextureUsage::RenderTarget | TextureUsage::Sampled,
                                  .debugName = "depth"});
    auto sampler = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    auto mipmapped = d.createSampler({.minFilter = Filter::Nearest,
                                      .magFilter = Filter::Nearest,
                                      .mipFilter = MipFilter::Nearest});
    auto compare = d.createSampler(
        {.minFilter = Filter::Nearest, .magFilter = Filter::Nearest, .compareEnable = true});
    const std::array<float, 8> params{0.5f};
    auto ubo = d.createBuffer({.size = 256, .usage = BufferUsage::Uniform});
    d.writeBuffer(ubo, 0, bytesOf(params));

    auto cmd = d.createCommandList();
    // Bound before the pass: it persists into it, and the draw that reads it is refused.
    cmd->setTexture(1, rt, sampler);
    cmd->beginRenderPass({.colors = {{.texture = rt}}, .debugName = "loop"});
    cmd->setPipeline(plain);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)")
        << "a pipeline that does not read slot 1";
    cmd->setPipeline(sampling);
    EXPECT_EQ(
        errorOf([&] { cmd->draw(3); }),
        "draw with pipeline 'sampling': slot 1 samples texture 'rt' (mip 0, layer 0), which colour attachment 0 "
        "of render pass 'loop' writes: a feedback loop, undefined on every API. Read another mip or layer, or a copy");
    cmd->setTexture(1, mip1, sampler);  // mip 1 while mip 0 is rendered: allowed
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(1, rt, sampler);  // bound inside the pass
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 0, layer 0)"),
              std::string::npos);
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
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 1, layer 0)"),
              std::string::npos);
    cmd->setTexture(1, mip0, sampler);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    // The whole texture: a sampler without a mip filter reads its base mip only (GL's rule too);
    // one with a mip filter may read mip 1.
    cmd->setTexture(1, rt, sampler);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(1, rt, mipmapped);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("slot 1 samples texture 'rt' (mip 1, layer 0)"),
              std::string::npos);
    cmd->endRenderPass();

    // The depth attachment: a pipeline that only tests depth may sample it, one that writes may not,
    // also when it replaces the reading pipeline without a new binding.
    cmd->setUniformBuffer(0, ubo);
    cmd->setTexture(1, depth, compare);
    cmd->beginRenderPass(
        {.colors = {{.texture = other}}, .depth = {.texture = depth, .load = LoadOp::Load}});
    cmd->setTexture(0, depth, compare);  // a loop for a moment: the uniform buffer replaces it
    cmd->setUniformBuffer(0, ubo);
    cmd->setPipeline(testsDepth);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setPipeline(writesDepth);
    EXPECT_EQ(
        errorOf([&] { cmd->draw(3); }),
        "draw with pipeline 'writes depth': slot 1 samples texture 'depth' (mip 0, layer 0), which the depth "
        "attachment of render pass writes: a feedback loop, undefined on every API. Read another mip or layer, or "
        "a copy (a pipeline that writes neither depth nor stencil may sample the depth attachment)");
    cmd->setPipeline(testsDepth);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    // One subresource as two attachments, and a secondary list reading its pass's target.
    EXPECT_EQ(
        errorOf([&] {
            cmd->beginRenderPass(
                {.colors = {{.texture = rt}, {.texture = mip0}}, .debugName = "twice"});
        }),
        "render pass 'twice': colour attachment 0 and colour attachment 1 are the same subresource (texture 'rt', "
        "mip 0, layer 0): each attachment needs its own");
    // The refused pass leaves nothing behind: storage textures bound after it are not checked
    // against the attachments it never began with.
    auto img = d.createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::Storage | TextureUsage::RenderTarget});
    auto img2 = d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::Storage});
    EXPECT_NE(errorOf([&] {
                  cmd->beginRenderPass({.colors = {{.texture = img}, {.texture = img}}});
              }).find("same subresource"),
              std::string::npos);
    auto cs = d.createShader({.stage = ShaderStage::Compute,
                              .binary = fe::shaders::find("conformance/storage_high_slots.comp")});
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
    EXPECT_NE(errorOf([&] { part->draw(3); }).find("slot 1 samples texture 'rt' (mip 0, layer 0)"),
              std::string::npos);
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
    auto buf = device->createBuffer(
        {.size = 256, .usage = BufferUsage::Uniform | BufferUsage::Storage}, bytesOf(params));
    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
         .debugName = "ubo at 0"});
    auto t = device->createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::Sampled});
    auto s = device->createSampler({});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setStorageBuffer(0, buf);
    EXPECT_NE(
        errorOf([&] {
            cmd->draw(3);
        }).find("pipeline 'ubo at 0': slot 0 expects a uniform buffer but a storage buffer is bound"),
        std::string::npos);
    cmd->setUniformBuffer(0, buf);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    auto other =
        device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    cmd->beginRenderPass({.colors = {{.texture = other}}});
    cmd->setPipeline(p);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->setTexture(0, t, s);
    EXPECT_NE(errorOf([&] {
                  cmd->draw(3);
              }).find("slot 0 expects a uniform buffer but a sampled texture is bound"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Draw state errors, the same on every backend: no pass, no pipeline (also in a later pass:
// a pass starts without one), compute pipeline.
TEST_P(DeviceErrors, DrawStateErrors) {
    auto vs = device->createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto cs = device->createShader(
        {.stage = ShaderStage::Compute, .binary = fe::shaders::find("conformance/fill.comp")});
    auto c = device->createComputePipeline(
        {.computeShader = cs,
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                      {1, BindingType::StorageTexture, ShaderStage::Compute}},
         .debugName = "fill"});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw outside a render pass"), std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    EXPECT_NE(errorOf([&] { cmd->drawIndexed(3); }).find("drawIndexed without a pipeline"),
              std::string::npos);
    cmd->setPipeline(p);
    EXPECT_EQ(errorOf([&] { cmd->draw(3); }), "(no error)");
    cmd->endRenderPass();
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw outside a render pass"), std::string::npos);
    cmd->beginRenderPass({.colors = {{.texture = t, .load = LoadOp::Load}}});
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw without a pipeline"), std::string::npos);
    cmd->setPipeline(c);
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("draw with compute pipeline 'fill'"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
}

// Vertex input, viewports, scissors, dispatch sizes, copies and fences: mistakes a port makes,
// one Error on every backend before any native call (lavapipe crashed on a missing index
// buffer; GL dropped what Vulkan drew).
TEST_P(DeviceErrors, DrawInputsAreCheckedAlike) {
    auto vs = device->createShader({.stage = ShaderStage::Vertex,
                                    .binary = fe::shaders::find("conformance/vertex_color.vert")});
    auto fs = device->createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .vertexBuffers =
             {{.stride = 24,
               .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}},
              {.stride = 8, .perInstance = true, .attributes = {{2, VertexFormat::Float2, 0}}}},
         .colorFormats = {Format::RGBA8},
         .debugName = "vc"});
    auto vertices = device->createBuffer({.size = 72, .usage = BufferUsage::Vertex});  // 3 vertices
    auto offsets = device->createBuffer({.size = 16, .usage = BufferUsage::Vertex});  // 2 instances
    auto indices = device->createBuffer(
        {.size = 12, .usage = BufferUsage::Index, .debugName = "idx"});  // 6 U16
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto has = [](const std::string& e, const std::string& s) {
        return e.find(s) != std::string::npos;
    };
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }),
                    "draw: pipeline 'vc' reads vertex buffer 0, which is not bound"));
    cmd->setVertexBuffer(0, vertices);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }), "reads vertex buffer 1, which is not bound"));
    cmd->setVertexBuffer(1, offsets);
    EXPECT_EQ(errorOf([&] { cmd->draw(3, 2); }), "(no error)");
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3, 1, 1); }),
                    "vertices [1, 4) reach past the bound vertex buffers"));
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3, 2, 0, 1); }), "instances [1, 3) reach past"));
    EXPECT_TRUE(has(errorOf([&] {
                        cmd->setVertexBuffer(0, vertices, 24);
                        cmd->draw(3);
                    }),
                    "vertices [0, 3)"));
    cmd->setVertexBuffer(0, vertices);
    EXPECT_TRUE(has(errorOf([&] { cmd->drawIndexed(3); }), "drawIndexed without an index buffer"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setIndexBuffer(indices, IndexType::U32, 2); }),
                    "offset 2 is not a multiple of 4"));
    cmd->setIndexBuffer(indices, IndexType::U16, 2);
    EXPECT_EQ(errorOf([&] { cmd->drawIndexed(5); }), "(no error)");
    EXPECT_TRUE(has(errorOf([&] { cmd->drawIndexed(3, 1, 3); }),
                    "indices [3, 6) reach past the index buffer, which holds 5"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setVertexBuffer(16, vertices); }),
                    "index 16 out of range (at most 16 vertex buffers)"));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 0, nan, 8}); }), "not finite"));
    EXPECT_TRUE(has(errorOf([&] {
                        cmd->setViewport({0, 8, 8, -8});
                    }),
                    "a negative height (Vulkan's y flip) is not supported"));
    EXPECT_TRUE(has(errorOf([&] {
                        cmd->setViewport({0, 0, 0, 8});
                    }),
                    "width and height must be positive"));
    EXPECT_TRUE(has(errorOf([&] { cmd->setViewport({0, 0, 8, 8, 0, 2}); }), "must lie in [0, 1]"));
    EXPECT_EQ(errorOf([&] {
                  cmd->setScissor({-4, -100, 16, 16});
              }),
              "(no error)");  // clipped: nothing left
    cmd->draw(3, 2);
    cmd->endRenderPass();
    auto b = device->createBuffer({.size = 64, .debugName = "bytes"});
    EXPECT_TRUE(
        has(errorOf([&] { cmd->copyBuffer(b, 16, b, 0, 32); }),
            "buffer 'bytes': copyBuffer: the source [0, 32) and destination [16, 48) overlap"));
    EXPECT_EQ(errorOf([&] { cmd->copyBuffer(b, 32, b, 0, 32); }), "(no error)");
    auto cs = device->createShader(
        {.stage = ShaderStage::Compute, .binary = fe::shaders::find("conformance/fill.comp")});
    auto c = device->createComputePipeline({.computeShader = cs});
    cmd->setPipeline(c);
    const std::array<uint32_t, 3> most = device->info().limits.maxComputeWorkGroupCount;
    EXPECT_GE(most[0], 65535u);
    if (most[0] < UINT32_MAX) {
        EXPECT_TRUE(has(errorOf([&] { cmd->dispatch(most[0] + 1); }),
                        "beyond the device's maxComputeWorkGroupCount"));
    }
    const FenceValue f = device->submit(*cmd);
    EXPECT_TRUE(has(errorOf([&] { device->wait(f + 1000); }),
                    "wait: fence " + std::to_string(f + 1000) + " was never issued"));
    EXPECT_TRUE(has(errorOf([&] { device->isComplete(f + 1); }), "isComplete: fence"));
    device->wait(f);
    for (auto buffer : {vertices, offsets, indices, b}) device->destroy(buffer);
}

// A texture bound where the shader declares another kind (Vulkan sampled it with a validation
// error, GL read black) is one Error; a view of the shader's kind is the way to bind it.
TEST_P(DeviceErrors, TexturesAreBoundAsTheKindTheShaderDeclares) {
    auto vs = device->createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/sample_array.frag")});
    auto p = device->createGraphicsPipeline({.vertexShader = vs,
                                             .fragmentShader = fs,
                                             .colorFormats = {Format::RGBA8},
                                             .debugName = "layers"});
    auto flat = device->createTexture({.width = 4, .height = 4, .debugName = "flat"});
    auto asArray = device->createTextureView(flat, {.dimension = TextureDimension::Texture2DArray});
    auto sampler =
        device->createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setTexture(1, flat, sampler);
    EXPECT_NE(errorOf([&] { cmd->draw(3); })
                  .find("pipeline 'layers': slot 1 is declared a Texture2DArray in its shader, "
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
    auto vs = device->createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    auto fs = device->createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    auto p = device->createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
    auto t = device->createTexture(
        {.width = 8, .height = 8, .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
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

// Binding ranges follow the device's rules before any native call: offsets a multiple of the
// kind's alignment, ranges at most its maximum; size 0 binds to the end, at most the maximum.
TEST_P(DeviceErrors, BindingOffsetsAndRangesFollowTheDeviceLimits) {
    Device& d = *device;
    const DeviceLimits& l = d.info().limits;
    ASSERT_GT(l.uniformBufferOffsetAlignment, 1u);
    ASSERT_GT(l.maxUniformBufferRange, 0u);
    auto big = d.createBuffer({.size = l.maxUniformBufferRange + 1024,
                               .usage = BufferUsage::Uniform | BufferUsage::Storage});
    auto cmd = d.createCommandList();
    const uint64_t half = l.uniformBufferOffsetAlignment / 2;
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, big, half, 16); })
                  .find("setUniformBuffer: offset " + std::to_string(half) +
                        " is not a multiple of the device's "
                        "uniformBufferOffsetAlignment (" +
                        std::to_string(l.uniformBufferOffsetAlignment) + ")"),
              std::string::npos);
    if (l.storageBufferOffsetAlignment > 1) {
        EXPECT_NE(errorOf([&] {
                      cmd->setStorageBuffer(0, big, l.storageBufferOffsetAlignment / 2, 16);
                  }).find("is not a multiple of the device's storageBufferOffsetAlignment"),
                  std::string::npos);
    }
    EXPECT_NE(errorOf([&] {
                  cmd->setUniformBuffer(0, big, 0, l.maxUniformBufferRange + 16);
              }).find("bytes exceed the device's maxUniformBufferRange"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, big, 0, 0); }),
              "(no error)");  // to the end, capped
    EXPECT_EQ(errorOf([&] { cmd->setUniformBuffer(0, big, l.uniformBufferOffsetAlignment, 16); }),
              "(no error)");
    d.destroy(big);
}

// A buffer bound as what it was not created for is the same gdi::Error on every backend (the
// Vulkan validation layer would report it; GL would bind it silently).
TEST_P(DeviceErrors, BuffersAreBoundOnlyAsTheirUsage) {
    Device& d = *device;
    auto uniformOnly =
        d.createBuffer({.size = 256, .usage = BufferUsage::Uniform, .debugName = "uniform only"});
    auto storageOnly =
        d.createBuffer({.size = 256, .usage = BufferUsage::Storage, .debugName = "storage only"});
    auto cmd = d.createCommandList();
    EXPECT_NE(errorOf([&] {
                  cmd->setStorageBuffer(0, uniformOnly);
              }).find("setStorageBuffer: buffer 'uniform only' lacks Storage usage"),
              std::string::npos);
    cmd->setUniformBuffer(
        0, uniformOnly);  // the same buffer as what it is: accepted, and again on the fast path
    cmd->setUniformBuffer(1, uniformOnly, 0, 16);
    EXPECT_NE(
        errorOf([&] { cmd->setStorageBuffer(1, uniformOnly, 0, 16); }).find("lacks Storage usage"),
        std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setUniformBuffer(0, storageOnly); }).find("lacks Uniform usage"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setVertexBuffer(0, storageOnly);
              }).find("setVertexBuffer: buffer 'storage only' lacks Vertex usage"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setIndexBuffer(storageOnly, IndexType::U16);
              }).find("lacks Index usage"),
              std::string::npos);
    d.destroy(uniformOnly);
    d.destroy(storageOnly);
}

// Mistakes a port makes with pipelines and dynamic state (found porting samples): each is the
// same Error on every backend before any native call.
TEST_P(DeviceErrors, PortingMistakesOfState) {
    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    // Blending an integer target: Vulkan's validation layer objected, GL ignored it.
    EXPECT_NE(errorOf([&] {
                  device->createGraphicsPipeline({.vertexShader = vs,
                                                  .fragmentShader = fs,
                                                  .blend = {{.enable = true}},
                                                  .colorFormats = {Format::R32U}});
              }).find("colour target 0 (R32U) is blended"),
              std::string::npos);
    GraphicsPipelineDesc nanConstant{
        .vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}};
    nanConstant.blendConstant[1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(errorOf([&] {
                  device->createGraphicsPipeline(nanConstant);
              }).find("blend constant values must be finite"),
              std::string::npos);
    // A sampler2DMS takes multisampled textures (msaa_texel_fetch): the shader is accepted.
    device->destroy(
        device->createShader({.stage = ShaderStage::Fragment,
                              .binary = fe::shaders::find("conformance/sample_ms.frag")}));
    auto target =
        device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}});  // dynamic state is set inside a pass
    const DeviceLimits& l = device->info().limits;
    ASSERT_GT(l.maxViewportSize, 0u);
    ASSERT_LT(l.viewportBounds[0], 0.0f);
    EXPECT_NE(errorOf([&] {
                  cmd->setViewport({0, 0, float(l.maxViewportSize) * 2, 64});
              }).find("at most the device's maxViewportSize"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setViewport({l.viewportBounds[0] * 2, 0, 16, 16});
              }).find("within the device's viewportBounds"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setViewport({0, 0, 1e30f, 64});
              }).find("maxViewportSize"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setBlendConstant({0, 0, std::numeric_limits<float>::infinity(), 1});
              }).find("must be finite"),
              std::string::npos);
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));
    device->destroy(target);
    device->destroy(fs);
    device->destroy(vs);
}

// Dynamic state set outside a pass changed nothing (each pass starts from its pipeline's
// values), silently on both backends; destroying a handle twice was a silent no-op. Both are
// Errors now, the same on every backend; destroying the null handle stays a no-op.
TEST_P(DeviceErrors, StateOutsideAPassAndDoubleDestroy) {
    Device& d = *device;
    auto cmd = d.createCommandList();
    const std::string outside = "outside a render pass";
    EXPECT_NE(errorOf([&] {
                  cmd->setViewport({0, 0, 8, 8});
              }).find("setViewport " + outside),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setScissor({0, 0, 8, 8});
              }).find("setScissor " + outside),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  cmd->setBlendConstant({1, 1, 1, 1});
              }).find("setBlendConstant " + outside),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setStencilReference(1); }).find("setStencilReference " + outside),
              std::string::npos);
    EXPECT_NE(errorOf([&] { cmd->setDepthBias(1, 1, 0); }).find("setDepthBias " + outside),
              std::string::npos);

    auto twice = [&](auto handle, const char* kind) {
        d.destroy(handle);
        const std::string e = errorOf([&] { d.destroy(handle); });
        EXPECT_NE(e.find(std::string("destroy: ") + kind + " handle " + std::to_string(handle.id) +
                         " is not live"),
                  std::string::npos)
            << kind << ": " << e;
        d.destroy(decltype(handle){});  // null: a no-op
    };
    twice(d.createBuffer({.size = 16}), "buffer");
    twice(d.createTexture({.width = 4, .height = 4}), "texture");
    twice(d.createSampler({}), "sampler");
    const ShaderHandle vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("conformance/triangle.vert")});
    const ShaderHandle fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("conformance/color.frag")});
    twice(d.createGraphicsPipeline(
              {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}),
          "pipeline");
    d.destroy(fs);
    twice(vs, "shader");
    twice(d.createTimer(), "timer");
    if (d.info().features.occlusionQueries)
        twice(d.createQuerySet({.type = QueryType::Occlusion, .count = 2}), "query set");
    EXPECT_NE(errorOf([&] { d.destroy(HeapHandle{0x00100001u}); }).find("destroy: heap handle"),
              std::string::npos);
    // The device is still whole: a list records and runs.
    const BufferHandle b = d.createBuffer({.size = 16});
    cmd->clearBuffer(b, 0, 16, 7);
    d.wait(d.submit(*cmd));
    EXPECT_EQ(d.readBuffer(b, 0, 4)[0], 7);
    d.destroy(b);
}

// A uniform range smaller than the block the pipeline declares at its slot: a warning in
// validation mode (Vulkan allows it while the shader stays inside) at the draw that uses it,
// whether the buffer or the pipeline came last; a whole block, or a short range rebound before
// any draw, gives none. (The reads past the range stay inside the buffer.)
TEST_P(DeviceErrors, RangeSmallerThanTheBlockWarns) {
    auto vs =
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = fe::shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = device->createShader({.stage = ShaderStage::Fragment,
                                    .binary = fe::shaders::find("conformance/ubo_color.frag")});
    // Each message is printed once a process: the backend in the name makes it this test's own.
    const std::string name = "32-byte block on " + GetParam();
    auto p = device->createGraphicsPipeline({.vertexShader = vs,
                                             .fragmentShader = fs,
                                             .colorFormats = {Format::RGBA8},
                                             .debugName = name.c_str()});
    // Offsets a multiple of the device's alignment (64 on NVIDIA's Vulkan, 256 on its GL).
    const uint64_t a = std::max<uint64_t>(device->info().limits.uniformBufferOffsetAlignment, 32);
    auto ubo = device->createBuffer({.size = 4 * a, .usage = BufferUsage::Uniform});
    auto t = device->createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    const uint64_t before = validate::warningCount();
    ::testing::internal::CaptureStderr();
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo, 0, 16);  // bound under the pipeline
    cmd->draw(3);
    EXPECT_EQ(validate::warningCount(), before + 1);
    cmd->setUniformBuffer(0, ubo, 0, 32);  // the whole block
    cmd->draw(3);
    EXPECT_EQ(validate::warningCount(), before + 1);
    cmd->setUniformBuffer(0, ubo, 0, 16);
    cmd->setUniformBuffer(0, ubo, a, 32);  // rebound before the draw: fine
    cmd->draw(3);
    EXPECT_EQ(validate::warningCount(), before + 1);
    cmd->setUniformBuffer(0, ubo, 2 * a, 16);
    cmd->setPipeline(p);  // the pipeline set over the short binding
    cmd->draw(3);
    EXPECT_EQ(validate::warningCount(), before + 2);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("fe validation warning: slot 0 holds a range of 16 bytes where pipeline '" +
                       name + "' declares a block of 32 bytes"),
              std::string::npos)
        << err;
    cmd->endRenderPass();
    cmd->reset();
    device->destroy(p);
    device->destroy(vs);
    device->destroy(fs);
    device->destroy(ubo);
    device->destroy(t);
}
