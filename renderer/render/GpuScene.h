// Layer 7 (Render): a Scene uploaded through the abstract device, ready for any technique.
// Geometry lives in one vertex and one index buffer; each (instance, primitive) pair becomes a
// DrawItem; lights live in one storage buffer of GpuLight records (fe_shading.glsl).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::render {

// std140 layouts shared with shaders/include/fe_scene.glsl.
struct FrameConstants {
    glm::mat4 viewProj;
    glm::mat4 invViewProj;
    glm::vec4 cameraPosition;  // xyz, w = exposure
    glm::vec4 viewport;        // width, height, 1/width, 1/height (full resolution)
    glm::vec4 illumViewport;   // the same for the I-buffer (redeferred)
    glm::uvec4
        counts;  // x = light count, y = illumination scale, z = image-based lighting samples, w = all lights
    glm::uvec4
        lightRange;  // forward shading: x first light, y count, z 1 = add emissive/unlit, w 1 = MSAA (forward-plus)
    glm::mat4 view;  // view from world (rigid)
    // Redeferred's reduced-rate sampling: xy the offset of each I-buffer texel's representative
    // pixel within its scale x scale block (scale / 2, or a jitter cycling through the block
    // with temporal accumulation), z the previous frame's history: 0 none, 1 valid from a still
    // view, 2 valid but the camera moved; w the most frames a pixel's history averages.
    glm::vec4 temporal{0.0f};
    glm::mat4 prevViewProj{1.0f};  // the previous frame's viewProj (temporal reprojection)
    // The light cluster grid's depth slices (ClusterLightGrid): x the near plane's view depth, y
    // slices / ln(far / near), z far: the view depth of the scene's far side.
    glm::vec4 clusters{0.0f};
    // Camera-relative rendering: clip space from eye space (world - cameraPosition.xyz, no
    // rotation: the view's rotation is in the matrix) and back. Geometry is transformed and
    // positions are rebuilt from depth in eye space, so no float ever holds "far from the origin"
    // times a matrix entry: at 1e5 from the origin that product lost 0.01 units (docs/BENCHMARKS.md,
    // stability). World positions are cameraPosition + an eye-space offset.
    glm::mat4 viewProjFromEye{1.0f};
    glm::mat4 invViewProjFromEye{1.0f};
    glm::uvec4 shading{0u};  // x: the BRDF, 0 glTF, 1 separable (resolveBrdf)
};

struct ObjectConstants {
    glm::mat4 world;
    glm::mat4 normalMatrix;  // inverse transpose of world (upper 3x3 used)
    glm::vec4 baseColorFactor;
    glm::vec4 emissiveNormalScale;  // rgb emissive factor, a normal scale
    glm::vec4 params;               // metallic, roughness, alpha cutoff, alpha mode (0,1,2)
    // x: bit0 normal map, bit1 unlit, bit2 mirrored, bit3 KHR_materials_specular textures, bit4
    // clearcoat (factor or roughness) textures, bit5 a clearcoat normal map, bits 8-31 the draw's
    // texture set; y, z: the
    // draw's firstIndex and baseVertex; w: its first triangle's visibility id (DrawItem).
    glm::uvec4 flags;
    // Per texture (base colour, metallic-roughness, normal, emissive, occlusion, transmission,
    // thickness, sheen colour, sheen roughness, specular, specular colour, clearcoat, clearcoat
    // roughness, clearcoat normal: FE_TEXTURE_* in fe_material.glsl) the rows of its KHR_texture_transform,
    // (a, b, c, set) and (d, e, f, 0): it samples (a u + b v + c, d u + e v + f) of TEXCOORD_set.
    glm::vec4 uvTransform[2 * 14];
    // x: the occlusion texture's strength (0 without one); y, z, w: KHR_materials_clearcoat's factor,
    // roughness and F0 (Material::clearcoatF0)
    glm::vec4 occlusion;
    // rgb: the dielectric's F0 before its clamp and specular factor (Material::specularColorF0), a:
    // the specular factor (KHR_materials_ior / specular: F0 = min(rgb x colour texel, 1) a x texel, F90 = a x texel)
    glm::vec4 dielectric;
    // KHR_materials_transmission and volume: x the factor, y the thickness (mesh units), z the
    // attenuation distance (0: infinite), w the index of refraction (0: infinite); rgb of
    // `attenuation` the attenuation colour.
    glm::vec4 transmission;
    glm::vec4 attenuation;
    glm::vec4 sheen;            // rgb KHR_materials_sheen's colour (0: none), a its roughness
    glm::vec4 clearcoatNormal;  // x: the clearcoat normal texture's scale
};

