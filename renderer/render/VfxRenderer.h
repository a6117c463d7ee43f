// Layer 7: the VFX renderer. GPU particles for the scene's emitters (assets::ParticleEmitter),
// added by SceneRenderer to every technique's translucency stage as render-graph passes whose
// buffer reads and writes the graph orders (reset, simulate, sort, draw):
//  1. simulate (compute): one invocation per particle slot; closed-form motion from the system's
//     time, so every backend and frame rate gives the same particles; the living ones are lit
//     (alpha-blended ones by every scene light) and appended to an additive and an alpha list,
//     counting each list's indirect draw;
//  2. sort (compute): the alpha list back to front, a bitonic sort in one work group;
//  3. draw: camera-facing billboards, drawn indirectly from the simulated counts: the sorted
//     alpha list source-over, then the additive list added; each fragment is tested against the
//     scene depth by hand and faded over the emitter's softness in front of it (soft particles).
// Time advances 1/60 s per frame (setTime() sets it), so frames are reproducible.
#pragma once
#include <vector>

#include "assets/Scene.h"
#include "graph/RenderGraph.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class VfxRenderer {
public:
    // Alpha-blended particles alive at once across the scene (sorted in one work group).
    static constexpr uint32_t kMaxSortedParticles = 1024;

    // Throws gdi::Error for emitters that cannot be drawn (non-finite or negative values, more
    // alpha-blended slots than kMaxSortedParticles).
    VfxRenderer(TechniqueContext& context, const std::vector<assets::ParticleEmitter>& emitters);
    VfxRenderer(const VfxRenderer&) = delete;
    VfxRenderer& operator=(const VfxRenderer&) = delete;

    // The particles pass: draws into `output` (loaded), reading `depth` (sampled).
    void declare(graph::RenderGraph& graph, graph::TextureId output, graph::TextureId depth);
    // Seconds since the systems started, of the next frame (default: one lifetime, so a first
    // frame already shows steady systems); each frame then advances it by 1/60 s.
    void setTime(double seconds) { time_ = seconds; }
    double time() const { return time_; }

    // What the last executed frame drew: its additive and alpha-blended particle counts, read
    // back from the indirect draws' arguments (waits for the device), and the alpha list's eye
    // distances in drawing order.
    struct Counts {
        uint32_t additive = 0, alpha = 0;
    };
    Counts lastCounts();
    std::vector<float> lastAlphaDistances();
    // The CPU's count of the particles alive at `seconds` (the same birth rule as the shader).
    static Counts aliveAt(const std::vector<assets::ParticleEmitter>& emitters, double seconds);

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    std::vector<assets::ParticleEmitter> emitters_;
    uint32_t slots_ = 0, additiveSlots_ = 0;
    double time_ = 0.0;
    UploadAllocation
        frame_;  // this frame's constants: uploaded by the simulation, read by the draws
    gdi::BufferHandle emitterBuffer_, additive_, alpha_, sorted_, args_, argsReset_;
    gdi::ShaderHandle simulateCs_, sortCs_, vs_, additiveFs_, alphaFs_;
    gdi::PipelineHandle simulate_, sort_, drawAdditive_, drawAlpha_;
};

}  // namespace fe::render
