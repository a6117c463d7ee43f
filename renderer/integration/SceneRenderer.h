// Layer 8 (Integration): renders a Scene with one lighting technique (render/TechniqueRenderer.h),
// every pass timed. The technique declares its passes; the scene renderer composes them with
// what every technique shares: the transparent pass (BLEND primitives drawn forward after the
// opaque ones, declared only when the scene has any), the background pass (BackgroundPass: the
// environment, a colour or transparency where nothing was drawn) and post-processing
// (PostProcess: tone mapping and antialiasing ending in the display image, culled unless a
// displayable image is asked for). With shadows it plans which lights cast them (ShadowPlan),
// stores those lights last in the light buffer and gives the technique the maps.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/GeometryRenderer.h"
#include "render/GpuScene.h"
#include "render/RenderSettings.h"
#include "render/ClusterLightGrid.h"
#include "render/BackgroundPass.h"
#include "render/EnvironmentMap.h"
#include "render/PostProcess.h"
#include "render/PrefilteredEnvironment.h"
#include "render/TechniqueRenderer.h"
#include "render/MeshDeformation.h"
#include "render/TransmissionPass.h"
#include "render/VfxRenderer.h"

namespace fe::render {

using graph::PassTiming;

// Lights evaluated per pixel with a surface in the last frame (RenderSettings::lightListStatistics).
struct LightListStatistics {
    std::string lists;  // "every light", "tile lists", "cluster lists" or "not measured (...)"
    bool measured = false;
    uint32_t pixels = 0;  // pixels with a surface
    double mean = 0;
    uint32_t p95 = 0, max = 0;
    // Mean lights whose range reaches the pixel's surface: what any exact culling walks at least,
    // so mean / reaching is how much a technique's lists walk in vain.
    double reaching = 0;
    // Pixels whose loop walks fewer of the lights reaching them than there are: a light dropped
    // (culling that is not exact). 0 for every technique; tests hold it there.
    uint32_t pixelsMissingALight = 0;
};

class SceneRenderer {
public:
    // RenderSettings::debugView's name for the per-pixel light-count heat map (the other names
    // are the graph's textures).
    static constexpr const char* kLightCountView = "light count";
    // The heat map of lights the technique's loop walks per pixel (its tile or cluster list, or
    // every light; the light-list statistics pass counts them), on a log scale. Refused for
    // techniques whose lists are not measured (light volumes, reduced-rate lists).
    static constexpr const char* kLightsEvaluatedView = "lights evaluated";

    SceneRenderer(gdi::Device& device, const assets::Scene& scene, const RenderSettings& settings);
    ~SceneRenderer();

    void renderFrame();
    // Linear L_o (RGBA32F) of the last frame.
    gdi::Image readOutput();
    // The displayable image of the last frame (RenderSettings::displayImage).
    const BackgroundPass& background() const { return *background_; }
    gdi::Image readDisplay();
    // The texture post-processing ends in (RGBA8_SRGB, CopySrc), e.g. for Device::present.
    gdi::TextureHandle displayTexture();
    // GPU time per pass of the last completed frame (empty where timestamps are unsupported).
    std::vector<PassTiming> passTimings();
    // Whether a frame's pass timestamps account for it: their sum is at least kTimersAccountFor of
    // the frame's wall time. On lavapipe a pass's timestamps measure command processing, not
    // rasterisation (a forward shading pass read 8.9 ms of a 385 ms frame); a CPU-bound frame on
    // a GPU can fail it too, and is then profiled as well (both figures are kept).
    static constexpr double kTimersAccountFor = 0.5;
    static bool timersAccountForFrame(const std::vector<PassTiming>& passes, double frameMs);
    // Renders one frame with a flush-and-wait after every pass: each pass's time is the wall
    // time from its submission to its completion, less an empty submission's (the least of the
    // frame's). Slower than a frame, but it accounts for the work whatever the timers measure.
    std::vector<PassTiming> profilePasses();
    // Pass times with the method that made them, from frames already rendered (per pass, its
    // timestamps in execution order; each frame's wall time): the timestamps when they account
    // for the frame, else `profiled` flush-and-wait frames rendered now.
    using PassSamples = std::vector<std::pair<std::string, std::vector<double>>>;
    struct PassTimes {
        std::string method;  // "gpu-timestamps" or "flush-and-wait"
        double timestampShare =
            0;               // the timestamps' medians summed, over the frames' median wall time
        PassSamples passes;  // by that method
        PassSamples timestamps;  // as given
    };
    PassTimes measurePassTimes(const PassSamples& timestamps, const std::vector<double>& frameMs,
                               uint32_t profiled);
    const graph::RenderGraph& graph() const { return graph_; }
    GpuScene& gpuScene() { return *gpuScene_; }
    // Replaces the scene's lights (scene order, e.g. an animation frame): uploaded in the order
    // the shadow plan made when the renderer was created (which lights cast shadows is kept).
    void updateLights(const std::vector<assets::Light>& lights);
    // Which lights cast shadows and how (empty when shadows are off).
    const ShadowPlan& shadowPlan() const { return shadowPlan_; }
    // The particle systems (null when the scene has no emitters).
    VfxRenderer* vfx() { return vfx_.get(); }
    // The camera of the next frames (a camera path); the scene's until this is called.
    void setCamera(const assets::Camera& camera);
    // After assets::poseScene moved the scene this renderer was made from (assets/Animation.h):
    // the next frames show that pose: the instances' transforms, skins and morph weights (the
    // meshes are deformed on the device each frame), the lights and the scene's camera.
    void updatePose();
    // The light cluster grid (null unless a clustered technique or blended surfaces need it).
    // Lists that overflow grow for the frames framesInFlight() after (ClusterLightGrid::beginFrame).
    const ClusterLightGrid* clusters() const { return clusters_.get(); }
    uint32_t framesInFlight() const { return queue_->framesInFlight(); }
    // How many lights the technique's shading loop walked per pixel in the last frame. Throws
    // unless the renderer was made with RenderSettings::lightListStatistics.
    LightListStatistics lightListStatistics();
    // Whether the technique's shading pass writes the display image, so the frame has no display
    // pass: RenderSettings::displayInShading, a technique that can (TechniqueInfo::writesDisplay)
    // and nothing after its passes that changes L_o or reads it (see the .cpp).
    bool displayInShading() const { return displayInShading_; }

private:
    void recordFrame(const std::function<void(const std::string& pass)>& afterPass);
    void buildGraph();
    graph::TextureId declareDebugView(graph::RenderGraph& g);
    graph::TextureId declareLightCountView(graph::RenderGraph& g);
    graph::TextureId declareLightsEvaluatedView(graph::RenderGraph& g);
    void declareListStatistics(graph::RenderGraph& g);

