// The technique table: one line per technique renderer.
#include "render/DeferredRenderer.h"
#include "render/ForwardMultipassRenderer.h"
#include "render/ForwardPlusRenderer.h"
#include "render/ForwardRenderer.h"
#include "render/ForwardZPrepassRenderer.h"
#include "render/LightPrepassRenderer.h"
#include "render/RedeferredRenderer.h"
#include "render/TiledDeferredRenderer.h"
#include "render/VisibilityBufferRenderer.h"
#include "render/ShaderSlots.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

namespace {
template <class T>
std::unique_ptr<TechniqueRenderer> make(TechniqueContext& c) {
    return std::make_unique<T>(c);
}
template <bool kTiled>
std::unique_ptr<TechniqueRenderer> makeRedeferred(TechniqueContext& c) {
    return std::make_unique<RedeferredRenderer>(c, kTiled);
}
template <ForwardPlusRenderer::Lists kLists>
std::unique_ptr<TechniqueRenderer> makeForwardLists(TechniqueContext& c) {
    return std::make_unique<ForwardPlusRenderer>(c, kLists);
}
template <TiledDeferredRenderer::Lists kLists>
std::unique_ptr<TechniqueRenderer> makeTiledDeferred(TechniqueContext& c) {
    return std::make_unique<TiledDeferredRenderer>(c, kLists);
}
template <bool kPacked>
std::unique_ptr<TechniqueRenderer> makeLightPrepass(TechniqueContext& c) {
    return std::make_unique<LightPrepassRenderer>(c, kPacked);
}
}  // namespace

const std::vector<TechniqueInfo>& techniques() {
    static const std::vector<TechniqueInfo> all = {
        {"forward", "one pass, every light in the shader loop", make<ForwardRenderer>, true},
        {"forward-multipass", "one additive pass per light (cost grows with objects x lights)",
         make<ForwardMultipassRenderer>, true},
        {"forward-zprepass", "depth-only pass front to back, then shading with depth test EQUAL",
         make<ForwardZPrepassRenderer>, true},
        {.name = "forward-plus",
         .summary =
             "Forward+: depth pre-pass, lights culled per 8x8 tile, one forward pass over the tile's list",
         .create = makeForwardLists<ForwardPlusRenderer::Lists::Tiles>,
         .msaa = true,
         .clustersUnderMsaa = true,
         .writesDisplay = true},
        {"clustered-forward",
         "depth pre-pass, lights assigned to 32x32-pixel x 32-slice clusters, one forward pass over the cluster's list",
         makeForwardLists<ForwardPlusRenderer::Lists::Clusters>, true, false, true},
        {.name = "deferred",
         .summary = "G-buffer, lights drawn as volumes, emissive",
         .create = make<DeferredRenderer>,
         .msaa = true,
         .gbuffer = true},
        {.name = "deferred-tiled",
         .summary =
             "G-buffer, one compute pass: lights culled per 16x16 tile, each pixel shaded once",
         .create = makeTiledDeferred<TiledDeferredRenderer::Lists::Tiles>,
         .msaa = true,
         .gbuffer = true},
        {.name = "clustered-deferred",
         .summary =
             "G-buffer, lights assigned to clusters, one compute pass: each pixel shades its cluster's lights",
         .create = makeTiledDeferred<TiledDeferredRenderer::Lists::Clusters>,
         .msaa = true,
         .clusters = true,
         .gbuffer = true},
        {"visibility-buffer",
         "triangle id + depth per pixel, one compute pass rebuilding each pixel's surface and shading its cluster's lights",
         make<VisibilityBufferRenderer>, true, false, true},
        {.name = "light-prepass",
         .summary =
             "normals+depth (RGBA8 packed), lights into a light buffer, scene again with materials",
         .create = makeLightPrepass<true>,
         .msaa = true,
         .separableBrdf = true},
        {.name = "light-prepass-unpacked",
         .summary = "light-prepass with an RGBA16F world-normal target, to measure packing",
         .create = makeLightPrepass<false>,
         .msaa = true,
         .separableBrdf = true},
        {.name = "redeferred",
         .summary = "G-buffer, I-buffer sums at 1/--illum-scale resolution, material pass",
         .create = makeRedeferred<false>,
         .illumScale = true,
         .separableBrdf = true,
         .gbuffer = true},
        {.name = "redeferred-tiled",
         .summary =
             "redeferred with the I-buffer filled by one compute pass culling lights per tile",
         .create = makeRedeferred<true>,
         .illumScale = true,
         .separableBrdf = true,
         .gbuffer = true},
    };
    return all;
}

