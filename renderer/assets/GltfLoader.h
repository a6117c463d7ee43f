// Layer 5 (Communication: Asset Loader): glTF 2.0 (.gltf + .bin/images, embedded, .glb) into a
// CPU-side Scene. No GPU work happens here.
//
// Supported
// ---------
// - The default scene (or scene 0, or LoadOptions::scene), its node hierarchy with TRS and matrix
//   transforms. Instances with det(world) < 0 are flagged `mirrored`.
// - Triangles, triangle strips and fans (converted to lists); POINTS / LINES / LINE_LOOP /
//   LINE_STRIP primitives are skipped with a warning.
// - POSITION, NORMAL, TANGENT (float), TEXCOORD_0 (float, normalized u8/u16), u8/u16/u32 indices
//   or none (0..n-1 generated), interleaved buffer views, sparse accessors (applied), accessors
//   without a buffer view (zeros + sparse).
// - Missing NORMAL: flat normals (glTF spec; the primitive is unwelded), or smooth normals with
//   LoadOptions::smoothNormals. Missing TANGENT with a normal map: generated from uv0 with the
//   MikkTSpace-like method of Geometry.h (hand-written: MikkTSpace has no Debian package).
//   Missing TANGENT without a normal map: any frame orthogonal to the normal.
// - Metallic-roughness materials, their five textures and samplers (images decoded to RGBA8 with
//   stb_image), alphaMode / alphaCutoff / doubleSided, KHR_materials_emissive_strength (folded
//   into emissiveFactor), KHR_materials_unlit (Material::unlit).
// - KHR_lights_punctual (position = node world translation, direction = node world -Z).
// - Every camera (perspective and orthographic) in depth-first node order (Scene::cameras), with
//   its node's world transform (scale removed); the first is Scene::camera. zfar absent = infinite.
// - EXT_mesh_gpu_instancing (one MeshInstance per instance).
// - Particle emitters: a node whose extras hold "fe_emitter" gets a ParticleEmitter at its world
//   position (keys in GltfLoader.cpp, addEmitter; docs/PARTICLES.md).
// - The node hierarchy (Scene::nodes), skins (JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1, u8/u16
//   joints, float or normalized weights), morph targets (POSITION, NORMAL, TANGENT deltas) and
//   animations (translation, rotation, scale and weights channels; LINEAR, STEP, CUBICSPLINE),
//   all through sparse accessors where the file has them. Meshes keep their rest pose; the scene
//   is returned posed at rest (assets::poseScene: joint matrices, morph weights from node.weights
//   or mesh.weights) and assets/Animation.h moves it to any instant of an animation.
//
// Warnings (Scene::warnings) rather than errors: ignored extensions that are not required,
// skipped primitive modes, cameras with invalid parameters, animation channels glTF does not
// allow (a TRS channel on a node with a matrix) or we do not read (KHR_animation_pointer).
//
// Errors: AssetError, message "<path>: <element>: <what>": missing / unreadable file, .glb
// without the glTF magic, malformed JSON (tinygltf's message), missing buffer file, accessor or
// buffer view out of bounds, index out of range, non-finite positions or transforms,
// unsupported component types, unsupported required extensions ("unsupported required extension
// KHR_draco_mesh_compression"), images that are missing or fail to decode, broken node
// hierarchies (cycles, two parents), dangling indices, skins naming joints they lack, animation
// samplers with decreasing key times or outputs that do not fit their keys, JSON nested deeper than 256 levels
// (tinygltf would overflow the stack), accessors without a buffer view above 2^24 components,
// images above 2^28 pixels. Bad input never crashes or hangs (fuzzed under ASan/UBSan).
// Resources are looked up next to the glTF file only, and only regular files are read.
//
// Defaults
// --------
// Camera, when the scene has none (LoadOptions::defaultCamera): yfov 45 degrees, up +Y, aimed at
// the centre c of the world bounds from the front (+Z, the glTF "front"), above and to the right:
// with r = half the bounds diagonal (1 if empty), the eye is at c + d v, v = normalize(0.5, 0.45,
// 1), d = r / sin(yfov / 2) (the bounding sphere touches the top and bottom of the view),
// znear = (d - r) / 2, zfar = d + 2r, aspect ratio unset. (Straight along -Z until 2026-11-29: a
// model lying in the XZ plane, TwoSidedPlane, was seen edge-on, an all-black image.)
// Lights, when the scene has none (LoadOptions::defaultLights), fixed relative to the camera
// (given in view space: +X right, +Y up, -Z forward; `direction` is where the light travels):
//   key:  directional, colour (1.0, 0.956, 0.898), 2.5 lux, direction normalize(0.5, -1, -1)
//         (from the viewer's upper left);
//   fill: directional, colour (0.85, 0.9, 1.0), 0.8 lux, direction normalize(-0.7, 0.2, -1)
//         (from the right, slightly below);
//   headlight: point at the eye, white, range infinite, intensity 0.7 * D^2 candela with D the
//         eye-to-bounds-centre distance (0.7 lux at the centre).
// A white Lambertian surface facing the default camera then reflects about 0.96 (exposure 1).
// fe render and fe view replace that rig by the default look unless lighting is asked for
// (assets::useDefaultSkyAndSun: builtin:sky as image-based light and background, and a sun with
// shadows); a library user calls it, or not, the same way.
#pragma once
#include <string>

#include "assets/AssetError.h"
#include "assets/Scene.h"

namespace fe::assets {

struct LoadOptions {
    int scene = -1;              // glTF scene index; -1 = the file's default scene, else 0
    bool defaultCamera = true;   // add the default camera when the scene has none
    bool defaultLights = true;   // add the default light rig when the scene has no lights
    bool smoothNormals = false;  // generated normals: false = flat (glTF spec), true = smooth
};

// Loads .gltf (JSON, external or embedded resources) and .glb (binary) files; the format is
// decided by the file's magic, and a .glb without the magic is an error. Throws AssetError.
Scene loadGltf(const std::string& path, const LoadOptions& options = {});

}  // namespace fe::assets
