// Layer 5: the glTF loader's insides, shared by its files (GltfLoader.cpp: files, hierarchy,
// scene traversal; GltfAnimation.cpp: nodes, skins, animations; GltfMeshes.cpp: accessors and
// primitives; GltfMaterials.cpp: materials, textures, images). Not part of the public interface:
// include assets/GltfLoader.h.
#pragma once
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "assets/Animation.h"
#include "assets/AssetError.h"
#include "assets/GltfLoader.h"

namespace fe::assets::gltf {

namespace fs = std::filesystem;

// Extensions whose data the loader understands, so a file may require them.
inline const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual",        "KHR_materials_emissive_strength",
    "KHR_materials_clearcoat",    "KHR_materials_ior",
    "KHR_materials_sheen",        "KHR_materials_specular",
    "KHR_materials_transmission", "KHR_materials_unlit",
    "KHR_materials_volume",       "KHR_texture_transform",
    "EXT_mesh_gpu_instancing",
};

// Limits that keep hostile files from allocating unbounded memory: components of an accessor
// without a buffer view (their size is not bounded by the file), decoded image pixels.
constexpr uint64_t kMaxVirtualAccessorComponents = uint64_t(1) << 24;
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;  // 1 GiB of RGBA8

// Accepted (componentType, normalized) pairs, per attribute semantic.
enum Comp : uint32_t {
    F32 = 1u << 0,
    U8N = 1u << 1,
    U16N = 1u << 2,
    S8N = 1u << 3,
    S16N = 1u << 4,
    U8 = 1u << 5,
    U16 = 1u << 6,
    U32 = 1u << 7,
};

inline uint32_t compBit(int componentType, bool normalized) {
    uint32_t bit = 0;
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            bit = normalized ? 0u : uint32_t(F32);
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            bit = normalized ? U8N : U8;
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            bit = normalized ? U16N : U16;
            break;
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            bit = normalized ? uint32_t(S8N) : 0u;
            break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            bit = normalized ? uint32_t(S16N) : 0u;
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            bit = normalized ? 0u : uint32_t(U32);
            break;
        default:
            break;
    }
    return bit;
}

inline std::string componentTypeName(int componentType, bool normalized) {
    std::string s;
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            s = "byte";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            s = "unsigned byte";
            break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            s = "short";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            s = "unsigned short";
            break;
        case TINYGLTF_COMPONENT_TYPE_INT:
            s = "int";
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            s = "unsigned int";
            break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            s = "float";
            break;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            s = "double";
            break;
        default:
            s = "unknown";
            break;
    }
    s += " (" + std::to_string(componentType) + ")";
    if (normalized) s += " normalized";
    return s;
}

inline std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "type " + std::to_string(type);
    }
}

// Reads one component and converts it as glTF defines normalized integers (3.11).
inline double readComponent(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            double v = p[0];
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            double v = static_cast<int8_t>(p[0]);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t u;
            std::memcpy(&u, p, 2);
            return normalized ? u / 65535.0 : double(u);
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t s;
            std::memcpy(&s, p, 2);
            return normalized ? std::max(s / 32767.0, -1.0) : double(s);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t u;
            std::memcpy(&u, p, 4);
            return double(u);
        }
        default:
            return 0.0;
    }
}

inline bool addOverflows(uint64_t a, uint64_t b, uint64_t& out) {
    return __builtin_add_overflow(a, b, &out);
}
inline bool mulOverflows(uint64_t a, uint64_t b, uint64_t& out) {
    return __builtin_mul_overflow(a, b, &out);
}

