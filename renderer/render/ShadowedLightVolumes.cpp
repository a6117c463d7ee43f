#include "render/ShadowedLightVolumes.h"

#include <algorithm>

namespace fe::render {

ShadowedLightVolumes::ShadowedLightVolumes(TechniqueContext& c, const std::string& shader,
                                           const std::string& cubeShader,
                                           std::vector<gdi::Format> targets)
    : ctx_(c) {
    if (!c.shadows) return;
    // Only the shaders some shadowed light needs.
    const auto& lights = c.shadows->plan().shadowed;
    auto has = [&](bool cube) {
        return std::any_of(lights.begin(), lights.end(), [&](const ShadowedLight& l) {
            return (l.kind == ShadowKind::Cube) == cube;
        });
    };
    if (has(false)) volumes_ = std::make_unique<LightVolumes>(c.device, shader, targets);
    if (has(true)) cubeVolumes_ = std::make_unique<LightVolumes>(c.device, cubeShader, targets);
}

ShadowedLightVolumes::~ShadowedLightVolumes() = default;

void ShadowedLightVolumes::declare(graph::RenderGraph& g,
                                   const std::function<void(graph::PassBuilder&)>& setup,
                                   std::function<void(graph::PassContext&)> bindInputs,
                                   FrameConstantsFn frame) {
    if (!ctx_.shadows) return;
    ctx_.shadows->declare(g, [&](graph::RenderGraph& graph, const ShadowMaps::Light& light) {
        graph.addPass(
            "shadowed light " + std::to_string(light.index),
            [&](graph::PassBuilder& b) {
                b.sample(light.map);
                setup(b);
            },
            [this, light, bindInputs, frame](graph::PassContext& pc) {
                pc.beginRenderPass();
                bindInputs(pc);
                ctx_.shadows->bind(pc.cmd, pc, light);
                LightVolumes& v = light.kind == ShadowKind::Cube ? *cubeVolumes_ : *volumes_;
                v.drawRange(pc.cmd, ctx_.queue, ctx_.scene, frame ? frame() : ctx_.frameConstants,
                            ctx_.frame, light.gpuLight, 1);
                pc.cmd.endRenderPass();
            });
    });
}

}  // namespace fe::render
