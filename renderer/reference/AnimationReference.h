// The CPU reference of glTF animation: poses and deformed vertices in double precision,
// evaluated from the file's keys on their own (not through assets::poseScene, which the renderer
// uses in float), so tests can hold both the CPU posing and the device's deformation pass to the
// glTF 2.0 specification's formulas (assets/Animation.h restates them).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "assets/Animation.h"
#include "assets/Scene.h"

namespace fe::render {

struct ReferencePose {
    std::vector<glm::dmat4> nodeWorld;
    // Per MeshInstance: its world, joint matrices (empty unless skinned) and morph weights
    // (empty unless its mesh has targets).
    std::vector<glm::dmat4> instanceWorld;
    std::vector<std::vector<glm::dmat4>> joints;
    std::vector<std::vector<double>> weights;
};

ReferencePose evaluatePose(const assets::Scene& scene, const assets::PoseTime& time);

struct DeformedVertex {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0};
    glm::dvec4 tangent{1.0, 0.0, 0.0, 1.0};
};
// The primitive's vertices morphed by `weights` then skinned by `joints` (either may be empty),
// in the space of the instance's node; normals and tangents unit length, a flat primitive's
// normals those of its deformed faces.
std::vector<DeformedVertex> deformVertices(const assets::Primitive& primitive,
                                           const std::vector<glm::dmat4>& joints,
                                           const std::vector<double>& weights);
// The same with an instance's pose as the scene holds it (assets::poseScene's float matrices).
std::vector<DeformedVertex> deformVertices(const assets::Primitive& primitive,
                                           const assets::MeshInstance& instance);

}  // namespace fe::render
