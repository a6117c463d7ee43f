// Layer 7 (Render): the specialization constants of the scene shaders (fe_shading.glsl,
// fe_material.glsl): what a pipeline's scene and material hold, so the driver's compiler drops
// the code of what they do not. CPU rasterizers (llvmpipe, lavapipe) run both sides of a branch
// under a lane mask, so a test of a uniform skips nothing there; a constant removes the code.
// On llvmpipe and lavapipe, builtin:lights at 1280x720 with 512 lights, forward-plus's shading
// pass took 0.7x its time (docs/MEASUREMENT_LOG.md, "Forward+ against bgfx 21-deferred: the
// fourteenth session"), the images byte for byte the same. Unspecialized, everything is on.
#pragma once
#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "shading/ShadingModel.h"

namespace fe::render {

struct ShaderFeatures {
    // constant_id of each (fe_shading.glsl, fe_material.glsl).
    static constexpr uint32_t kLightTypesId = 200, kBrdfModelsId = 201, kMaterialId = 202;
    // The tone mapper of forward-plus's display output (fe_forward_pass.glsl, FE_DISPLAY_OUT).
    static constexpr uint32_t kDisplayTonemapId = 205;
    // FE_LIGHT_TYPES: the light types the scene's lights have.
    static constexpr uint32_t kDirectional = 1, kPoint = 2, kSpot = 4, kAllLights = 7;
    // FE_BRDF_MODELS: the BRDFs the pipeline may shade with (both: frame.shading.x picks).
    static constexpr uint32_t kGltf = 1, kSeparable = 2, kBothBrdfs = 3;
    // FE_MATERIAL_FEATURES: base colour, metallic-roughness, emissive or occlusion texture;
    // normal map; specular textures; clearcoat textures; clearcoat normal map; sheen; the MASK
    // alpha mode (the alpha test's discard).
    static constexpr uint32_t kBaseTextures = 1, kNormalMap = 2, kSpecularTextures = 4,
                              kClearcoatTextures = 8, kClearcoatNormalMap = 16, kSheen = 32,
                              kAlphaMask = 64, kAllMaterial = 0xffffffffu;
    // The features GpuScene keys per material; the others (the extensions') per scene.
    static constexpr uint32_t kPerMaterial = kBaseTextures | kNormalMap | kAlphaMask;

    uint32_t lightTypes = kAllLights;
    uint32_t brdfModels = kBothBrdfs;
    uint32_t material = kAllMaterial;

    static uint32_t lightTypesOf(const std::vector<assets::Light>& lights);
    static uint32_t brdfOf(shading::Brdf brdf) {
        return brdf == shading::Brdf::Separable ? kSeparable : kGltf;
    }
    static uint32_t materialOf(const assets::Material& m);

    // The constants for a pipeline of these shaders: only the ids one of them declares (a
    // pipeline given an id none declares is an Error).
    std::vector<gdi::SpecializationConstant> constantsFor(
        const gdi::Device& device, std::initializer_list<gdi::ShaderHandle> shaders) const;
};

// Of `values`, those whose id one of `shaders` declares.
std::vector<gdi::SpecializationConstant> declaredConstants(
    const gdi::Device& device, std::initializer_list<gdi::ShaderHandle> shaders,
    std::initializer_list<gdi::SpecializationConstant> values);

// A compute pipeline of one shader, made for each light types and BRDF it is asked for, at first
// use: the scene's lights may change types (SceneRenderer::updateLights), the settings the BRDF.
class FeatureComputePipelines {
public:
    FeatureComputePipelines(gdi::Device& device, gdi::ShaderHandle shader, std::string debugName)
        : objects_(device), device_(device), shader_(shader), name_(std::move(debugName)) {}
    gdi::PipelineHandle operator()(const ShaderFeatures& features);

private:
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    gdi::ShaderHandle shader_;
    std::string name_;
    std::map<std::pair<uint32_t, uint32_t>, gdi::PipelineHandle> made_;
};

}  // namespace fe::render
