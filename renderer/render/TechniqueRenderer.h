// Layer 7 (Render): a lighting technique is a renderer that declares its passes and buffers on
// the render graph. It writes the opaque scene's outgoing radiance L_o into `output` and leaves
// the scene depth in `depth`; layer 8 (integration/SceneRenderer) adds the transparent and
// display passes. Adding a technique is adding a renderer and its line in techniques().
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/GeometryRenderer.h"
#include "render/EnvironmentMap.h"
#include "render/GpuScene.h"
#include "render/ShaderFeatures.h"
#include "render/RenderSettings.h"
#include "shading/ShadingModel.h"
#include "render/ShadowMaps.h"

namespace fe::render {

class ClusterLightGrid;

// What every technique draws with, owned by the scene renderer. frame and frameConstants are
// those of the frame being recorded (valid inside pass bodies).
// A pass body's frame constants, when they differ from the frame's (an I-buffer of another rate).
using FrameConstantsFn = std::function<UploadAllocation()>;

struct TechniqueContext {
    gdi::Device& device;
    CommandQueue& queue;
    GpuScene& scene;
    GeometryRenderer& geometry;
    const RenderSettings& settings;
    const FrameConstants& frame;             // this frame's constants on the CPU
    const UploadAllocation& frameConstants;  // ... and their upload
    glm::vec3 eye;
    gdi::SamplerHandle pointSampler;  // nearest, clamped: reads of full-resolution buffers
    gdi::ShaderHandle fullscreenVs;   // scene/fullscreen.vert
    // What image-based lighting reads when the frame is lit by its environment (RenderSettings::ibl()).
    EnvironmentLight environmentLight;
    // The shadowed lights' maps when the frame has shadows (RenderSettings::shadows). The
    // technique's own light loops and volumes cover the unshadowed lights; it adds each shadowed
    // light in a pass of its own through ShadowMaps::declare.
    ShadowMaps* shadows = nullptr;
    // The light cluster grid, when the technique reads it (TechniqueInfo::clusters) or the scene
    // has blended surfaces (the translucent pass reads it) and the device has compute shaders.
    ClusterLightGrid* clusters = nullptr;
    // The display image (kDisplayFormat) for a technique that writes it in its shading pass
    // (TechniqueInfo::writesDisplay), when nothing after its passes changes L_o
    // (SceneRenderer::displayInShading); invalid otherwise. Set before each declare().
    graph::TextureId display;
};

// The scene shaders' specialization for this frame's light passes (ShaderFeatures): the scene's
// light types and the frame's BRDF (FrameConstants::shading.x); they sample no material.
inline ShaderFeatures frameFeatures(const TechniqueContext& c) {
    return {
        .lightTypes = c.scene.lightTypes(),
        .brdfModels = c.frame.shading.x == 1u ? ShaderFeatures::kSeparable : ShaderFeatures::kGltf};
}

constexpr gdi::Format kRadianceFormat = gdi::Format::RGBA32F;  // linear L_o, exact enough for .pfm
constexpr gdi::Format kSceneDepthFormat = gdi::Format::D32F;

// What forward-style techniques render into: `output` and `depth` themselves, or with --msaa N
// multisampled transients that the technique's last pass resolves into them (colour averaged,
// depth from sample 0, so the transparent pass after it tests against real surface depths).
struct ForwardTargets {
    graph::TextureId color, depth;        // what the technique's passes render into
    graph::TextureId output, sceneDepth;  // the single-sample results
    MeshPassTargets formats;
    // The shadowed lights' passes come after the technique's own and resolve in the last of
    // them (TechniqueRenderer::declareShadowedForward): resolveIn() then declares nothing.
    bool resolveLater = false;
    // Declares the resolves in the pass that ends the technique (nothing at one sample).
    void resolveIn(graph::PassBuilder& b) const;
};

// Which lights a technique's shading loop walks for a pixel, for the light-list statistics
// (SceneRenderer::lightListStatistics): every light, a tile list (the graph texture of
// TileLightCulling, declared by declare()), the cluster grid's list, or not measured (light
// volumes: the lights whose volume covers the pixel; redeferred's lists at the I-buffer's rate).
struct LightLists {
    enum class Kind { EveryLight, Tiles, Clusters, NotMeasured } kind = Kind::EveryLight;
    graph::TextureId tiles;  // Kind::Tiles
};

class TechniqueRenderer {
public:
    explicit TechniqueRenderer(TechniqueContext& context) : ctx_(context) {}
    virtual ~TechniqueRenderer() = default;
    // Declares the passes that fill `output` (L_o, kRadianceFormat) and `depth` (transient).
    virtual void declare(graph::RenderGraph& graph, graph::TextureId output,
                         graph::TextureId depth) = 0;
    // What the shading loop walks (valid after declare).
    virtual LightLists lightLists() const { return {}; }

protected:
    // resolveLater is set when shadowed lights follow (declareShadowedForward).
    ForwardTargets forwardTargets(graph::RenderGraph& g, graph::TextureId output,
                                  graph::TextureId depth) const;
    bool hasShadowedLights() const { return ctx_.shadows && ctx_.shadows->any(); }
    // Forward techniques, after their own passes: each shadowed light's map and a pass adding
    // that light into t.color where depth is EQUAL (MeshPass::ForwardShadowed); the last one
    // resolves t. `objects`: the technique's object constants of this frame, if it keeps them.
    void declareShadowedForward(graph::RenderGraph& g, const ForwardTargets& t,
                                std::vector<UploadAllocation>* objects);
    // Sets a pipeline and binds the frame constants and the scene's lights at their slots.
    void bindFrameAndLights(gdi::CommandList& cmd, gdi::PipelineHandle pipeline) const;
    // A pass body: one full-screen triangle with the frame constants and graph textures bound.
    using SlotTextures = std::vector<std::pair<uint32_t, graph::TextureId>>;
    std::function<void(graph::PassContext&)> fullscreen(gdi::PipelineHandle pipeline,
                                                        SlotTextures inputs) const;
    TechniqueContext& ctx_;
};

struct TechniqueInfo {
    const char* name;
    const char* summary;  // one line for `fe render --help`
    std::unique_ptr<TechniqueRenderer> (*create)(TechniqueContext&);
    // Renders with hardware MSAA (--msaa N): the forward ones into multisampled targets, the
    // deferred ones and the visibility buffer from a multisampled G-buffer (GBuffer.h). The
    // light pre-pass's light pass is per pixel; redeferred's I-buffer sums refuse with a message.
    bool msaa = false;
    // Has an I-buffer, so takes --illum-scale (redeferred and redeferred-tiled).
    bool illumScale = false;
    // Reads the light cluster grid (TechniqueContext::clusters).
    bool clusters = false;
    // Reads the grid with --msaa N > 1 only (forward-plus: a fragment outside its tile's depth
    // bounds walks its cluster's list).
    bool clustersUnderMsaa = false;
    // Accumulates light sums the material multiplies afterwards (I-buffer, light buffer): only
    // the separable BRDF factors that way, so glTF's is not available (RenderSettings::shadingModel).
    bool separableBrdf = false;
    // Shades from a G-buffer (base colour, metallic, normal, roughness, emissive): the material's
    // dielectric Fresnel (KHR_materials_ior / specular) is not there, so 0.04 and 1 are used.
    bool gbuffer = false;
    // Can write the display image in its shading pass (TechniqueContext::display): forward-plus.
    bool writesDisplay = false;
    // Evaluates every material input of the glTF model under `brdf` (what materialWarnings asks).
    bool fullMaterial(shading::Brdf brdf) const {
        return !gbuffer && !separableBrdf && brdf == shading::Brdf::Gltf;
    }
    // The BRDF it shades with when RenderSettings::shadingModel is Auto.
    shading::Brdf defaultBrdf() const {
        return separableBrdf ? shading::Brdf::Separable : shading::Brdf::Gltf;
    }
    // Every technique lights the scene by its environment with --ibl-samples N (checked for
    // every line of the table by EnvironmentTests).
};
// Every technique, in the order help lists them (Techniques.cpp).
const std::vector<TechniqueInfo>& techniques();
// Throws gdi::Error listing the valid names.
const TechniqueInfo& findTechnique(const std::string& name);
std::string techniqueNames();  // "forward, deferred, ..."
// The BRDF a frame of `settings` shades with (FE_BRDF_GLTF, FE_BRDF_SEPARABLE in fe_shading.glsl)
// and the CPU reference to compare it with (ReferenceOptions::brdf): Auto resolved by the
// technique; Gltf where the technique cannot evaluate it is a gdi::Error.
shading::Brdf resolveBrdf(const RenderSettings& settings);

}  // namespace fe::render
