#include "render/BackgroundPass.h"

#include <cmath>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

Background::Kind resolveBackground(const Background& background, bool sceneHasEnvironment) {
    if (background.kind == Background::Kind::Environment && !sceneHasEnvironment)
        throw gdi::Error(
            "an environment background needs an environment (--environment FILE.hdr|builtin:sky)");
    for (int c = 0; c < 3; ++c)
        if (!(background.color[c] >= 0.0f && background.color[c] <= 1.0f))
            throw gdi::Error("the background colour's channels must lie in [0, 1] (sRGB-encoded)");
    if (background.kind == Background::Kind::Auto)
        return sceneHasEnvironment ? Background::Kind::Environment : Background::Kind::Auto;
    return background.kind;
}

BackgroundPass::BackgroundPass(gdi::Device& device, CommandQueue& queue,
                               const RenderSettings& settings, const EnvironmentMap* environment,
                               const UploadAllocation& frameConstants)
    : objects_(device),
      queue_(queue),
      settings_(settings),
      environment_(environment),
      frameConstants_(frameConstants),
      kind_(resolveBackground(settings.background, environment != nullptr)) {
    if (kind_ != Background::Kind::Color && kind_ != Background::Kind::Transparent) return;
    vs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/background.vert")}));
    fs_ =
        objects_.add(device.createShader({.stage = gdi::ShaderStage::Fragment,
                                          .binary = shaders::find("scene/background_color.frag")}));
    // The far-plane triangle passes LessOrEqual where nothing was drawn, Greater where a surface was.
    uncovered_ = objects_.add(device.createGraphicsPipeline(
        {.vertexShader = vs_,
         .fragmentShader = fs_,
         .depthStencil = {.depthTest = true,
                          .depthWrite = false,
                          .depthCompare = gdi::CompareOp::LessOrEqual},
         .colorFormats = {kRadianceFormat},
         .depthFormat = kSceneDepthFormat,
         .debugName = "background uncovered"}));
    covered_ = objects_.add(
        device.createGraphicsPipeline({.vertexShader = vs_,
                                       .fragmentShader = fs_,
                                       .depthStencil = {.depthTest = true,
                                                        .depthWrite = false,
                                                        .depthCompare = gdi::CompareOp::Greater},
                                       .blend = {{.writeMask = gdi::ColorMask::A}},
                                       .colorFormats = {kRadianceFormat},
                                       .depthFormat = kSceneDepthFormat,
                                       .debugName = "background covered"}));
}

void BackgroundPass::declare(graph::RenderGraph& g, graph::TextureId radiance,
                             graph::TextureId depth) {
    if (kind_ == Background::Kind::Auto) return;
    g.addPass(
        "background",
        [&](graph::PassBuilder& b) {
            b.colorTarget(radiance, gdi::LoadOp::Load);
            b.depthTarget(depth, gdi::LoadOp::Load);
        },
        [this](graph::PassContext& pc) {
            pc.beginRenderPass();
            if (kind_ == Background::Kind::Environment) {
                environment_->drawBackground(pc.cmd, frameConstants_);
            } else {
                for (const auto& [pipeline, value] :
                     {std::pair{uncovered_, glm::vec4(0.0f)}, {covered_, glm::vec4(0, 0, 0, 1)}}) {
                    const UploadAllocation block = queue_.upload(value);
                    pc.cmd.setPipeline(pipeline);
                    pc.cmd.setUniformBuffer(kSlotObject, block.buffer, block.offset, block.size);
                    pc.cmd.draw(3);
                }
            }
            pc.cmd.endRenderPass();
        });
}

glm::uvec2 BackgroundPass::displayConstants() const {
    if (!settings_.debugView.empty())
        return glm::uvec2(0);  // a debug view shows its texture as it is
    const glm::vec3& c = settings_.background.color;
    auto byte = [](float v) { return uint32_t(std::lround(v * 255.0f)); };
    const uint32_t packed =
        byte(c.r) | byte(c.g) << 8 | byte(c.b) << 16 | 255u << 24;  // unpackUnorm4x8's order
    switch (kind_) {
        case Background::Kind::Color:
            return {1u, packed};
        case Background::Kind::Transparent:
            return {2u, 0u};
        default:
            return glm::uvec2(0);
    }
}

}  // namespace fe::render