struct GpuLight {
    glm::vec4 positionRange;
    glm::vec4 colorIntensity;
    glm::vec4 directionType;
    glm::vec4 spotScaleOffset;
};
static_assert(sizeof(GpuLight) == 64, "GpuScene::kUniformLightBytes assumes 64-byte light records");
GpuLight toGpuLight(const assets::Light& light);

struct DrawItem {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t baseVertex = 0;
    uint32_t material = 0;
    uint32_t instance = 0;
    assets::AlphaMode alphaMode = assets::AlphaMode::Opaque;
    bool transmissive =
        false;  // assets::Material::transmissive: drawn by MeshPass::Transmission alone
    bool doubleSided = false;
    bool mirrored = false;
    glm::vec3 worldCenter{0.0f};  // for back-to-front sorting of blended draws
    // The visibility buffer's id of the draw's first triangle: triangles are numbered from 1
    // across the draws in scene order (0: no surface).
    uint32_t firstTriangle = 0;
    uint32_t textureSet = 0;  // which of GpuScene::textureSets() its material samples
};

// One primitive of one animated instance (MeshInstance::deformed()): the mesh deformation pass
// (MeshDeformation.h) writes its rest pose, morphed and skinned, to vertices of its own, which
// its draws use.
struct Deformation {
    uint32_t instance = 0;
    uint32_t restFirst = 0;    // first rest-pose vertex in the vertex buffer
    uint32_t outputFirst = 0;  // first deformed vertex
    uint32_t vertexCount = 0;
    bool flatNormals = false;  // assets::Primitive::flatNormals
    uint32_t skinFirst = ~0u;  // first SkinInfluences record in skinBuffer(); ~0u: not skinned
    uint32_t morphFirst = 0;   // first float of its targets' deltas in morphBuffer()
    uint32_t targetCount = 0;
};

struct MaterialTextures {
    gdi::TextureHandle baseColor, metallicRoughness, normal, emissive, occlusion, transmission,
        thickness, sheenColor, sheenRoughness, specular, specularColor, clearcoat,
        clearcoatRoughness, clearcoatNormal;
    gdi::SamplerHandle baseColorSampler, metallicRoughnessSampler, normalSampler, emissiveSampler,
        occlusionSampler, transmissionSampler, thicknessSampler, sheenColorSampler,
        sheenRoughnessSampler, specularSampler, specularColorSampler, clearcoatSampler,
        clearcoatRoughnessSampler, clearcoatNormalSampler;
    // The scene's sheen albedo table (the same in every set), bound with them: what samples a
    // material may shade a sheen.
    gdi::TextureHandle sheenAlbedo;
    gdi::SamplerHandle sheenAlbedoSampler;
    bool operator==(const MaterialTextures&) const = default;
    // Binds them at their shader slots (ShaderSlots.h).
    void bind(gdi::CommandList& cmd) const;
};

