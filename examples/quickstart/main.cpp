// README's C++ quick start, word for word (tests/readme_snippet.sh keeps the two the same):
// a device, a pipeline, a draw, the image read back.
#include <cstdio>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

int main() {
    auto device = createDevice({.backend = "auto"});  // Vulkan, else GL (also FE_BACKEND)
    const ShaderHandle vs = device->createShader(
        {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("triangle/triangle.vert")});
    const ShaderHandle fs = device->createShader(
        {.stage = ShaderStage::Fragment, .binary = fe::shaders::find("triangle/triangle.frag")});
    const TextureHandle target =
        device->createTexture({.format = Format::RGBA8,
                               .width = 128,
                               .height = 128,
                               .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
    const PipelineHandle pipeline = device->createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});

    auto cmd = device->createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0.1f, 0.1f, 0.1f, 1.0f}}}});
    cmd->setPipeline(pipeline);
    cmd->draw(3);  // the vertex shader makes the triangle's corners from FE_VERTEX_ID
    cmd->endRenderPass();
    device->wait(device->submit(*cmd));

    writePng(device->readTexture(target), "quickstart.png");
    std::printf("drew a triangle on %s\n", device->info().backend.c_str());
    for (auto h : {vs, fs}) device->destroy(h);
    device->destroy(pipeline);
    device->destroy(target);
}