const TechniqueInfo& findTechnique(const std::string& name) {
    for (const TechniqueInfo& t : techniques())
        if (name == t.name) return t;
    throw gdi::Error("unknown technique '" + name + "' (valid: " + techniqueNames() + ")");
}

shading::Brdf resolveBrdf(const RenderSettings& s) {
    const TechniqueInfo& t = findTechnique(s.technique);
    if (s.shadingModel == ShadingModel::Gltf && t.separableBrdf)
        throw gdi::Error(
            "technique " + s.technique +
            " shades with the separable BRDF only (its light sums need it to factor): the glTF BRDF needs "
            "forward, deferred, deferred-tiled, clustered or the visibility buffer");
    switch (s.shadingModel) {
        case ShadingModel::Gltf:
            return shading::Brdf::Gltf;
        case ShadingModel::Separable:
            return shading::Brdf::Separable;
        default:
            return t.defaultBrdf();
    }
}

std::string techniqueNames() {
    std::string s;
    for (const TechniqueInfo& t : techniques()) s += (s.empty() ? "" : ", ") + std::string(t.name);
    return s;
}

ForwardTargets TechniqueRenderer::forwardTargets(graph::RenderGraph& g, graph::TextureId output,
                                                 graph::TextureId depth) const {
    const RenderSettings& s = ctx_.settings;
    ForwardTargets t{output,
                     depth,
                     output,
                     depth,
                     {{kRadianceFormat}, kSceneDepthFormat, s.msaa},
                     hasShadowedLights()};
    if (s.msaa > 1) {
        t.color = g.createTexture("msaa L_o", {.format = kRadianceFormat,
                                               .width = s.width,
                                               .height = s.height,
                                               .sampleCount = s.msaa});
        t.depth = g.createTexture("msaa depth", {.format = kSceneDepthFormat,
                                                 .width = s.width,
                                                 .height = s.height,
                                                 .sampleCount = s.msaa});
    }
    return t;
}

void ForwardTargets::resolveIn(graph::PassBuilder& b) const {
    if (color == output || resolveLater) return;
    b.resolve(color, output);
    b.resolve(depth, sceneDepth);
}

void TechniqueRenderer::declareShadowedForward(graph::RenderGraph& g, const ForwardTargets& t,
                                               std::vector<UploadAllocation>* objects) {
    if (!hasShadowedLights()) return;
    ctx_.shadows->declare(g, [&](graph::RenderGraph& graph, const ShadowMaps::Light& light) {
        graph.addPass(
            "shadowed light " + std::to_string(light.index),
            [&](graph::PassBuilder& b) {
                b.sample(light.map);
                b.colorTarget(t.color, gdi::LoadOp::Load);
                b.depthTarget(t.depth, gdi::LoadOp::Load);
                if (light.last) {
                    ForwardTargets now = t;
                    now.resolveLater = false;
                    now.resolveIn(b);
                }
            },
            [this, t, light, objects](graph::PassContext& pc) {
                pc.beginRenderPass();
                FrameConstants fc = ctx_.frame;
                fc.lightRange =
                    glm::uvec4(light.gpuLight, 1u, 0u, 0u);  // this light alone, no emissive
                const UploadAllocation perLight = ctx_.queue.upload(fc);
                ctx_.shadows->bind(pc.cmd, pc, light);
                ctx_.geometry.draw(pc.cmd, ctx_.queue,
                                   light.kind == ShadowKind::Cube ? MeshPass::ForwardShadowedCube
                                                                  : MeshPass::ForwardShadowed,
                                   t.formats, perLight, ctx_.eye, objects);
                pc.cmd.endRenderPass();
            });
    });
}

void TechniqueRenderer::bindFrameAndLights(gdi::CommandList& cmd,
                                           gdi::PipelineHandle pipeline) const {
    cmd.setPipeline(pipeline);
    const UploadAllocation& fc = ctx_.frameConstants;
    cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
    cmd.setStorageBuffer(kSlotLights, ctx_.scene.lightBuffer());
}

std::function<void(graph::PassContext&)> TechniqueRenderer::fullscreen(gdi::PipelineHandle pipeline,
                                                                       SlotTextures inputs) const {
    return [this, pipeline, inputs](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setPipeline(pipeline);
        const UploadAllocation& fc = ctx_.frameConstants;
        pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
        for (const auto& [slot, id] : inputs)
            pc.cmd.setTexture(slot, pc.texture(id), ctx_.pointSampler);
        pc.cmd.draw(3);
        pc.cmd.endRenderPass();
    };
}

}  // namespace fe::render
