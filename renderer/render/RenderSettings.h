// Layer 7: what a frame is rendered with, shared by every technique renderer and layer 8.
#pragma once
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "shading/Tonemap.h"

namespace fe::render {

// Shadow maps (render/ShadowPlan.h says which lights get one and how they are fitted).
struct ShadowSettings {
    bool enabled = false;
    uint32_t mapSize = 1024;   // texels per side of each map: a cascade, a spot map, a cube face
    uint32_t cascades = 4;     // per directional light, 1..4
    uint32_t pointBudget = 4;  // point lights with a shadow cube, the most important first
    bool pcf = true;  // the device's 2x2 bilinear comparison; false: one nearest comparison
};

// Redeferred: an I-buffer rate per illumination source (1, 2 or 4 per axis; 0: illumScale's), the
// seed's "dedicated shading rate per illumination source" (fe render --rates).
struct SourceRates {
    uint32_t punctual = 0;     // the lights without shadows
    uint32_t shadowed = 0;     // the lights with shadow maps
    uint32_t iblDiffuse = 0;   // the environment's L_dg
    uint32_t iblSpecular = 0;  // the environment's L_sg1, L_sg2
};

// Antialiasing of the display image as a post-process (hardware MSAA is RenderSettings::msaa).
// Taa: the projection jitters by a sub-pixel Halton offset per frame and a resolve pass blends
// each frame with the reprojected, neighbourhood-clamped history (converges over frames).
enum class AntiAliasing : uint32_t { None, Fxaa, Taa };

// The BRDF a frame shades with (docs/SHADING.md). Auto: glTF 2.0's wherever the technique can
// evaluate it, the separable model of ../shared/SHADING.md in the techniques whose light sums
// factor it out of the material (TechniqueInfo::separableBrdf: redeferred, light-prepass).
enum class ShadingModel : uint32_t { Auto, Gltf, Separable };

// What the frame shows where no surface is (SceneRenderer's "background" pass).
struct Background {
    enum class Kind : uint32_t {
        Auto,         // the scene's environment where it has one, else black
        Environment,  // the scene's environment (an Error without one)
        Color,        // `color` in the display image
        Transparent,  // alpha 0 in the display image (RGBA PNG); blended surfaces keep theirs
    };
    Kind kind = Kind::Auto;
    // Kind::Color: the display image's sRGB-encoded value in [0, 1] (what "#rrggbb" says), 8 bits
    // a channel. Color and Transparent keep coverage in L_o's alpha (0 where nothing is drawn,
    // blended surfaces "over" it); the display pass composites the tone-mapped colour over the
    // background colour, or writes the coverage as alpha. L_o (a .pfm) holds 0 there.
    glm::vec3 color{0.0f};
};

struct RenderSettings {
    std::string technique = "forward";  // a name from techniques() (TechniqueRenderer.h)
    uint32_t width = 320;
    uint32_t height = 240;
    uint32_t illumScale = 1;  // redeferred I-buffer: 1, 2 or 4
    uint32_t msaa = 1;        // samples per pixel (TechniqueInfo::msaa: all but redeferred)
    // Redeferred options from the seed's considerations, each measured (docs/BENCHMARKS.md):
    // the specular sums L_sg1, L_sg2 at full resolution while L_dg stays at 1/illumScale, so only
    // the smooth diffuse term is upsampled (redeferred-tiled only; "separate upscaling for
    // diffuse and specular").
    bool illumSplit = false;
    // The material pass takes w_o.n from the G-buffer (written by the geometry pass) instead of
    // rebuilding it from depth and the normal; applies at illumScale 1, where nothing else needs
    // depth or normals there (consideration A).
    bool precomputedNoV = true;
    // deferred-tiled: lights culled per tile by a pass of their own (TileLightCulling) rather
    // than by each shading work group in shared memory within the one dispatch (measured both
    // ways, docs/BENCHMARKS.md). redeferred-tiled always uses the culling pass.
    bool tileCullingPass = true;
    // The translucent pass lights each blended fragment with its cluster's lights (the light
    // cluster grid, made for it when the technique has none); off: with every light, the way
    // it was measured against (the same image: a culled light adds exactly 0).
    bool translucentClusters = true;
    // The light cluster grid of clustered-deferred, clustered-forward (at one sample) and the
    // visibility buffer is bounded by the opaque depth each cluster holds (ClusterLightGrid::
    // declareBounded: an opaque pixel walks only the lights reaching those depths); off: every
    // pixel walks its slice's whole list, as before (the same image; measured both ways).
    bool clusterDepthBounds = true;
    // The compute passes that share nothing with the graphics passes around them (the light
    // cluster grid's assignment when it is not bounded by depth, the particles' simulation) run
    // on the compute queue beside them (RenderGraph::execute(CommandQueue&); a device with one
    // queue orders them as before); off: every pass on the graphics list, in order.
    bool asyncCompute = true;
    // A "light-list-statistics" pass after the technique's: per pixel, the lights its shading
    // loop walks (SceneRenderer::lightListStatistics). measureLightLists turns it on in a renderer of
    // its own (fe render --verbose, fe bench, the director), out of the timed frames.
    bool lightListStatistics = false;
    // Image-based lighting: samples per pixel for each of the specular and diffuse terms (0: the
    // environment is only the background). Needs an environment and a technique that takes it
    // (TechniqueInfo::ibl).
    uint32_t iblSamples = 0;
    // Image-based lighting by the fast path instead (PrefilteredEnvironment: prefiltered cube,
    // split-sum table, SH irradiance); iblSamples is then unused.
    bool iblPrefiltered = false;
    bool ibl() const { return iblSamples > 0 || iblPrefiltered; }
    // Separable on any technique (to compare with the redeferred family under one model); Gltf
    // on a technique with TechniqueInfo::separableBrdf is an Error.
    ShadingModel shadingModel = ShadingModel::Auto;
    ShadowSettings shadows;
    SourceRates rates;
    // Redeferred at illumScale > 1: the reduced-rate sampling jitters through each I-buffer
    // block from frame to frame and accumulates over frames (TemporalAccumulation; the seed's
    // consideration D).
    bool temporal = false;
    uint32_t rate(uint32_t sourceRate) const { return sourceRate ? sourceRate : illumScale; }
    // The sources this frame has (shadowed lights with shadows on, the environment's two with
    // image-based lighting) do not all share one rate: then each rate gets an I-buffer of its
    // own, upsampled into the full-rate one (RedeferredRenderer).
    bool perSourceRates() const {
        const uint32_t p = rate(rates.punctual);
        return (shadows.enabled && rate(rates.shadowed) != p) ||
               (ibl() && (rate(rates.iblDiffuse) != p || rate(rates.iblSpecular) != p));
    }
    float exposure = 1.0f;
    // The display image's post-processing (render/PostProcess.h): exposure x L_o through a tone
    // mapper (clamp keeps the image comparable with the exact reference), then antialiasing.
    shading::Tonemap tonemap = shading::Tonemap::Clamp;
    AntiAliasing antiAliasing = AntiAliasing::None;
    Background background;
    // A debug view: the display shows this intermediate texture of the frame's graph (by its
    // name, as RenderGraph::textures() lists them: "gbuffer1 normal+roughness", "depth", ...)
    // instead of L_o, scaled by the exposure; "light count": a heat map of how many lights reach
    // each pixel (SceneRenderer::kLightCountView). Empty: the frame itself.
    std::string debugView;
    // Also produce the displayable image (RGBA8_SRGB) on the GPU; without it the graph culls
    // the post-processing passes.
    bool displayImage = false;
    // forward-plus writes the display image in its shading pass, one full-screen pass fewer,
    // where nothing after that pass changes L_o (SceneRenderer::displayInShading: the same
    // pixels). false: always the display pass (to compare the two).
    bool displayInShading = true;
    // Alias transient memory (false: every transient texture has memory of its own).
    bool aliasing = true;
};

}  // namespace fe::render
