// Layer 5 (Communication: Asset Loader): the CPU-side scene every renderer draws.
//
// Plain data, no GPU objects and no graphics API: a renderer uploads it through the abstract
// device (gdi) itself. Conventions are glTF's: right-handed world, +Y up, metres, a camera looks
// along its local -Z with +Y up, counter-clockwise front faces, linear colours (sRGB textures
// are flagged, not converted), light units of KHR_lights_punctual (lux / candela), see
// ../shared/SHADING.md. Material values are stored as authored: the roughness clamp to
// [0.045, 1] of SHADING.md is the shaders' job, not the loader's.
#pragma once
#include "assets/Environment.h"
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace fe::assets {

// Axis-aligned box; empty() until something is added.
struct AABB {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const AABB& b) {
        if (!b.empty()) {
            extend(b.min);
            extend(b.max);
        }
    }
    glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : (min + max) * 0.5f; }
    glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
    // Box around the 8 transformed corners (conservative for rotations).
    AABB transformed(const glm::mat4& m) const;
};
using Bounds = AABB;

// 72 bytes, tightly packed: uploadable as one interleaved vertex buffer (position RGB32F @0,
// normal RGB32F @12, tangent RGBA32F @24, uv0 RG32F @40, uv1 RG32F @48, color RGBA32F @56).
// Both glTF texture coordinate sets and COLOR_0 are always present (uv1 = 0 and colour = white
// where the file has none), so every pipeline has one vertex layout and no shader variant.
struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz unit, w = +-1: bitangent = w * cross(n, t)
    glm::vec2 uv0{0.0f};
    glm::vec2 uv1{0.0f};
    glm::vec4 color{1.0f};  // linear COLOR_0, multiplies the base colour (alpha too)
};
static_assert(sizeof(Vertex) == 72, "Vertex must stay tightly packed for direct upload");

// A vertex's skin influences: glTF's JOINTS_0/WEIGHTS_0 in [0] and JOINTS_1/WEIGHTS_1 in [1]
// (zero weights where the file has no second set). Joints index the skin's joint list; weights
// are used as stored (not renormalised), as the glTF spec asks. 64 bytes: uploadable as is.
struct SkinInfluences {
    glm::uvec4 joints[2]{glm::uvec4(0u), glm::uvec4(0u)};
    glm::vec4 weights[2]{glm::vec4(0.0f), glm::vec4(0.0f)};
};
static_assert(sizeof(SkinInfluences) == 64,
              "SkinInfluences must stay tightly packed for direct upload");

// A morph target: per-vertex displacements, each list empty when the target leaves that
// attribute alone (glTF POSITION, NORMAL and TANGENT deltas; the tangent's w never changes).
struct MorphTarget {
    std::vector<glm::vec3> position, normal, tangent;
};

// Always an indexed triangle list (strips/fans are converted, non-indexed input gets 0..n-1).
struct Primitive {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    uint32_t material = 0;  // always a valid index into Scene::materials
    AABB bounds;            // object space, of the rest pose
    // Deformation (assets/Animation.h), kept beside the rest pose in `vertices`: the skin
    // influences per vertex (empty: the primitive cannot be skinned) and the morph targets.
    std::vector<SkinInfluences> skin;
    std::vector<MorphTarget> targets;
    // The file had no NORMAL: the primitive is unwelded (vertex 3t + k is corner k of triangle
    // t) and a deformed pose gets its face normals again from the deformed positions.
    bool flatNormals = false;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    AABB bounds;                 // object space, union of the primitives (rest pose)
    std::vector<float> weights;  // glTF mesh.weights: the morph targets' default weights
};

enum class Filter : uint8_t { Nearest, Linear };
enum class MipFilter : uint8_t { None, Nearest, Linear };
enum class Wrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };

struct Sampler {
    Filter minFilter = Filter::Linear;
    Filter magFilter = Filter::Linear;
    MipFilter mipFilter = MipFilter::Linear;
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
    // False only when the file asked for a non-mipmapped minification filter.
    bool mipmaps = true;
};

