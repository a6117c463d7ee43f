// Layer 7/8: renders a Scene with one lighting technique, every pass timed.
//   forward:    one pass, every light in the shader loop
//   deferred:   G-buffer, lights as volumes accumulated additively, then emissive
//   redeferred: G-buffer, illumination pass into the I-buffer (optionally at 1/2 or 1/4 of the
//               resolution per axis), material pass turning the sums into L_o
// BLEND primitives are drawn forward after the opaque ones in every technique. Only the passes
// and buffers the scene needs are created (no transparent pass without BLEND primitives, no
// G-buffer for forward, no I-buffer outside redeferred).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/GeometryRenderer.h"
#include "render/GpuScene.h"
#include "render/LightVolumes.h"

namespace fe::render {

enum class Technique { Forward, Deferred, Redeferred };
const char* techniqueName(Technique t);
// Throws gdi::Error listing the valid names.
Technique techniqueFromName(const std::string& name);

struct RenderSettings {
    Technique technique = Technique::Forward;
    uint32_t width = 320;
    uint32_t height = 240;
    uint32_t illumScale = 1;  // redeferred I-buffer: 1, 2 or 4
    float exposure = 1.0f;
    // Also produce the displayable image (RGBA8_SRGB, clamp(exposure x L_o)) on the GPU;
    // without it the graph culls the display pass.
    bool displayImage = false;
    // Alias transient memory (false: every transient texture has memory of its own).
    bool aliasing = true;
};

using graph::PassTiming;

class SceneRenderer {
public:
    SceneRenderer(gdi::Device& device, const assets::Scene& scene, const RenderSettings& settings);
    ~SceneRenderer();

    void renderFrame();
    // Linear L_o (RGBA32F) of the last frame.
    gdi::Image readOutput();
    // The displayable image of the last frame (RenderSettings::displayImage).
    gdi::Image readDisplay();
    // The texture the display pass writes (RGBA8_SRGB, CopySrc), e.g. for Device::present.
    gdi::TextureHandle displayTexture();
    // GPU time per pass of the last completed frame (empty where timestamps are unsupported).
    std::vector<PassTiming> passTimings();
    const graph::RenderGraph& graph() const { return graph_; }
    GpuScene& gpuScene() { return *gpuScene_; }

private:
    void buildGraph();
    void bindGBuffer(gdi::CommandList& cmd, bool albedo);

    gdi::Device& device_;
    const assets::Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<CommandQueue> queue_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<GeometryRenderer> geometry_;
    std::unique_ptr<LightVolumes> volumes_;
    graph::RenderGraph graph_;
    graph::TextureId output_, display_, depth_, gb0_, gb1_, gb2_, i0_, i1_, i2_;
    gdi::TextureHandle outputTexture_;
    gdi::SamplerHandle pointSampler_;
    gdi::ShaderHandle fullscreenVs_, lightingFs_, displayFs_;
    gdi::PipelineHandle lightingPipeline_, displayPipeline_;
    UploadAllocation frameConstants_;  // of the frame being recorded
    gdi::FenceValue lastFence_ = 0;
};

}  // namespace fe::render
