#include "render/GpuScene.h"

#include "render/ShaderFeatures.h"
#include "render/ShaderSlots.h"
#include "shading/ShadingModel.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <string>

namespace fe::render {

namespace {

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// srgbToLinear of each 8-bit value, the same floats: a pow per texel and channel was most of the
// time a textured model took to load.
const std::array<float, 256> kSrgbToLinear = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(i / 255.0f);
    return t;
}();

// Next mip level by a 2x2 box filter; sRGB colour channels are averaged in linear space.
std::vector<uint8_t> downsample(const std::vector<uint8_t>& src, uint32_t w, uint32_t h,
                                bool srgb) {
    uint32_t nw = std::max(1u, w / 2), nh = std::max(1u, h / 2);
    std::vector<uint8_t> dst(size_t(nw) * nh * 4);
    for (uint32_t y = 0; y < nh; ++y)
        for (uint32_t x = 0; x < nw; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                float sum = 0;
                int n = 0;
                for (uint32_t dy = 0; dy < 2; ++dy)
                    for (uint32_t dx = 0; dx < 2; ++dx) {
                        uint32_t sx = std::min(w - 1, x * 2 + dx), sy = std::min(h - 1, y * 2 + dy);
                        const uint8_t v = src[(size_t(sy) * w + sx) * 4 + c];
                        sum += (srgb && c < 3) ? kSrgbToLinear[v] : v / 255.0f;
                        ++n;
                    }
                float v = sum / float(n);
                if (srgb && c < 3) v = linearToSrgb(v);
                dst[(size_t(y) * nw + x) * 4 + c] =
                    uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
            }
    return dst;
}

gdi::Filter toFilter(assets::Filter f) {
    return f == assets::Filter::Nearest ? gdi::Filter::Nearest : gdi::Filter::Linear;
}
gdi::AddressMode toAddress(assets::Wrap w) {
    switch (w) {
        case assets::Wrap::ClampToEdge:
            return gdi::AddressMode::ClampToEdge;
        case assets::Wrap::MirroredRepeat:
            return gdi::AddressMode::MirroredRepeat;
        default:
            return gdi::AddressMode::Repeat;
    }
}

gdi::TextureHandle solidTexture(gdi::DeviceObjects& objects, uint8_t r, uint8_t g, uint8_t b,
                                uint8_t a, bool srgb, const char* name) {
    gdi::Device& device = objects.device();
    gdi::TextureHandle t = objects.add(
        device.createTexture({.format = srgb ? gdi::Format::RGBA8_SRGB : gdi::Format::RGBA8,
                              .width = 1,
                              .height = 1,
                              .debugName = name}));
    const uint8_t px[4] = {r, g, b, a};
    device.writeTexture(t, {}, gdi::bytesOf(px));
    return t;
}

}  // namespace

GpuLight toGpuLight(const assets::Light& l) {
    GpuLight g{};
    g.positionRange = glm::vec4(l.position, l.range);
    g.colorIntensity = glm::vec4(l.color, l.intensity);
    float type = l.type == assets::LightType::Directional ? 0.0f
                 : l.type == assets::LightType::Point     ? 1.0f
                                                          : 2.0f;
    g.directionType = glm::vec4(l.direction, type);
    float s = 1.0f / std::max(0.001f, std::cos(l.innerConeAngle) - std::cos(l.outerConeAngle));
    g.spotScaleOffset = glm::vec4(s, -std::cos(l.outerConeAngle) * s, 0.0f, 0.0f);
    return g;
}

