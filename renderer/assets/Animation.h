// Layer 5 (Communication: Asset Loader): glTF 2.0 animation on the CPU-side scene: keyframe
// sampling, the node hierarchy's world transforms, skins' joint matrices and morph weights.
//
// A scene from the glTF loader keeps its nodes, skins and animations (Scene::nodes, skins,
// animations) and is loaded in its rest pose. poseScene() moves it to an instant of one
// animation: every MeshInstance's world (and its joints and weights when deformed), the
// lights and cameras hung from nodes, and Scene::bounds. The mesh data never changes: the
// renderer deforms the rest pose on the device each frame (render/MeshDeformation.h), the CPU
// reference deforms it in double precision (reference/AnimationReference.h).
//
//   assets::Scene scene = assets::loadGltf("Fox.glb");
//   const int32_t walk = assets::findAnimation(scene, "Walk");  // or "1"
//   assets::poseScene(scene, {.animation = walk, .seconds = 0.5});
//   renderer.updatePose();  // a SceneRenderer made from `scene` uploads the pose
//
// Sampling follows the glTF 2.0 specification (3.11 and Appendix C): before the first key the
// first value, after the last key the last value (PoseTime::loop wraps the time into
// [0, duration) instead); STEP holds a key's value until the next; LINEAR interpolates, rotations
// by spherical linear interpolation along the shorter arc; CUBICSPLINE is the Hermite spline of
// the keys' values and tangents, the tangents scaled by the key interval, rotations normalised
// after. Skinning: joint matrix j = inverse(world of the skinned mesh's node) x world of joint j
// x inverse bind matrix j; a vertex is moved by the sum of its influences' joint matrices times
// their weights, as stored. Morph weights come from the animation, else node.weights, else
// mesh.weights (0 where none is given).
#pragma once
#include <cstdint>
#include <string>

#include "assets/Scene.h"

namespace fe::assets {

// PoseTime::animation for every animation of the scene at once (each wrapping on its own
// duration with `loop`; where two animate the same property, the later one wins), as the Khronos
// Sample Viewer plays a file by default.
inline constexpr int32_t kAllAnimations = -2;

struct PoseTime {
    // Into Scene::animations; -1: the rest pose (the nodes' own transforms); kAllAnimations.
    int32_t animation = -1;
    double seconds = 0.0;
    bool loop = false;  // wrap the time into [0, duration); else hold the first / last key
};

// The animation named by `indexOrName` (a number is an index, else a name, exactly; "all":
// kAllAnimations unless one is named so). Throws AssetError listing the scene's animations when
// there is no such one.
int32_t findAnimation(const Scene& scene, const std::string& indexOrName);
// The same for Scene::cameras.
int32_t findCamera(const Scene& scene, const std::string& indexOrName);

// The value of `sampler` at `seconds` (no wrapping), `sampler.width` floats into `out`;
// `rotation`: the values are quaternions (x, y, z, w), interpolated as such.
void sampleAnimation(const AnimationSampler& sampler, float seconds, bool rotation, float* out);

// Moves the scene to `time` (see the top of this file). Throws AssetError when `time` names no
// animation or is not finite. Cheap enough per frame: no vertex is touched.
void poseScene(Scene& scene, const PoseTime& time = {});

// The object-space bounds of `primitive` deformed by `instance`'s joints and weights
// (conservative: see MeshInstance::posedBounds).
AABB deformedBounds(const Primitive& primitive, const MeshInstance& instance);

}  // namespace fe::assets
