#include "render/LightPrepassRenderer.h"

#include "render/ShaderSlots.h"

namespace fe::render {

LightPrepassRenderer::LightPrepassRenderer(TechniqueContext& c, bool packed) : TechniqueRenderer(c), packed_(packed) {
    volumes_ = std::make_unique<LightVolumes>(
        c.device, packed ? "scene/lpp_light.frag" : "scene/lpp_light_unpacked.frag", std::vector{kLightBuffer},
        std::vector<gdi::BindingSlot>{{kSlotGBuffer1, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment},
                                      {kSlotDepth, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment}});
}

LightPrepassRenderer::~LightPrepassRenderer() = default;

void LightPrepassRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    const RenderSettings& s = ctx_.settings;
    const gdi::Format normalFormat = packed_ ? kPackedNormals : kUnpackedNormals;
    const graph::TextureId normals = g.createTexture(packed_ ? "lpp normal.xy+roughness (packed)" : "lpp normal+roughness",
                                                     {.format = normalFormat, .width = s.width, .height = s.height});
    const graph::TextureId light = g.createTexture("lpp light buffer", {.format = kLightBuffer, .width = s.width, .height = s.height});
    g.addPass("lpp-normals", [&](graph::PassBuilder& b) {
        b.colorTarget(normals);
        b.depthTarget(depth);
    }, [this, normalFormat](graph::PassContext& pc) {
        pc.beginRenderPass();
        objects_.clear();
        ctx_.geometry.draw(pc.cmd, ctx_.queue, packed_ ? MeshPass::NormalRoughness : MeshPass::NormalRoughnessUnpacked,
                           {{normalFormat}, kSceneDepthFormat}, ctx_.frameConstants, ctx_.eye, &objects_);
        pc.cmd.endRenderPass();
    });
    g.addPass("lpp-lights", [&](graph::PassBuilder& b) {
        b.sample(normals);
        b.sample(depth);
        b.colorTarget(light);
    }, [this, normals, depth](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setTexture(kSlotGBuffer1, pc.texture(normals), ctx_.pointSampler);
        pc.cmd.setTexture(kSlotDepth, pc.texture(depth), ctx_.pointSampler);
        volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene, ctx_.frameConstants);
        pc.cmd.endRenderPass();
    });
    g.addPass("lpp-material", [&](graph::PassBuilder& b) {
        b.sample(light);
        b.colorTarget(output);
        b.depthTarget(depth, gdi::LoadOp::Load);
    }, [this, light](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setTexture(kSlotIBuffer0, pc.texture(light), ctx_.pointSampler);
        ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::LightPrepassMaterial, {{kRadianceFormat}, kSceneDepthFormat},
                           ctx_.frameConstants, ctx_.eye, &objects_);
        pc.cmd.endRenderPass();
    });
}

}  // namespace fe::render
