// Example (f): the shader stages ports bring, on the abstract device alone (fe::gdi):
//  - a cube shaded by HLSL shaders (mesh.vert.hlsl, mesh.frag.hlsl: compiled by fe-hlsl at build
//    time, registers as slots, a glm matrix as mul(M, v));
//  - its normals drawn by a geometry shader (normals.geom: each vertex becomes a thin quad along
//    its normal, in yellow);
//  - a floor of 16 quad patches tessellated 8 x 8 and displaced in waves (terrain.tesc,
//    terrain.tese).
//   fe_example_stages [--backend NAME] [--out FILE.png] [--validation]
// Prints what it sees (each part's pixels found by colour) in words that are the same on every
// backend; the images agree within a few pixels (tests/check_png.py --like). The floor's patches
// are recorded on a second thread into a list of their own, and the cube's upload goes through
// the copy queue, which the frame waits for. Then four mistakes on purpose, each printed: the
// same gdi::Error on every backend.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <exception>
#include <future>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/Image.h"
#include "fe/gdi/ShaderRegistry.h"

using namespace fe::gdi;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

struct Frame {  // the uniform block every stage here reads at slot 0 (std140, HLSL's packing)
    glm::mat4 viewProj;
    glm::vec4 lightDir;
};

struct Vertex {
    glm::vec3 position, normal;
};

// A unit cube's 12 triangles, each face with its normal.
std::vector<Vertex> cube() {
    std::vector<Vertex> v;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 n(0), u(0), w(0);
            n[axis] = side, u[(axis + 1) % 3] = 1, w[(axis + 2) % 3] = 1;
            const glm::vec3 c = 0.6f * n;
            const glm::vec3 p[4] = {c + 0.6f * (-u - w), c + 0.6f * (u - w), c + 0.6f * (u + w),
                                    c + 0.6f * (-u + w)};
            for (int i : {0, 1, 2, 0, 2, 3}) v.push_back({p[i], n});
        }
    return v;
}

ShaderHandle shader(DeviceObjects& o, ShaderStage stage, const char* path) {
    return o.add(o.device().createShader({.stage = stage, .binary = fe::shaders::find(path)}));
}

}  // namespace

