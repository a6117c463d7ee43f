// Layer 7 (Render): which lights cast shadows and how their shadow maps see the scene. Plain
// CPU math, no device: the GPU renderer (ShadowMaps) and the tests that ask the CPU reference
// for the same shadowed lights both plan with it.
//
// Visibility is binary and exact in the reference (a shadow ray from the surface to the light,
// every non-BLEND triangle occluding from either side); a shadow map approximates it:
//  - directional lights: 1 to 4 cascades, each an orthographic map around the bounding sphere of
//    one slice of the view frustum (slices split half-way between uniform and logarithmic), its
//    depth range stretched over the whole scene so every caster is inside;
//  - spot lights: one perspective map through the outer cone;
//  - point lights: a cube map, one 90-degree face per axis; only the `pointBudget` most important
//    point lights (below) get one, the others light without shadows.
// The frustum is cut where the scene's bounds end, so no map is spent on empty space.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "assets/Scene.h"
#include "render/RenderSettings.h"

namespace fe::render {

enum class ShadowKind : uint8_t { Cascades, Spot, Cube };

struct ShadowedLight {
    uint32_t light = 0;  // index into the scene's lights
    ShadowKind kind = ShadowKind::Spot;
    uint32_t layers = 1;  // cascades, 1 (spot) or 6 (cube faces)
};

struct ShadowPlan {
    // The order in which the GPU stores the lights: every unshadowed light first, then the
    // shadowed ones in the order of `shadowed`, so the techniques' own light loops cover the
    // prefix [0, unshadowedCount) and each shadowed light is added by a pass of its own.
    std::vector<uint32_t> order;
    uint32_t unshadowedCount = 0;
    std::vector<ShadowedLight> shadowed;
    // Per scene light: does it cast shadows (what the CPU reference is told).
    std::vector<bool> castsShadow() const;
};

// The importance of a point light, by which the budget is filled: what it gives the middle of
// the view, intensity x luminance x range window / d^2, d its distance to the camera's central
// ray through the scene (clamped below at 1 % of that ray's length).
double shadowImportance(const assets::Light& light, const assets::Camera& camera,
                        const assets::AABB& bounds);

ShadowPlan planShadows(const std::vector<assets::Light>& lights, const assets::Camera& camera,
                       const assets::AABB& bounds, const ShadowSettings& settings);

// One shadowed light's projections for the current camera and light positions.
struct ShadowProjection {
    std::array<glm::mat4, 6>
        viewProj{};               // per layer: world -> the map's clip space (Vulkan conventions)
    glm::vec4 cascadeEnds{0.0f};  // cascades: the view depth at which cascade i ends
    // World size of one texel: per cascade (orthographic), or at unit distance from the light.
    glm::vec4 texelWorld{0.0f};
    float nearPlane = 0.0f, farPlane = 0.0f;  // spot and cube: the perspective depth range
    uint32_t layers = 1;
};

ShadowProjection shadowProjection(const assets::Light& light, ShadowKind kind, uint32_t layers,
                                  const assets::Camera& camera, float aspect,
                                  const assets::AABB& bounds, uint32_t mapSize);

// Cube faces (+X -X +Y -Y +Z -Z): the projection of direction d = P - light into face f's clip
// space, matching the cube map face selection of both APIs, depth 0 at `nearPlane`, 1 at `farPlane`.
glm::mat4 cubeFaceProjection(uint32_t face, const glm::vec3& light, float nearPlane,
                             float farPlane);

}  // namespace fe::render
