#include "render/EnvironmentMap.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

namespace {
constexpr double kPi = 3.14159265358979323846;
glm::vec4 v4(const glm::dvec3& v) { return glm::vec4(glm::vec3(v), 0.0f); }
}  // namespace

void EnvironmentLight::bind(gdi::CommandList& cmd) const {
    cmd.setTexture(kSlotEnvironment, cube, sampler);
    if (!prefiltered()) return;
    cmd.setUniformBuffer(kSlotIblSh, sh);
    cmd.setTexture(kSlotIblLut, lut, sampler);
}

std::string EnvironmentLight::shader(const std::string& sampled) const {
    if (!prefiltered()) return sampled;
    return sampled.substr(0, sampled.size() - 5) + "_prefiltered.frag";
}

EnvironmentMap::EnvironmentMap(gdi::Device& device, const assets::Environment& e,
                               gdi::ShaderHandle fullscreenVs, uint32_t faceSize)
    : objects_(device) {
    const uint32_t mips = uint32_t(std::floor(std::log2(double(faceSize)))) + 1;
    cube_ = objects_.add(device.createTexture(
        {.dimension = gdi::TextureDimension::TextureCube,
         .format = kFormat,
         .width = faceSize,
         .height = faceSize,
         .depthOrLayers = 6,
         .mipLevels = mips,
         .usage = gdi::TextureUsage::Sampled | gdi::TextureUsage::RenderTarget |
                  gdi::TextureUsage::CopySrc | gdi::TextureUsage::CopyDst,
         .debugName = "environment cube"}));
    sampler_ = objects_.add(device.createSampler({.mipFilter = gdi::MipFilter::Linear,
                                                  .addressU = gdi::AddressMode::ClampToEdge,
                                                  .addressV = gdi::AddressMode::ClampToEdge,
                                                  .addressW = gdi::AddressMode::ClampToEdge,
                                                  .debugName = "environment"}));

    // The faces: one full-screen triangle each, into mip 0 of that face. What draws them is
    // freed once they are drawn, or when something throws before.
    gdi::DeviceObjects temporary(device);
    const bool image = e.kind == assets::Environment::Kind::Image;
    const gdi::ShaderHandle fs = temporary.add(device.createShader(
        {.stage = gdi::ShaderStage::Fragment,
         .binary = shaders::find(image ? "scene/env_equirect.frag" : "scene/env_sky.frag")}));
    gdi::TextureHandle source;
    gdi::SamplerHandle sourceSampler;
    if (image) {
        source = temporary.add(device.createTexture({.format = gdi::Format::RGBA32F,
                                                     .width = e.width,
                                                     .height = e.height,
                                                     .debugName = "environment equirect"}));
        std::vector<float> rgba(size_t(e.width) * e.height * 4, 1.0f);
        for (size_t i = 0; i < size_t(e.width) * e.height; ++i)
            for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = e.rgb[i * 3 + c];
        device.writeTexture(source, {}, gdi::bytesOf(rgba));
        sourceSampler =
            temporary.add(device.createSampler({.addressU = gdi::AddressMode::Repeat,
                                                .addressV = gdi::AddressMode::ClampToEdge,
                                                .debugName = "environment equirect"}));
    }
    const gdi::PipelineHandle faces =
        temporary.add(device.createGraphicsPipeline({.vertexShader = fullscreenVs,
                                                     .fragmentShader = fs,
                                                     .colorFormats = {kFormat},
                                                     .debugName = "environment faces"}));
    const assets::SkyModel& sky = e.sky;
    std::vector<Params> params(6);
    for (uint32_t f = 0; f < 6; ++f)
        params[f] = {glm::vec4(float(f), float(faceSize), 0, 0),
                     v4(sky.zenith),
                     v4(sky.horizon),
                     v4(sky.ground),
                     v4(sky.sunDirection),
                     v4(sky.sunRadiance),
                     glm::vec4(float(std::cos(sky.sunOuterDegrees * kPi / 180.0)),
                               float(std::cos(sky.sunInnerDegrees * kPi / 180.0)), 0, 0)};
    // One uniform block per face, each at an offset the device's alignment allows.
    const uint64_t align =
        std::max<uint64_t>(16, device.info().limits.uniformBufferOffsetAlignment);
    const uint64_t stride = (sizeof(Params) + align - 1) / align * align;
    std::vector<std::byte> blocks(stride * 6);
    for (uint32_t f = 0; f < 6; ++f)
        std::memcpy(blocks.data() + f * stride, &params[f], sizeof(Params));
    const gdi::BufferHandle ubo =
        temporary.add(device.createBuffer({.size = blocks.size(),
                                           .usage = gdi::BufferUsage::Uniform,
                                           .debugName = "environment faces"},
                                          gdi::ByteSpan(blocks)));
    auto cmd = device.createCommandList();
    for (uint32_t f = 0; f < 6; ++f) {
        gdi::RenderPassDesc rp{
            .colors = {{.texture = cube_, .layer = f, .load = gdi::LoadOp::DontCare}},
            .debugName = "environment face"};
        cmd->beginRenderPass(rp);
        cmd->setPipeline(faces);
        cmd->setUniformBuffer(kSlotObject, ubo, f * stride, sizeof(Params));
        if (image) cmd->setTexture(kSlotEnvironmentSource, source, sourceSampler);
        cmd->draw(3);
        cmd->endRenderPass();
    }
    cmd->generateMips(cube_);
    device.wait(device.submit(*cmd));
    temporary.clear();

    backgroundVs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/background.vert")}));
    backgroundFs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/background.frag")}));
    background_ = objects_.add(device.createGraphicsPipeline(
        {.vertexShader = backgroundVs_,
         .fragmentShader = backgroundFs_,
         .depthStencil = {.depthTest = true,
                          .depthWrite = false,
                          .depthCompare = gdi::CompareOp::LessOrEqual},
         .colorFormats = {kRadianceFormat},
         .depthFormat = kSceneDepthFormat,
         .debugName = "background"}));
}

void EnvironmentMap::drawBackground(gdi::CommandList& cmd, const UploadAllocation& fc) const {
    cmd.setPipeline(background_);
    cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
    cmd.setTexture(kSlotEnvironment, cube_, sampler_);
    cmd.draw(3);
}

}  // namespace fe::render
