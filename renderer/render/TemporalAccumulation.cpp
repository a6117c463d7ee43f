#include "render/TemporalAccumulation.h"

#include <string>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

glm::uvec2 temporalOffset(uint32_t scale, uint64_t frame) {
    // Bayer matrices (rows y, columns x): rank k is the k-th position visited.
    static const uint32_t bayer2[2][2] = {{0, 2}, {3, 1}};
    static const uint32_t bayer4[4][4] = {
        {0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
    if (scale != 2 && scale != 4) return {0, 0};
    const uint32_t k = uint32_t(frame % (uint64_t(scale) * scale));
    for (uint32_t y = 0; y < scale; ++y)
        for (uint32_t x = 0; x < scale; ++x)
            if ((scale == 2 ? bayer2[y][x] : bayer4[y][x]) == k) return {x, y};
    return {0, 0};
}

TemporalAccumulation::TemporalAccumulation(TechniqueContext& c) : objects_(c.device), ctx_(c) {
    const RenderSettings& s = c.settings;
    auto cmd = c.device.createCommandList();
    for (size_t i = 0; i < history_.size(); ++i) {
        history_[i] = objects_.add(c.device.createTexture(
            {.format = kFormat,
             .width = s.width,
             .height = s.height,
             .usage = gdi::TextureUsage::Sampled | gdi::TextureUsage::RenderTarget,
             .debugName = "temporal history"}));
        cmd->beginRenderPass({.colors = {{.texture = history_[i]}},
                              .debugName = "clear history"});  // defined contents
        cmd->endRenderPass();
    }
    c.device.wait(c.device.submit(*cmd));
    // Under motion the history is read between texels (RGBA32F filtering: every device here has it).
    linear_ = objects_.add(c.device.createSampler({.addressU = gdi::AddressMode::ClampToEdge,
                                                   .addressV = gdi::AddressMode::ClampToEdge,
                                                   .debugName = "temporal history"}));
    auto fragment = [&](const char* name) {
        return objects_.add(c.device.createShader(
            {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(name)}));
    };
    resolveFs_ = fragment("scene/temporal_resolve.frag");
    keepFs_ = fragment("scene/temporal_keep.frag");
    resolve_ =
        objects_.add(c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                                      .fragmentShader = resolveFs_,
                                                      .colorFormats = {kFormat, kFormat, kFormat},
                                                      .debugName = "temporal resolve"}));
    keep_ =
        objects_.add(c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                                      .fragmentShader = keepFs_,
                                                      .colorFormats = {kFormat, kFormat, kFormat},
                                                      .debugName = "temporal keep"}));
}

std::array<graph::TextureId, 3> TemporalAccumulation::declare(
    graph::RenderGraph& g, const GBuffer& gbuffer, const std::array<graph::TextureId, 3>& ib) {
    const RenderSettings& s = ctx_.settings;
    std::array<graph::TextureId, 3> history, accumulated;
    static const char* names[3] = {"L_dg", "L_sg1", "L_sg2"};
    for (size_t i = 0; i < 3; ++i) {
        history[i] = g.importTexture(std::string("temporal history ") + names[i], history_[i],
                                     ctx_.device.desc(history_[i]));
        accumulated[i] = g.createTexture(std::string("temporal ") + names[i],
                                         {.format = kFormat, .width = s.width, .height = s.height});
    }
    g.addPass(
        "temporal-resolve",
        [&](graph::PassBuilder& b) {
            gbuffer.sampleIn(b, false);
            for (auto t : ib) b.sample(t);
            for (auto t : history) b.sample(t);
            for (auto t : accumulated) b.colorTarget(t);
        },
        [this, &gbuffer, ib, history](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setPipeline(resolve_);
            const UploadAllocation& fc = ctx_.frameConstants;
            pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
            gbuffer.bind(pc.cmd, pc, ctx_.pointSampler, false);
            const uint32_t slots[6] = {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2,
                                       kSlotHistory0, kSlotHistory1, kSlotHistory2};
            for (size_t i = 0; i < 3; ++i) {
                pc.cmd.setTexture(slots[i], pc.texture(ib[i]), ctx_.pointSampler);
                pc.cmd.setTexture(slots[3 + i], pc.texture(history[i]), linear_);
            }
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
    // Next frame's history: read after this frame, so the graph must not cull it.
    g.addPass(
        "temporal-keep",
        [&](graph::PassBuilder& b) {
            for (auto t : accumulated) b.sample(t);
            for (auto t : history) b.colorTarget(t, gdi::LoadOp::DontCare);
            b.sideEffect();
        },
        [this, accumulated](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setPipeline(keep_);
            const uint32_t slots[3] = {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2};
            for (size_t i = 0; i < 3; ++i)
                pc.cmd.setTexture(slots[i], pc.texture(accumulated[i]), ctx_.pointSampler);
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
    return accumulated;
}

}  // namespace fe::render
