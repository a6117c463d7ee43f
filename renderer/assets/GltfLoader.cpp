// glTF 2.0 loader on top of tinygltf (JSON + container parsing) and stb_image (decoding).
// tinygltf only parses; everything it does not check (accessor bounds, dangling indices,
// hierarchy sanity, finite values) is validated here before use, so malformed files end in an
// AssetError instead of a crash.

// tinygltf's implementation is in TinyGltf.cpp, stb_image's in ImageDecode.cpp.
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "assets/GltfLoader.h"
#include "assets/Animation.h"
#include "assets/ImageDecode.h"
#include "assets/JpegDecode.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>

#include "assets/Geometry.h"

namespace fe::assets {

namespace {

namespace fs = std::filesystem;

// Extensions whose data the loader understands, so a file may require them.
const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_clearcoat",
    "KHR_materials_ior",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_volume",
    "KHR_texture_transform",
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

uint32_t compBit(int componentType, bool normalized) {
    uint32_t bit = 0;
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: bit = normalized ? 0u : uint32_t(F32); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: bit = normalized ? U8N : U8; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: bit = normalized ? U16N : U16; break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: bit = normalized ? uint32_t(S8N) : 0u; break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: bit = normalized ? uint32_t(S16N) : 0u; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: bit = normalized ? 0u : uint32_t(U32); break;
        default: break;
    }
    return bit;
}

std::string componentTypeName(int componentType, bool normalized) {
    std::string s;
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: s = "byte"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: s = "unsigned byte"; break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: s = "short"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: s = "unsigned short"; break;
        case TINYGLTF_COMPONENT_TYPE_INT: s = "int"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: s = "unsigned int"; break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT: s = "float"; break;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: s = "double"; break;
        default: s = "unknown"; break;
    }
    s += " (" + std::to_string(componentType) + ")";
    if (normalized) s += " normalized";
    return s;
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "type " + std::to_string(type);
    }
}

// Reads one component and converts it as glTF defines normalized integers (3.11).
double readComponent(const unsigned char* p, int componentType, bool normalized) {
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
        default: return 0.0;
    }
}

bool addOverflows(uint64_t a, uint64_t b, uint64_t& out) { return __builtin_add_overflow(a, b, &out); }
bool mulOverflows(uint64_t a, uint64_t b, uint64_t& out) { return __builtin_mul_overflow(a, b, &out); }

std::string trimTrailing(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

std::string oneLine(std::string s) {
    s = trimTrailing(std::move(s));
    for (auto& c : s)
        if (c == '\n') c = ';';
    return s;
}

std::string lowerExtension(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

// An index stored in an extension object; -1 when absent, not a number or out of int range
// (tinygltf's GetNumberAsInt would convert out-of-range doubles with undefined behaviour).
int valueIndex(const tinygltf::Value& v) {
    if (!v.IsNumber()) return -1;
    double d = v.GetNumberAsDouble();
    return d >= 0.0 && d < 2147483647.0 ? int(d) : -1;
}

const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& ext, const char* name) {
    auto it = ext.find(name);
    return it == ext.end() ? nullptr : &it->second;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (12-byte header, then chunk 0: uint32
// length, uint32 type 'JSON', data). A .glb whose header does not parse yields the whole file.
std::string_view jsonText(const std::vector<unsigned char>& bytes, bool binary) {
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
size_t jsonNestingDepth(std::string_view text) {
    size_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (char c : text) {
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
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
std::vector<std::string> requiredExtensions(std::string_view text) {
    std::vector<std::string> out;
    nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (!j.is_object()) return out;
    auto it = j.find("extensionsRequired");
    if (it == j.end() || !it->is_array()) return out;
    for (const auto& e : *it)
        if (e.is_string()) out.push_back(e.get<std::string>());
    return out;
}

// Nodes with both "matrix" and any of "translation", "rotation", "scale", which glTF 2.0 forbids
// (5.25). tinygltf keeps the matrix and drops the rest without a word, so this reads the JSON.
std::vector<size_t> nodesWithMatrixAndTrs(std::string_view text) {
    std::vector<size_t> out;
    nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("nodes") || !j["nodes"].is_array()) return out;
    const nlohmann::json& nodes = j["nodes"];
    for (size_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].is_object() && nodes[n].contains("matrix") &&
            (nodes[n].contains("translation") || nodes[n].contains("rotation") || nodes[n].contains("scale")))
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
            warn("nothing to draw: no node of the scene has a mesh (an empty frame will be rendered)");
        finalizeScene(scene_, opt_.defaultCamera, opt_.defaultLights);
        return std::move(scene_);
    }

    // tinygltf callbacks (static trampolines below).
    bool storeImageBytes(tinygltf::Image* image, int index, std::string* err, const unsigned char* bytes, int size);
    bool fileExists(const std::string& absPath) const;
    bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path) const;

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
        return name.empty() ? "node " + std::to_string(n) : "node " + std::to_string(n) + " '" + name + "'";
    }
    std::string materialLabel(int m) const {
        const auto& name = model_.materials[size_t(m)].name;
        return name.empty() ? "material " + std::to_string(m) : "material '" + name + "'";
    }

    template <class Vec>
    void checkIndex(int index, const Vec& v, const std::string& what) const {
        if (index < 0 || size_t(index) >= v.size()) {
            fail(what + " " + std::to_string(index) + " does not exist (the file has " + std::to_string(v.size()) + ")");
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
    void readNumbers(const tinygltf::Value& v, const char* key, const std::string& where, float* out, int count);
    void readTextureTransform(const tinygltf::Value& t, int& texCoord, TextureRef& ref, const std::string& what);
    // KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat into mat, with their textures.
    void readDielectric(const tinygltf::Material& gm, Material& mat, const std::string& label);
    // KHR_materials_transmission and KHR_materials_volume into mat, with their textures.
    void readTransmission(const tinygltf::Material& gm, Material& mat, const std::string& label);
    // A textureInfo inside an extension (ext[key]), as getTexture reads the core ones.
    TextureRef extensionTexture(const tinygltf::Value& ext, const char* key, const std::string& what, bool srgb = false);
    // KHR_materials_sheen into mat, with its textures.
    void readSheen(const tinygltf::Material& gm, Material& mat, const std::string& label);
    glm::mat4 localTransform(int n) const;
    glm::mat4 checkedFinite(const glm::mat4& m, int n) const;

    // Validated, converted accessor contents: count * components values, row-major per element.
    template <class T>
    std::vector<T> readAccessor(int index, const std::string& what, int expectedType, uint32_t allowed);
    const unsigned char* bufferViewData(int bv, const std::string& ctx, uint64_t& length);

    uint32_t getMesh(int gltfMesh);
    bool loadPrimitive(int m, int p, Primitive& out);
    uint32_t getMaterial(int gltfMaterial);
    uint32_t defaultMaterial();
    TextureRef getTexture(int gltfTexture, int texCoord, bool srgb, const tinygltf::ExtensionMap& infoExt,
                          const std::string& what);
    void decodeImage(int image, const std::string& what, TextureImage& out);
    void addCamera(int node);
    void addLight(int node, const tinygltf::Value& ext);
    void addMeshInstances(int node);
    void buildNodes();
    void readSkins();
    void readAnimations();
    // samplers: which of out.samplers holds (glTF sampler, path, node for weights) already.
    void readChannel(int a, const tinygltf::AnimationChannel& c, Animation& out, std::map<std::tuple<int, int, int>, uint32_t>& samplers);
    AnimationSampler readSampler(int a, int s, AnimationPath path, int node);
    // The morph targets of the primitive's attributes, and its skin influences.
    void readMorphTargets(int m, int p, size_t vertexCount, Primitive& out);
    void readSkinInfluences(const tinygltf::Primitive& gp, const std::string& label, size_t vertexCount, Primitive& out);

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
    std::map<std::tuple<int, int, bool>, int32_t> textureMap_;  // (image, sampler, sRGB) -> scene texture
    std::map<int, int32_t> imageTexture_;  // glTF image -> first scene texture holding its pixels
};

// ---------------------------------------------------------------------------------------------
// tinygltf glue

bool imageLoaderTrampoline(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                           const unsigned char* bytes, int size, void* user) {
    return static_cast<Loader*>(user)->storeImageBytes(image, index, err, bytes, size);
}

// Images are kept encoded at parse time and decoded only if a material uses them, with our own
// error messages. Images stored in a buffer view are range-checked here because tinygltf 2.7
// hands us a pointer into the buffer without checking the view against the buffer size.
bool Loader::storeImageBytes(tinygltf::Image* image, int index, std::string* err, const unsigned char* bytes,
                             int size) {
    if (image->bufferView >= 0) {
        // tinygltf has already checked both indices.
        const auto& bv = model_.bufferViews[size_t(image->bufferView)];
        const auto& buf = model_.buffers[size_t(bv.buffer)];
        uint64_t end = 0;
        if (addOverflows(bv.byteOffset, bv.byteLength, end) || end > buf.data.size()) {
            if (err) {
                *err += "image " + std::to_string(index) + ": bufferView " + std::to_string(image->bufferView) +
                        " exceeds buffer " + std::to_string(bv.buffer) + "\n";
            }
            return false;
        }
    }
    if (size < 0 || (size > 0 && bytes == nullptr)) return false;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

bool fileExistsTrampoline(const std::string& absPath, void* user) {
    return static_cast<Loader*>(user)->fileExists(absPath);
}
std::string expandTrampoline(const std::string& p, void*) { return p; }
bool readTrampoline(std::vector<unsigned char>* out, std::string* err, const std::string& p, void* user) {
    return static_cast<Loader*>(user)->readWholeFile(out, err, p);
}
bool writeTrampoline(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is disabled";
    return false;
}

// Resources resolve next to the glTF file only (tinygltf would also search the working
// directory), and only regular files are read (a FIFO or device would hang or never end).
bool Loader::fileExists(const std::string& absPath) const {
    if (absPath.compare(0, baseDir_.size(), baseDir_) != 0) return false;
    std::error_code ec;
    return fs::is_regular_file(fs::path(absPath), ec);
}

bool Loader::readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& p) const {
    std::error_code ec;
    fs::path fp = fs::path(p);
    if (!fs::is_regular_file(fp, ec)) {
        if (err) *err += "not a regular file";
        return false;
    }
    auto size = fs::file_size(fp, ec);
    if (ec || size > 0xFFFFFFFFull) {
        if (err) *err += ec ? ec.message() : std::string("file larger than 4 GiB");
        return false;
    }
    std::ifstream in(fp, std::ios::binary);
    out->resize(size_t(size));
    if (!in || (size && !in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size)))) {
        if (err) *err += "read error";
        return false;
    }
    return true;
}

// 4.4 GLB file format: the 12-byte header's version is 2 and its length the file's; then
// chunks (uint32 length, uint32 type, data), each starting and ending 4-byte aligned; the first
// is the one JSON chunk, a BIN chunk if present is the second and only one; chunks of other
// types are ignored, as the specification requires. tinygltf reads the first two chunks
// and looks no further, so what it would let through is refused here, naming the chunk.
void Loader::checkGlbLayout(const std::vector<unsigned char>& bytes) const {
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;
    };
    if (bytes.size() < 12) fail("GLB header truncated: " + std::to_string(bytes.size()) + " bytes, 12 needed");
    if (const uint32_t version = u32(4); version != 2)
        fail("GLB header version " + std::to_string(version) + " (glTF 2.0 binaries have version 2)");
    if (const uint32_t length = u32(8); length != bytes.size())
        fail("GLB header length " + std::to_string(length) + " but the file has " + std::to_string(bytes.size()) +
             " bytes");
    bool bin = false;
    size_t index = 0;
    for (size_t at = 12; at < bytes.size(); ++index) {
        const std::string where = "GLB chunk " + std::to_string(index) + " at byte " + std::to_string(at);
        if (bytes.size() - at < 8) fail(where + ": truncated chunk header");
        const uint32_t length = u32(at), type = u32(at + 4);
        std::string name;
        for (int i = 0; i < 4; ++i) {
            const char c = char((type >> (8 * i)) & 0xff);
            name += (c >= 32 && c < 127) ? std::string(1, c) : "\\x" + std::to_string(unsigned(uint8_t(c)));
        }
        const bool isJson = type == 0x4E4F534Au, isBin = type == 0x004E4942u;
        const std::string chunk = where + " (" + (isBin ? std::string("BIN") : name) + ")";
        if (index == 0 && !isJson) fail(chunk + ": the first chunk must be JSON");
        if (index > 0 && isJson) fail(chunk + ": duplicate JSON chunk (a GLB has exactly one, the first)");
        if (isBin && bin) fail(chunk + ": duplicate BIN chunk (a GLB has at most one)");
        if (isBin && index != 1) fail(chunk + ": the BIN chunk must directly follow the JSON chunk");
        if (length % 4 != 0)
            fail(chunk + ": length " + std::to_string(length) + " is not a multiple of 4 (chunks are 4-byte aligned)");
        if (length > bytes.size() - at - 8)
            fail(chunk + ": length " + std::to_string(length) + " runs past the end of the file");
        bin = bin || isBin;
        at += 8 + size_t(length);
    }
}

