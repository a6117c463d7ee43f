// Invalid descriptions give clear errors, never crashes, on every backend.
#include <gtest/gtest.h>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

class DeviceErrors : public fe::testing::BackendTest {};

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

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
    EXPECT_NE(errorOf([&] { device->writeBuffer(b, 8, data, 16); }).find("exceeds its size 16"), std::string::npos);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(DeviceErrors);