int main(int argc, char** argv) {
    std::string backend = "auto", out = "stages.png";
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            backend = argv[++i];
        else if (a == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (a == "--validation")
            validation = true;
        else {
            std::fprintf(stderr, "usage: %s [--backend NAME] [--out FILE.png] [--validation]\n",
                         argv[0]);
            return 2;
        }
    }
    try {
        auto device = createDevice({.backend = backend, .validation = validation});
        const DeviceFeatures& f = device->info().features;
        if (!f.geometryShaders || !f.tessellationShaders) {
            std::fprintf(stderr, "stages: %s has no %s shaders\n", device->info().backend.c_str(),
                         f.geometryShaders ? "tessellation" : "geometry");
            return 1;
        }
        DeviceObjects o(*device);
        // Vulkan's clip space (y down, depth 0 to 1) from glm: the zero-to-one projection, y flipped.
        glm::mat4 proj =
            glm::perspectiveRH_ZO(glm::radians(45.0f), float(kWidth) / kHeight, 0.1f, 20.0f);
        proj[1][1] = -proj[1][1];
        const Frame frame{proj * glm::lookAtRH(glm::vec3(2.6f, 2.0f, 3.6f), glm::vec3(0, -0.3f, 0),
                                               glm::vec3(0, 1, 0)),
                          glm::vec4(glm::normalize(glm::vec3(0.4f, 1.0f, 0.6f)), 0)};
        const BufferHandle frameUbo = o.add(device->createBuffer(
            {.size = sizeof frame, .usage = BufferUsage::Uniform, .debugName = "frame"},
            bytesOf(frame)));
        // The cube's vertices reach the GPU through the copy queue (a staging buffer, a copy), and
        // the frame waits for that submission's fence.
        const std::vector<Vertex> mesh = cube();
        const uint64_t meshBytes = mesh.size() * sizeof(Vertex);
        const BufferHandle staging = o.add(device->createBuffer({.size = meshBytes,
                                                                 .usage = BufferUsage::CopySrc,
                                                                 .access = MemoryAccess::Upload,
                                                                 .debugName = "cube staging"}));
        std::memcpy(device->map(staging), mesh.data(), meshBytes);
        const BufferHandle meshVb =
            o.add(device->createBuffer({.size = meshBytes,
                                        .usage = BufferUsage::Vertex | BufferUsage::CopyDst,
                                        .debugName = "cube"}));
        auto upload = device->createCommandList({.queue = QueueKind::Copy});
        upload->copyBuffer(meshVb, 0, staging, 0, meshBytes);
        const FenceValue uploaded = device->submit(*upload);
        std::vector<glm::vec2>
            patches;  // 4 x 4 patches over [-2, 2]^2, control points in quad order
        for (int z = 0; z < 4; ++z)
            for (int x = 0; x < 4; ++x) {
                const float x0 = -2.0f + x, z0 = -2.0f + z;
                for (glm::vec2 p : {glm::vec2(x0, z0), glm::vec2(x0 + 1, z0), glm::vec2(x0, z0 + 1),
                                    glm::vec2(x0 + 1, z0 + 1)})
                    patches.push_back(p);
            }
        const BufferHandle patchVb =
            o.add(device->createBuffer({.size = patches.size() * sizeof(glm::vec2),
                                        .usage = BufferUsage::Vertex,
                                        .debugName = "terrain patches"},
                                       bytesOf(patches)));

        const VertexBufferLayout meshLayout{
            .stride = sizeof(Vertex),
            .attributes = {{0, VertexFormat::Float3, 0}, {1, VertexFormat::Float3, 12}}};
        const DepthStencilState depth{
            .depthTest = true, .depthWrite = true, .depthCompare = CompareOp::LessOrEqual};
        const PipelineHandle shaded = o.add(device->createGraphicsPipeline(
            {.vertexShader = shader(o, ShaderStage::Vertex, "stages/mesh.vert.hlsl"),
             .fragmentShader = shader(o, ShaderStage::Fragment, "stages/mesh.frag.hlsl"),
             .vertexBuffers = {meshLayout},
             .depthStencil = depth,
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D32F,
             .debugName = "cube (HLSL)"}));
        const PipelineHandle normals = o.add(device->createGraphicsPipeline(
            {.vertexShader = shader(o, ShaderStage::Vertex, "stages/normals.vert"),
             .fragmentShader = shader(o, ShaderStage::Fragment, "stages/flat.frag"),
             .geometryShader = shader(o, ShaderStage::Geometry, "stages/normals.geom"),
             .vertexBuffers = {meshLayout},
             .depthStencil = depth,
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D32F,
             .debugName = "normals (geometry shader)"}));
        const PipelineHandle terrain = o.add(device->createGraphicsPipeline(
            {.vertexShader = shader(o, ShaderStage::Vertex, "stages/terrain.vert"),
             .fragmentShader = shader(o, ShaderStage::Fragment, "stages/terrain.frag"),
             .tessControlShader = shader(o, ShaderStage::TessControl, "stages/terrain.tesc"),
             .tessEvaluationShader = shader(o, ShaderStage::TessEvaluation, "stages/terrain.tese"),
             .patchControlPoints = 4,
             .vertexBuffers = {{.stride = 8, .attributes = {{0, VertexFormat::Float2, 0}}}},
             .topology = PrimitiveTopology::PatchList,
             .depthStencil = depth,
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D32F,
             .debugName = "terrain (tessellated)"}));

        const TextureHandle color = o.add(
            device->createTexture({.width = kWidth,
                                   .height = kHeight,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                                   .debugName = "stages"}));
        const TextureHandle depthTarget =
            o.add(device->createTexture({.format = Format::D32F,
                                         .width = kWidth,
                                         .height = kHeight,
                                         .usage = TextureUsage::RenderTarget,
                                         .debugName = "stages depth"}));
        const RenderPassDesc pass{.colors = {{.texture = color, .load = LoadOp::Load}},
                                  .depth = {.texture = depthTarget, .load = LoadOp::Load}};
        // The floor recorded on another thread, into a list submitted first.
        std::future<std::unique_ptr<CommandList>> floor = std::async(std::launch::async, [&] {
            auto list = device->createCommandList();
            list->beginRenderPass(
                {.colors = {{.texture = color, .clear = {0.02f, 0.02f, 0.03f, 1}}},
                 .depth = {.texture = depthTarget, .clearDepth = 1.0f}});
            list->setUniformBuffer(0, frameUbo);
            list->setPipeline(terrain);
            list->setVertexBuffer(0, patchVb);
            list->draw(uint32_t(patches.size()));
            list->endRenderPass();
            return list;
        });
        auto cmd = device->createCommandList();
        cmd->beginRenderPass(pass);
        cmd->setUniformBuffer(0, frameUbo);
        cmd->setPipeline(shaded);
        cmd->setVertexBuffer(0, meshVb);
        cmd->draw(uint32_t(mesh.size()));
        cmd->setPipeline(normals);
        cmd->draw(uint32_t(mesh.size()));
        cmd->endRenderPass();
        std::unique_ptr<CommandList> floorList = floor.get();
        CommandList* frameLists[] = {floorList.get(), cmd.get()};
        device->wait(device->submit(frameLists, {.waitFor = uploaded}));
        const Image image = device->readTexture(color);
        writePng(image, out);

        // Each part by its colour: yellow normals, red-dominant mesh, blue-green terrain.
        uint32_t mesh_ = 0, normals_ = 0, terrain_ = 0, terrainBright = 0;
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                const auto t = image.texel(x, y);
                if (t[0] > 0.9f && t[1] > 0.9f && t[2] < 0.1f)
                    ++normals_;
                else if (t[0] > t[1] + 0.2f && t[0] > 0.2f)
                    ++mesh_;
                else if (t[2] > 0.5f && t[0] < 0.1f)
                    ++terrain_, terrainBright += t[1] > 0.6f;
            }
        const uint32_t total = kWidth * kHeight;
        std::printf("stages on %s: wrote %s\n", device->info().backend.c_str(), out.c_str());
        std::printf("the cube (HLSL) covers %s of the image\n",
                    mesh_ > total / 20 ? "more than 5 %" : "too little");
        std::printf("its normals (geometry shader) are drawn: %s\n", normals_ > 100 ? "yes" : "no");
        std::printf("the floor (tessellated, displaced) covers %s, rising in places: %s\n",
                    terrain_ > total / 5 ? "more than 20 %" : "too little",
                    terrainBright > 100 && terrainBright < terrain_ ? "yes" : "no");
        // Mistakes on purpose: each refused before any native call, in the same words everywhere.
        auto mistake = [&](int n, const std::function<void()>& f) {
            try {
                f();
                std::printf("mistake %d: not refused\n", n);
            } catch (const Error& e) {
                std::printf("mistake %d: %s\n", n, e.what());
            }
        };
        mistake(1, [&] {  // tessellation shaders drawing triangles
            o.add(device->createGraphicsPipeline(
                {.vertexShader = shader(o, ShaderStage::Vertex, "stages/terrain.vert"),
                 .fragmentShader = shader(o, ShaderStage::Fragment, "stages/terrain.frag"),
                 .tessControlShader = shader(o, ShaderStage::TessControl, "stages/terrain.tesc"),
                 .tessEvaluationShader =
                     shader(o, ShaderStage::TessEvaluation, "stages/terrain.tese"),
                 .patchControlPoints = 4,
                 .colorFormats = {Format::RGBA8},
                 .debugName = "triangles"}));
        });
        mistake(2, [&] {  // a vertex shader where the geometry shader goes
            o.add(device->createGraphicsPipeline(
                {.vertexShader = shader(o, ShaderStage::Vertex, "stages/normals.vert"),
                 .fragmentShader = shader(o, ShaderStage::Fragment, "stages/flat.frag"),
                 .geometryShader = shader(o, ShaderStage::Vertex, "stages/normals.vert"),
                 .vertexBuffers = {meshLayout},
                 .colorFormats = {Format::RGBA8},
                 .debugName = "no geometry"}));
        });
        mistake(3, [&] {  // a render pass on a copy-queue list, on another thread
            std::async(std::launch::async, [&] {
                auto list = device->createCommandList({.queue = QueueKind::Copy});
                list->beginRenderPass(pass);
            }).get();
        });
        mistake(4, [&] {  // rendering into a BGRA texture seen as RGBA (sampled only), on a thread
            const TextureHandle bgra = o.add(
                device->createTexture({.format = Format::BGRA8,
                                       .width = 8,
                                       .height = 8,
                                       .usage = TextureUsage::Sampled | TextureUsage::RenderTarget,
                                       .viewFormats = {Format::RGBA8}}));
            const TextureHandle seenAsRgba =
                o.add(device->createTextureView(bgra, {.format = Format::RGBA8}));
            std::async(std::launch::async, [&] {
                auto list = device->createCommandList();
                list->beginRenderPass({.colors = {{.texture = seenAsRgba}}});
            }).get();
        });
        const bool seen = mesh_ > total / 20 && normals_ > 100 && terrain_ > total / 5 &&
                          terrainBright > 100 && terrainBright < terrain_;
        std::printf("%s\n", seen ? "every stage seen" : "a stage is missing from the image");
        if (validation && device->validationErrorCount() != 0) {
            std::fprintf(stderr, "stages: %u validation error(s)\n",
                         device->validationErrorCount());
            return 1;
        }
        return seen ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stages: %s\n", e.what());
        return 1;
    }
}
