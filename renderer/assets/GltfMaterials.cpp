// The glTF loader: materials and their extensions, textures, samplers and images.
#include "assets/GltfLoaderInternal.h"

#include "assets/ImageDecode.h"
#include "assets/JpegDecode.h"

namespace fe::assets::gltf {

void Loader::readNumbers(const tinygltf::Value& v, const char* key, const std::string& where,
                         float* out, int count) {
    if (!v.Has(key)) return;
    const tinygltf::Value& x = v.Get(key);
    // Finite as a float: what is kept (a finite double such as 1e39 overflows it).
    auto finiteFloat = [](const tinygltf::Value& n) {
        return n.IsNumber() && std::isfinite(float(n.GetNumberAsDouble()));
    };
    if (count == 0) {
        if (!finiteFloat(x)) fail(where + "." + key + " must be a number, finite as a float");
        *out = float(x.GetNumberAsDouble());
        return;
    }
    const std::string shape = where + "." + key + " must be an array of " + std::to_string(count) +
                              " numbers, finite as floats";
    if (!x.IsArray() || int(x.ArrayLen()) != count) fail(shape);
    for (int i = 0; i < count; ++i) {
        if (!finiteFloat(x.Get(i))) fail(shape);
        out[i] = float(x.Get(i).GetNumberAsDouble());
    }
}

void Loader::readDielectric(const tinygltf::Material& gm, Material& mat, const std::string& label) {
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_ior")) {
        readNumbers(*e, "ior", label + ": KHR_materials_ior", &mat.ior, 0);
        // The extension allows 0 for an infinite index (F0 = 1); anything else below 1 is not a dielectric.
        if (mat.ior == 0.0f)
            mat.ior = std::numeric_limits<float>::infinity();
        else if (!(mat.ior >= 1.0f))
            fail(label + ": KHR_materials_ior.ior " + std::to_string(mat.ior) +
                 " must be at least 1 (or 0)");
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_clearcoat")) {
        const std::string where = label + ": KHR_materials_clearcoat";
        readNumbers(*e, "clearcoatFactor", where, &mat.clearcoat, 0);
        readNumbers(*e, "clearcoatRoughnessFactor", where, &mat.clearcoatRoughness, 0);
        if (!(mat.clearcoat >= 0.0f && mat.clearcoat <= 1.0f))
            fail(where + ".clearcoatFactor must lie in [0, 1]");
        if (!(mat.clearcoatRoughness >= 0.0f && mat.clearcoatRoughness <= 1.0f))
            fail(where + ".clearcoatRoughnessFactor must lie in [0, 1]");
        mat.clearcoatTexture = extensionTexture(*e, "clearcoatTexture", where);
        mat.clearcoatRoughnessTexture = extensionTexture(*e, "clearcoatRoughnessTexture", where);
        mat.clearcoatNormalTexture = extensionTexture(*e, "clearcoatNormalTexture", where);
        if (mat.clearcoatNormalTexture.valid())
            readNumbers(e->Get("clearcoatNormalTexture"), "scale",
                        where + ".clearcoatNormalTexture", &mat.clearcoatNormalScale, 0);
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_specular")) {
        const std::string where = label + ": KHR_materials_specular";
        readNumbers(*e, "specularFactor", where, &mat.specular, 0);
        readNumbers(*e, "specularColorFactor", where, &mat.specularColor.x, 3);
        if (!(mat.specular >= 0.0f && mat.specular <= 1.0f))
            fail(where + ".specularFactor must lie in [0, 1]");
        if (!(glm::all(glm::greaterThanEqual(mat.specularColor, glm::vec3(0.0f)))))
            fail(where + ".specularColorFactor must not be negative");
        mat.specularTexture = extensionTexture(*e, "specularTexture", where);
        mat.specularColorTexture = extensionTexture(*e, "specularColorTexture", where, true);
    }
}