void Loader::parseFile() {
    fs::path fp = fs::path(path_);
    std::error_code ec;
    if (!fs::exists(fp, ec)) fail("file not found");
    if (!fs::is_regular_file(fp, ec)) fail("not a regular file");
    std::vector<unsigned char> bytes;
    std::string readErr;
    baseDir_ = fs::absolute(fp, ec).parent_path().string();
    if (!readWholeFile(&bytes, &readErr, fp.string())) fail("cannot read file: " + readErr);

    const bool magic = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const std::string ext = lowerExtension(fp);
    if (ext == ".glb" && !magic) {
        std::string found;
        for (size_t i = 0; i < std::min<size_t>(4, bytes.size()); ++i) {
            char c = char(bytes[i]);
            found += (c >= 32 && c < 127) ? std::string(1, c) : "\\x" + std::to_string(unsigned(bytes[i]));
        }
        fail("not a binary glTF: bad magic '" + found + "' (expected 'glTF')");
    }
    if (magic && ext != ".glb") warn("binary glTF content in a file named '" + fp.filename().string() + "'");

    if (magic) checkGlbLayout(bytes);
    const std::string_view json = jsonText(bytes, magic);
    // 3.1 JSON encoding: UTF-8 without a byte order mark; exporters must not write one, and
    // clients may ignore it rather than fail, so it is a warning (an error under --strict).
    if (json.substr(0, 3) == "\xEF\xBB\xBF")
        warn("the JSON starts with a UTF-8 byte order mark, which glTF 2.0 forbids; it was ignored");
    if (jsonNestingDepth(json) > kMaxJsonDepth) {
        fail("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    }
    auto failUnsupportedRequired = [&] {
        for (const auto& e : requiredExtensions(json)) {
            if (!kSupportedExtensions.count(e)) fail("unsupported required extension " + e);
        }
    };

    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(&imageLoaderTrampoline, this);
    tinygltf::FsCallbacks cb{};
    cb.FileExists = &fileExistsTrampoline;
    cb.ExpandFilePath = &expandTrampoline;
    cb.ReadWholeFile = &readTrampoline;
    cb.WriteWholeFile = &writeTrampoline;
    cb.user_data = this;
    gltf.SetFsCallbacks(cb);

    std::string err, warnings;
    bool ok = false;
    try {
        // The model being filled is our member, so storeImageBytes() can look at its buffers.
        if (magic) {
            ok = gltf.LoadBinaryFromMemory(&model_, &err, &warnings, bytes.data(), unsigned(bytes.size()), baseDir_);
        } else {
            ok = gltf.LoadASCIIFromString(&model_, &err, &warnings, reinterpret_cast<const char*>(bytes.data()),
                                          unsigned(bytes.size()), baseDir_);
        }
    } catch (const std::exception& e) {
        failUnsupportedRequired();
        fail(std::string("glTF parse error: ") + e.what());
    }
    if (!ok) {
        failUnsupportedRequired();
        fail("glTF parse error: " + oneLine(err.empty() ? std::string("unknown error") : err));
    }
    std::istringstream ws(warnings);
    for (std::string line; std::getline(ws, line);) {
        if (!trimTrailing(line).empty()) warn("tinygltf: " + trimTrailing(line));
    }
    if (scene_.name.empty()) scene_.name = fp.stem().string();
    checkAsset();
    for (size_t n : nodesWithMatrixAndTrs(json))
        warn(nodeLabel(int(n)) + " has both a matrix and translation/rotation/scale, which glTF 2.0 forbids; the matrix is used");
}

// What the glTF 2.0 specification requires and the parser lets through.
void Loader::checkAsset() {
    // 3.2 Asset: "version" is required, "<major>.<minor>"; a loader must not load a major version
    // it does not implement, and "minVersion" names the least version a loader must support.
    const std::string& v = model_.asset.version;
    if (v.empty()) fail("asset.version is missing (glTF 2.0 requires it)");
    if (v.rfind("2.", 0) != 0 || v.size() < 3) fail("asset.version '" + v + "': this loader reads glTF 2.x only");
    const std::string& min = model_.asset.minVersion;
    if (!min.empty() && min != "2.0") fail("asset.minVersion '" + min + "': this loader implements glTF 2.0");
    // 5.x glTF: "scene" (the default scene) must be defined only when "scenes" is.
    if (model_.defaultScene >= 0 && model_.scenes.empty())
        fail("scene " + std::to_string(model_.defaultScene) + " is set but the file has no scenes (glTF 2.0 forbids it)");
}

void Loader::checkExtensions() {
    for (const auto& e : model_.extensionsRequired) {
        if (!kSupportedExtensions.count(e)) fail("unsupported required extension " + e);
    }
    for (const auto& e : model_.extensionsUsed) {
        if (kSupportedExtensions.count(e)) continue;
        warn("extension " + e + " is not supported and is ignored");
    }
}

// Finite doubles can still overflow float (1e39): check what we actually keep.
glm::mat4 Loader::checkedFinite(const glm::mat4& m, int n) const {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) fail(nodeLabel(n) + ": non-finite transform");
    return m;
}

glm::mat4 Loader::localTransform(int n) const {
    const auto& node = model_.nodes[size_t(n)];
    auto finite = [](const std::vector<double>& v) {
        return std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); });
    };
    if (!finite(node.matrix) || !finite(node.translation) || !finite(node.rotation) || !finite(node.scale)) {
        fail(nodeLabel(n) + ": non-finite transform");
    }
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(nodeLabel(n) + ": matrix must have 16 numbers");
        glm::dmat4 m = glm::make_mat4(node.matrix.data());  // both column-major
        return checkedFinite(glm::mat4(m), n);
    }
    glm::mat4 t(1.0f), r(1.0f), s(1.0f);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) fail(nodeLabel(n) + ": translation must have 3 numbers");
        t = glm::translate(glm::mat4(1.0f), glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(nodeLabel(n) + ": rotation must have 4 numbers");
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // w, x, y, z
        double len = glm::length(q);
        if (len > 1e-12) r = glm::mat4(glm::mat4_cast(q / len));  // exporters round; renormalise
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(nodeLabel(n) + ": scale must have 3 numbers");
        s = glm::scale(glm::mat4(1.0f), glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return checkedFinite(t * r * s, n);
}

// World transforms of every node (joints may live outside the drawn scene), with the
// hierarchy checked to be a forest: every child index valid, one parent per node, no cycles.
// Iterative, so a deep chain cannot overflow the stack.
void Loader::buildHierarchy() {
    const size_t n = model_.nodes.size();
    parent_.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (int c : model_.nodes[i].children) {
            checkIndex(c, model_.nodes, nodeLabel(int(i)) + ": child node");
            if (size_t(c) == i) fail(nodeLabel(c) + " is its own child");
            if (parent_[size_t(c)] != -1) {
                fail(nodeLabel(c) + " has two parents (" + nodeLabel(parent_[size_t(c)]) +
                     " and " + nodeLabel(int(i)) + ")");
            }
            parent_[size_t(c)] = int(i);
        }
    }
    world_.assign(n, glm::mat4(1.0f));
    std::vector<char> done(n, 0);
    size_t reached = 0;
    std::vector<int> stack;
    for (size_t root = 0; root < n; ++root) {
        if (parent_[root] != -1) continue;
        stack.push_back(int(root));
        while (!stack.empty()) {
            int i = stack.back();
            stack.pop_back();
            glm::mat4 parentWorld = parent_[size_t(i)] >= 0 ? world_[size_t(parent_[size_t(i)])] : glm::mat4(1.0f);
            world_[size_t(i)] = checkedFinite(parentWorld * localTransform(i), i);  // products can overflow too
            done[size_t(i)] = 1;
            ++reached;
            for (int c : model_.nodes[size_t(i)].children) stack.push_back(c);
        }
    }
    if (reached != n) {
        size_t bad = size_t(std::find(done.begin(), done.end(), 0) - done.begin());
        fail("node hierarchy has a cycle through " + nodeLabel(int(bad)));
    }
}