GpuScene::GpuScene(gdi::Device& device, const assets::Scene& scene)
    : objects_(device), device_(device), scene_(scene) {
    // Geometry: every primitive appended to one vertex and one index buffer.
    std::vector<assets::Vertex> vertices;
    std::vector<uint32_t> indices;
    struct Range {
        uint32_t firstIndex, indexCount;
        int32_t baseVertex;
    };
    std::vector<std::vector<Range>> ranges(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (const assets::Primitive& p : scene.meshes[m].primitives) {
            ranges[m].push_back(
                {uint32_t(indices.size()), uint32_t(p.indices.size()), int32_t(vertices.size())});
            vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
            indices.insert(indices.end(), p.indices.begin(), p.indices.end());
        }
    // Animated instances: each deformed primitive gets vertices of its own (initially its rest
    // pose), the skin influences and morph deltas go to buffers the deformation reads.
    std::vector<assets::SkinInfluences> influences;
    std::vector<float> deltas;
    std::map<std::pair<size_t, size_t>, std::pair<uint32_t, uint32_t>>
        sources;  // (mesh, primitive) -> (skin, morph)
    std::map<std::pair<uint32_t, size_t>, int32_t>
        deformedBase;  // (instance, primitive) -> first deformed vertex
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const assets::MeshInstance& inst = scene.instances[i];
        if (!inst.deformed()) continue;
        const assets::Mesh& mesh = scene.meshes.at(inst.meshIndex);
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const assets::Primitive& prim = mesh.primitives[p];
            const bool skinned = inst.skin >= 0 && !prim.skin.empty();
            if (!skinned && prim.targets.empty()) continue;
            auto [src, fresh] =
                sources.try_emplace({inst.meshIndex, p}, ~0u, uint32_t(deltas.size()));
            if (fresh) {
                if (!prim.skin.empty()) {
                    src->second.first = uint32_t(influences.size());
                    influences.insert(influences.end(), prim.skin.begin(), prim.skin.end());
                }
                for (const assets::MorphTarget& t : prim.targets)
                    for (size_t v = 0; v < prim.vertices.size(); ++v)
                        for (const std::vector<glm::vec3>* d :
                             {&t.position, &t.normal, &t.tangent}) {
                            const glm::vec3 x = d->empty() ? glm::vec3(0.0f) : (*d)[v];
                            deltas.insert(deltas.end(), {x.x, x.y, x.z});
                        }
            }
            Deformation d{.instance = i,
                          .restFirst = uint32_t(ranges[inst.meshIndex][p].baseVertex),
                          .outputFirst = uint32_t(vertices.size()),
                          .vertexCount = uint32_t(prim.vertices.size()),
                          .flatNormals = prim.flatNormals,
                          .skinFirst = skinned ? src->second.first : ~0u,
                          .morphFirst = src->second.second,
                          .targetCount = uint32_t(prim.targets.size())};
            deformedBase[{i, p}] = int32_t(vertices.size());
            vertices.insert(vertices.end(), prim.vertices.begin(), prim.vertices.end());
            deformations_.push_back(d);
        }
    }
    if (vertices.empty()) vertices.push_back({});  // a buffer needs at least one byte
    if (indices.empty()) indices.push_back(0);
    if (!deformations_.empty()) {
        if (influences.empty()) influences.push_back({});
        if (deltas.empty()) deltas.push_back(0.0f);
        skin_ = objects_.add(
            device.createBuffer({.size = influences.size() * sizeof(assets::SkinInfluences),
                                 .usage = gdi::BufferUsage::Storage,
                                 .debugName = "skin influences"},
                                gdi::bytesOf(influences)));
        morph_ = objects_.add(device.createBuffer({.size = deltas.size() * sizeof(float),
                                                   .usage = gdi::BufferUsage::Storage,
                                                   .debugName = "morph target deltas"},
                                                  gdi::bytesOf(deltas)));
    }
    vertices_ = objects_.add(
        device.createBuffer({.size = vertices.size() * sizeof(assets::Vertex),
                             .usage = gdi::BufferUsage::Vertex | gdi::BufferUsage::Storage,
                             .debugName = "scene vertices"},
                            gdi::bytesOf(vertices)));
    indices_ = objects_.add(
        device.createBuffer({.size = indices.size() * 4,
                             .usage = gdi::BufferUsage::Index | gdi::BufferUsage::Storage,
                             .debugName = "scene indices"},
                            gdi::bytesOf(indices)));

    uint64_t triangles = 0;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const assets::MeshInstance& inst = scene.instances[i];
        const assets::Mesh& mesh = scene.meshes.at(inst.meshIndex);
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const assets::Primitive& prim = mesh.primitives[p];
            const assets::Material& mat = scene.materials.at(prim.material);
            DrawItem d;
            d.firstIndex = ranges[inst.meshIndex][p].firstIndex;
            d.indexCount = ranges[inst.meshIndex][p].indexCount;
            const auto deformed = deformedBase.find({i, p});
            d.baseVertex = deformed != deformedBase.end() ? deformed->second
                                                          : ranges[inst.meshIndex][p].baseVertex;
            d.material = prim.material;
            d.instance = i;
            d.alphaMode = mat.alphaMode;
            d.transmissive = mat.transmissive();
            d.doubleSided = mat.doubleSided;
            d.mirrored = inst.mirrored;
            d.worldCenter = glm::vec3(inst.world * glm::vec4(prim.bounds.center(), 1.0f));
            if (!d.indexCount) continue;
            if (triangles + d.indexCount / 3 >= uint64_t(1) << 32)
                throw gdi::Error(
                    "scene has more than 2^32 - 1 triangles (the visibility buffer's ids)");
            d.firstTriangle = uint32_t(triangles + 1);
            triangles += d.indexCount / 3;
            draws_.push_back(d);
        }
    }

    // Textures, with CPU-generated mip chains when the sampler wants mipmaps.
    for (const assets::TextureImage& img : scene.textures) {
        uint32_t mips = 1;
        if (img.sampler.mipmaps && img.sampler.mipFilter != assets::MipFilter::None)
            for (uint32_t s = std::max(img.width, img.height); s > 1; s >>= 1) ++mips;
        gdi::TextureHandle t = objects_.add(
            device.createTexture({.format = img.srgb ? gdi::Format::RGBA8_SRGB : gdi::Format::RGBA8,
                                  .width = img.width,
                                  .height = img.height,
                                  .mipLevels = mips,
                                  .debugName = img.name.c_str()}));
        std::vector<uint8_t> level = img.pixels;
        uint32_t w = img.width, h = img.height;
        for (uint32_t m = 0; m < mips; ++m) {
            device.writeTexture(t, {.mipLevel = m}, gdi::bytesOf(level));
            if (m + 1 < mips) {
                level = downsample(level, w, h, img.srgb);
                w = std::max(1u, w / 2);
                h = std::max(1u, h / 2);
            }
        }
        textures_.push_back(t);
        const assets::Sampler& s = img.sampler;
        samplers_.push_back(objects_.add(device.createSampler({
            .minFilter = toFilter(s.minFilter),
            .magFilter = toFilter(s.magFilter),
            .mipFilter = mips == 1                                   ? gdi::MipFilter::None
                         : s.mipFilter == assets::MipFilter::Nearest ? gdi::MipFilter::Nearest
                                                                     : gdi::MipFilter::Linear,
            .addressU = toAddress(s.wrapS),
            .addressV = toAddress(s.wrapT),
        })));
    }
    white_ = solidTexture(objects_, 255, 255, 255, 255, true, "default white");
    black_ = solidTexture(objects_, 0, 0, 0, 255, true, "default black");
    flatNormal_ = solidTexture(objects_, 128, 128, 255, 255, false, "default normal");
    defaultSampler_ = objects_.add(device.createSampler(
        {.minFilter = gdi::Filter::Nearest, .magFilter = gdi::Filter::Nearest}));
    // The sheen's albedo table (read texel by texel, fe_shading.glsl): made only for a scene with a sheen.
    const bool sheen = std::any_of(scene.materials.begin(), scene.materials.end(),
                                   [](const assets::Material& m) { return m.hasSheen(); });
    const std::vector<float> zero(1, 0.0f);
    const std::vector<float>& table = sheen ? shading::sheenAlbedoTable() : zero;
    const uint32_t side = sheen ? uint32_t(shading::kSheenTableSize) : 1u;
    sheenAlbedo_ = objects_.add(device.createTexture({.format = gdi::Format::R32F,
                                                      .width = side,
                                                      .height = side,
                                                      .debugName = "sheen albedo table"}));
    device.writeTexture(sheenAlbedo_, {}, gdi::bytesOf(table));

    for (const assets::Material& m : scene.materials) {
        auto pick = [&](const assets::TextureRef& r, gdi::TextureHandle fallback,
                        gdi::TextureHandle& tex, gdi::SamplerHandle& smp) {
            if (r.valid() && size_t(r.index) < textures_.size()) {
                tex = textures_[r.index];
                smp = samplers_[r.index];
            } else {
                tex = fallback;
                smp = defaultSampler_;
            }
        };
        MaterialTextures mt;
        pick(m.baseColorTexture, white_, mt.baseColor, mt.baseColorSampler);
        pick(m.metallicRoughnessTexture, white_, mt.metallicRoughness, mt.metallicRoughnessSampler);
        pick(m.normalTexture, flatNormal_, mt.normal, mt.normalSampler);
        pick(m.emissiveTexture, white_, mt.emissive, mt.emissiveSampler);
        pick(m.occlusionTexture, white_, mt.occlusion, mt.occlusionSampler);
        pick(m.transmissionTexture, white_, mt.transmission, mt.transmissionSampler);
        pick(m.thicknessTexture, white_, mt.thickness, mt.thicknessSampler);
        pick(m.sheenColorTexture, white_, mt.sheenColor, mt.sheenColorSampler);
        pick(m.sheenRoughnessTexture, white_, mt.sheenRoughness, mt.sheenRoughnessSampler);
        pick(m.specularTexture, white_, mt.specular, mt.specularSampler);
        pick(m.specularColorTexture, white_, mt.specularColor, mt.specularColorSampler);
        pick(m.clearcoatTexture, white_, mt.clearcoat, mt.clearcoatSampler);
        pick(m.clearcoatRoughnessTexture, white_, mt.clearcoatRoughness,
             mt.clearcoatRoughnessSampler);
        pick(m.clearcoatNormalTexture, flatNormal_, mt.clearcoatNormal, mt.clearcoatNormalSampler);
        mt.sheenAlbedo = sheenAlbedo_;
        mt.sheenAlbedoSampler = defaultSampler_;
        hasOcclusion_ =
            hasOcclusion_ || (m.occlusionTexture.valid() && m.occlusionStrength != 0.0f);
        hasLayered_ = hasLayered_ || m.clearcoat > 0.0f || m.hasSheen();
        materialTextures_.push_back(mt);
        materialFeatures_.push_back(ShaderFeatures::materialOf(m));
    }
    // The extensions' features are the scene's (any material's), the common ones each
    // material's own: each distinct set is a pipeline of every shading pass to compile, and a
    // scene mixing extension textures would make many of the largest shaders.
    uint32_t extensions = 0;
    for (uint32_t f : materialFeatures_) extensions |= f & ~ShaderFeatures::kPerMaterial;
    for (uint32_t& f : materialFeatures_) f = (f & ShaderFeatures::kPerMaterial) | extensions;
    for (DrawItem& d : draws_) {
        const MaterialTextures& mt = materialTextures_[d.material];
        auto it = std::find(textureSets_.begin(), textureSets_.end(), mt);
        d.textureSet = uint32_t(it - textureSets_.begin());
        if (it == textureSets_.end()) textureSets_.push_back(mt);
    }
    // A pass binding one set at a time still binds one in a scene without draws.
    if (textureSets_.empty()) {
        MaterialTextures none;
        for (gdi::TextureHandle* t :
             {&none.baseColor, &none.metallicRoughness, &none.emissive, &none.occlusion,
              &none.transmission, &none.thickness, &none.sheenColor, &none.sheenRoughness,
              &none.specular, &none.specularColor, &none.clearcoat, &none.clearcoatRoughness})
            *t = white_;
        none.normal = none.clearcoatNormal = flatNormal_;
        none.sheenAlbedo = sheenAlbedo_;
        for (gdi::SamplerHandle* s :
             {&none.baseColorSampler, &none.metallicRoughnessSampler, &none.normalSampler,
              &none.emissiveSampler, &none.occlusionSampler, &none.transmissionSampler,
              &none.thicknessSampler, &none.sheenColorSampler, &none.sheenRoughnessSampler,
              &none.specularSampler, &none.specularColorSampler, &none.clearcoatSampler,
              &none.clearcoatRoughnessSampler, &none.clearcoatNormalSampler,
              &none.sheenAlbedoSampler})
            *s = defaultSampler_;
        textureSets_.push_back(none);
    }
    updateLights(scene.lights);
}