void Loader::readTransmission(const tinygltf::Material& gm, Material& mat,
                              const std::string& label) {
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_transmission")) {
        const std::string where = label + ": KHR_materials_transmission";
        readNumbers(*e, "transmissionFactor", where, &mat.transmission, 0);
        if (!(mat.transmission >= 0.0f && mat.transmission <= 1.0f))
            fail(where + ".transmissionFactor must lie in [0, 1]");
        mat.transmissionTexture = extensionTexture(*e, "transmissionTexture", where);
        if (mat.alphaMode == AlphaMode::Blend && mat.transmission > 0.0f)
            warn(
                where +
                " on a BLEND material is not drawn: it blends instead (make it OPAQUE to see through it)");
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_volume")) {
        const std::string where = label + ": KHR_materials_volume";
        readNumbers(*e, "thicknessFactor", where, &mat.thickness, 0);
        readNumbers(*e, "attenuationDistance", where, &mat.attenuationDistance, 0);
        readNumbers(*e, "attenuationColor", where, &mat.attenuationColor.x, 3);
        if (!(mat.thickness >= 0.0f)) fail(where + ".thicknessFactor must not be negative");
        if (!(mat.attenuationDistance > 0.0f))
            fail(where + ".attenuationDistance must be positive");
        if (!glm::all(glm::greaterThanEqual(mat.attenuationColor, glm::vec3(0.0f))) ||
            !glm::all(glm::lessThanEqual(mat.attenuationColor, glm::vec3(1.0f))))
            fail(where + ".attenuationColor must lie in [0, 1]");
        mat.thicknessTexture = extensionTexture(*e, "thicknessTexture", where);
        if (mat.transmission == 0.0f)
            warn(where + " without KHR_materials_transmission has no effect here");
    }
}

void Loader::readSheen(const tinygltf::Material& gm, Material& mat, const std::string& label) {
    const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_sheen");
    if (!e) return;
    const std::string where = label + ": KHR_materials_sheen";
    readNumbers(*e, "sheenColorFactor", where, &mat.sheenColor.x, 3);
    readNumbers(*e, "sheenRoughnessFactor", where, &mat.sheenRoughness, 0);
    if (!glm::all(glm::greaterThanEqual(mat.sheenColor, glm::vec3(0.0f))) ||
        !glm::all(glm::lessThanEqual(mat.sheenColor, glm::vec3(1.0f))))
        fail(where + ".sheenColorFactor must lie in [0, 1]");
    if (!(mat.sheenRoughness >= 0.0f && mat.sheenRoughness <= 1.0f))
        fail(where + ".sheenRoughnessFactor must lie in [0, 1]");
    mat.sheenColorTexture = extensionTexture(*e, "sheenColorTexture", where, true);
    mat.sheenRoughnessTexture = extensionTexture(*e, "sheenRoughnessTexture", where);
}

TextureRef Loader::extensionTexture(const tinygltf::Value& ext, const char* key,
                                    const std::string& what, bool srgb) {
    if (!ext.Has(key)) return {};
    const tinygltf::Value& info = ext.Get(key);
    const std::string where = what + "." + key;
    if (!info.IsObject() || !info.Has("index")) fail(where + " must be an object with an index");
    const int index = valueIndex(info.Get("index"));
    if (index < 0) fail(where + ".index must be a non-negative integer");
    int texCoord = 0;
    if (info.Has("texCoord")) {
        texCoord = valueIndex(info.Get("texCoord"));
        if (texCoord < 0) fail(where + ".texCoord must be a non-negative integer");
    }
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions") && info.Get("extensions").IsObject()) {
        const tinygltf::Value& x = info.Get("extensions");
        for (const std::string& k : x.Keys()) extensions[k] = x.Get(k);
    }
    return getTexture(index, texCoord, srgb, extensions, where);
}

// KHR_texture_transform on a textureInfo: offset, rotation, scale, and a texCoord that overrides
// the textureInfo's.
void Loader::readTextureTransform(const tinygltf::Value& t, int& texCoord, TextureRef& ref,
                                  const std::string& what) {
    const std::string where = what + ": KHR_texture_transform";
    if (!t.IsObject()) fail(where + " must be an object");
    readNumbers(t, "offset", where, &ref.transform.offset.x, 2);
    readNumbers(t, "rotation", where, &ref.transform.rotation, 0);
    readNumbers(t, "scale", where, &ref.transform.scale.x, 2);
    if (t.Has("texCoord")) {
        const int set = valueIndex(t.Get("texCoord"));
        if (set < 0) fail(where + ".texCoord must be a non-negative integer");
        texCoord = set;
    }
}

// A particle emitter from a node's extras: {"fe_emitter": {"rate": 100, "lifetime": 2,
// "velocity": [0, 1, 0], "spread": 0.3, "gravity": [0, -1, 0], "size": [0.1, 0.3],
// "colorStart": [r, g, b, a], "colorEnd": [r, g, b, a], "blend": "additive" | "alpha",
// "softness": 0.2}}, every key optional (ParticleEmitter's defaults). It sits at the node's world
// position; velocity and gravity are in world space. A malformed value is an error naming it.

// ---------------------------------------------------------------------------------------------
// Materials and textures