// Every node of the file (joints and animated nodes may lie outside the drawn scene), its
// transform as the file gives it: TRS, with the rotation normalised, or a fixed matrix.
void Loader::buildNodes() {
    scene_.nodes.resize(model_.nodes.size());
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
        const auto& gn = model_.nodes[i];
        Node& node = scene_.nodes[i];
        node.name = gn.name;
        node.parent = parent_[i];
        node.world = world_[i];
        if (!gn.matrix.empty()) node.matrix = localTransform(int(i));
        if (gn.translation.size() == 3) node.translation = glm::vec3(gn.translation[0], gn.translation[1], gn.translation[2]);
        if (gn.scale.size() == 3) node.scale = glm::vec3(gn.scale[0], gn.scale[1], gn.scale[2]);
        if (gn.rotation.size() == 4) {
            glm::dquat q(gn.rotation[3], gn.rotation[0], gn.rotation[1], gn.rotation[2]);
            if (glm::length(q) > 1e-12) node.rotation = glm::quat(q / glm::length(q));
        }
        for (double w : gn.weights) {
            if (!std::isfinite(w)) fail(nodeLabel(int(i)) + ": non-finite morph weight");
            node.weights.push_back(float(w));
        }
    }
}

void Loader::readSkins() {
    for (size_t s = 0; s < model_.skins.size(); ++s) {
        const auto& gs = model_.skins[s];
        const std::string label = "skin " + std::to_string(s);
        Skin skin;
        skin.name = gs.name;
        std::vector<float> ibm;
        if (gs.inverseBindMatrices >= 0) {
            ibm = readAccessor<float>(gs.inverseBindMatrices, "inverseBindMatrices of " + label, TINYGLTF_TYPE_MAT4, F32);
            if (ibm.size() < gs.joints.size() * 16) fail(label + ": fewer inverseBindMatrices than joints");
        }
        for (size_t j = 0; j < gs.joints.size(); ++j) {
            checkIndex(gs.joints[j], model_.nodes, label + ": joint node");
            skin.joints.push_back(uint32_t(gs.joints[j]));
            glm::mat4 inv = ibm.empty() ? glm::mat4(1.0f) : glm::make_mat4(&ibm[j * 16]);
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(inv[c].x + inv[c].y + inv[c].z + inv[c].w)) fail(label + ": non-finite inverse bind matrix");
            skin.inverseBindMatrices.push_back(inv);
        }
        scene_.skins.push_back(std::move(skin));
    }
}

void Loader::readAnimations() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
        const auto& ga = model_.animations[a];
        Animation anim;
        anim.name = ga.name;
        std::map<std::tuple<int, int, int>, uint32_t> samplers;
        for (const auto& c : ga.channels) readChannel(int(a), c, anim, samplers);
        for (const AnimationSampler& sm : anim.samplers)
            if (!sm.times.empty()) anim.duration = std::max(anim.duration, sm.times.back());
        scene_.animations.push_back(std::move(anim));
    }
}

