#include "render/TileLightCulling.h"

#include <algorithm>

#include "fe/gdi/ShaderRegistry.h"
#include "render/LightVolumes.h"
#include "render/ShaderFeatures.h"
#include "render/ShaderSlots.h"

namespace fe::render {

TileLightCulling::TileLightCulling(TechniqueContext& c, bool multisampledDepth)
    : objects_(c.device), ctx_(c), multisampledDepth_(multisampledDepth) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("tiled light culling needs compute shaders, which " +
                         c.device.info().backend + " lacks");
    uniformLights_ = lightsFitUniformBlock(c);
    cs_ = objects_.add(
        c.device.createShader({.stage = gdi::ShaderStage::Compute,
                               .binary = listPassShader("tile_light_culling", uniformLights_, false,
                                                        multisampledDepth)}));
    // Without MSAA the depth bounds are not widened: the constant removes the slope's fetches
    // (a uniform's test would not, on CPU rasterizers: ShaderFeatures).
    pipeline_ = objects_.add(c.device.createComputePipeline(
        {.computeShader = cs_,
         .specialization = declaredConstants(
             c.device, {cs_},
             {gdi::SpecializationConstant::of(kWidenBoundsId, c.settings.msaa > 1)}),
         .debugName = "light culling"}));
}

bool TileLightCulling::lightsFitUniformBlock(const TechniqueContext& c) {
    return GpuScene::lightsFitUniformBlock(c.scene.lightCount(), c.device.info().limits);
}

const gdi::ShaderBinary& TileLightCulling::listPassShader(const std::string& name,
                                                          bool uniformLights, bool layered,
                                                          bool multisampled) {
    std::string variant = multisampled ? "FE_MULTISAMPLED" : "";
    if (layered) variant += variant.empty() ? "FE_LAYERED" : "+FE_LAYERED";
    if (!uniformLights)
        variant += variant.empty() ? "FE_LIGHTS_IN_STORAGE" : "+FE_LIGHTS_IN_STORAGE";
    return shaders::find("scene/" + name + ".comp" + (variant.empty() ? "" : ":" + variant));
}

const gdi::ShaderBinary& TileLightCulling::shader(const std::string& name) const {
    return listPassShader(name, uniformLights_, false, multisampledDepth_);
}

void TileLightCulling::bindLights(gdi::CommandList& cmd, const TechniqueContext& c,
                                  bool uniformLights) {
    c.scene.bindLights(cmd, kSlotLights, uniformLights);
}

std::vector<uint32_t> TileLightCulling::lightsInView(const std::vector<assets::Light>& lights,
                                                     uint32_t count, const FrameConstants& seen,
                                                     bool uniformBlock) {
    std::vector<uint32_t> block(4, 0u);
    const uint32_t end = std::min<uint32_t>(count, uint32_t(lights.size()));
    for (uint32_t i = 0; i < end; ++i)
        if (!lightOutOfView(lights[i], seen)) block.push_back(i);
    block[0] = uint32_t(block.size() - 4);
    if (uniformBlock) block.resize(4 + GpuScene::kUniformLights, 0u);
    return block;
}

void TileLightCulling::bindFrameAndLights(gdi::CommandList& cmd,
                                          gdi::PipelineHandle pipeline) const {
    cmd.setPipeline(pipeline);
    const UploadAllocation& fc = ctx_.frameConstants;
    cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
    bindLights(cmd, ctx_, uniformLights_);
}

graph::TextureId TileLightCulling::declare(graph::RenderGraph& g, graph::TextureId depth) {
    const RenderSettings& s = ctx_.settings;
    // One block of the list texture per list tile; the pass runs one invocation per 32x32 block.
    const uint32_t tilesX = (s.width + kTileSize - 1) / kTileSize,
                   tilesY = (s.height + kTileSize - 1) / kTileSize;
    // Room for every light (up to kMaxListLength) and the header, within the device's texture limit.
    const uint32_t entries = std::min(ctx_.scene.lightCount(), kMaxListLength) + kListHeader;
    const uint32_t maxDim = ctx_.device.info().limits.maxTextureSize2D;
    const uint32_t blockHeight =
        std::max(1u, std::min((entries + kBlockWidth - 1) / kBlockWidth, maxDim / tilesY));
    if (tilesX * kBlockWidth > maxDim)
        throw gdi::Error("tiled light culling: " + std::to_string(s.width) +
                         " pixels wide needs a list texture wider than " + std::to_string(maxDim));
    const graph::TextureId lists =
        g.createTexture("tile light lists", {.format = gdi::Format::R32U,
                                             .width = tilesX * kBlockWidth,
                                             .height = tilesY * blockHeight});
    g.addPass(
        "light-culling",
        [&](graph::PassBuilder& b) {
            b.sample(depth);
            b.storage(lists);
        },
        [this, depth, lists,
         blocks = ((s.width + 31) / 32) * ((s.height + 31) / 32)](graph::PassContext& pc) {
            bindFrameAndLights(pc.cmd, pipeline_);
            pc.cmd.setTexture(kSlotDepth, pc.texture(depth), ctx_.pointSampler);
            pc.cmd.setStorageTexture(kSlotTileLightsOut, pc.texture(lists));
            const UploadAllocation inView = ctx_.queue.upload(gdi::bytesOf(lightsInView(
                ctx_.scene.lights(), ctx_.frame.counts.x, ctx_.frame, uniformLights_)));
            if (uniformLights_)
                pc.cmd.setUniformBuffer(kSlotVisibleLights, inView.buffer, inView.offset,
                                        inView.size);
            else
                pc.cmd.setStorageBuffer(kSlotVisibleLights, inView.buffer, inView.offset,
                                        inView.size);
            // With MSAA (forward-plus) the depth is sample 0's and fragments shade at pixel centres;
            // the multisampled variant reads every sample instead.
            if (!multisampledDepth_)
                pc.cmd.setConstants(
                    glm::vec4(ctx_.settings.msaa > 1 ? 0.5f : 0.0f, 0.0f, 0.0f, 0.0f));
            pc.cmd.dispatch((blocks + 63) / 64, 1);
        });
    return lists;
}

void TileLightCulling::bindLists(gdi::CommandList& cmd, const graph::PassContext& pc,
                                 graph::TextureId lists) const {
    cmd.setTexture(kSlotTileLights, pc.texture(lists), ctx_.pointSampler);
}

}  // namespace fe::render
