#include "render/ShaderFeatures.h"

#include <algorithm>

#include "fe/gdi/ShaderReflection.h"

namespace fe::render {

uint32_t ShaderFeatures::lightTypesOf(const std::vector<assets::Light>& lights) {
    uint32_t types = 0;
    for (const assets::Light& l : lights)
        types |= l.type == assets::LightType::Directional ? kDirectional
                 : l.type == assets::LightType::Spot      ? kSpot
                                                          : kPoint;
    return types;
}

uint32_t ShaderFeatures::materialOf(const assets::Material& m) {
    uint32_t f = 0;
    if (m.baseColorTexture.valid() || m.metallicRoughnessTexture.valid() ||
        m.emissiveTexture.valid() || m.occlusionTexture.valid())
        f |= kBaseTextures;
    if (m.normalTexture.valid()) f |= kNormalMap;
    if (m.specularTexture.valid() || m.specularColorTexture.valid()) f |= kSpecularTextures;
    if (m.clearcoatTexture.valid() || m.clearcoatRoughnessTexture.valid()) f |= kClearcoatTextures;
    if (m.clearcoatNormalTexture.valid()) f |= kClearcoatNormalMap;
    if (m.hasSheen()) f |= kSheen;
    if (m.alphaMode == assets::AlphaMode::Mask) f |= kAlphaMask;
    return f;
}

std::vector<gdi::SpecializationConstant> declaredConstants(
    const gdi::Device& device, std::initializer_list<gdi::ShaderHandle> shaders,
    std::initializer_list<gdi::SpecializationConstant> values) {
    auto declared = [&](uint32_t id) {
        return std::any_of(shaders.begin(), shaders.end(), [&](gdi::ShaderHandle s) {
            if (!s) return false;
            const auto& constants = device.shaderInterface(s).specConstants;
            return std::any_of(constants.begin(), constants.end(),
                               [&](const auto& c) { return c.id == id; });
        });
    };
    std::vector<gdi::SpecializationConstant> out;
    for (const gdi::SpecializationConstant& v : values)
        if (declared(v.id)) out.push_back(v);
    return out;
}

std::vector<gdi::SpecializationConstant> ShaderFeatures::constantsFor(
    const gdi::Device& device, std::initializer_list<gdi::ShaderHandle> shaders) const {
    using C = gdi::SpecializationConstant;
    return declaredConstants(device, shaders,
                             {C::of(kLightTypesId, lightTypes), C::of(kBrdfModelsId, brdfModels),
                              C::of(kMaterialId, material)});
}

gdi::PipelineHandle FeatureComputePipelines::operator()(const ShaderFeatures& features) {
    const std::pair key{features.lightTypes, features.brdfModels};
    if (auto it = made_.find(key); it != made_.end()) return it->second;
    const gdi::PipelineHandle p = objects_.add(
        device_.createComputePipeline({.computeShader = shader_,
                                       .specialization = features.constantsFor(device_, {shader_}),
                                       .debugName = name_.c_str()}));
    made_.emplace(key, p);
    return p;
}

}  // namespace fe::render
