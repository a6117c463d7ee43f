#include "render/VisibilityBufferRenderer.h"

#include "fe/gdi/ShaderRegistry.h"

#include "render/ClusterLightGrid.h"
#include "render/ShaderSlots.h"
#include "render/TileLightCulling.h"

namespace fe::render {

VisibilityBufferRenderer::VisibilityBufferRenderer(TechniqueContext& c)
    : TechniqueRenderer(c),
      objects_(c.device),
      uniformLights_(TileLightCulling::lightsFitUniformBlock(c)) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("technique visibility-buffer needs compute shaders, which " +
                         c.device.info().backend + " lacks");
    if (!c.clusters) throw gdi::Error("visibility-buffer: the renderer made no light cluster grid");
    if (c.settings.msaa > 1 && c.shadows && c.shadows->any()) {
        addFs_ = objects_.add(c.device.createShader(
            {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/copy.frag")}));
        addPipeline_ = objects_.add(
            c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                             .fragmentShader = addFs_,
                                             .blend = {{.enable = true,
                                                        .srcColor = gdi::BlendFactor::One,
                                                        .dstColor = gdi::BlendFactor::One,
                                                        .srcAlpha = gdi::BlendFactor::Zero,
                                                        .dstAlpha = gdi::BlendFactor::One}},
                                             .colorFormats = {kRadianceFormat},
                                             .debugName = "shadowed lights added"}));
    }
    std::vector<ObjectConstants> records;
    for (const DrawItem& d : c.scene.draws()) records.push_back(c.scene.objectConstants(d));
    if (records.empty()) records.emplace_back();  // a buffer needs at least one byte
    draws_ = objects_.add(c.device.createBuffer({.size = records.size() * sizeof(ObjectConstants),
                                                 .usage = gdi::BufferUsage::Storage,
                                                 .debugName = "visibility draws"},
                                                gdi::bytesOf(records)));
    const std::string name = !c.settings.ibl() ? "visibility_resolve"
                             : c.environmentLight.prefiltered()
                                 ? "visibility_resolve_ibl_prefiltered"
                                 : "visibility_resolve_ibl";
    cs_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Compute,
         .binary = TileLightCulling::listPassShader(
             name, uniformLights_, c.scene.hasLayeredMaterials(), c.settings.msaa > 1)}));
    pipelines_ = std::make_unique<FeatureComputePipelines>(c.device, cs_, "visibility resolve");
}

void VisibilityBufferRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                       graph::TextureId depth) {
    const RenderSettings& s = ctx_.settings;
    // --msaa N: N ids a pixel and a multisampled depth, resolved (sample 0) into `depth` for the
    // passes after the technique; the resolve shades each triangle of a pixel once, weighted by
    // its samples, and walks whole cluster lists (bounds would hold sample 0's depths only).
    const uint32_t samples = s.msaa;
    const graph::TextureId ids = g.createTexture(
        samples > 1 ? "msaa visibility triangle ids" : "visibility triangle ids",
        {.format = kIdFormat, .width = s.width, .height = s.height, .sampleCount = samples});
    const graph::TextureId visibleDepth =
        samples > 1 ? g.createTexture("msaa depth", {.format = kSceneDepthFormat,
                                                     .width = s.width,
                                                     .height = s.height,
                                                     .sampleCount = samples})
                    : depth;
    g.addPass(
        "visibility",
        [&](graph::PassBuilder& b) {
            b.colorTarget(ids);  // cleared to 0: no surface
            b.depthTarget(visibleDepth);
            if (visibleDepth != depth) b.resolve(visibleDepth, depth);
        },
        [this, samples](graph::PassContext& pc) {
            pc.beginRenderPass();
            objectUploads_.clear();
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::Visibility,
                               {{kIdFormat}, kSceneDepthFormat, samples}, ctx_.frameConstants,
                               ctx_.eye, &objectUploads_);
            pc.cmd.endRenderPass();
        });
    const ClusterLightGrid::Lists lists =
        samples > 1 ? ctx_.clusters->declare(g) : ctx_.clusters->declareBounded(g, depth);
    g.addPass(
        "visibility-resolve",
        [&](graph::PassBuilder& b) {
            b.sample(ids);
            if (samples == 1) b.sample(depth);
            ClusterLightGrid::read(b, lists);
            b.storage(output);
        },
        [this, ids, depth, output, samples](graph::PassContext& pc) {
            gdi::CommandList& cmd = pc.cmd;
            bindFrameAndLights(cmd, (*pipelines_)(frameFeatures(ctx_)));
            TileLightCulling::bindLights(cmd, ctx_, uniformLights_);
            ctx_.clusters->bindLists(cmd);
            if (ctx_.settings.ibl()) ctx_.environmentLight.bind(cmd);
            cmd.setTexture(kSlotVisibility, pc.texture(ids), ctx_.pointSampler);
            if (samples == 1) cmd.setTexture(kSlotDepth, pc.texture(depth), ctx_.pointSampler);
            cmd.setStorageBuffer(kSlotDraws, draws_);
            cmd.setStorageBuffer(kSlotVertices, ctx_.scene.vertexBuffer());
            cmd.setStorageBuffer(kSlotIndices, ctx_.scene.indexBuffer());
            cmd.setStorageTexture(kSlotRadianceOut, pc.texture(output));
            const RenderSettings& rs = ctx_.settings;
            const std::vector<MaterialTextures>& sets = ctx_.scene.textureSets();
            for (uint32_t set = 0; set < sets.size();
                 ++set) {  // never empty (GpuScene::textureSets)
                // Multisampled, a dispatch adds to what the earlier ones stored.
                if (samples > 1 && set > 0)
                    cmd.barrier(gdi::TextureBarrier{.texture = pc.texture(output),
                                                    .before = gdi::ResourceState::Storage,
                                                    .after = gdi::ResourceState::Storage});
                sets[set].bind(cmd);
                cmd.setConstants(glm::uvec4(set, set == 0 ? 1u : 0u, 0u, 0u));
                cmd.dispatch((rs.width + kGroupSize - 1) / kGroupSize,
                             (rs.height + kGroupSize - 1) / kGroupSize);
            }
        });
    if (samples == 1) {
        declareShadowedForward(
            g,
            ForwardTargets{
                output, depth, output, depth, {{kRadianceFormat}, kSceneDepthFormat, 1}, false},
            &objectUploads_);
        return;
    }
    if (!hasShadowedLights()) return;
    // Multisampled: the shadowed lights' forward passes add into a target of their own, cleared
    // first, against the multisampled depth; the last resolves it (and sample 0's depth again),
    // and one full-screen pass adds the result into L_o.
    const graph::TextureId shadowed =
                               g.createTexture("msaa shadowed L_o", {.format = kRadianceFormat,
                                                                     .width = s.width,
                                                                     .height = s.height,
                                                                     .sampleCount = samples}),
                           resolved = g.createTexture(
                               "shadowed L_o",
                               {.format = kRadianceFormat, .width = s.width, .height = s.height});
    g.addPass(
        "shadowed clear", [&](graph::PassBuilder& b) { b.colorTarget(shadowed); },
        [](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.endRenderPass();
        });
    declareShadowedForward(g,
                           ForwardTargets{shadowed,
                                          visibleDepth,
                                          resolved,
                                          depth,
                                          {{kRadianceFormat}, kSceneDepthFormat, samples},
                                          true},
                           &objectUploads_);
    g.addPass(
        "shadowed lights added",
        [&](graph::PassBuilder& b) {
            b.sample(resolved);
            b.colorTarget(output, gdi::LoadOp::Load);
        },
        fullscreen(addPipeline_, {{kSlotRadiance, resolved}}));
}

}  // namespace fe::render
