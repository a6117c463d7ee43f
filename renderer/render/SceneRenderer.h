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
};

struct PassTiming {
    std::string name;
    double gpuMilliseconds = 0;
};

struct TargetInfo {
    std::string name;
    gdi::Format format;
    uint32_t width, height;
    uint64_t bytes() const { return uint64_t(width) * height * gdi::formatInfo(format).bytesPerPixel; }
};

class SceneRenderer {
public:
    SceneRenderer(gdi::Device& device, const assets::Scene& scene, const RenderSettings& settings);
    ~SceneRenderer();

    void renderFrame();
    // Linear L_o (RGBA32F) of the last frame.
    gdi::Image readOutput();
    // GPU time per pass of the last completed frame (empty where timestamps are unsupported).
    std::vector<PassTiming> passTimings();
    const std::vector<TargetInfo>& targets() const { return targets_; }
    GpuScene& gpuScene() { return *gpuScene_; }

private:
    void beginTimed(gdi::CommandList& cmd, const char* name);
    void endTimed(gdi::CommandList& cmd);
    gdi::TextureHandle makeTarget(const char* name, gdi::Format format, uint32_t w, uint32_t h);

    gdi::Device& device_;
    const assets::Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<CommandQueue> queue_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<GeometryRenderer> geometry_;
    std::unique_ptr<LightVolumes> volumes_;
    std::vector<TargetInfo> targets_;
    std::vector<gdi::TextureHandle> ownedTextures_;
    gdi::TextureHandle output_, depth_, gb0_, gb1_, gb2_, i0_, i1_, i2_;
    gdi::SamplerHandle pointSampler_;
    gdi::ShaderHandle fullscreenVs_, fullscreenFs_;
    gdi::PipelineHandle fullscreenPipeline_;
    struct Timer {
        std::string name;
        gdi::TimerHandle timer;
    };
    std::vector<Timer> timers_;
    size_t timerCursor_ = 0;
    gdi::FenceValue lastFence_ = 0;
};

}  // namespace fe::render
