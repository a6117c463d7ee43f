// Layer 7 (Render): draws scene meshes into whatever pass asks (forward, G-buffer, transparent).
// Owns the pipeline variants a mesh pass needs: one per (pass kind, cull mode, winding), since
// double-sided materials draw without culling and mirrored instances flip their front face.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "render/EnvironmentMap.h"
#include "render/GpuScene.h"
#include "render/ShaderFeatures.h"
#include "shading/ShadingModel.h"

namespace fe::render {

// Which pipeline state a mesh pass draws with (GeometryRenderer::pipeline has the table).
enum class MeshPass {
    Forward,          // shade, depth test <=, depth write
    GBuffer,          // write the G-buffer, depth test <=, depth write
    Transparent,      // BLEND items back to front, source-over, no depth write
    DepthPrepass,     // opaque items front to back, depth only (alpha test for MASK)
    ForwardEqual,     // shade where depth EQUALs the pre-pass depth, no depth write
    ForwardAdditive,  // shade and add (One, One) where depth is EQUAL: further lights of multipass
    NormalRoughness,  // light pre-pass 1: packed normal + roughness, depth write
    NormalRoughnessUnpacked,  // ... the RGBA16F variant
    LightPrepassMaterial,  // light pre-pass 3: material x light buffer (slot kSlotIBuffer0), depth EQUAL
    ShadowCaster,          // depth only into a shadow map: no culling, slope-scaled depth bias
    ForwardShadowed,  // ForwardAdditive for one light with its shadow map (kSlotShadow, kSlotShadowMap)
    ForwardShadowedCube,  // ... a point light with its shadow cube
    ForwardTiled,  // ForwardEqual over the pixel's tile light list (kSlotTileLights, forward-plus)
    ForwardClustered,  // ForwardEqual over the fragment's cluster list (kSlotClusterLights, clustered-forward)
    TransparentClustered,  // Transparent over the fragment's cluster list (any technique, with a cluster grid)
    Visibility,  // triangle ids (R32U) and depth, vertices pulled (kSlotVertices, kSlotIndices), front to back
    Transmission,  // transmissive items (KHR_materials_transmission) over the opaque scene's copy
                   // (kSlotTransmitted), every light, depth test <=, depth write
};

// What the pass renders into; pipelines are specialised to these formats.
struct MeshPassTargets {
    std::vector<gdi::Format> colorFormats;
    gdi::Format depthFormat = gdi::Format::D32F;
    uint32_t samples = 1;
    // ForwardTiled with a second colour target: the display image, written through this tone
    // mapper (shading::Tonemap's value; SceneRenderer::displayInShading).
    uint32_t displayTonemap = 0;
};

class GeometryRenderer {
public:
    GeometryRenderer(gdi::Device& device, GpuScene& scene);

    // Draws the scene's draw items that belong to `pass` (opaque+mask; blend sorted back to
    // front; or transmissive). `frameConstants` is the per-frame uniform allocation. Passes that draw the same
    // items again in a frame share `objects` (cleared at the start of each frame): each item's
    // object constants are uploaded the first time it is drawn and reused after.
    // Image-based lighting in the forward-shaded passes (Forward, ForwardEqual, Transparent) and
    // the light pre-pass material pass: forward_ibl.frag / lpp_material_ibl.frag reading this
    // cube (frame.counts.z samples per term). Before any draw.
    void setEnvironment(const EnvironmentLight& light);
    void draw(gdi::CommandList& cmd, CommandQueue& queue, MeshPass pass,
              const MeshPassTargets& targets, const UploadAllocation& frameConstants,
              const glm::vec3& eye, std::vector<UploadAllocation>* objects = nullptr);

    uint32_t drawCount(MeshPass pass) const;
    // The BRDF the shading passes' pipelines are specialized for (ShaderFeatures), the one the
    // frame constants name (FrameConstants::shading.x); until set, both (the shader picks).
    void setBrdf(shading::Brdf brdf) { brdfModels_ = ShaderFeatures::brdfOf(brdf); }

private:
    gdi::PipelineHandle pipeline(MeshPass pass, const MeshPassTargets& targets, gdi::CullMode cull,
                                 gdi::FrontFace face, uint32_t materialFeatures);
    std::vector<const DrawItem*> items(MeshPass pass, const glm::vec3& eye) const;

    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    GpuScene& scene_;
    bool uniformLights_;  // the forward shaders read the lights as the uniform block (GpuScene)
    // Every shader is made at its first pipeline (shader()).
    gdi::ShaderHandle vs_, forwardFs_, gbufferFs_, gbufferOcclusionFs_, depthFs_, lppNormalsFs_,
        lppNormalsUnpackedFs_, lppMaterialFs_;
    std::map<std::vector<uint32_t>, gdi::PipelineHandle> pipelines_;
    gdi::ShaderHandle forwardShadowedFs_, forwardShadowedCubeFs_;
    gdi::ShaderHandle forwardIblFs_, lppMaterialIblFs_;  // with an environment (setEnvironment)
    gdi::ShaderHandle forwardTiledFs_, forwardTiledMsaaFs_, forwardTiledDisplayFs_,
        forwardClusteredFs_;
    gdi::ShaderHandle visibilityVs_, visibilityFs_;
    gdi::ShaderHandle transmissionFs_;
    gdi::ShaderHandle shader(gdi::ShaderHandle& made, gdi::ShaderStage stage,
                             const std::string& path);
    gdi::ShaderHandle fragment(gdi::ShaderHandle& made, const std::string& path);
    gdi::ShaderHandle listShader(gdi::ShaderHandle& made, const char* name,
                                 const char* variant = nullptr);
    std::string lightsVariant(const std::string& path, const char* variant = nullptr) const;
    gdi::ShaderHandle visibilityShaders();
    gdi::ShaderHandle transmissionShader();
    uint32_t brdfModels_ = ShaderFeatures::kBothBrdfs;
    EnvironmentLight environment_;
    bool hasEnvironment_ = false;
};

}  // namespace fe::render
