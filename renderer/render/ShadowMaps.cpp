#include "render/ShadowMaps.h"

#include <string>

#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
constexpr gdi::Format kShadowMapFormat = gdi::Format::D32F;
}  // namespace

ShadowMaps::ShadowMaps(gdi::Device& device, CommandQueue& queue, GeometryRenderer& geometry,
                       const ShadowPlan& plan, const ShadowSettings& settings)
    : objects_(device), queue_(queue), geometry_(geometry), plan_(plan), settings_(settings) {
    // Linear comparison: the device's 2x2 percentage-closer filter (PCF); Nearest: one texel.
    const gdi::Filter filter = settings.pcf ? gdi::Filter::Linear : gdi::Filter::Nearest;
    sampler_ = objects_.add(device.createSampler({.minFilter = filter,
                                                  .magFilter = filter,
                                                  .addressU = gdi::AddressMode::ClampToEdge,
                                                  .addressV = gdi::AddressMode::ClampToEdge,
                                                  .addressW = gdi::AddressMode::ClampToEdge,
                                                  .compareEnable = true,
                                                  .compare = gdi::CompareOp::LessOrEqual}));
    constants_.resize(plan.shadowed.size());
    layers_.resize(plan.shadowed.size());
    lightPositions_.resize(plan.shadowed.size());
}

void ShadowMaps::update(const assets::Camera& camera, float aspect, const assets::AABB& bounds,
                        const std::vector<assets::Light>& sceneLights) {
    objectConstants_.clear();
    for (size_t i = 0; i < plan_.shadowed.size(); ++i) {
        const ShadowedLight& s = plan_.shadowed[i];
        const assets::Light& light = sceneLights.at(s.light);
        const ShadowProjection p =
            shadowProjection(light, s.kind, s.layers, camera, aspect, bounds, settings_.mapSize);
        Constants c{};
        for (uint32_t l = 0; l < 4 && l < s.layers; ++l) c.viewProj[l] = p.viewProj[l];
        c.cascadeEnds = p.cascadeEnds;
        c.texelWorld = p.texelWorld;
        if (s.kind == ShadowKind::Cube)
            c.depthParams =
                glm::vec4(p.farPlane / (p.farPlane - p.nearPlane),
                          -p.nearPlane * p.farPlane / (p.farPlane - p.nearPlane), 0.0f, 0.0f);
        c.params = glm::uvec4(plan_.unshadowedCount + uint32_t(i),
                              s.kind == ShadowKind::Cascades ? s.layers : 0u, 0u, 0u);
        constants_[i] = queue_.upload(c);
        layers_[i].clear();
        for (uint32_t l = 0; l < s.layers; ++l) {
            FrameConstants fc{};
            fc.viewProj = fc.viewProjFromEye = p.viewProj[l];  // the eye at the origin: world space
            fc.invViewProj = fc.invViewProjFromEye = glm::inverse(p.viewProj[l]);
            layers_[i].push_back(queue_.upload(fc));
        }
        // Directional casters are sorted from the sun's side of the scene.
        lightPositions_[i] = s.kind == ShadowKind::Cascades
                                 ? bounds.center() - light.direction * glm::length(bounds.size())
                                 : light.position;
    }
}

void ShadowMaps::declare(graph::RenderGraph& g, const Accumulate& accumulate) {
    static const char* faces[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (size_t i = 0; i < plan_.shadowed.size(); ++i) {
        const ShadowedLight& s = plan_.shadowed[i];
        const std::string name = "shadow " + std::to_string(i);
        const graph::TextureId map = g.createTexture(
            name + " map",
            {.format = kShadowMapFormat,
             .width = settings_.mapSize,
             .height = settings_.mapSize,
             .dimension = s.kind == ShadowKind::Cube ? gdi::TextureDimension::TextureCube
                                                     : gdi::TextureDimension::Texture2DArray,
             .layers = s.layers});
        for (uint32_t l = 0; l < s.layers; ++l) {
            const std::string layer = s.kind == ShadowKind::Cube ? std::string(" face ") + faces[l]
                                      : s.kind == ShadowKind::Cascades
                                          ? " cascade " + std::to_string(l)
                                          : std::string();
            g.addPass(
                name + layer,
                [&](graph::PassBuilder& b) { b.depthTarget(map, gdi::LoadOp::Clear, 1.0f, l); },
                [this, i, l](graph::PassContext& pc) {
                    pc.beginRenderPass();
                    geometry_.draw(pc.cmd, queue_, MeshPass::ShadowCaster,
                                   {{}, kShadowMapFormat, 1}, layers_[i][l], lightPositions_[i],
                                   &objectConstants_);
                    pc.cmd.endRenderPass();
                });
        }
        accumulate(g, Light{.index = uint32_t(i),
                            .gpuLight = plan_.unshadowedCount + uint32_t(i),
                            .kind = s.kind,
                            .map = map,
                            .last = i + 1 == plan_.shadowed.size()});
    }
}

void ShadowMaps::bind(gdi::CommandList& cmd, const graph::PassContext& pc,
                      const Light& light) const {
    const UploadAllocation& c = constants_[light.index];
    cmd.setUniformBuffer(kSlotShadow, c.buffer, c.offset, c.size);
    cmd.setTexture(kSlotShadowMap, pc.texture(light.map), sampler_);
}

}  // namespace fe::render
