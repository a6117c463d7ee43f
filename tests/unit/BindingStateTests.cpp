// Bindings persist across draws and pipeline switches: a slot set once is what every later
// draw sees until it is set again, whichever pipelines come in between. On Vulkan this covers
// the incremental push-descriptor path (only slots set since the last draw are pushed; a
// pipeline with another layout disturbs the set, so everything is pushed again).
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "BackendTest.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe;
using namespace fe::gdi;
using fe::testing::errorOf;

namespace {

class BindingState : public fe::testing::BackendTest {};

struct Params {
    float color[4];
    float depth[4];
};

}  // namespace

TEST_P(BindingState, SlotsPersistAcrossDrawsAndPipelineSwitches) {
    Device& d = *device;
    constexpr uint32_t kSize = 64, kStride = 256;
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")});
    const GraphicsPipelineDesc desc{
        .vertexShader = vs,
        .fragmentShader = fs,
        .colorFormats = {Format::RGBA8},
        .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}};
    PipelineHandle a = d.createGraphicsPipeline(desc);
    // b declares one more slot, so its layout is not compatible with a's: switching between
    // them disturbs Vulkan's push descriptors.
    GraphicsPipelineDesc descB = desc;
    descB.bindings.push_back({1, BindingType::UniformBuffer, ShaderStage::AllGraphics});
    PipelineHandle b = d.createGraphicsPipeline(descB);
    const std::array<std::array<float, 4>, 3> colors = {{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}}};
    std::vector<uint8_t> bytes(kStride * colors.size());
    for (size_t i = 0; i < colors.size(); ++i) {
        Params p{{colors[i][0], colors[i][1], colors[i][2], colors[i][3]}, {0.5f, 0, 0, 0}};
        std::memcpy(&bytes[i * kStride], &p, sizeof p);
    }
    BufferHandle ubo =
        d.createBuffer({.size = bytes.size(), .usage = BufferUsage::Uniform}, gdi::bytesOf(bytes));
    TextureHandle target =
        d.createTexture({.format = Format::RGBA8,
                         .width = kSize,
                         .height = kSize,
                         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});

    // Eight vertical stripes, each drawn through a scissor: {pipeline, colour set before it or -1}.
    const std::array<std::pair<PipelineHandle, int>, 8> stripes = {{
        {a, 0},   // red
        {a, -1},  // still red: nothing changed
        {b, -1},  // another layout, nothing rebound: red must be pushed again
        {b, 1},   // green
        {a, -1},  // back to a: green
        {a, 2},   // blue
        {a, 0},   // red
        {b, -1},  // red
    }};
    const std::array<int, 8> expected = {0, 0, 0, 1, 1, 2, 0, 0};
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
    cmd->setUniformBuffer(1, ubo, 0, sizeof(Params));  // b's extra slot, set once
    for (uint32_t i = 0; i < stripes.size(); ++i) {
        cmd->setPipeline(stripes[i].first);
        if (stripes[i].second >= 0)
            cmd->setUniformBuffer(0, ubo, uint64_t(stripes[i].second) * kStride, sizeof(Params));
        cmd->setScissor({.x = int32_t(i * kSize / 8), .y = 0, .width = kSize / 8, .height = kSize});
        cmd->draw(3);
    }
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    Image img = d.readTexture(target);
    for (uint32_t i = 0; i < stripes.size(); ++i) {
        const auto& want = colors[size_t(expected[i])];
        for (uint32_t y : {0u, kSize / 2, kSize - 1}) {
            auto t = img.texel(i * kSize / 8 + kSize / 16, y);
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(t[size_t(c)], want[size_t(c)], 1.0 / 255)
                    << "stripe " << i << " row " << y;
        }
    }
}

// A draw whose pipeline declares a slot never bound in this recording is an error, even
// after earlier draws with other pipelines pushed descriptors.
TEST_P(BindingState, UnboundSlotStillFailsAfterOtherDraws) {
    Device& d = *device;
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")});
    PipelineHandle p = d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}});
    TextureHandle target = d.createTexture(
        {.format = Format::RGBA8, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}});
    cmd->setPipeline(p);
    EXPECT_THROW(cmd->draw(3), Error);
    EXPECT_THROW(cmd->draw(3), Error);  // still unbound: the check is not skipped the second time
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
}