inline std::string trimTrailing(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

inline std::string oneLine(std::string s) {
    s = trimTrailing(std::move(s));
    for (auto& c : s)
        if (c == '\n') c = ';';
    return s;
}

inline std::string lowerExtension(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

// An index stored in an extension object; -1 when absent, not a number or out of int range
// (tinygltf's GetNumberAsInt would convert out-of-range doubles with undefined behaviour).
inline int valueIndex(const tinygltf::Value& v) {
    if (!v.IsNumber()) return -1;
    double d = v.GetNumberAsDouble();
    return d >= 0.0 && d < 2147483647.0 ? int(d) : -1;
}

inline const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& ext, const char* name) {
    auto it = ext.find(name);
    return it == ext.end() ? nullptr : &it->second;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (12-byte header, then chunk 0: uint32
// length, uint32 type 'JSON', data). A .glb whose header does not parse yields the whole file.
inline std::string_view jsonText(const std::vector<unsigned char>& bytes, bool binary) {
    std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (!binary) return all;
    if (bytes.size() < 20 || std::memcmp(bytes.data() + 16, "JSON", 4) != 0) return all;
    uint32_t chunkLen = 0;
    std::memcpy(&chunkLen, bytes.data() + 12, 4);
    if (chunkLen > bytes.size() - 20) return all;
    return all.substr(20, chunkLen);
}

// Deepest [ / { nesting outside strings. tinygltf converts "extras" and "extensions" to its
// Value type recursively, so a hostile file nesting arrays 100000 deep overflows the stack;
// this linear scan rejects such files first.
inline size_t jsonNestingDepth(std::string_view text) {
    size_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}
constexpr size_t kMaxJsonDepth = 256;  // glTF itself needs about 10

// extensionsRequired straight from the JSON. tinygltf rejects some extension-only constructs
// (Draco accessors have no bufferView) with a generic message; when it fails, this tells
// whether an unsupported required extension is the real reason. Malformed JSON: empty list.
inline std::vector<std::string> requiredExtensions(std::string_view text) {
    std::vector<std::string> out;
    nlohmann::json j =
        nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (!j.is_object()) return out;
    auto it = j.find("extensionsRequired");
    if (it == j.end() || !it->is_array()) return out;
    for (const auto& e : *it)
        if (e.is_string()) out.push_back(e.get<std::string>());
    return out;
}

// Nodes with both "matrix" and any of "translation", "rotation", "scale", which glTF 2.0 forbids
// (5.25). tinygltf keeps the matrix and drops the rest without a word, so this reads the JSON.
inline std::vector<size_t> nodesWithMatrixAndTrs(std::string_view text) {
    std::vector<size_t> out;
    nlohmann::json j =
        nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("nodes") || !j["nodes"].is_array()) return out;
    const nlohmann::json& nodes = j["nodes"];
    for (size_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].is_object() && nodes[n].contains("matrix") &&
            (nodes[n].contains("translation") || nodes[n].contains("rotation") ||
             nodes[n].contains("scale")))
            out.push_back(n);
    return out;
}
class Loader {
public:
    Loader(std::string path, const LoadOptions& options) : path_(std::move(path)), opt_(options) {}

    Scene run() {
        parseFile();
        checkExtensions();
        buildHierarchy();
        buildNodes();
        readSkins();
        traverseScene();
        readAnimations();
        // The rest pose: joint matrices, morph weights and posed bounds of the deformed instances.
        poseScene(scene_, {});
        if (scene_.instances.empty() && scene_.emitters.empty())
            warn(
                "nothing to draw: no node of the scene has a mesh (an empty frame will be rendered)");
        finalizeScene(scene_, opt_.defaultCamera, opt_.defaultLights);
        return std::move(scene_);
    }

    // tinygltf callbacks (static trampolines below).
    bool storeImageBytes(tinygltf::Image* image, int index, std::string* err,
                         const unsigned char* bytes, int size);
    bool fileExists(const std::string& absPath) const;
    bool readWholeFile(std::vector<unsigned char>* out, std::string* err,
                       const std::string& path) const;

private:
    [[noreturn]] void fail(const std::string& msg) const { throw AssetError(path_ + ": " + msg); }
    void checkGlbLayout(const std::vector<unsigned char>& bytes) const;

    void warn(const std::string& msg) {
        if (warned_.insert(msg).second) scene_.warnings.push_back(msg);
    }

    // ---- labels used in messages ----
    std::string meshLabel(int m) const {
        const auto& name = model_.meshes[size_t(m)].name;
        return name.empty() ? "mesh " + std::to_string(m) : "mesh '" + name + "'";
    }
    std::string nodeLabel(int n) const {
        const auto& name = model_.nodes[size_t(n)].name;
        return name.empty() ? "node " + std::to_string(n)
                            : "node " + std::to_string(n) + " '" + name + "'";
    }
    std::string materialLabel(int m) const {
        const auto& name = model_.materials[size_t(m)].name;
        return name.empty() ? "material " + std::to_string(m) : "material '" + name + "'";
    }

    template <class Vec>
    void checkIndex(int index, const Vec& v, const std::string& what) const {
        if (index < 0 || size_t(index) >= v.size()) {
            fail(what + " " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(v.size()) + ")");
        }
    }

    void parseFile();
    void checkExtensions();
    void buildHierarchy();
    void traverseScene();
    void checkAsset();
    void addEmitter(int n, const tinygltf::Value& extras);
    // v[key] into out: a finite number (count 0) or an array of `count` finite numbers; absent
    // keys leave out as it is, anything else is an error naming where.
    void readNumbers(const tinygltf::Value& v, const char* key, const std::string& where,
                     float* out, int count);
    void readTextureTransform(const tinygltf::Value& t, int& texCoord, TextureRef& ref,
                              const std::string& what);
    // KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat into mat, with their textures.
    void readDielectric(const tinygltf::Material& gm, Material& mat, const std::string& label);
    // KHR_materials_transmission and KHR_materials_volume into mat, with their textures.
    void readTransmission(const tinygltf::Material& gm, Material& mat, const std::string& label);
    // A textureInfo inside an extension (ext[key]), as getTexture reads the core ones.
    TextureRef extensionTexture(const tinygltf::Value& ext, const char* key,
                                const std::string& what, bool srgb = false);
    // KHR_materials_sheen into mat, with its textures.
    void readSheen(const tinygltf::Material& gm, Material& mat, const std::string& label);
    glm::mat4 localTransform(int n) const;
    glm::mat4 checkedFinite(const glm::mat4& m, int n) const;

    // Validated, converted accessor contents: count * components values, row-major per element.
    template <class T>
    std::vector<T> readAccessor(int index, const std::string& what, int expectedType,
                                uint32_t allowed);
    const unsigned char* bufferViewData(int bv, const std::string& ctx, uint64_t& length);

    uint32_t getMesh(int gltfMesh);
    bool loadPrimitive(int m, int p, Primitive& out);
    uint32_t getMaterial(int gltfMaterial);
    uint32_t defaultMaterial();
    TextureRef getTexture(int gltfTexture, int texCoord, bool srgb,
                          const tinygltf::ExtensionMap& infoExt, const std::string& what);
    void decodeImage(int image, const std::string& what, TextureImage& out);
    void addCamera(int node);
    void addLight(int node, const tinygltf::Value& ext);
    void addMeshInstances(int node);
    void buildNodes();
    void readSkins();
    void readAnimations();
    // samplers: which of out.samplers holds (glTF sampler, path, node for weights) already.
    void readChannel(int a, const tinygltf::AnimationChannel& c, Animation& out,
                     std::map<std::tuple<int, int, int>, uint32_t>& samplers);
    AnimationSampler readSampler(int a, int s, AnimationPath path, int node);
    // The morph targets of the primitive's attributes, and its skin influences.
    void readMorphTargets(int m, int p, size_t vertexCount, Primitive& out);
    void readSkinInfluences(const tinygltf::Primitive& gp, const std::string& label,
                            size_t vertexCount, Primitive& out);

    std::string path_;
    LoadOptions opt_;
    tinygltf::Model model_;
    Scene scene_;
    std::set<std::string> warned_;
    std::string baseDir_;

    std::vector<int> parent_;
    std::vector<glm::mat4> world_;
    std::map<int, uint32_t> meshMap_;  // glTF mesh -> scene mesh
    std::map<int, uint32_t> materialMap_;
    int defaultMaterial_ = -1;
    std::map<std::tuple<int, int, bool>, int32_t>
        textureMap_;                       // (image, sampler, sRGB) -> scene texture
    std::map<int, int32_t> imageTexture_;  // glTF image -> first scene texture holding its pixels
};

// ---------------------------------------------------------------------------------------------
// Accessors (a template: every file reads them)

template <class T>
std::vector<T> Loader::readAccessor(int index, const std::string& what, int expectedType,
                                    uint32_t allowed) {
    checkIndex(index, model_.accessors, what + ": accessor");
    const auto& a = model_.accessors[size_t(index)];
    const std::string ctx = "accessor " + std::to_string(index) + " (" + what + ")";
    if (a.type != expectedType)
        fail(ctx + ": type " + typeName(a.type) + ", expected " + typeName(expectedType));
    if (!(compBit(a.componentType, a.normalized) & allowed)) {
        fail(ctx + ": unsupported component type " +
             componentTypeName(a.componentType, a.normalized));
    }
    const uint64_t comps = uint64_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    const uint64_t csize = uint64_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)));
    const uint64_t elemSize = comps * csize;
    const uint64_t count = a.count;

    const unsigned char* data = nullptr;
    uint64_t stride = elemSize;
    if (a.bufferView >= 0) {
        uint64_t viewLen = 0;
        data = bufferViewData(a.bufferView, ctx, viewLen);
        const auto& bv = model_.bufferViews[size_t(a.bufferView)];
        if (bv.byteStride != 0) {
            if (bv.byteStride < elemSize) {
                fail(ctx + ": bufferView " + std::to_string(a.bufferView) + " byteStride " +
                     std::to_string(bv.byteStride) + " is smaller than the element size " +
                     std::to_string(elemSize));
            }
            stride = bv.byteStride;
        }
        // Last element ends at byteOffset + (count-1)*stride + elemSize.
        uint64_t need = 0, span = 0;
        bool overflow = count > 0 && (mulOverflows(count - 1, stride, span) ||
                                      addOverflows(span, elemSize, span) ||
                                      addOverflows(span, a.byteOffset, need));
        if (overflow || need > viewLen || a.byteOffset > viewLen) {
            fail(ctx + ": byteOffset+count*stride exceeds bufferView " +
                 std::to_string(a.bufferView) + " length (" +
                 (overflow ? std::string("overflow") : std::to_string(need)) + " > " +
                 std::to_string(viewLen) + ")");
        }
        data += a.byteOffset;
    } else if (count * comps > kMaxVirtualAccessorComponents) {  // count < 2^64 / 16 after tinygltf
        fail(ctx + ": count " + std::to_string(count) + " without a bufferView is too large");
    }

    std::vector<T> out(size_t(count * comps), T(0));
    if (data) {
        for (uint64_t e = 0; e < count; ++e) {
            const unsigned char* p = data + e * stride;
            for (uint64_t c = 0; c < comps; ++c) {
                out[size_t(e * comps + c)] =
                    static_cast<T>(readComponent(p + c * csize, a.componentType, a.normalized));
            }
        }
    }

    if (a.sparse.isSparse) {
        const uint64_t sc = uint64_t(std::max(a.sparse.count, 0));
        if (a.sparse.count < 0 || sc > count)
            fail(ctx + ": sparse count " + std::to_string(a.sparse.count) + " exceeds count");
        const int ict = a.sparse.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(ctx + ": unsupported sparse index component type " +
                 componentTypeName(ict, false));
        }
        const uint64_t isize = uint64_t(tinygltf::GetComponentSizeInBytes(uint32_t(ict)));
        uint64_t ilen = 0, vlen = 0;
        const unsigned char* idata =
            bufferViewData(a.sparse.indices.bufferView, ctx + " sparse indices", ilen);
        const unsigned char* vdata =
            bufferViewData(a.sparse.values.bufferView, ctx + " sparse values", vlen);
        uint64_t ioff = uint64_t(std::max(a.sparse.indices.byteOffset, 0));
        uint64_t voff = uint64_t(std::max(a.sparse.values.byteOffset, 0));
        uint64_t ineed = 0, vneed = 0;
        if (mulOverflows(sc, isize, ineed) || addOverflows(ineed, ioff, ineed) || ineed > ilen) {
            fail(ctx + ": sparse indices exceed bufferView " +
                 std::to_string(a.sparse.indices.bufferView) + " length");
        }
        if (mulOverflows(sc, elemSize, vneed) || addOverflows(vneed, voff, vneed) || vneed > vlen) {
            fail(ctx + ": sparse values exceed bufferView " +
                 std::to_string(a.sparse.values.bufferView) + " length");
        }
        for (uint64_t k = 0; k < sc; ++k) {
            uint64_t target = uint64_t(readComponent(idata + ioff + k * isize, ict, false));
            if (target >= count) {
                fail(ctx + ": sparse index " + std::to_string(target) + " >= count " +
                     std::to_string(count));
            }
            const unsigned char* p = vdata + voff + k * elemSize;
            for (uint64_t c = 0; c < comps; ++c) {
                out[size_t(target * comps + c)] =
                    static_cast<T>(readComponent(p + c * csize, a.componentType, a.normalized));
            }
        }
    }
    return out;
}

}  // namespace fe::assets::gltf