// Decoded image + how it is sampled. A glTF texture used both as colour (sRGB) and as data
// (linear) becomes two entries, so the renderer can pick an _SRGB format per entry.
struct TextureImage {
    std::string name;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;  // RGBA8, rows top to bottom, width * height * 4 bytes
    bool srgb = false;            // true for baseColor / emissive, false for data textures
    Sampler sampler;
};

enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, as the Khronos Sample Viewer
// evaluates it: u' = cos(r) s_u u + sin(r) s_v v + o_u, v' = -sin(r) s_u u + cos(r) s_v v + o_v
// (TextureTransformTest's arrows then point at their green markers).
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
    bool identity() const {
        return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
    }
    // The two rows of the affine map: u' = dot(row0, (u, v, 1)), v' = dot(row1, (u, v, 1)).
    glm::vec3 row0() const {
        return {std::cos(rotation) * scale.x, std::sin(rotation) * scale.y, offset.x};
    }
    glm::vec3 row1() const {
        return {-std::sin(rotation) * scale.x, std::cos(rotation) * scale.y, offset.y};
    }
    glm::vec2 apply(const glm::vec2& uv) const {
        return {glm::dot(row0(), glm::vec3(uv, 1.0f)), glm::dot(row1(), glm::vec3(uv, 1.0f))};
    }
};

struct TextureRef {
    int32_t index = -1;  // into Scene::textures, -1 = none
    uint32_t texCoord =
        0;  // 0: Vertex::uv0, 1: Vertex::uv1 (KHR_texture_transform's override applied)
    TextureTransform transform;
    bool valid() const { return index >= 0; }
};

// glTF 2.0 metallic-roughness, see SHADING.md "Inputs".
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;          // perceptual, unclamped
    glm::vec3 emissiveFactor{0.0f};  // already multiplied by KHR_materials_emissive_strength
    float emissiveStrength = 1.0f;   // informative: the factor already applied above
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;       // indirect light x (1 + strength (occlusion - 1))
    TextureRef baseColorTexture;          // sRGB
    TextureRef metallicRoughnessTexture;  // linear, G = roughness, B = metallic
    TextureRef normalTexture;             // linear, tangent space
    TextureRef emissiveTexture;           // sRGB
    TextureRef occlusionTexture;          // linear, R
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    bool unlit = false;  // KHR_materials_unlit: output = baseColor, no lighting
    // KHR_materials_ior and KHR_materials_specular (factors): the dielectric's Fresnel, F0 =
    // min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular and F90 = specular (docs/SHADING.md).
    float ior = 1.5f;  // at least 1; infinite for the extension's 0
    float specular = 1.0f;
    glm::vec3 specularColor{1.0f};
    TextureRef specularTexture;       // linear, A: times specular
    TextureRef specularColorTexture;  // sRGB, RGB: times specularColor
    // ((ior - 1) / (ior + 1))^2 specularColor: F0 before the clamp and the specular factor.
    glm::vec3 specularColorF0() const {
        const float r = std::isinf(ior)
                            ? 1.0f
                            : (ior - 1.0f) / (ior + 1.0f);  // KHR_materials_ior's 0: infinite
        return glm::vec3(r * r) * specularColor;
    }
    // With the textures' texels where they are sampled (1 without them).
    glm::vec3 dielectricF0(glm::vec3 colorTexel = glm::vec3(1.0f),
                           float specularTexel = 1.0f) const {
        return glm::min(specularColorF0() * colorTexel, glm::vec3(1.0f)) * specular * specularTexel;
    }
    float dielectricF90(float specularTexel = 1.0f) const { return specular * specularTexel; }
    // KHR_materials_clearcoat (factors): a second, dielectric GGX layer over the whole material,
    // on the interpolated vertex normal, its Fresnel F0 = ((ior - 1) / (ior + 1))^2 (docs/SHADING.md).
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    TextureRef clearcoatTexture;           // linear, R: times clearcoat
    TextureRef clearcoatRoughnessTexture;  // linear, G: times clearcoatRoughness
    TextureRef
        clearcoatNormalTexture;  // linear, tangent space: the layer's normal (else the vertex normal)
    float clearcoatNormalScale = 1.0f;
    float clearcoatF0() const {
        const float r = std::isinf(ior) ? 1.0f : (ior - 1.0f) / (ior + 1.0f);
        return r * r;
    }
    // KHR_materials_transmission: the fraction of the dielectric's diffuse light replaced by light
    // passing through the surface (times its texture's R); KHR_materials_volume: the volume's
    // thickness in mesh units (times its texture's G; 0: thin-walled) and Beer-Lambert attenuation
    // (attenuationColor reached after attenuationDistance, infinite: none). docs/SHADING.md.
    float transmission = 0.0f;
    TextureRef transmissionTexture;  // linear, R
    float thickness = 0.0f;
    TextureRef thicknessTexture;  // linear, G
    glm::vec3 attenuationColor{1.0f};
    float attenuationDistance = std::numeric_limits<float>::infinity();
    // KHR_materials_sheen: a Charlie-distribution sheen layer over the base (docs/SHADING.md), its
    // colour times the colour texture's RGB (sRGB), its perceptual roughness times the roughness
    // texture's A.
    glm::vec3 sheenColor{0.0f};
    float sheenRoughness = 0.0f;
    TextureRef sheenColorTexture;      // sRGB
    TextureRef sheenRoughnessTexture;  // linear, A
    bool hasSheen() const { return sheenColor != glm::vec3(0.0f); }
    // Drawn after the opaque scene, which it sees through (a BLEND material blends instead).
    bool transmissive() const { return transmission > 0.0f && alphaMode != AlphaMode::Blend; }
    // The defaults' dielectric (F0 0.04, F90 1): what a G-buffer technique shades with.
    bool defaultDielectric() const {
        return ior == 1.5f && specular == 1.0f && specularColor == glm::vec3(1.0f) &&
               !specularTexture.valid() && !specularColorTexture.valid();
    }
    // Inputs only the techniques that shade the whole material evaluate (TechniqueInfo::fullMaterial).
    bool needsFullMaterial() const {
        return !defaultDielectric() || clearcoat > 0.0f || hasSheen();
    }
};