// A renderer may create pipelines while recording (first use of a material). The bound
// pipeline must survive the pool growing underneath it, and the new ones must work at once.
TEST_P(BindingState, PipelinesCreatedMidRecording) {
    Device& d = *device;
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")});
    const GraphicsPipelineDesc desc{
        .vertexShader = vs,
        .fragmentShader = fs,
        .colorFormats = {Format::RGBA8},
        .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}},
        .debugName = "first"};
    const Params green{{0, 1, 0, 1}, {0.5f, 0, 0, 0}};
    BufferHandle ubo =
        d.createBuffer({.size = sizeof green, .usage = BufferUsage::Uniform}, gdi::bytesOf(green));
    TextureHandle target =
        d.createTexture({.format = Format::RGBA8,
                         .width = 16,
                         .height = 16,
                         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(d.createGraphicsPipeline(desc));
    std::vector<PipelineHandle> later;
    for (int i = 0; i < 40; ++i) later.push_back(d.createGraphicsPipeline(desc));  // the pool grows
    cmd->setScissor({.x = 0, .y = 0, .width = 8, .height = 16});
    EXPECT_NE(errorOf([&] { cmd->draw(3); }).find("pipeline 'first'"),
              std::string::npos);  // names the bound one
    cmd->setUniformBuffer(0, ubo);
    cmd->draw(3);  // left half, through the pipeline bound before the pool grew
    cmd->setPipeline(later.back());
    cmd->setScissor({.x = 8, .y = 0, .width = 8, .height = 16});
    cmd->draw(3);  // right half, through the newest one
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    Image img = d.readTexture(target);
    for (uint32_t x : {2u, 13u}) {
        auto t = img.texel(x, 8);
        EXPECT_NEAR(t[0], 0.0, 1.0 / 255) << "x " << x;
        EXPECT_NEAR(t[1], 1.0, 1.0 / 255) << "x " << x;
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(BindingState);

// GL records a bind that repeats the stream's last uniform bind (slot, buffer and size) in a
// dense form naming only the offset. A secondary list executed between two such binds binds its
// own buffer there, so the primary's next bind must name its buffer again: each stripe shows the
// colour its own bind selects, never the secondary list's.
TEST_P(BindingState, BindsAfterSecondaryListsNameTheirBuffer) {
    Device& d = *device;
    constexpr uint32_t kSize = 32, kStride = 256;
    DeviceObjects objects(d);
    auto vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    PipelineHandle p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}}));
    auto paramsOf = [&](std::initializer_list<std::array<float, 4>> colors) {
        std::vector<uint8_t> bytes(kStride * colors.size());
        size_t i = 0;
        for (const auto& c : colors) {
            Params params{{c[0], c[1], c[2], c[3]}, {0.5f, 0, 0, 0}};
            std::memcpy(&bytes[i++ * kStride], &params, sizeof params);
        }
        return objects.add(d.createBuffer({.size = bytes.size(), .usage = BufferUsage::Uniform},
                                          gdi::bytesOf(bytes)));
    };
    const BufferHandle primaryColors = paramsOf({{1, 0, 0, 1}, {0, 1, 0, 1}});  // red, green
    const BufferHandle secondaryColors = paramsOf({{0, 0, 1, 1}});              // blue
    TextureHandle target =
        objects.add(d.createTexture({.format = Format::RGBA8,
                                     .width = kSize,
                                     .height = kSize,
                                     .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
    const RenderPassDesc pass{.colors = {{.texture = target, .clear = {0, 0, 0, 1}}},
                              .secondaryLists = true};
    auto stripe = [&](CommandList& c, uint32_t i) {
        c.setScissor({.x = int32_t(i * kSize / 4), .y = 0, .width = kSize / 4, .height = kSize});
        c.draw(3);
    };
    auto part = d.createCommandList();
    part->beginSecondary(pass);
    part->setPipeline(p);
    part->setUniformBuffer(0, secondaryColors, 0, sizeof(Params));
    stripe(*part, 1);
    part->endSecondary();
    auto cmd = d.createCommandList();
    cmd->beginRenderPass(pass);
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, primaryColors, 0, sizeof(Params));  // red
    stripe(*cmd, 0);
    cmd->executeSecondary(*part);  // blue
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, primaryColors, kStride, sizeof(Params));  // green
    stripe(*cmd, 2);
    cmd->setUniformBuffer(0, primaryColors, 0, sizeof(Params));  // red
    stripe(*cmd, 3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image img = d.readTexture(target);
    const std::array<std::array<float, 4>, 4> expected = {
        {{1, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {1, 0, 0, 1}}};
    for (uint32_t i = 0; i < 4; ++i) {
        const auto t = img.texel(i * kSize / 4 + kSize / 8, kSize / 2);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(t[size_t(c)], expected[i][size_t(c)], 1.0 / 255) << "stripe " << i;
    }
}