void Loader::readChannel(int a, const tinygltf::AnimationChannel& c, Animation& anim,
                         std::map<std::tuple<int, int, int>, uint32_t>& samplers) {
    const auto& ga = model_.animations[size_t(a)];
    const std::string label = "animation " + std::to_string(a) + (ga.name.empty() ? "" : " '" + ga.name + "'");
    checkIndex(c.sampler, ga.samplers, label + ": channel sampler");
    if (c.target_node < 0) return;  // glTF: a channel without a target node is ignored
    checkIndex(c.target_node, model_.nodes, label + ": channel target node");
    AnimationPath path;
    if (c.target_path == "translation") path = AnimationPath::Translation;
    else if (c.target_path == "rotation") path = AnimationPath::Rotation;
    else if (c.target_path == "scale") path = AnimationPath::Scale;
    else if (c.target_path == "weights") path = AnimationPath::Weights;
    else {
        warn(label + ": channel on '" + c.target_path + "' ignored");
        return;
    }
    if (path != AnimationPath::Weights && !model_.nodes[size_t(c.target_node)].matrix.empty()) {
        warn(label + ": " + nodeLabel(c.target_node) + " has a matrix, which glTF does not animate: its " + c.target_path +
             " channel ignored");
        return;
    }
    // A sampler is read once per path it animates (its output's layout depends on the path) and,
    // for weights, per node (the width is its mesh's target count).
    const auto key = std::make_tuple(c.sampler, int(path), path == AnimationPath::Weights ? c.target_node : -1);
    auto found = samplers.find(key);
    if (found == samplers.end()) {
        anim.samplers.push_back(readSampler(a, c.sampler, path, c.target_node));
        found = samplers.emplace(key, uint32_t(anim.samplers.size() - 1)).first;
    }
    anim.channels.push_back({.sampler = found->second, .node = uint32_t(c.target_node), .path = path});
}

AnimationSampler Loader::readSampler(int a, int si, AnimationPath path, int node) {
    const auto& gs = model_.animations[size_t(a)].samplers[size_t(si)];
    const std::string label = "animation " + std::to_string(a) + " sampler " + std::to_string(si);
    AnimationSampler s;
    if (gs.interpolation.empty() || gs.interpolation == "LINEAR") s.interpolation = Interpolation::Linear;
    else if (gs.interpolation == "STEP") s.interpolation = Interpolation::Step;
    else if (gs.interpolation == "CUBICSPLINE") s.interpolation = Interpolation::CubicSpline;
    else fail(label + ": unknown interpolation '" + gs.interpolation + "'");
    s.times = readAccessor<float>(gs.input, "input of " + label, TINYGLTF_TYPE_SCALAR, F32);
    if (s.times.empty()) fail(label + ": no keys (an input accessor of count 0)");
    for (size_t k = 0; k < s.times.size(); ++k) {
        if (!std::isfinite(s.times[k])) fail(label + ": non-finite key time");
        if (k && s.times[k] < s.times[k - 1]) fail(label + ": key times decrease (" + std::to_string(s.times[k - 1]) +
                                                   " then " + std::to_string(s.times[k]) + ")");
    }
    const bool weights = path == AnimationPath::Weights;
    const int type = weights ? TINYGLTF_TYPE_SCALAR : path == AnimationPath::Rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
    const uint32_t allowed = weights || path == AnimationPath::Rotation ? F32 | S8N | U8N | S16N | U16N : F32;
    s.values = readAccessor<float>(gs.output, "output of " + label, type, allowed);
    for (float v : s.values)
        if (!std::isfinite(v)) fail(label + ": non-finite output value");
    const size_t perKey = s.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const size_t elements = s.times.size() * perKey;
    if (weights) {
        // One weight per morph target of the node's mesh, per element.
        if (elements == 0 || s.values.size() % elements != 0)
            fail(label + ": " + std::to_string(s.values.size()) + " output weights for " + std::to_string(s.times.size()) +
                 " keys is not a whole number per key");
        s.width = uint32_t(s.values.size() / elements);
        const int mesh = model_.nodes[size_t(node)].mesh;
        if (mesh >= 0 && mesh < int(model_.meshes.size()))
            for (const auto& p : model_.meshes[size_t(mesh)].primitives)
                if (!p.targets.empty() && p.targets.size() != s.width)
                    fail(label + ": " + std::to_string(s.width) + " weights per key for " + meshLabel(mesh) + "'s " +
                         std::to_string(p.targets.size()) + " morph targets");
    } else {
        s.width = path == AnimationPath::Rotation ? 4 : 3;
        if (s.values.size() != elements * s.width)
            fail(label + ": output count " + std::to_string(s.values.size() / s.width) + " for " + std::to_string(s.times.size()) +
                 " keys (" + std::to_string(perKey) + " per key expected)");
    }
    return s;
}

void Loader::traverseScene() {
    std::vector<int> roots;
    if (model_.scenes.empty()) {
        warn("the file has no scenes: drawing every root node");
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            if (parent_[i] == -1) roots.push_back(int(i));
    } else {
        int s = opt_.scene >= 0 ? opt_.scene : (model_.defaultScene >= 0 ? model_.defaultScene : 0);
        checkIndex(s, model_.scenes, "scene");
        const auto& sc = model_.scenes[size_t(s)];
        if (!sc.name.empty()) scene_.name = sc.name;
        for (int r : sc.nodes) {
            checkIndex(r, model_.nodes, "scene " + std::to_string(s) + ": node");
            roots.push_back(r);
        }
    }
    // Depth-first, children in file order: defines which camera is "first".
    std::vector<char> visited(model_.nodes.size(), 0);
    std::vector<int> stack;
    for (int r : roots) {
        stack.push_back(r);
        while (!stack.empty()) {
            int n = stack.back();
            stack.pop_back();
            if (visited[size_t(n)]) {
                warn(nodeLabel(n) + " is listed twice in the scene; drawn once");
                continue;
            }
            visited[size_t(n)] = 1;
            const auto& node = model_.nodes[size_t(n)];
            if (node.camera >= 0) addCamera(n);
            if (auto* ext = findExtension(node.extensions, "KHR_lights_punctual")) addLight(n, *ext);
            if (node.extras.IsObject() && node.extras.Has("fe_emitter")) addEmitter(n, node.extras.Get("fe_emitter"));
            if (node.mesh >= 0) addMeshInstances(n);
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
        }
    }
}

// Every camera of the scene, in depth-first node order (the first is drawn from unless another
// is chosen); the node's world transform with its scale removed.
void Loader::addCamera(int n) {
    const auto& node = model_.nodes[size_t(n)];
    checkIndex(node.camera, model_.cameras, nodeLabel(n) + ": camera");
    const auto& cam = model_.cameras[size_t(node.camera)];
    const std::string label = "camera " + std::to_string(node.camera);
    Camera c;
    if (cam.type == "perspective") {
        const auto& p = cam.perspective;
        const double kPi = 3.14159265358979323846;
        if (!(p.yfov > 0.0 && p.yfov < kPi) || !(p.znear > 0.0) || !(p.zfar == 0.0 || p.zfar > p.znear) ||
            !std::isfinite(p.znear) || !std::isfinite(p.zfar)) {
            warn(label + " ignored: invalid yfov/znear/zfar");
            return;
        }
        c.yfov = float(p.yfov);
        c.znear = float(p.znear);
        c.zfar = p.zfar > 0.0 ? float(p.zfar) : std::numeric_limits<float>::infinity();
        if (p.aspectRatio > 0.0 && std::isfinite(p.aspectRatio)) c.aspectRatio = float(p.aspectRatio);
    } else if (cam.type == "orthographic") {
        const auto& o = cam.orthographic;
        if (!(o.xmag != 0.0 && o.ymag != 0.0 && std::isfinite(o.xmag) && std::isfinite(o.ymag)) || !(o.znear >= 0.0) ||
            !(o.zfar > o.znear) || !std::isfinite(o.zfar)) {
            warn(label + " ignored: invalid xmag/ymag/znear/zfar");
            return;
        }
        c.orthographic = glm::vec2(float(o.xmag), float(o.ymag));
        c.znear = float(o.znear);
        c.zfar = float(o.zfar);
    } else {
        warn(label + " of unknown type '" + cam.type + "' ignored");
        return;
    }
    const glm::mat4& w = world_[size_t(n)];
    glm::vec3 eye(w[3]), back(w[2]), up(w[1]);
    if (!(glm::length(back) > 1e-12f) || !(glm::length(up) > 1e-12f) ||
        !(glm::length(glm::cross(up, back)) > 1e-12f)) {
        warn(label + " ignored: degenerate node transform");
        return;
    }
    c.worldFromView = Camera::lookAlong(eye, -back, up, c.yfov, c.znear, c.zfar).worldFromView;
    c.name = cam.name.empty() ? node.name : cam.name;
    c.node = n;
    scene_.cameras.push_back(c);
    if (!scene_.camera) {
        scene_.camera = c;
        scene_.cameraIndex = 0;
    }
}