uint32_t Loader::defaultMaterial() {
    if (defaultMaterial_ < 0) {
        Material m;  // glTF's default material: white, metallic 1, roughness 1
        m.name = "default";
        defaultMaterial_ = int(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return uint32_t(defaultMaterial_);
}

uint32_t Loader::getMaterial(int gi) {
    auto it = materialMap_.find(gi);
    if (it != materialMap_.end()) return it->second;
    const auto& gm = model_.materials[size_t(gi)];
    const std::string label = materialLabel(gi);
    const auto& pbr = gm.pbrMetallicRoughness;
    Material mat;
    mat.name = gm.name;
    if (pbr.baseColorFactor.size() == 4) {
        mat.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                        pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    }
    mat.metallic = float(pbr.metallicFactor);
    mat.roughness = float(pbr.roughnessFactor);
    if (gm.emissiveFactor.size() == 3) {
        mat.emissiveFactor =
            glm::vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
    }
    if (auto* es = findExtension(gm.extensions, "KHR_materials_emissive_strength")) {
        const auto& v = es->Get("emissiveStrength");
        if (v.IsNumber()) mat.emissiveStrength = float(v.GetNumberAsDouble());
        mat.emissiveFactor *= mat.emissiveStrength;
    }
    mat.unlit = findExtension(gm.extensions, "KHR_materials_unlit") != nullptr;
    readDielectric(gm, mat, label);
    mat.normalScale = float(gm.normalTexture.scale);
    mat.occlusionStrength = float(gm.occlusionTexture.strength);
    if (gm.alphaMode == "OPAQUE" || gm.alphaMode.empty()) {
        mat.alphaMode = AlphaMode::Opaque;
    } else if (gm.alphaMode == "MASK") {
        mat.alphaMode = AlphaMode::Mask;
    } else if (gm.alphaMode == "BLEND") {
        mat.alphaMode = AlphaMode::Blend;
    } else {
        warn(label + ": unknown alphaMode '" + gm.alphaMode + "', using OPAQUE");
    }
    mat.alphaCutoff = float(gm.alphaCutoff);
    mat.doubleSided = gm.doubleSided;
    readTransmission(gm, mat, label);
    readSheen(gm, mat, label);

    const float checks[] = {mat.baseColorFactor.x, mat.baseColorFactor.y, mat.baseColorFactor.z,
                            mat.baseColorFactor.w, mat.metallic,          mat.roughness,
                            mat.emissiveFactor.x,  mat.emissiveFactor.y,  mat.emissiveFactor.z,
                            mat.normalScale,       mat.occlusionStrength, mat.alphaCutoff};
    for (float f : checks)
        if (!std::isfinite(f)) fail(label + ": non-finite factor");

    mat.baseColorTexture =
        getTexture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true,
                   pbr.baseColorTexture.extensions, "baseColorTexture of " + label);
    mat.metallicRoughnessTexture =
        getTexture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                   pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture of " + label);
    mat.normalTexture = getTexture(gm.normalTexture.index, gm.normalTexture.texCoord, false,
                                   gm.normalTexture.extensions, "normalTexture of " + label);
    mat.occlusionTexture =
        getTexture(gm.occlusionTexture.index, gm.occlusionTexture.texCoord, false,
                   gm.occlusionTexture.extensions, "occlusionTexture of " + label);
    mat.emissiveTexture = getTexture(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, true,
                                     gm.emissiveTexture.extensions, "emissiveTexture of " + label);

    uint32_t index = uint32_t(scene_.materials.size());
    scene_.materials.push_back(std::move(mat));
    materialMap_[gi] = index;
    return index;
}

TextureRef Loader::getTexture(int gt, int texCoord, bool srgb,
                              const tinygltf::ExtensionMap& infoExt, const std::string& what) {
    TextureRef ref;
    if (gt < 0) return ref;
    checkIndex(gt, model_.textures, what + ": texture");
    if (const tinygltf::Value* t = findExtension(infoExt, "KHR_texture_transform"))
        readTextureTransform(*t, texCoord, ref, what);
    if (texCoord > 1) {
        warn(what + " uses TEXCOORD_" + std::to_string(texCoord) +
             "; only TEXCOORD_0 and TEXCOORD_1 are read, TEXCOORD_0 is used instead");
        texCoord = 0;
    }
    ref.texCoord = uint32_t(std::max(texCoord, 0));

    const auto& tex = model_.textures[size_t(gt)];
    if (tex.source < 0) {
        warn("texture " + std::to_string(gt) + " has no image source (extension-only image?); " +
             what + " ignored");
        return ref;
    }
    checkIndex(tex.source, model_.images, "texture " + std::to_string(gt) + ": image");
    if (tex.sampler >= 0)
        checkIndex(tex.sampler, model_.samplers, "texture " + std::to_string(gt) + ": sampler");
    // Keyed by what the GPU texture depends on, so glTF textures repeating the same image and
    // sampler (CesiumMilkTruck) share one decoded copy.
    auto key = std::make_tuple(tex.source, tex.sampler, srgb);
    auto it = textureMap_.find(key);
    if (it != textureMap_.end()) {
        ref.index = it->second;
        return ref;
    }

    TextureImage ti;
    ti.name = tex.name.empty() ? model_.images[size_t(tex.source)].name : tex.name;
    if (ti.name.empty()) ti.name = model_.images[size_t(tex.source)].uri;
    ti.srgb = srgb;
    if (tex.sampler >= 0) {
        const auto& s = model_.samplers[size_t(tex.sampler)];
        ti.sampler.magFilter =
            s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
        switch (s.minFilter) {
            case TINYGLTF_TEXTURE_FILTER_NEAREST:
                ti.sampler = {
                    Filter::Nearest, ti.sampler.magFilter, MipFilter::None, {}, {}, false};
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR:
                ti.sampler = {Filter::Linear, ti.sampler.magFilter, MipFilter::None, {}, {}, false};
                break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
                ti.sampler.minFilter = Filter::Nearest, ti.sampler.mipFilter = MipFilter::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
                ti.sampler.minFilter = Filter::Linear, ti.sampler.mipFilter = MipFilter::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
                ti.sampler.minFilter = Filter::Nearest, ti.sampler.mipFilter = MipFilter::Linear;
                break;
            default:  // LINEAR_MIPMAP_LINEAR or unspecified: trilinear, the usual viewer default
                ti.sampler.minFilter = Filter::Linear, ti.sampler.mipFilter = MipFilter::Linear;
                break;
        }
        auto wrap = [](int w) {
            switch (w) {
                case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
                    return Wrap::ClampToEdge;
                case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
                    return Wrap::MirroredRepeat;
                default:
                    return Wrap::Repeat;
            }
        };
        ti.sampler.wrapS = wrap(s.wrapS);
        ti.sampler.wrapT = wrap(s.wrapT);
    }
    // An image already decoded for another sampler / colour space is copied, not decoded again.
    if (auto done = imageTexture_.find(tex.source); done != imageTexture_.end()) {
        const TextureImage& other = scene_.textures[size_t(done->second)];
        ti.width = other.width;
        ti.height = other.height;
        ti.pixels = other.pixels;
    } else {
        decodeImage(tex.source, what + " (texture " + std::to_string(gt) + ")", ti);
    }

    ref.index = int32_t(scene_.textures.size());
    scene_.textures.push_back(std::move(ti));
    textureMap_[key] = ref.index;
    imageTexture_.emplace(tex.source, ref.index);
    return ref;
}

void Loader::decodeImage(int ii, const std::string& what, TextureImage& out) {
    const auto& gi = model_.images[size_t(ii)];
    std::string label = "image " + std::to_string(ii);
    if (!gi.uri.empty() && gi.uri.compare(0, 5, "data:") != 0)
        label += " ('" + gi.uri + "')";
    else if (!gi.name.empty())
        label += " ('" + gi.name + "')";
    label += " used by " + what;
    if (gi.image.empty()) fail(label + ": image file missing, empty or unreadable");
    if (gi.image.size() > size_t(INT32_MAX)) fail(label + ": encoded image too large");
    const auto* bytes = gi.image.data();
    if (looksLikeJpeg(bytes, gi.image.size())) {
        try {
            JpegImage jpeg = decodeJpeg(bytes, gi.image.size(), kMaxImagePixels);
            out.width = jpeg.width;
            out.height = jpeg.height;
            out.pixels = std::move(jpeg.rgba);
        } catch (const std::runtime_error& e) {
            fail(label + ": cannot decode JPEG (" + e.what() + ")");
        }
        model_.images[size_t(ii)].image.clear();
        model_.images[size_t(ii)].image.shrink_to_fit();
        return;
    }
    try {
        DecodedImage image = assets::decodeImage(bytes, gi.image.size(), kMaxImagePixels);
        out.width = image.width;
        out.height = image.height;
        out.pixels = std::move(image.rgba);
    } catch (const std::runtime_error& e) {
        fail(label + ": cannot decode (" + e.what() + ")");
    }
    // Only the decoded copy is needed from now on.
    model_.images[size_t(ii)].image.clear();
    model_.images[size_t(ii)].image.shrink_to_fit();
}

}  // namespace fe::assets::gltf