GpuScene::~GpuScene() {
    device_.waitIdleOrLost();  // a destructor must not throw
}

void GpuScene::updateLights(const std::vector<assets::Light>& lights, uint32_t unshadowed) {
    std::vector<GpuLight> records;
    for (const assets::Light& l : lights) records.push_back(toGpuLight(l));
    if (records.empty()) records.push_back({});  // bound even when empty; count says 0
    const uint64_t bytes = std::max(records.size() * sizeof(GpuLight), kUniformLightBytes);
    if (bytes > lightCapacity_) {
        objects_.destroy(lights_);
        lightCapacity_ = 0;  // until the new buffer exists
        lights_ = objects_.add(
            device_.createBuffer({.size = bytes,
                                  .usage = gdi::BufferUsage::Storage | gdi::BufferUsage::Uniform,
                                  .debugName = "scene lights"}));
        lightCapacity_ = bytes;
    }
    device_.writeBuffer(lights_, 0, gdi::bytesOf(records));
    lightCount_ = uint32_t(lights.size());
    unshadowedCount_ = std::min(unshadowed, lightCount_);
    currentLights_ = lights;
    lightTypes_ = ShaderFeatures::lightTypesOf(lights);
}

void GpuScene::updatePose() {
    for (DrawItem& d : draws_) {
        const assets::MeshInstance& inst = scene_.instances[d.instance];
        const assets::AABB& local =
            inst.posedBounds.empty() ? scene_.meshes[inst.meshIndex].bounds : inst.posedBounds;
        d.worldCenter = glm::vec3(inst.world * glm::vec4(local.center(), 1.0f));
        d.mirrored = inst.mirrored;
    }
}

