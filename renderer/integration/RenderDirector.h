// Layer 8 (Integration): the Render Director picks the lighting technique and its options
// from what a scene needs (`fe render --technique auto`), and says why. The scene renderer
// then builds only what that technique and the scene need: no G-buffer for forward, no
// I-buffer outside redeferred, no transparent pass without BLEND primitives (SceneRenderer).
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

// What in a scene drives the choice.
struct SceneNeeds {
    uint32_t lights = 0;          // every light
    uint32_t boundedLights = 0;   // point and spot lights with a range (cullable per tile)
    uint32_t blendPrimitives = 0; // instances x primitives with BLEND materials
};
SceneNeeds sceneNeeds(const assets::Scene& scene);

// Settings with technique "auto" get one chosen; any other technique is kept as asked.
DirectorChoice direct(const assets::Scene& scene, const RenderSettings& requested, const gdi::DeviceInfo& device);

// Up to this many lights, forward shading (one pass, no G-buffer) is chosen over the deferred
// techniques. Measured (builtin:lights, 640x360, vulkan/lavapipe, median of 5 frames): forward
// 23.3 / 23.3 / 31.8 / 45.1 ms at 2 / 4 / 8 / 16 lights, deferred-tiled 28.6 / 28.3 / 28.1 /
// 27.9 ms: the crossover lies between 4 and 8 (docs/BENCHMARKS.md).
constexpr uint32_t kForwardMaxLights = 4;

}  // namespace fe::render