struct MeshInstance {
    uint32_t meshIndex = 0;
    glm::mat4 world{1.0f};
    // det(world) < 0: the transform mirrors, so counter-clockwise faces become clockwise on
    // screen; the renderer must flip its front-face (cull) setting for this instance.
    bool mirrored = false;
    std::string name;  // the glTF node name, for messages and debugging
    // The node it hangs from (Scene::nodes; -1: none, world is fixed) and, for
    // EXT_mesh_gpu_instancing, the instance's transform under it: world = node's world x local.
    int32_t node = -1;
    glm::mat4 local{1.0f};
    // Deformation of the current pose (assets::poseScene keeps these): a skin (Scene::skins, -1:
    // none) and its joint matrices, inverse(world of the node) x world of joint j x inverse bind
    // matrix j, taking a rest-pose vertex to the node's space; the morph weights, one per target
    // of the mesh (empty: no targets).
    int32_t skin = -1;
    std::vector<glm::mat4> joints;
    std::vector<float> weights;
    // Object-space bounds of the posed mesh (conservative: the rest bounds displaced by the
    // weighted morph targets' extremes, then under each joint matrix); the mesh's when empty.
    AABB posedBounds;
    bool deformed() const { return skin >= 0 || !weights.empty(); }
};

// A glTF node: its transform as TRS (animation channels target these) or as a fixed matrix.
struct Node {
    std::string name;
    int32_t parent = -1;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    glm::vec3 scale{1.0f};
    std::optional<glm::mat4> matrix;  // set: the node's transform, TRS unused (not animatable)
    std::vector<float> weights;  // node.weights: the morph weights of its mesh, else the mesh's
    glm::mat4 world{1.0f};       // of the current pose (assets::poseScene)
    glm::mat4 localTransform() const;
};