ObjectConstants GpuScene::objectConstants(const DrawItem& item) const {
    const assets::MeshInstance& inst = scene_.instances[item.instance];
    const assets::Material& m = scene_.materials[item.material];
    ObjectConstants o{};
    o.world = inst.world;
    o.normalMatrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(inst.world))));
    o.baseColorFactor = m.baseColorFactor;
    o.emissiveNormalScale = glm::vec4(m.emissiveFactor, m.normalScale);
    o.params = glm::vec4(m.metallic, m.roughness, m.alphaCutoff, float(int(m.alphaMode)));
    const bool specularTextures = m.specularTexture.valid() || m.specularColorTexture.valid();
    const bool clearcoatTextures =
        m.clearcoatTexture.valid() || m.clearcoatRoughnessTexture.valid();
    o.flags = glm::uvec4((m.normalTexture.valid() ? 1u : 0u) | (m.unlit ? 2u : 0u) |
                             (item.mirrored ? 4u : 0u) | (specularTextures ? 8u : 0u) |
                             (clearcoatTextures ? 16u : 0u) |
                             (m.clearcoatNormalTexture.valid() ? 32u : 0u) | (item.textureSet << 8),
                         item.firstIndex, uint32_t(item.baseVertex), item.firstTriangle);
    const assets::TextureRef* refs[14] = {
        &m.baseColorTexture,          &m.metallicRoughnessTexture, &m.normalTexture,
        &m.emissiveTexture,           &m.occlusionTexture,         &m.transmissionTexture,
        &m.thicknessTexture,          &m.sheenColorTexture,        &m.sheenRoughnessTexture,
        &m.specularTexture,           &m.specularColorTexture,     &m.clearcoatTexture,
        &m.clearcoatRoughnessTexture, &m.clearcoatNormalTexture};
    for (int t = 0; t < 14; ++t) {
        o.uvTransform[2 * t] =
            glm::vec4(refs[t]->transform.row0(), float(refs[t]->texCoord == 1 ? 1 : 0));
        o.uvTransform[2 * t + 1] = glm::vec4(refs[t]->transform.row1(), 0.0f);
    }
    o.occlusion = glm::vec4(m.occlusionTexture.valid() ? m.occlusionStrength : 0.0f, m.clearcoat,
                            m.clearcoatRoughness, m.clearcoatF0());
    o.dielectric = glm::vec4(m.specularColorF0(), m.specular);
    o.transmission = glm::vec4(m.transmissive() ? m.transmission : 0.0f, m.thickness,
                               std::isinf(m.attenuationDistance) ? 0.0f : m.attenuationDistance,
                               std::isinf(m.ior) ? 0.0f : m.ior);
    o.attenuation = glm::vec4(m.attenuationColor, 0.0f);
    o.sheen = glm::vec4(m.sheenColor, m.sheenRoughness);
    o.clearcoatNormal = glm::vec4(m.clearcoatNormalScale, 0.0f, 0.0f, 0.0f);
    return o;
}

