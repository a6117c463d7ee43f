#include "render/LightPrepassRenderer.h"

#include "render/ShaderSlots.h"

namespace fe::render {

LightPrepassRenderer::LightPrepassRenderer(TechniqueContext& c, bool packed)
    : TechniqueRenderer(c), packed_(packed) {
    volumes_ = std::make_unique<LightVolumes>(
        c.device, packed ? "scene/lpp_light.frag" : "scene/lpp_light_unpacked.frag",
        std::vector{kLightBuffer});
    if (c.shadows)
        shadowed_ = std::make_unique<ShadowedLightVolumes>(
            c, packed ? "scene/lpp_light_shadowed.frag" : "scene/lpp_light_unpacked_shadowed.frag",
            packed ? "scene/lpp_light_shadowed_cube.frag"
                   : "scene/lpp_light_unpacked_shadowed_cube.frag",
            std::vector{kLightBuffer});
}

LightPrepassRenderer::~LightPrepassRenderer() = default;

void LightPrepassRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                   graph::TextureId depth) {
    const RenderSettings& s = ctx_.settings;
    const gdi::Format normalFormat = packed_ ? kPackedNormals : kUnpackedNormals;
    const char* normalName = packed_ ? "lpp normal.xy+roughness (packed)" : "lpp normal+roughness";
    const graph::TextureId normals =
        g.createTexture(normalName, {.format = normalFormat, .width = s.width, .height = s.height});
    const graph::TextureId light = g.createTexture(
        "lpp light buffer", {.format = kLightBuffer, .width = s.width, .height = s.height});
    // With --msaa N the two geometry passes are multisampled and share one multisampled depth
    // (the material pass tests EQUAL per sample), while the light pass stays per pixel: it reads
    // the normals averaged by the resolve and depth from sample 0. That is the deck's argument
    // for the technique: edges are antialiased by the material pass at no extra lighting cost;
    // the price is edge pixels lit for one surface's depth with the edge's mean normal.
    const ForwardTargets t = forwardTargets(g, output, depth);
    graph::TextureId normalTarget = normals;
    if (s.msaa > 1)
        normalTarget = g.createTexture(
            std::string("msaa ") + normalName,
            {.format = normalFormat, .width = s.width, .height = s.height, .sampleCount = s.msaa});
    const MeshPassTargets normalTargets{{normalFormat}, kSceneDepthFormat, s.msaa};
    g.addPass(
        "lpp-normals",
        [&](graph::PassBuilder& b) {
            b.colorTarget(normalTarget);
            b.depthTarget(t.depth);
            if (s.msaa > 1) {
                b.resolve(normalTarget, normals);
                b.resolve(t.depth, t.sceneDepth);
            }
        },
        [this, normalTargets](graph::PassContext& pc) {
            pc.beginRenderPass();
            objects_.clear();
            ctx_.geometry.draw(
                pc.cmd, ctx_.queue,
                packed_ ? MeshPass::NormalRoughness : MeshPass::NormalRoughnessUnpacked,
                normalTargets, ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
    g.addPass(
        "lpp-lights",
        [&](graph::PassBuilder& b) {
            b.sample(normals);
            b.sample(t.sceneDepth);
            b.colorTarget(light);
        },
        [this, normals, sceneDepth = t.sceneDepth](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setTexture(kSlotGBuffer1, pc.texture(normals), ctx_.pointSampler);
            pc.cmd.setTexture(kSlotDepth, pc.texture(sceneDepth), ctx_.pointSampler);
            volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene, ctx_.frameConstants, ctx_.frame);
            pc.cmd.endRenderPass();
        });
    if (shadowed_)
        shadowed_->declare(
            g,
            [&](graph::PassBuilder& b) {
                b.sample(normals);
                b.sample(t.sceneDepth);
                b.colorTarget(light, gdi::LoadOp::Load);
            },
            [this, normals, sceneDepth = t.sceneDepth](graph::PassContext& pc) {
                pc.cmd.setTexture(kSlotGBuffer1, pc.texture(normals), ctx_.pointSampler);
                pc.cmd.setTexture(kSlotDepth, pc.texture(sceneDepth), ctx_.pointSampler);
            });
    g.addPass(
        "lpp-material",
        [&](graph::PassBuilder& b) {
            b.sample(light);
            b.colorTarget(t.color);
            b.depthTarget(t.depth, gdi::LoadOp::Load);
            if (s.msaa > 1) b.resolve(t.color, t.output);  // depth was resolved by lpp-normals
        },
        [this, light, targets = t.formats](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setTexture(kSlotIBuffer0, pc.texture(light), ctx_.pointSampler);
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::LightPrepassMaterial, targets,
                               ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
}

}  // namespace fe::render
