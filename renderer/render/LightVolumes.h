// Layer 7 (Render): lights drawn as volumes, shared by the deferred lighting pass and the
// redeferred illumination pass: a sphere per ranged point light, a cone per ranged spot light
// and a full-screen triangle for directional and unbounded lights. One instanced draw per shape.
#pragma once
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "render/GpuScene.h"

namespace fe::render {

// Whether a ranged light's sphere of influence lies wholly outside the view: beyond one of the
// four side planes of `seen`'s frustum (eye-relative clip space, viewProjFromEye, as
// light_volume.vert draws; the planes meet at the eye, so what lies behind it is out too). Such
// a light's volume covers no pixel, and outside its range the fragment shader adds nothing, so
// LightVolumes skips it without changing a pixel. Directional and unbounded lights: never.
bool lightOutOfView(const assets::Light& light, const FrameConstants& seen);

class LightVolumes {
public:
    // `fragmentShader` decides what a volume computes (deferred radiance or I-buffer sums);
    // every colour target is accumulated additively (alpha too: the light pre-pass keeps its
    // monochrome specular there; shaders that write alpha 0 leave it as it was).
    LightVolumes(gdi::Device& device, const std::string& fragmentShader,
                 std::vector<gdi::Format> targets);

    // Draws the lights without shadows, [0, scene.unshadowedLightCount()). `seen`: the frame's
    // constants on the CPU, whose camera culls the lights whose range lies outside the view.
    void draw(gdi::CommandList& cmd, CommandQueue& queue, const GpuScene& scene,
              const UploadAllocation& frame, const FrameConstants& seen);
    // Draws lights [first, first + count) of the light buffer (a shadowed light's own pass).
    void drawRange(gdi::CommandList& cmd, CommandQueue& queue, const GpuScene& scene,
                   const UploadAllocation& frame, const FrameConstants& seen, uint32_t first,
                   uint32_t count);

    struct Counts {
        uint32_t spheres = 0, cones = 0, fullscreen = 0;
    };
    static Counts classify(const std::vector<assets::Light>& lights);

private:
    gdi::DeviceObjects objects_;
    gdi::BufferHandle mesh_;
    uint32_t sphereFirst_ = 0, sphereCount_ = 0, coneFirst_ = 0, coneCount_ = 0;
    gdi::ShaderHandle vs_, fs_;
    gdi::PipelineHandle volumePipeline_, fullscreenPipeline_;
};

}  // namespace fe::render