// A glTF skin: joints (node indices) and their inverse bind matrices (identity when absent).
struct Skin {
    std::string name;
    std::vector<uint32_t> joints;
    std::vector<glm::mat4> inverseBindMatrices;
};

enum class AnimationPath : uint8_t { Translation, Rotation, Scale, Weights };
enum class Interpolation : uint8_t { Linear, Step, CubicSpline };

// A keyframe sampler: `times` (seconds, strictly increasing) and `values`, `width` floats per
// key (3 translation/scale, 4 rotation as x, y, z, w, the morph target count for weights); a
// CUBICSPLINE sampler stores three elements per key: in-tangent, value, out-tangent.
struct AnimationSampler {
    std::vector<float> times;
    std::vector<float> values;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t width = 0;
};

struct AnimationChannel {
    uint32_t sampler = 0;
    uint32_t node = 0;
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    float duration = 0.0f;  // the last key time over all samplers (keys start at or after 0)
};

enum class LightType : uint8_t { Directional, Point, Spot };

// KHR_lights_punctual, already in world space.
struct Light {
    std::string name;
    int32_t node = -1;  // the node it hangs from (Scene::nodes; -1: none); posed with it
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;                  // lux (directional) or candela (point, spot)
    float range = 0.0f;                      // 0 = infinite
    glm::vec3 position{0.0f};                // point, spot
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, where the light travels (spot, directional)
    float innerConeAngle = 0.0f;             // radians (spot)
    float outerConeAngle = 0.78539816339f;   // radians (spot), pi/4 as in glTF
};

// A particle emitter (the VFX renderer, render/VfxRenderer.h): particles born at `rate` per
// second at `position`, leaving along `velocity` within a cone of half-angle `spread`, falling
// with `gravity`, living `lifetime` seconds while size and colour blend from start to end.
// Additive particles emit light (fire, sparks); alpha-blended ones are lit by the scene's lights
// and drawn back to front (smoke). A glTF node gets one through its extras (GltfLoader.h).
struct ParticleEmitter {
    enum class Blend { Additive, Alpha };
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 velocity{0.0f, 1.0f, 0.0f};    // m/s
    float spread = 0.3f;                     // radians
    float rate = 100.0f;                     // particles per second
    float lifetime = 2.0f;                   // seconds
    glm::vec3 gravity{0.0f, -1.0f, 0.0f};    // m/s^2
    float sizeStart = 0.1f, sizeEnd = 0.3f;  // billboard half-width, metres
    glm::vec4 colorStart{1.0f},
        colorEnd{1.0f, 1.0f, 1.0f, 0.0f};  // linear; additive: radiance, alpha: albedo
    Blend blend = Blend::Additive;
    float softness = 0.2f;  // metres over which a particle fades out in front of scene depth
    uint32_t maxParticles() const { return uint32_t(std::ceil(rate * lifetime)); }
};

// Perspective camera. worldFromView is a rigid transform (scale removed): column 3 is the eye,
// -column 2 the viewing direction, column 1 up.
struct Camera {
    std::string name;
    glm::mat4 worldFromView{1.0f};
    float yfov = 0.78539816339f;  // radians, vertical
    float znear = 0.1f;
    float zfar = std::numeric_limits<float>::infinity();  // +inf = infinite far plane
    std::optional<float> aspectRatio;                     // width / height; unset = the viewport's
    // Orthographic (glTF camera.orthographic): the half width and half height of the view volume
    // (xmag, ymag); yfov and aspectRatio are then unused.
    std::optional<glm::vec2> orthographic;
    // The node it hangs from (Scene::nodes; -1: none): assets::poseScene moves it with the node.
    int32_t node = -1;

    glm::vec3 eye() const { return glm::vec3(worldFromView[3]); }
    glm::vec3 forward() const { return -glm::normalize(glm::vec3(worldFromView[2])); }
    glm::vec3 up() const { return glm::normalize(glm::vec3(worldFromView[1])); }
    glm::mat4 viewFromWorld() const;
    bool infiniteFar() const { return !(zfar < std::numeric_limits<float>::infinity()); }

