// Layer 7: post-processing as render-graph passes, from the technique's linear L_o to the
// displayable image: exposure and a tone mapper (RenderSettings::tonemap: clamp, the ACES fit or
// Khronos PBR Neutral), then antialiasing (RenderSettings::antiAliasing: FXAA after the tone
// mapper, or TAA before it, on linear L_o, with a history texture kept across frames). Each step is a
// pass reading the previous one's texture, so the chain's intermediates are transients the graph
// can alias with the technique's buffers; the graph culls the whole chain when nothing reads the
// display image.
#pragma once
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/RenderSettings.h"

namespace fe::render {

constexpr gdi::Format kDisplayFormat = gdi::Format::RGBA8_SRGB;  // what a screen shows

// One full-screen triangle into `target` with `pipeline`, sampling `source` at kSlotRadiance
// with `sampler` and reading the frame's constants (as they are when the pass executes): each
// step of post-processing, and the scene renderer's debug view.
void addFullscreenPass(graph::RenderGraph& graph, const char* name, graph::TextureId source,
                       graph::TextureId target, gdi::PipelineHandle pipeline,
                       gdi::SamplerHandle sampler, const UploadAllocation& frameConstants);

class PostProcess {
public:
    // `frameConstants` is read when each frame's passes execute (exposure is cameraPosition.w).
    // `background`: the display pass's background mode (BackgroundPass::displayConstants().x,
    // FrameConstants::shading.y), which its pipeline is specialized for.
    PostProcess(gdi::Device& device, const RenderSettings& settings, gdi::ShaderHandle fullscreenVs,
                const UploadAllocation& frameConstants, uint32_t background);
    // fe_display_pass.glsl's FE_BACKGROUND (a specialization constant; 3: read the frame's).
    static constexpr uint32_t kBackgroundId = 204;
    PostProcess(const PostProcess&) = delete;
    PostProcess& operator=(const PostProcess&) = delete;

    // Declares the chain reading `radiance` (and, for TAA, the scene `depth`); returns the
    // display image (kDisplayFormat).
    graph::TextureId declare(graph::RenderGraph& graph, graph::TextureId radiance,
                             graph::TextureId depth);

    // TAA: the sub-pixel offset (in pixels, within [-0.5, 0.5)) the projection is jittered by
    // for frame `frameIndex` (Halton 2, 3 over 8 frames); zero without TAA.
    glm::vec2 jitter(uint64_t frameIndex) const;
    // TAA: this frame's constants (after CommandQueue::beginFrame): the previous frame's
    // unjittered view-projection, and whether there is a history (false on the first frame
    // and after a camera cut). Records this frame's for the next.
    void beginFrame(CommandQueue& queue, const glm::mat4& viewProjUnjittered, bool historyValid);

private:
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    const RenderSettings& settings_;
    const UploadAllocation& frameConstants_;
    gdi::SamplerHandle pointSampler_, linearSampler_;
    gdi::ShaderHandle tonemapFs_, fxaaFs_, taaFs_, copyFs_;
    gdi::PipelineHandle tonemapPipeline_, fxaaPipeline_, taaPipeline_, copyPipeline_;
    gdi::TextureHandle history_;     // TAA: last frame's result (RGBA32F, kept across frames)
    UploadAllocation taaConstants_;  // TAA: this frame's
    glm::mat4 previousViewProj_{1.0f};
};

}  // namespace fe::render
