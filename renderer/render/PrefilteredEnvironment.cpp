#include "render/PrefilteredEnvironment.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"
#include "render/SplitSumTable.h"

namespace fe::render {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr gdi::Format kPrefilteredFormat = gdi::Format::RGBA32F;  // bright suns exceed half floats
constexpr gdi::Format kLutFormat = gdi::Format::RGBA32F;

// The nine real SH basis functions at unit d (R&H 2001's constants).
std::array<double, 9> basis(const glm::dvec3& d) {
    return {0.282095,
            0.488603 * d.y,
            0.488603 * d.z,
            0.488603 * d.x,
            1.092548 * d.x * d.y,
            1.092548 * d.y * d.z,
            0.315392 * (3.0 * d.z * d.z - 1.0),
            1.092548 * d.x * d.z,
            0.546274 * (d.x * d.x - d.y * d.y)};
}

// Blocks of std140 uniforms, one per draw, each at an offset the device allows.
template <class T>
gdi::BufferHandle uniformBlocks(gdi::DeviceObjects& objects, const std::vector<T>& blocks,
                                uint64_t& stride, const char* name) {
    gdi::Device& device = objects.device();
    const uint64_t align =
        std::max<uint64_t>(16, device.info().limits.uniformBufferOffsetAlignment);
    stride = (sizeof(T) + align - 1) / align * align;
    std::vector<std::byte> bytes(stride * blocks.size());
    for (size_t i = 0; i < blocks.size(); ++i)
        std::memcpy(bytes.data() + i * stride, &blocks[i], sizeof(T));
    return objects.add(device.createBuffer(
        {.size = bytes.size(), .usage = gdi::BufferUsage::Uniform, .debugName = name},
        gdi::ByteSpan(bytes)));
}
}  // namespace

std::array<glm::dvec3, 9> radianceSH(const assets::Environment& e) {
    std::array<glm::dvec3, 9> sh{};
    auto add = [&](const glm::dvec3& d, double solidAngle) {
        const glm::dvec3 L = e.radiance(d) * solidAngle;
        const auto y = basis(d);
        for (int i = 0; i < 9; ++i) sh[i] += L * y[i];
    };
    const bool image = e.kind == assets::Environment::Kind::Image;
    const uint32_t rows = image ? e.height : 512, cols = image ? e.width : 1024;
    // directionFromEquirect's sines and cosines, each column's and row's taken once.
    std::vector<double> sinPhi(cols), cosPhi(cols);
    for (uint32_t u = 0; u < cols; ++u) {
        const double phi = ((u + 0.5) / cols - 0.5) * 2.0 * kPi;
        sinPhi[u] = std::sin(phi), cosPhi[u] = std::cos(phi);
    }
    for (uint32_t v = 0; v < rows; ++v) {
        // The row's exact solid angle, shared by its columns.
        const double solidAngle =
            (std::cos(v * kPi / rows) - std::cos((v + 1) * kPi / rows)) * (2.0 * kPi / cols);
        const double theta = (v + 0.5) / rows * kPi;
        const double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
        for (uint32_t u = 0; u < cols; ++u)
            add({sinTheta * sinPhi[u], cosTheta, -sinTheta * cosPhi[u]}, solidAngle);
    }
    return sh;
}

glm::dvec3 irradianceFromSH(const std::array<glm::dvec3, 9>& L, const glm::dvec3& n) {
    const double c1 = 0.429043, c2 = 0.511664, c3 = 0.743125, c4 = 0.886227, c5 = 0.247708;
    const glm::dvec3 E = c1 * L[8] * (n.x * n.x - n.y * n.y) + c3 * L[6] * n.z * n.z + c4 * L[0] -
                         c5 * L[6] +
                         2.0 * c1 * (L[4] * n.x * n.y + L[7] * n.x * n.z + L[5] * n.y * n.z) +
                         2.0 * c2 * (L[3] * n.x + L[1] * n.y + L[2] * n.z);
    return glm::max(E, glm::dvec3(0.0));
}