void Loader::readNumbers(const tinygltf::Value& v, const char* key, const std::string& where, float* out, int count) {
    if (!v.Has(key)) return;
    const tinygltf::Value& x = v.Get(key);
    // Finite as a float: what is kept (a finite double such as 1e39 overflows it).
    auto finiteFloat = [](const tinygltf::Value& n) { return n.IsNumber() && std::isfinite(float(n.GetNumberAsDouble())); };
    if (count == 0) {
        if (!finiteFloat(x)) fail(where + "." + key + " must be a number, finite as a float");
        *out = float(x.GetNumberAsDouble());
        return;
    }
    const std::string shape = where + "." + key + " must be an array of " + std::to_string(count) + " numbers, finite as floats";
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
        if (mat.ior == 0.0f) mat.ior = std::numeric_limits<float>::infinity();
        else if (!(mat.ior >= 1.0f)) fail(label + ": KHR_materials_ior.ior " + std::to_string(mat.ior) + " must be at least 1 (or 0)");
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_clearcoat")) {
        const std::string where = label + ": KHR_materials_clearcoat";
        readNumbers(*e, "clearcoatFactor", where, &mat.clearcoat, 0);
        readNumbers(*e, "clearcoatRoughnessFactor", where, &mat.clearcoatRoughness, 0);
        if (!(mat.clearcoat >= 0.0f && mat.clearcoat <= 1.0f)) fail(where + ".clearcoatFactor must lie in [0, 1]");
        if (!(mat.clearcoatRoughness >= 0.0f && mat.clearcoatRoughness <= 1.0f))
            fail(where + ".clearcoatRoughnessFactor must lie in [0, 1]");
        mat.clearcoatTexture = extensionTexture(*e, "clearcoatTexture", where);
        mat.clearcoatRoughnessTexture = extensionTexture(*e, "clearcoatRoughnessTexture", where);
        mat.clearcoatNormalTexture = extensionTexture(*e, "clearcoatNormalTexture", where);
        if (mat.clearcoatNormalTexture.valid()) readNumbers(e->Get("clearcoatNormalTexture"), "scale", where + ".clearcoatNormalTexture",
                                                            &mat.clearcoatNormalScale, 0);
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_specular")) {
        const std::string where = label + ": KHR_materials_specular";
        readNumbers(*e, "specularFactor", where, &mat.specular, 0);
        readNumbers(*e, "specularColorFactor", where, &mat.specularColor.x, 3);
        if (!(mat.specular >= 0.0f && mat.specular <= 1.0f)) fail(where + ".specularFactor must lie in [0, 1]");
        if (!(glm::all(glm::greaterThanEqual(mat.specularColor, glm::vec3(0.0f)))))
            fail(where + ".specularColorFactor must not be negative");
        mat.specularTexture = extensionTexture(*e, "specularTexture", where);
        mat.specularColorTexture = extensionTexture(*e, "specularColorTexture", where, true);
    }
}

void Loader::readTransmission(const tinygltf::Material& gm, Material& mat, const std::string& label) {
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_transmission")) {
        const std::string where = label + ": KHR_materials_transmission";
        readNumbers(*e, "transmissionFactor", where, &mat.transmission, 0);
        if (!(mat.transmission >= 0.0f && mat.transmission <= 1.0f)) fail(where + ".transmissionFactor must lie in [0, 1]");
        mat.transmissionTexture = extensionTexture(*e, "transmissionTexture", where);
        if (mat.alphaMode == AlphaMode::Blend && mat.transmission > 0.0f)
            warn(where + " on a BLEND material is not drawn: it blends instead (make it OPAQUE to see through it)");
    }
    if (const tinygltf::Value* e = findExtension(gm.extensions, "KHR_materials_volume")) {
        const std::string where = label + ": KHR_materials_volume";
        readNumbers(*e, "thicknessFactor", where, &mat.thickness, 0);
        readNumbers(*e, "attenuationDistance", where, &mat.attenuationDistance, 0);
        readNumbers(*e, "attenuationColor", where, &mat.attenuationColor.x, 3);
        if (!(mat.thickness >= 0.0f)) fail(where + ".thicknessFactor must not be negative");
        if (!(mat.attenuationDistance > 0.0f)) fail(where + ".attenuationDistance must be positive");
        if (!glm::all(glm::greaterThanEqual(mat.attenuationColor, glm::vec3(0.0f))) ||
            !glm::all(glm::lessThanEqual(mat.attenuationColor, glm::vec3(1.0f))))
            fail(where + ".attenuationColor must lie in [0, 1]");
        mat.thicknessTexture = extensionTexture(*e, "thicknessTexture", where);
        if (mat.transmission == 0.0f) warn(where + " without KHR_materials_transmission has no effect here");
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
    if (!(mat.sheenRoughness >= 0.0f && mat.sheenRoughness <= 1.0f)) fail(where + ".sheenRoughnessFactor must lie in [0, 1]");
    mat.sheenColorTexture = extensionTexture(*e, "sheenColorTexture", where, true);
    mat.sheenRoughnessTexture = extensionTexture(*e, "sheenRoughnessTexture", where);
}

