// Layer 7 test oracle: the scene ray-cast on the CPU and shaded with the double-precision
// SHADING.md model (renderer/shading/ShadingModel.h). Independent of every GPU code path:
// visibility by ray-triangle intersection through each pixel centre, attributes interpolated
// with exact (perspective-correct) barycentrics, textures sampled bilinearly from level 0.
// Opaque and MASK materials only; BLEND primitives are ignored (draw them forward on top).
// Shadows: exact binary visibility by shadow rays for the lights the options name.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "assets/Scene.h"
#include "shading/ShadingModel.h"

namespace fe::render {

struct ReferenceImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::dvec3>
        radiance;                   // L_o per pixel, rows top to bottom; where nothing is hit, the
                                    // scene's environment along the ray (or 0)
    std::vector<int32_t> surface;   // id of the hit (instance, primitive) pair, -1 for background
    std::vector<uint8_t> textured;  // 1 where the hit material samples a texture
    // Bit k set: the k-th shadow-casting light (ReferenceOptions::castsShadow, counted in scene
    // order, the first 32) is hidden from the surface seen in the pixel by a shadow ray.
    std::vector<uint32_t> occluded;
    // True where the pixel or one of its 8 neighbours sees a different surface: rasterization
    // coverage rules may legitimately pick another surface there.
    bool nearEdge(uint32_t x, uint32_t y) const;
    // True where a pixel within `radius` pixels has other lights occluded: a shadow edge.
    bool nearShadowEdge(uint32_t x, uint32_t y, uint32_t radius) const;
};

struct ReferenceOptions {
    // Image-based lighting from the scene's environment (shading::shadeEnvironment), samples per
    // term per pixel; 0: the environment is only seen along missed rays.
    uint32_t iblSamples = 0;
    // Per scene light: it casts shadows, tested per pixel by a ray from the surface to the light
    // (to infinity for a directional light) against every non-BLEND triangle, either side, MASK
    // materials by their alpha cutoff. Empty: no light casts shadows (render/ShadowPlan.h says
    // which lights the GPU shadows).
    std::vector<bool> castsShadow;
    // The BRDF of the punctual lights and the environment (shading::Brdf): glTF 2.0's, or the separable model the
    // redeferred and light-prepass techniques shade with (render::resolveBrdf).
    shading::Brdf brdf = shading::Brdf::Gltf;
};

ReferenceImage renderReference(const assets::Scene& scene, const assets::Camera& camera,
                               uint32_t width, uint32_t height,
                               const ReferenceOptions& options = {});

}  // namespace fe::render