PrefilteredEnvironment::PrefilteredEnvironment(gdi::Device& device,
                                               const assets::Environment& environment,
                                               gdi::TextureHandle cube,
                                               gdi::SamplerHandle cubeSampler,
                                               gdi::ShaderHandle fullscreenVs)
    : objects_(device) {
    prefiltered_ = objects_.add(
        device.createTexture({.dimension = gdi::TextureDimension::TextureCube,
                              .format = kPrefilteredFormat,
                              .width = kFaceSize,
                              .height = kFaceSize,
                              .depthOrLayers = 6,
                              .mipLevels = kLevels,
                              .usage = gdi::TextureUsage::Sampled | gdi::TextureUsage::RenderTarget,
                              .debugName = "prefiltered environment"}));
    // The split-sum table depends on no environment: compiled in (SplitSumTable.h), uploaded.
    static_assert(kLutSize == kSplitSumSize && kLutSamples == kSplitSumSamples);
    lut_ = objects_.add(device.createTexture({.format = kLutFormat,
                                              .width = kLutSize,
                                              .height = 2 * kLutSize,
                                              .debugName = "split-sum table"}));
    device.writeTexture(lut_, {}, gdi::bytesOf(bakedSplitSumTable()));
    sampler_ = objects_.add(device.createSampler({.mipFilter = gdi::MipFilter::Linear,
                                                  .addressU = gdi::AddressMode::ClampToEdge,
                                                  .addressV = gdi::AddressMode::ClampToEdge,
                                                  .addressW = gdi::AddressMode::ClampToEdge,
                                                  .debugName = "prefiltered environment"}));
    std::array<glm::vec4, 9> coefficients;
    const std::array<glm::dvec3, 9> sh = radianceSH(environment);
    for (int i = 0; i < 9; ++i) coefficients[i] = glm::vec4(glm::vec3(sh[i]), 0.0f);
    sh_ = objects_.add(device.createBuffer({.size = sizeof(coefficients),
                                            .usage = gdi::BufferUsage::Uniform,
                                            .debugName = "irradiance SH"},
                                           gdi::bytesOf(coefficients)));

    struct Block {
        glm::vec4 params;
        glm::uvec4 samples;
    };
    const gdi::TextureDesc source = device.desc(cube);
    // Solid angle of a source texel at level 0 (the average over a face: 4 pi / 6 faces).
    const float texelSolidAngle = float(4.0 * kPi / (6.0 * double(source.width) * source.width));
    std::vector<Block> blocks;
    for (uint32_t level = 0; level < kLevels; ++level)
        for (uint32_t face = 0; face < 6; ++face)
            blocks.push_back({glm::vec4(float(face), float(kFaceSize >> level),
                                        float(level) / float(kLevels - 1), texelSolidAngle),
                              glm::uvec4(kPrefilterSamples, 0, 0, 0)});
    // What draws the cube: freed once it is drawn, or when something throws before.
    gdi::DeviceObjects temporary(device);
    uint64_t stride = 0;
    const gdi::BufferHandle ubo = uniformBlocks(temporary, blocks, stride, "prefilter blocks");
    auto shader = [&](const char* name) {
        return temporary.add(device.createShader(
            {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(name)}));
    };
    const gdi::ShaderHandle prefilterFs = shader("scene/ibl_prefilter.frag");
    const gdi::PipelineHandle prefilter =
        temporary.add(device.createGraphicsPipeline({.vertexShader = fullscreenVs,
                                                     .fragmentShader = prefilterFs,
                                                     .colorFormats = {kPrefilteredFormat},
                                                     .debugName = "prefilter environment"}));
    auto cmd = device.createCommandList();
    for (uint32_t level = 0; level < kLevels; ++level)
        for (uint32_t face = 0; face < 6; ++face) {
            cmd->beginRenderPass({.colors = {{.texture = prefiltered_,
                                              .mipLevel = level,
                                              .layer = face,
                                              .load = gdi::LoadOp::DontCare}},
                                  .debugName = "prefilter face"});
            cmd->setPipeline(prefilter);
            cmd->setUniformBuffer(kSlotObject, ubo, (level * 6 + face) * stride, sizeof(Block));
            cmd->setTexture(kSlotEnvironment, cube, cubeSampler);
            cmd->draw(3);
            cmd->endRenderPass();
        }
    device.wait(device.submit(*cmd));
}

}  // namespace fe::render