TextureRef Loader::extensionTexture(const tinygltf::Value& ext, const char* key, const std::string& what, bool srgb) {
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
void Loader::readTextureTransform(const tinygltf::Value& t, int& texCoord, TextureRef& ref, const std::string& what) {
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
void Loader::addEmitter(int n, const tinygltf::Value& v) {
    const std::string where = nodeLabel(n) + ": extras.fe_emitter";
    if (!v.IsObject()) fail(where + " must be an object");
    ParticleEmitter e;
    e.name = model_.nodes[size_t(n)].name.empty() ? "node " + std::to_string(n) : model_.nodes[size_t(n)].name;
    auto number = [&](const char* key, float& out) { readNumbers(v, key, where, &out, 0); };
    auto vector = [&](const char* key, float* out, int count) { readNumbers(v, key, where, out, count); };
    for (const std::string& key : v.Keys())
        if (key != "rate" && key != "lifetime" && key != "velocity" && key != "spread" && key != "gravity" && key != "size" &&
            key != "colorStart" && key != "colorEnd" && key != "blend" && key != "softness")
            fail(where + ": unknown key '" + key + "'");
    number("rate", e.rate);
    number("lifetime", e.lifetime);
    number("spread", e.spread);
    number("softness", e.softness);
    vector("velocity", &e.velocity.x, 3);
    vector("gravity", &e.gravity.x, 3);
    float size[2] = {e.sizeStart, e.sizeEnd};
    vector("size", size, 2);
    e.sizeStart = size[0], e.sizeEnd = size[1];
    vector("colorStart", &e.colorStart.x, 4);
    vector("colorEnd", &e.colorEnd.x, 4);
    if (v.Has("blend")) {
        const tinygltf::Value& b = v.Get("blend");
        if (!b.IsString() || (b.Get<std::string>() != "additive" && b.Get<std::string>() != "alpha"))
            fail(where + ".blend must be \"additive\" or \"alpha\"");
        e.blend = b.Get<std::string>() == "alpha" ? ParticleEmitter::Blend::Alpha : ParticleEmitter::Blend::Additive;
    }
    if (!(e.rate > 0.0f) || !(e.lifetime > 0.0f) || !std::isfinite(e.rate * e.lifetime))
        fail(where + ": rate and lifetime must be positive numbers");
    e.position = glm::vec3(world_[size_t(n)][3]);
    scene_.emitters.push_back(e);
}

void Loader::addLight(int n, const tinygltf::Value& ext) {
    if (!ext.Get("light").IsNumber()) fail(nodeLabel(n) + ": KHR_lights_punctual without a light index");
    int li = valueIndex(ext.Get("light"));
    checkIndex(li, model_.lights, nodeLabel(n) + ": KHR_lights_punctual light");
    const auto& gl = model_.lights[size_t(li)];
    Light l;
    l.name = gl.name.empty() ? model_.nodes[size_t(n)].name : gl.name;
    l.node = n;
    if (gl.type == "directional") {
        l.type = LightType::Directional;
    } else if (gl.type == "point") {
        l.type = LightType::Point;
    } else if (gl.type == "spot") {
        l.type = LightType::Spot;
    } else {
        warn("light " + std::to_string(li) + " of unknown type '" + gl.type + "' ignored");
        return;
    }
    if (gl.color.size() == 3) l.color = glm::vec3(gl.color[0], gl.color[1], gl.color[2]);
    l.intensity = float(gl.intensity);
    l.range = l.type == LightType::Directional ? 0.0f : float(std::max(gl.range, 0.0));
    if (l.type == LightType::Spot) {
        l.innerConeAngle = float(gl.spot.innerConeAngle);
        l.outerConeAngle = float(gl.spot.outerConeAngle);
    }
    const glm::mat4& w = world_[size_t(n)];
    l.position = glm::vec3(w[3]);
    glm::vec3 d = glm::mat3(w) * glm::vec3(0.0f, 0.0f, -1.0f);
    l.direction = glm::length(d) > 1e-12f ? glm::normalize(d) : glm::vec3(0.0f, 0.0f, -1.0f);
    if (!std::isfinite(l.intensity) || !std::isfinite(l.range) || !std::isfinite(l.color.x + l.color.y + l.color.z)) {
        fail("light " + std::to_string(li) + ": non-finite colour, intensity or range");
    }
    scene_.lights.push_back(l);
}

void Loader::addMeshInstances(int n) {
    const auto& node = model_.nodes[size_t(n)];
    checkIndex(node.mesh, model_.meshes, nodeLabel(n) + ": mesh");
    int skin = -1;
    if (node.skin >= 0) {
        checkIndex(node.skin, model_.skins, nodeLabel(n) + ": skin");
        skin = node.skin;
    }
    uint32_t mi = getMesh(node.mesh);
    if (scene_.meshes[mi].primitives.empty()) return;  // nothing drawable (e.g. only lines)
    if (skin >= 0) {
        const size_t joints = scene_.skins[size_t(skin)].joints.size();
        for (const Primitive& p : scene_.meshes[mi].primitives)
            for (const SkinInfluences& v : p.skin)
                for (int set = 0; set < 2; ++set)
                    for (int k = 0; k < 4; ++k)
                        if (v.weights[set][k] != 0.0f && v.joints[set][k] >= joints)
                            fail(nodeLabel(n) + ": " + meshLabel(node.mesh) + " names joint " + std::to_string(v.joints[set][k]) +
                                 " of skin " + std::to_string(skin) + ", which has " + std::to_string(joints));
        if (std::none_of(scene_.meshes[mi].primitives.begin(), scene_.meshes[mi].primitives.end(),
                         [](const Primitive& p) { return !p.skin.empty(); }))
            warn(nodeLabel(n) + ": skinned node whose mesh has no JOINTS_0/WEIGHTS_0; drawn unskinned");
    }

    // The node's world is set by poseScene; instances of EXT_mesh_gpu_instancing add their own
    // transform under it (ignored on a skinned node, whose transform the glTF spec ignores).
    const glm::mat4 nodeWorld = world_[size_t(n)];
    std::vector<glm::mat4> worlds;
    const tinygltf::Value* inst = findExtension(node.extensions, "EXT_mesh_gpu_instancing");
    if (inst && inst->Get("attributes").IsObject() && skin < 0) {
        const tinygltf::Value& attrs = inst->Get("attributes");
        std::vector<float> t, r, s;
        size_t count = SIZE_MAX;
        auto read = [&](const char* name, int type, uint32_t allowed, std::vector<float>& out, size_t comps) {
            const tinygltf::Value& a = attrs.Get(name);
            if (!a.IsNumber()) return;
            out = readAccessor<float>(valueIndex(a), std::string(name) + " of EXT_mesh_gpu_instancing on " + nodeLabel(n),
                                      type, allowed);
            size_t c = out.size() / comps;
            if (count != SIZE_MAX && c != count) fail(nodeLabel(n) + ": EXT_mesh_gpu_instancing attribute counts differ");
            count = c;
        };
        read("TRANSLATION", TINYGLTF_TYPE_VEC3, F32, t, 3);
        read("ROTATION", TINYGLTF_TYPE_VEC4, F32 | S8N | S16N, r, 4);
        read("SCALE", TINYGLTF_TYPE_VEC3, F32, s, 3);
        if (count == SIZE_MAX) count = 1;
        for (size_t i = 0; i < count; ++i) {
            glm::mat4 m(1.0f);
            if (!t.empty()) m = glm::translate(m, glm::vec3(t[i * 3], t[i * 3 + 1], t[i * 3 + 2]));
            if (!r.empty()) {
                glm::quat q(r[i * 4 + 3], r[i * 4], r[i * 4 + 1], r[i * 4 + 2]);
                float len = glm::length(q);
                if (len > 1e-12f) m = m * glm::mat4_cast(q / len);
            }
            if (!s.empty()) m = glm::scale(m, glm::vec3(s[i * 3], s[i * 3 + 1], s[i * 3 + 2]));
            worlds.push_back(m);
        }
    } else {
        worlds.push_back(glm::mat4(1.0f));
    }
    for (const auto& local : worlds) {
        const glm::mat4 w = nodeWorld * local;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(w[c][r])) fail(nodeLabel(n) + ": non-finite world transform");
        MeshInstance mi2;
        mi2.meshIndex = mi;
        mi2.world = w;
        mi2.local = local;
        mi2.node = n;
        mi2.skin = skin;
        mi2.mirrored = glm::determinant(glm::mat3(w)) < 0.0f;
        mi2.name = node.name;
        scene_.instances.push_back(std::move(mi2));
    }
}

// ---------------------------------------------------------------------------------------------
// Accessors

const unsigned char* Loader::bufferViewData(int bvIndex, const std::string& ctx, uint64_t& length) {
    checkIndex(bvIndex, model_.bufferViews, ctx + ": bufferView");
    const auto& bv = model_.bufferViews[size_t(bvIndex)];
    checkIndex(bv.buffer, model_.buffers, ctx + ": bufferView " + std::to_string(bvIndex) + ": buffer");
    const auto& buf = model_.buffers[size_t(bv.buffer)];
    uint64_t end = 0;
    if (addOverflows(bv.byteOffset, bv.byteLength, end) || end > buf.data.size()) {
        fail("bufferView " + std::to_string(bvIndex) + ": byteOffset+byteLength (" + std::to_string(end) +
             ") exceeds buffer " + std::to_string(bv.buffer) + " length " + std::to_string(buf.data.size()));
    }
    length = bv.byteLength;
    return buf.data.data() + bv.byteOffset;
}

template <class T>
std::vector<T> Loader::readAccessor(int index, const std::string& what, int expectedType, uint32_t allowed) {
    checkIndex(index, model_.accessors, what + ": accessor");
    const auto& a = model_.accessors[size_t(index)];
    const std::string ctx = "accessor " + std::to_string(index) + " (" + what + ")";
    if (a.type != expectedType) fail(ctx + ": type " + typeName(a.type) + ", expected " + typeName(expectedType));
    if (!(compBit(a.componentType, a.normalized) & allowed)) {
        fail(ctx + ": unsupported component type " + componentTypeName(a.componentType, a.normalized));
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
                fail(ctx + ": bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(bv.byteStride) +
                     " is smaller than the element size " + std::to_string(elemSize));
            }
            stride = bv.byteStride;
        }
        // Last element ends at byteOffset + (count-1)*stride + elemSize.
        uint64_t need = 0, span = 0;
        bool overflow = count > 0 && (mulOverflows(count - 1, stride, span) || addOverflows(span, elemSize, span) ||
                                      addOverflows(span, a.byteOffset, need));
        if (overflow || need > viewLen || a.byteOffset > viewLen) {
            fail(ctx + ": byteOffset+count*stride exceeds bufferView " + std::to_string(a.bufferView) + " length (" +
                 (overflow ? std::string("overflow") : std::to_string(need)) + " > " + std::to_string(viewLen) + ")");
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
                out[size_t(e * comps + c)] = static_cast<T>(readComponent(p + c * csize, a.componentType, a.normalized));
            }
        }
    }

    if (a.sparse.isSparse) {
        const uint64_t sc = uint64_t(std::max(a.sparse.count, 0));
        if (a.sparse.count < 0 || sc > count) fail(ctx + ": sparse count " + std::to_string(a.sparse.count) + " exceeds count");
        const int ict = a.sparse.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(ctx + ": unsupported sparse index component type " + componentTypeName(ict, false));
        }
        const uint64_t isize = uint64_t(tinygltf::GetComponentSizeInBytes(uint32_t(ict)));
        uint64_t ilen = 0, vlen = 0;
        const unsigned char* idata = bufferViewData(a.sparse.indices.bufferView, ctx + " sparse indices", ilen);
        const unsigned char* vdata = bufferViewData(a.sparse.values.bufferView, ctx + " sparse values", vlen);
        uint64_t ioff = uint64_t(std::max(a.sparse.indices.byteOffset, 0));
        uint64_t voff = uint64_t(std::max(a.sparse.values.byteOffset, 0));
        uint64_t ineed = 0, vneed = 0;
        if (mulOverflows(sc, isize, ineed) || addOverflows(ineed, ioff, ineed) || ineed > ilen) {
            fail(ctx + ": sparse indices exceed bufferView " + std::to_string(a.sparse.indices.bufferView) + " length");
        }
        if (mulOverflows(sc, elemSize, vneed) || addOverflows(vneed, voff, vneed) || vneed > vlen) {
            fail(ctx + ": sparse values exceed bufferView " + std::to_string(a.sparse.values.bufferView) + " length");
        }
        for (uint64_t k = 0; k < sc; ++k) {
            uint64_t target = uint64_t(readComponent(idata + ioff + k * isize, ict, false));
            if (target >= count) {
                fail(ctx + ": sparse index " + std::to_string(target) + " >= count " + std::to_string(count));
            }
            const unsigned char* p = vdata + voff + k * elemSize;
            for (uint64_t c = 0; c < comps; ++c) {
                out[size_t(target * comps + c)] = static_cast<T>(readComponent(p + c * csize, a.componentType, a.normalized));
            }
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Meshes

uint32_t Loader::getMesh(int m) {
    auto it = meshMap_.find(m);
    if (it != meshMap_.end()) return it->second;
    const auto& gm = model_.meshes[size_t(m)];
    Mesh mesh;
    mesh.name = gm.name;
    for (size_t p = 0; p < gm.primitives.size(); ++p) {
        Primitive prim;
        if (loadPrimitive(m, int(p), prim)) mesh.primitives.push_back(std::move(prim));
    }
    for (double w : gm.weights) {
        if (!std::isfinite(w)) fail(meshLabel(m) + ": non-finite morph weight");
        mesh.weights.push_back(float(w));
    }
    computeBounds(mesh);
    uint32_t index = uint32_t(scene_.meshes.size());
    scene_.meshes.push_back(std::move(mesh));
    meshMap_[m] = index;
    return index;
}

void Loader::readMorphTargets(int m, int p, size_t n, Primitive& out) {
    const auto& gp = model_.meshes[size_t(m)].primitives[size_t(p)];
    const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
    for (size_t t = 0; t < gp.targets.size(); ++t) {
        MorphTarget target;
        auto read = [&](const char* name, std::vector<glm::vec3>& into) {
            auto it = gp.targets[t].find(name);
            if (it == gp.targets[t].end()) return;
            const std::string what = std::string(name) + " of morph target " + std::to_string(t) + " of " + label;
            const std::vector<float> d = readAccessor<float>(it->second, what, TINYGLTF_TYPE_VEC3, F32 | S8N | S16N);
            if (d.size() / 3 != n) fail(label + ": morph target " + std::to_string(t) + " " + name + " count differs from POSITION");
            into.resize(n);
            for (size_t i = 0; i < n; ++i) {
                into[i] = glm::vec3(d[i * 3], d[i * 3 + 1], d[i * 3 + 2]);
                if (!std::isfinite(into[i].x + into[i].y + into[i].z)) fail("non-finite value in " + what);
            }
        };
        read("POSITION", target.position);
        read("NORMAL", target.normal);
        read("TANGENT", target.tangent);
        out.targets.push_back(std::move(target));
    }
}

void Loader::readSkinInfluences(const tinygltf::Primitive& gp, const std::string& label, size_t n, Primitive& out) {
    for (int set = 0; set < 2; ++set) {
        const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
        auto ja = gp.attributes.find(js), wa = gp.attributes.find(ws);
        if (ja == gp.attributes.end() && wa == gp.attributes.end()) continue;
        if (ja == gp.attributes.end() || wa == gp.attributes.end()) fail(label + ": " + js + " and " + ws + " come together");
        const std::vector<uint32_t> j = readAccessor<uint32_t>(ja->second, js + " of " + label, TINYGLTF_TYPE_VEC4, U8 | U16);
        const std::vector<float> w = readAccessor<float>(wa->second, ws + " of " + label, TINYGLTF_TYPE_VEC4, F32 | U8N | U16N);
        if (j.size() != n * 4 || w.size() != n * 4) fail(label + ": " + js + "/" + ws + " count differs from POSITION");
        out.skin.resize(n);
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 4; ++k) {
                const float weight = w[i * 4 + size_t(k)];
                if (!std::isfinite(weight)) fail("non-finite " + ws + " value in " + label);
                out.skin[i].joints[set][k] = j[i * 4 + size_t(k)];
                out.skin[i].weights[set][k] = weight;
            }
    }
}

