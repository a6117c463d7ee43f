// Layer 8 (Integration): the Render Director picks the lighting technique and its options
// from what a scene needs (`fe render --technique auto`), and says why. The scene renderer
// then builds only what that technique and the scene need: no G-buffer for forward, no
// I-buffer outside redeferred, no transparent pass without BLEND primitives (SceneRenderer).
//
// The choice, in order (each threshold is a measurement, see the constants below):
//   - lights that cover the screen nearly as often as there are lights (every pixel would shade
//     most of them anyway): forward (exact, one pass, no G-buffer; takes --msaa). Precisely:
//     lights <= kVolumeCostPerForwardLight x coverage (SceneNeeds::lightCoverage);
//   - more lights and --msaa N: clustered-forward (exact, keeps hardware MSAA, each fragment
//     shading its cluster's lights: measured fastest with MSAA, docs/BENCHMARKS.md many lights);
//     without compute shaders light-prepass, which keeps hardware MSAA with lights drawn per
//     pixel; its RGBA16F normal target when the scene's smoothest material is below
//     kPackedNormalsMinRoughness (8-bit normals lose such highlights);
//   - more lights whose volumes cover the screen less than kTiledMinCoverage times: deferred
//     (light volumes cost what they cover; tiles cost a fixed culling pass);
//   - more, with compute shaders: on a GPU visibility-buffer (measured fastest there, an H200);
//     on a CPU rasterizer forward-plus, or clustered-forward where a probe frame shows a deep
//     scene (its clusters walk at most kDeepSceneClusterToTileRatio x the tiles' lights; measured
//     from 32 to 512 lights on builtin:lights and builtin:atrium: forward-plus faster than
//     deferred-tiled in every case and fastest on builtin:lights, clustered-forward fastest in
//     the atrium; docs/BENCHMARKS.md director crossovers), or deferred-tiled when an error
//     budget may reduce the illumination rate (its G-buffer feeds the I-buffer); translucent
//     surfaces do not change the choice: their pass reads the cluster grid whatever the
//     technique. Without compute shaders: deferred;
//   - with an error budget (DirectorOptions), the reduced-rate technique redeferred-tiled at
//     illumination scale 4, then 2, when a probe frame of it stays within the budget against the
//     exact image of the technique it would replace. Without a budget nothing inexact is chosen.
#pragma once
#include <string>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"
#include "render/RenderSettings.h"

namespace fe::render {

struct DirectorChoice {
    RenderSettings settings;           // the request with the technique decided
    std::vector<std::string> reasons;  // one line per decision, for --verbose
};

struct DirectorOptions {
    // Percentage of pixels that may differ from the exact image by more than 5/255 in some
    // channel of the displayed 8-bit sRGB image (exposure applied, clamped). 0: exact
    // techniques only. Checked by rendering probe frames on the device given to direct().
    double errorBudgetPercent = 0.0;
};

// What in a scene drives the choice.
struct SceneNeeds {
    uint32_t lights = 0;           // every light
    uint32_t boundedLights = 0;    // point and spot lights with a range (cullable per tile)
    uint32_t blendPrimitives = 0;  // instances x primitives with BLEND materials
    // Instances x primitives whose material only a full-material technique shows
    // (assets::Material::needsFullMaterial: KHR_materials_ior / specular / clearcoat).
    uint32_t fullMaterialPrimitives = 0;
    // Sum over lights of the screen fraction their range sphere covers (1 for lights without a
    // range, and for spheres around the eye): how many times over the lights cover the screen.
    // The projected disc is not clipped to the screen, so this errs high.
    double lightCoverage = 0.0;
    // Perceptual roughness of the lit materials drawn (factor x the texture's range).
    float minRoughness = 1.0f, maxRoughness = 0.0f;
};
// `aspect` is the viewport's width / height (the camera's own aspect ratio wins if it has one).
SceneNeeds sceneNeeds(const assets::Scene& scene, float aspect);

// Settings with technique "auto" get one chosen; any other technique is kept as asked. With a
// device, an error budget is checked by probe frames; without one it is reported as unused.
DirectorChoice direct(const assets::Scene& scene, const RenderSettings& requested,
                      const gdi::DeviceInfo& info, gdi::Device* probeDevice = nullptr,
                      const DirectorOptions& options = {});

// The error-budget metric (DirectorOptions::errorBudgetPercent) between two linear L_o images.
double percentPixelsOver5Of255(const gdi::Image& a, const gdi::Image& b, float exposure);

// Forward shades every light at every pixel; light volumes shade a light only where it reaches,
// but each covered pixel costs more (a G-buffer read and a blend per light). This is that cost
// ratio: a screen's worth of volume against one light in forward's loop. Measured
// (builtin:lights, 640x360, median of 5 frames, docs/BENCHMARKS.md): forward adds 1.5 ms per
// light on vulkan and gl-egl; deferred adds 7.6 (vulkan) and 8.1 (gl-egl) ms per screen covered.
constexpr double kVolumeCostPerForwardLight = 5.0;
// Below this roughness the packed 8-bit normals of light-prepass lose highlights. Measured
// (RenderAccuracy.PackedNormalsHoldFromDirectorThreshold, a plane's highlight summed over 9x9
// pixels, packed / RGBA16F normals): 0.053 at roughness 0.05, 0.735 at 0.1, 0.991 at 0.15,
// 0.9996 at 0.2, 1.004 at 0.3, every backend the same.
constexpr float kPackedNormalsMinRoughness = 0.2f;
// Light coverage (SceneNeeds::lightCoverage) from which tiled culling beats light volumes.
// Measured with the light-culling pass (builtin:lights, 640x360, median of 5 frames, deferred /
// deferred-tiled): gl-egl 25.3 / 30.4 ms at coverage 0.3, 29.5 / 28.0 at 0.5, 28.1 / 26.2 at
// 1.1; on vulkan tiles win at every coverage measured (20.7 / 12.5 ms at 0.1). The GL crossover
// is taken for both (docs/BENCHMARKS.md).
constexpr double kTiledMinCoverage = 0.4;
// Many lights on a CPU rasterizer: clustered-forward when a probe frame's cluster lists walk at
// most this many times the lights of its depth-bounded tile lists (a deep scene), else
// forward-plus. Measured (lights walked per pixel, clusters / tiles, at 64x48 to 640x360):
// builtin:atrium 0.46-1.09, where clustered-forward was 7-29 % faster than forward-plus;
// builtin:lights 1.44-3.59, where forward-plus was 1.2-1.9x faster (docs/BENCHMARKS.md).
constexpr double kDeepSceneClusterToTileRatio = 1.3;

}  // namespace fe::render