class GpuScene {
public:
    GpuScene(gdi::Device& device, const assets::Scene& scene);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    const assets::Scene& scene() const { return scene_; }
    gdi::BufferHandle vertexBuffer() const { return vertices_; }
    gdi::BufferHandle indexBuffer() const { return indices_; }
    gdi::BufferHandle lightBuffer() const { return lights_; }
    uint32_t lightCount() const { return lightCount_; }
    // The light buffer is also a uniform block of kUniformLights records (64 KiB; FE_UNIFORM_LIGHTS
    // in fe_scene.glsl) for the passes that read the lights faster that way (the list passes and the
    // forward shaders): it is never smaller, so the block's whole range can be bound whatever the
    // light count.
    static constexpr uint32_t kUniformLights = 1024;
    static constexpr uint64_t kUniformLightBytes = uint64_t(kUniformLights) * 64;
    // Whether `lightCount` lights fit the uniform block and the device binds 64 KiB of one: the
    // passes that read lights then take the block (faster on lavapipe), else each shader's
    // FE_LIGHTS_IN_STORAGE variant reads the storage buffer.
    static bool lightsFitUniformBlock(uint32_t lightCount, const gdi::DeviceLimits& limits) {
        return lightCount <= kUniformLights && limits.maxUniformBufferRange >= kUniformLightBytes;
    }
    // Binds the lights at `slot` as the uniform block or the storage buffer; the block only while
    // the lights fit it (the renderer keeps the count it was made for).
    void bindLights(gdi::CommandList& cmd, uint32_t slot, bool uniformBlock) const;
    const std::vector<DrawItem>& draws() const { return draws_; }
    // Animation: the deformed primitives and the data their deformation reads (null handles
    // when no instance is skinned or morphed).
    const std::vector<Deformation>& deformations() const { return deformations_; }
    gdi::BufferHandle skinBuffer() const { return skin_; }
    gdi::BufferHandle morphBuffer() const { return morph_; }
    // After assets::poseScene moved the scene: the draws' sorting centres follow the instances
    // (their transforms are read per frame anyway).
    void updatePose();
    const MaterialTextures& textures(uint32_t material) const {
        return materialTextures_[material];
    }
    // The distinct texture bindings of the materials (many share the defaults): a pass that
    // shades every material at once binds one set at a time (VisibilityBufferRenderer). Never
    // empty: a scene without draws has the defaults' set.
    const std::vector<MaterialTextures>& textureSets() const { return textureSets_; }
    ObjectConstants objectConstants(const DrawItem& item) const;
    // Replaces the light list (e.g. animated builtin:lights); the count may change. The first
    // `unshadowed` lights are lit by a technique's own light loop or volumes; each light after
    // them casts shadows and is added by a pass of its own (ShadowMaps, SceneRenderer orders them).
    void updateLights(const std::vector<assets::Light>& lights, uint32_t unshadowed = ~0u);
    uint32_t unshadowedLightCount() const { return unshadowedCount_; }
    // The lights as last uploaded (the scene's, or those of the last updateLights()).
    const std::vector<assets::Light>& lights() const { return currentLights_; }
    // Their types (ShaderFeatures::lightTypesOf): the scene shaders' specialization.
    uint32_t lightTypes() const { return lightTypes_; }

    bool hasBlend() const;
    bool hasOpaque() const;  // neither blended nor transmissive
    bool hasTransmissive() const;
    // Some material has a clearcoat or a sheen: the full-material shaders are then their FE_LAYERED
    // variants, which alone evaluate those lobes (on CPU rasterizers a branch around them is not
    // free: forward with 1024 lights measured 572 -> 1384 ms a frame with the sheen's untaken).
    bool hasLayeredMaterials() const { return hasLayered_; }
    // Some material darkens indirect light by an occlusion texture (strength not 0): the
    // G-buffer techniques then store it (GBuffer::gb3).
    bool hasOcclusion() const { return hasOcclusion_; }
    // What material `index` uses (ShaderFeatures::materialOf): the scene shaders' specialization.
    uint32_t materialFeatures(uint32_t index) const { return materialFeatures_[index]; }
    gdi::TextureHandle white() const { return white_; }  // 1x1 opaque white, linear

    static constexpr uint32_t kVertexStride = sizeof(assets::Vertex);

private:
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    const assets::Scene& scene_;
    gdi::BufferHandle vertices_, indices_, lights_, skin_, morph_;
    std::vector<Deformation> deformations_;
    uint64_t lightCapacity_ = 0;
    std::vector<assets::Light> currentLights_;
    uint32_t lightCount_ = 0;
    uint32_t unshadowedCount_ = 0;
    std::vector<DrawItem> draws_;
    std::vector<gdi::TextureHandle> textures_;
    std::vector<gdi::SamplerHandle> samplers_;
    std::vector<MaterialTextures> materialTextures_, textureSets_;
    gdi::TextureHandle white_, black_, flatNormal_, sheenAlbedo_;
    bool hasOcclusion_ = false;
    bool hasLayered_ = false;
    std::vector<uint32_t> materialFeatures_;  // by material
    uint32_t lightTypes_ = 0;
    gdi::SamplerHandle defaultSampler_;
};

}  // namespace fe::render
