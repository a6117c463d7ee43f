// Example (a): a triangle on the abstract device alone (fe::gdi), the same code on every backend.
//   fe_example_triangle [--backend auto|vulkan|gl-egl|gl-osmesa|vulkan-glfw|gl-glfw] [--out FILE.png] [--window] [--validation]
// Headless, it draws one frame into a texture, reads it back and checks its middle pixel (exit 1
// if the device drew something else); with --window it shows the triangle until the window closes.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

int main(int argc, char** argv) {
    std::string backend = "auto", out = "triangle.png";
    bool window = false, validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            backend = argv[++i];
        else if (a == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (a == "--window")
            window = true;
        else if (a == "--validation")
            validation = true;  // tests: Khronos layer / GL debug output on, errors fail
        else {
            std::fprintf(stderr,
                         "usage: %s [--backend NAME] [--out FILE.png] [--window] [--validation]\n",
                         argv[0]);
            return 2;
        }
    }
    try {
        auto device =
            createDevice({.backend = backend, .validation = validation, .window = window});
        const ShaderHandle vs = device->createShader(
            {.stage = ShaderStage::Vertex, .binary = fe::shaders::find("triangle/triangle.vert")});
        const ShaderHandle fs =
            device->createShader({.stage = ShaderStage::Fragment,
                                  .binary = fe::shaders::find("triangle/triangle.frag")});
        const TextureHandle target =
            device->createTexture({.format = Format::RGBA8,
                                   .width = 128,
                                   .height = 128,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                                   .debugName = "triangle target"});
        const PipelineHandle pipeline =
            device->createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = fs,
                                            .colorFormats = {Format::RGBA8},
                                            .debugName = "triangle"});
        auto frame = [&] {
            auto cmd = device->createCommandList();
            cmd->beginRenderPass(
                {.colors = {{.texture = target, .clear = {0.1f, 0.1f, 0.1f, 1.0f}}}});
            cmd->setPipeline(pipeline);
            cmd->draw(3);
            cmd->endRenderPass();
            device->wait(device->submit(*cmd));
        };
        frame();
        const Image image = device->readTexture(target);
        writePng(image, out);
        // Blue, green and red meet at the centroid in roughly equal parts.
        const auto mid = image.texel(64, 80);
        const bool drawn = mid[0] > 0.15f && mid[1] > 0.15f && mid[2] > 0.15f;
        std::printf("%s: %s, middle pixel (%.2f %.2f %.2f), wrote %s\n",
                    device->info().backend.c_str(), drawn ? "triangle drawn" : "TRIANGLE MISSING",
                    mid[0], mid[1], mid[2], out.c_str());
        while (window && device->present(target)) frame();
        device->destroy(pipeline);
        device->destroy(target);
        device->destroy(vs);
        device->destroy(fs);
        if (device->validationErrorCount())
            std::printf("%u validation error(s)\n", unsigned(device->validationErrorCount()));
        return drawn && device->validationErrorCount() == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_triangle: %s\n", e.what());
        return 1;
    }
}