bool Loader::loadPrimitive(int m, int p, Primitive& out) {
    const auto& gm = model_.meshes[size_t(m)];
    const auto& gp = gm.primitives[size_t(p)];
    const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
    const int mode = gp.mode < 0 ? TINYGLTF_MODE_TRIANGLES : gp.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        static const char* names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        std::string name = mode >= 0 && mode < 4 ? names[mode] : "mode " + std::to_string(mode);
        warn(label + ": " + name + " primitive skipped (only triangles are drawn)");
        return false;
    }
    auto attr = [&](const char* name) {
        auto it = gp.attributes.find(name);
        return it == gp.attributes.end() ? -1 : it->second;
    };
    const int aPos = attr("POSITION");
    if (aPos < 0) {
        warn(label + ": no POSITION attribute; primitive skipped");
        return false;
    }

    const std::vector<float> pos = readAccessor<float>(aPos, "POSITION of " + label, TINYGLTF_TYPE_VEC3, F32);
    const size_t n = pos.size() / 3;
    for (size_t i = 0; i < pos.size(); ++i) {
        if (!std::isfinite(pos[i])) {
            fail("non-finite POSITION value (vertex " + std::to_string(i / 3) + ") in " + label + " (accessor " +
                 std::to_string(aPos) + ")");
        }
    }
    auto readMatching = [&](const char* name, int type, uint32_t allowed, size_t comps) {
        std::vector<float> v;
        int a = attr(name);
        if (a < 0) return v;
        v = readAccessor<float>(a, std::string(name) + " of " + label, type, allowed);
        if (v.size() / comps != n) {
            fail("accessor " + std::to_string(a) + " (" + name + " of " + label + "): count " + std::to_string(v.size() / comps) +
                 " differs from POSITION count " + std::to_string(n));
        }
        for (float f : v)
            if (!std::isfinite(f)) fail(std::string("non-finite ") + name + " value in " + label);
        return v;
    };
    const std::vector<float> nrm = readMatching("NORMAL", TINYGLTF_TYPE_VEC3, F32, 3);
    const std::vector<float> tan = readMatching("TANGENT", TINYGLTF_TYPE_VEC4, F32, 4);
    const std::vector<float> uv = readMatching("TEXCOORD_0", TINYGLTF_TYPE_VEC2, F32 | U8N | U16N, 2);
    const std::vector<float> uv1 = readMatching("TEXCOORD_1", TINYGLTF_TYPE_VEC2, F32 | U8N | U16N, 2);
    // COLOR_0 is VEC3 or VEC4 (alpha 1 when absent), float or normalized unsigned integers.
    std::vector<float> color;
    size_t colorComps = 4;
    if (const int a = attr("COLOR_0"); a >= 0) {
        checkIndex(a, model_.accessors, "COLOR_0 of " + label + ": accessor");
        const int type = model_.accessors[size_t(a)].type;
        colorComps = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        color = readMatching("COLOR_0", colorComps == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, F32 | U8N | U16N, colorComps);
    }

    out.vertices.resize(n);
    for (size_t i = 0; i < n; ++i) {
        Vertex& v = out.vertices[i];
        v.position = glm::vec3(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
        if (!nrm.empty()) v.normal = glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
        if (!tan.empty()) v.tangent = glm::vec4(tan[i * 4], tan[i * 4 + 1], tan[i * 4 + 2], tan[i * 4 + 3]);
        if (!uv.empty()) v.uv0 = glm::vec2(uv[i * 2], uv[i * 2 + 1]);
        if (!uv1.empty()) v.uv1 = glm::vec2(uv1[i * 2], uv1[i * 2 + 1]);
        if (!color.empty()) {
            const float* c = &color[i * colorComps];
            v.color = glm::vec4(c[0], c[1], c[2], colorComps == 4 ? c[3] : 1.0f);
        }
    }

    // Indices.
    std::vector<uint32_t> idx;
    if (gp.indices >= 0) {
        idx = readAccessor<uint32_t>(gp.indices, "indices of " + label, TINYGLTF_TYPE_SCALAR, U8 | U16 | U32);
        for (uint32_t i : idx) {
            if (i >= n) fail("index " + std::to_string(i) + " >= vertex count " + std::to_string(n) + " in " + label);
        }
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) idx = triangleStripToList(idx);
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) idx = triangleFanToList(idx);
    if (idx.size() % 3 != 0) {
        warn(label + ": index count not a multiple of 3; trailing indices dropped");
        idx.resize(idx.size() - idx.size() % 3);
    }
    out.indices = std::move(idx);

    // Deformation data, kept beside the rest pose (assets/Animation.h).
    readMorphTargets(m, p, n, out);
    readSkinInfluences(gp, label, n, out);

    // Material (needed to know whether tangents must be generated).
    if (gp.material >= 0) {
        checkIndex(gp.material, model_.materials, label + ": material");
        out.material = getMaterial(gp.material);
    } else {
        out.material = defaultMaterial();
    }
    const Material& mat = scene_.materials[out.material];

    // Normals.
    if (nrm.empty()) {
        if (opt_.smoothNormals) {
            generateSmoothNormals(out);
        } else {
            // Unwelded: corner k of triangle t becomes vertex 3t + k; its deformation data follows.
            const std::vector<uint32_t> corners = out.indices;
            generateFlatNormals(out);
            out.flatNormals = true;
            auto remap = [&](auto& list) {
                if (list.empty()) return;
                std::remove_reference_t<decltype(list)> unwelded(corners.size());
                for (size_t k = 0; k < corners.size(); ++k) unwelded[k] = list[corners[k]];
                list = std::move(unwelded);
            };
            remap(out.skin);
            for (MorphTarget& t : out.targets) {
                remap(t.position);
                remap(t.normal);
                remap(t.tangent);
            }
        }
    } else {
        std::vector<glm::vec3> smooth;
        size_t repaired = 0;
        for (size_t i = 0; i < out.vertices.size(); ++i) {
            glm::vec3& nv = out.vertices[i].normal;
            float len = glm::length(nv);
            if (len > 1e-8f && std::isfinite(len)) {
                nv /= len;
                continue;
            }
            if (smooth.empty()) smooth = computeSmoothNormals(out);
            nv = smooth[i];
            ++repaired;
        }
        if (repaired) warn(label + ": " + std::to_string(repaired) + " zero-length normal(s) replaced by smooth normals");
    }

    // Tangents.
    if (!tan.empty()) {
        for (auto& v : out.vertices) {
            glm::vec3 t(v.tangent);
            t -= v.normal * glm::dot(v.normal, t);  // an exporter's rounding can bend it off the plane
            float len = glm::length(t);
            glm::vec3 tt = len > 1e-8f ? t / len : anyPerpendicular(v.normal);
            v.tangent = glm::vec4(tt, v.tangent.w < 0.0f ? -1.0f : 1.0f);
        }
    } else if (mat.normalTexture.valid()) {
        const uint32_t set = mat.normalTexture.texCoord;
        if ((set == 0 ? uv : uv1).empty()) {
            warn(label + ": normal map without TEXCOORD_" + std::to_string(set) + "; tangents cannot be generated");
            setFallbackTangents(out);
        } else {
            generateTangents(out, set);
        }
    } else {
        setFallbackTangents(out);
    }
    computeBounds(out);
    return true;
}

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
        mat.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                        pbr.baseColorFactor[3]);
    }
    mat.metallic = float(pbr.metallicFactor);
    mat.roughness = float(pbr.roughnessFactor);
    if (gm.emissiveFactor.size() == 3) {
        mat.emissiveFactor = glm::vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
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

    const float checks[] = {mat.baseColorFactor.x, mat.baseColorFactor.y, mat.baseColorFactor.z, mat.baseColorFactor.w,
                            mat.metallic,          mat.roughness,         mat.emissiveFactor.x,  mat.emissiveFactor.y,
                            mat.emissiveFactor.z,  mat.normalScale,       mat.occlusionStrength, mat.alphaCutoff};
    for (float f : checks)
        if (!std::isfinite(f)) fail(label + ": non-finite factor");

    mat.baseColorTexture = getTexture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true,
                                      pbr.baseColorTexture.extensions, "baseColorTexture of " + label);
    mat.metallicRoughnessTexture =
        getTexture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                   pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture of " + label);
    mat.normalTexture = getTexture(gm.normalTexture.index, gm.normalTexture.texCoord, false, gm.normalTexture.extensions,
                                   "normalTexture of " + label);
    mat.occlusionTexture = getTexture(gm.occlusionTexture.index, gm.occlusionTexture.texCoord, false,
                                      gm.occlusionTexture.extensions, "occlusionTexture of " + label);
    mat.emissiveTexture = getTexture(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, true,
                                     gm.emissiveTexture.extensions, "emissiveTexture of " + label);

    uint32_t index = uint32_t(scene_.materials.size());
    scene_.materials.push_back(std::move(mat));
    materialMap_[gi] = index;
    return index;
}

