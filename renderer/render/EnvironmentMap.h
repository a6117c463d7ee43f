// Layer 7: an environment (assets/Environment.h) on the GPU. A cube map with a full mip chain,
// made once when the scene is loaded by drawing each face (builtin:sky evaluated per texel, or
// the equirectangular image sampled bilinearly), then drawn as the background: a full-screen
// triangle at the far plane wherever the depth buffer still holds it.
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "assets/Environment.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"

namespace fe::render {

// What a frame's image-based lighting reads (TechniqueContext::environmentLight): the
// environment's cube for the sampled estimator, or the fast path's prefiltered cube, table and
// harmonics (PrefilteredEnvironment). Null when the frame is not lit by its environment.
struct EnvironmentLight {
    gdi::TextureHandle cube;
    gdi::SamplerHandle sampler;
    gdi::TextureHandle lut;  // the fast path only
    gdi::BufferHandle sh;    // the fast path only
    explicit operator bool() const { return bool(cube); }
    bool prefiltered() const { return bool(lut); }
    // Binds the cube at kSlotEnvironment, on the fast path also the table and SH.
    void bind(gdi::CommandList& cmd) const;
    // The shader for this path: "scene/x.frag" or, on the fast path, "scene/x_prefiltered.frag".
    std::string shader(const std::string& sampled) const;
};

class EnvironmentMap {
public:
    // Face size in texels: 256 resolves builtin:sky's one-degree sun limb (0.35 degrees a texel
    // at a face's centre).
    static constexpr uint32_t kDefaultFaceSize = 256;
    static constexpr gdi::Format kFormat = gdi::Format::RGBA32F;  // HDR suns exceed half floats

    EnvironmentMap(gdi::Device& device, const assets::Environment& environment,
                   gdi::ShaderHandle fullscreenVs, uint32_t faceSize = kDefaultFaceSize);
    EnvironmentMap(const EnvironmentMap&) = delete;
    EnvironmentMap& operator=(const EnvironmentMap&) = delete;

    gdi::TextureHandle cube() const { return cube_; }
    gdi::SamplerHandle sampler() const { return sampler_; }  // trilinear, clamped
    // Inside a render pass on L_o (kRadianceFormat) and the scene depth (D32F, loaded): draws the
    // environment where the depth is 1.
    void drawBackground(gdi::CommandList& cmd, const UploadAllocation& frameConstants) const;

    // The face passes' uniform block (fe_environment.glsl), std140.
    struct Params {
        glm::vec4 faceSize, zenith, horizon, ground, sunDirection, sunRadiance, sunCos;
    };

private:
    gdi::DeviceObjects objects_;
    gdi::TextureHandle cube_;
    gdi::SamplerHandle sampler_;
    gdi::ShaderHandle backgroundVs_, backgroundFs_;
    gdi::PipelineHandle background_;
};

}  // namespace fe::render