    // The camera turned `radians` about the vertical (+Y) axis through `center`: a camera path
    // around a scene (fe render --orbit).
    Camera orbited(const glm::vec3& center, float radians) const;
    // Right-handed look-at; `up` need not be orthogonal to `forward` but must not be parallel.
    static Camera lookAlong(const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& up,
                            float yfov, float znear, float zfar);
};

struct Scene {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<TextureImage> textures;
    std::vector<MeshInstance> instances;
    std::vector<Light> lights;
    std::optional<Camera> camera;  // the camera drawn from
    // The file's cameras, in depth-first node order (the first is `camera` after loading);
    // assets::poseScene moves them with their nodes and `camera` with the one `cameraIndex`
    // names, while `camera` is that one (a camera of your own put in `camera` stays; -1: none).
    std::vector<Camera> cameras;
    int32_t cameraIndex = -1;
    // The node hierarchy, skins and animations of a glTF file (assets/Animation.h poses them).
    std::vector<Node> nodes;
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    std::optional<Environment> environment;  // drawn as the background where nothing is drawn
    std::vector<ParticleEmitter> emitters;   // the VFX renderer's particle systems
    Bounds bounds;  // world space, union of the instances; empty if nothing is drawn
    bool hasDefaultLights = false;  // lights were added by the loader (the file had none)
    bool hasDefaultCamera = false;  // camera was made by the loader (the file had none)
    // Made to show shadows (builtin:shadows, builtin:particles, the default look's sun): front
    // ends (fe render, fe view) turn shadow maps on unless told otherwise.
    bool showsShadows = false;
    std::vector<std::string> warnings;  // what was ignored or approximated, one line each
};

// --- helpers shared by the glTF loader and the builtin scenes (Scene.cpp) ---

// Union of every instance's transformed mesh bounds.
AABB computeWorldBounds(const Scene& scene);

// The camera used when a scene has none: see "Defaults" in GltfLoader.h.
Camera makeDefaultCamera(const AABB& worldBounds);

// The light rig used when a scene has none, placed relative to `camera`: see "Defaults" in
// GltfLoader.h. Appends to scene.lights and sets hasDefaultLights.
void addDefaultLights(Scene& scene, const Camera& camera);

// The default look of a model without lights of its own (hasDefaultLights), what fe render and
// fe view show it with unless lighting is asked for: the default light rig is replaced by a sun
// (a directional light from above, behind and to the left of the camera: kDefaultSun*) that casts
// shadows (showsShadows), and the scene's environment becomes builtin:sky with that sun's
// direction and no sun disc of its own (the directional light is the sun: the disc would count it
// twice), to light the scene by image-based lighting and show behind it. Returns false, changing
// nothing, when the scene has lights of its own.
bool useDefaultSkyAndSun(Scene& scene);
inline constexpr float kDefaultSunIlluminance = 3.0f;   // lux, colour (1, 0.956, 0.898)
inline constexpr float kDefaultSunMinElevation = 0.6f;  // sin of the sun's elevation, at least

// Throws AssetError naming the first non-finite number (NaN or infinity) in the scene: a vertex
// position, normal, tangent or uv, a material factor, an instance transform, a light or the
// camera. Nothing downstream can shade such data into anything but garbage. Denormal numbers
// are finite and pass. The material extensions' factors must also lie in the ranges the loader
// enforces (transmission in [0, 1], ior at least 1, ...), so a material built in code is refused
// as a file is.
void checkFinite(const Scene& scene);
// A camera a view can be made from: finite, an invertible transform, yfov in (0, pi),
// 0 < znear < zfar (zfar may be infinite), a positive aspect ratio when set. Throws AssetError.
void checkCamera(const Camera& camera);

// Checks the scene is finite (checkFinite), recomputes bounds, then adds the default camera /
// lights when asked and missing.
void finalizeScene(Scene& scene, bool addDefaultCameraIfMissing, bool addDefaultLightsIfMissing);

}  // namespace fe::assets