void MaterialTextures::bind(gdi::CommandList& cmd) const {
    cmd.setTexture(kSlotBaseColor, baseColor, baseColorSampler);
    cmd.setTexture(kSlotMetalRough, metallicRoughness, metallicRoughnessSampler);
    cmd.setTexture(kSlotNormalMap, normal, normalSampler);
    cmd.setTexture(kSlotEmissive, emissive, emissiveSampler);
    cmd.setTexture(kSlotOcclusion, occlusion, occlusionSampler);
    cmd.setTexture(kSlotTransmission, transmission, transmissionSampler);
    cmd.setTexture(kSlotThickness, thickness, thicknessSampler);
    cmd.setTexture(kSlotSheenColor, sheenColor, sheenColorSampler);
    cmd.setTexture(kSlotSheenRoughness, sheenRoughness, sheenRoughnessSampler);
    cmd.setTexture(kSlotSheenAlbedo, sheenAlbedo, sheenAlbedoSampler);
    cmd.setTexture(kSlotSpecular, specular, specularSampler);
    cmd.setTexture(kSlotSpecularColor, specularColor, specularColorSampler);
    cmd.setTexture(kSlotClearcoat, clearcoat, clearcoatSampler);
    cmd.setTexture(kSlotClearcoatRoughness, clearcoatRoughness, clearcoatRoughnessSampler);
    cmd.setTexture(kSlotClearcoatNormal, clearcoatNormal, clearcoatNormalSampler);
}

bool GpuScene::hasBlend() const {
    return std::any_of(draws_.begin(), draws_.end(),
                       [](const DrawItem& d) { return d.alphaMode == assets::AlphaMode::Blend; });
}
bool GpuScene::hasOpaque() const {
    return std::any_of(draws_.begin(), draws_.end(), [](const DrawItem& d) {
        return d.alphaMode != assets::AlphaMode::Blend && !d.transmissive;
    });
}
bool GpuScene::hasTransmissive() const {
    return std::any_of(draws_.begin(), draws_.end(),
                       [](const DrawItem& d) { return d.transmissive; });
}

void GpuScene::bindLights(gdi::CommandList& cmd, uint32_t slot, bool uniformBlock) const {
    if (!uniformBlock) {
        cmd.setStorageBuffer(slot, lights_);
        return;
    }
    if (lightCount_ > kUniformLights)
        throw gdi::Error("lights as a uniform block: " + std::to_string(lightCount_) +
                         " lights where it holds " + std::to_string(kUniformLights) +
                         " (the pass was made for fewer)");
    cmd.setUniformBuffer(slot, lights_, 0, kUniformLightBytes);
}

}  // namespace fe::render