    // First: destroyed last, after the members below that use its objects.
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    const assets::Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<CommandQueue> queue_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<GeometryRenderer> geometry_;
    FrameConstants frame_{};           // of the frame being recorded
    UploadAllocation frameConstants_;  // its upload
    gdi::SamplerHandle pointSampler_;
    gdi::ShaderHandle fullscreenVs_;
    std::unique_ptr<PostProcess> postProcess_;
    gdi::ShaderHandle debugViewFs_;  // RenderSettings::debugView
    gdi::PipelineHandle
        debugViewPipeline_;  // tone mapping and antialiasing, ending in the display image
    std::unique_ptr<TechniqueContext> context_;
    std::unique_ptr<TechniqueRenderer> technique_;
    std::unique_ptr<VfxRenderer> vfx_;             // when the scene has particle emitters
    std::unique_ptr<EnvironmentMap> environment_;  // when the scene has an environment
    std::unique_ptr<BackgroundPass> background_;
    std::unique_ptr<TransmissionPass> transmission_;       // with transmissive surfaces
    std::unique_ptr<MeshDeformation> deformation_;         // with skinned or morphed instances
    std::unique_ptr<PrefilteredEnvironment> prefiltered_;  // image-based lighting's fast path
    ShadowPlan shadowPlan_;
    std::unique_ptr<ShadowMaps> shadows_;         // when some light casts shadows
    std::unique_ptr<ClusterLightGrid> clusters_;  // TechniqueContext::clusters
    gdi::TextureHandle listCounts_;  // lights evaluated per pixel (R32U), with statistics
    gdi::TextureHandle
        reachingCounts_;             // lights reaching each pixel's surface (R32U), with statistics
    graph::TextureId listCountsId_;  // listCounts_ in the graph
    gdi::ShaderHandle listStatisticsCs_;
    gdi::PipelineHandle listStatisticsPipeline_;
    std::vector<assets::Light> sceneLights_;  // the current lights, scene order
    assets::Camera camera_;                   // the current camera
    uint64_t frameIndex_ = 0;                 // frames rendered
    glm::mat4 prevViewProj_{1.0f};
    graph::RenderGraph graph_;
    graph::TextureId output_, display_, depth_;
    gdi::TextureHandle outputTexture_;
    gdi::FenceValue lastFence_ = 0;
    bool displayInShading_ = false;
};

// Lights walked per pixel in one frame of `scene` rendered with `settings` by a renderer of its
// own (RenderSettings::lightListStatistics on, no display image). The statistics pass walks every
// light at every pixel, far slower than the technique it measures, so a caller that times frames
// measures them here rather than in its timed renderer. `prepare`, when given, sets that renderer
// up as the caller's last frame was (updateLights, setCamera) before it renders.
LightListStatistics measureLightLists(gdi::Device& device, const assets::Scene& scene,
                                      RenderSettings settings,
                                      const std::function<void(SceneRenderer&)>& prepare = {});

}  // namespace fe::render