TextureRef Loader::getTexture(int gt, int texCoord, bool srgb, const tinygltf::ExtensionMap& infoExt,
                              const std::string& what) {
    TextureRef ref;
    if (gt < 0) return ref;
    checkIndex(gt, model_.textures, what + ": texture");
    if (const tinygltf::Value* t = findExtension(infoExt, "KHR_texture_transform")) readTextureTransform(*t, texCoord, ref, what);
    if (texCoord > 1) {
        warn(what + " uses TEXCOORD_" + std::to_string(texCoord) + "; only TEXCOORD_0 and TEXCOORD_1 are read, TEXCOORD_0 is used instead");
        texCoord = 0;
    }
    ref.texCoord = uint32_t(std::max(texCoord, 0));

    const auto& tex = model_.textures[size_t(gt)];
    if (tex.source < 0) {
        warn("texture " + std::to_string(gt) + " has no image source (extension-only image?); " + what + " ignored");
        return ref;
    }
    checkIndex(tex.source, model_.images, "texture " + std::to_string(gt) + ": image");
    if (tex.sampler >= 0) checkIndex(tex.sampler, model_.samplers, "texture " + std::to_string(gt) + ": sampler");
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
        ti.sampler.magFilter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
        switch (s.minFilter) {
            case TINYGLTF_TEXTURE_FILTER_NEAREST:
                ti.sampler = {Filter::Nearest, ti.sampler.magFilter, MipFilter::None, {}, {}, false};
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
                case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
                case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
                default: return Wrap::Repeat;
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
    if (!gi.uri.empty() && gi.uri.compare(0, 5, "data:") != 0) label += " ('" + gi.uri + "')";
    else if (!gi.name.empty()) label += " ('" + gi.name + "')";
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

}  // namespace

Scene loadGltf(const std::string& path, const LoadOptions& options) {
    Loader loader(path, options);
    try {
        return loader.run();
    } catch (const AssetError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw AssetError(path + ": out of memory while loading");
    } catch (const std::exception& e) {
        throw AssetError(path + ": " + e.what());
    }
}

}  // namespace fe::assets
