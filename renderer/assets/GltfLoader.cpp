// glTF 2.0 loader on top of tinygltf (JSON + container parsing) and stb_image (decoding).
// tinygltf only parses; everything it does not check (accessor bounds, dangling indices,
// hierarchy sanity, finite values) is validated here before use, so malformed files end in an
// AssetError instead of a crash.

#include "assets/GltfLoaderInternal.h"

#include <fstream>
#include <sstream>

#include "assets/Animation.h"

namespace fe::assets {

namespace gltf {

// ---------------------------------------------------------------------------------------------
// tinygltf glue

bool imageLoaderTrampoline(tinygltf::Image* image, const int index, std::string* err, std::string*,
                           int, int, const unsigned char* bytes, int size, void* user) {
    return static_cast<Loader*>(user)->storeImageBytes(image, index, err, bytes, size);
}

// Images are kept encoded at parse time and decoded only if a material uses them, with our own
// error messages. Images stored in a buffer view are range-checked here because tinygltf 2.7
// hands us a pointer into the buffer without checking the view against the buffer size.
bool Loader::storeImageBytes(tinygltf::Image* image, int index, std::string* err,
                             const unsigned char* bytes, int size) {
    if (image->bufferView >= 0) {
        // tinygltf has already checked both indices.
        const auto& bv = model_.bufferViews[size_t(image->bufferView)];
        const auto& buf = model_.buffers[size_t(bv.buffer)];
        uint64_t end = 0;
        if (addOverflows(bv.byteOffset, bv.byteLength, end) || end > buf.data.size()) {
            if (err) {
                *err += "image " + std::to_string(index) + ": bufferView " +
                        std::to_string(image->bufferView) + " exceeds buffer " +
                        std::to_string(bv.buffer) + "\n";
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
bool readTrampoline(std::vector<unsigned char>* out, std::string* err, const std::string& p,
                    void* user) {
    return static_cast<Loader*>(user)->readWholeFile(out, err, p);
}
bool writeTrampoline(std::string* err, const std::string&, const std::vector<unsigned char>&,
                     void*) {
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

bool Loader::readWholeFile(std::vector<unsigned char>* out, std::string* err,
                           const std::string& p) const {
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
    if (bytes.size() < 12)
        fail("GLB header truncated: " + std::to_string(bytes.size()) + " bytes, 12 needed");
    if (const uint32_t version = u32(4); version != 2)
        fail("GLB header version " + std::to_string(version) +
             " (glTF 2.0 binaries have version 2)");
    if (const uint32_t length = u32(8); length != bytes.size())
        fail("GLB header length " + std::to_string(length) + " but the file has " +
             std::to_string(bytes.size()) + " bytes");
    bool bin = false;
    size_t index = 0;
    for (size_t at = 12; at < bytes.size(); ++index) {
        const std::string where =
            "GLB chunk " + std::to_string(index) + " at byte " + std::to_string(at);
        if (bytes.size() - at < 8) fail(where + ": truncated chunk header");
        const uint32_t length = u32(at), type = u32(at + 4);
        std::string name;
        for (int i = 0; i < 4; ++i) {
            const char c = char((type >> (8 * i)) & 0xff);
            name += (c >= 32 && c < 127) ? std::string(1, c)
                                         : "\\x" + std::to_string(unsigned(uint8_t(c)));
        }
        const bool isJson = type == 0x4E4F534Au, isBin = type == 0x004E4942u;
        const std::string chunk = where + " (" + (isBin ? std::string("BIN") : name) + ")";
        if (index == 0 && !isJson) fail(chunk + ": the first chunk must be JSON");
        if (index > 0 && isJson)
            fail(chunk + ": duplicate JSON chunk (a GLB has exactly one, the first)");
        if (isBin && bin) fail(chunk + ": duplicate BIN chunk (a GLB has at most one)");
        if (isBin && index != 1)
            fail(chunk + ": the BIN chunk must directly follow the JSON chunk");
        if (length % 4 != 0)
            fail(chunk + ": length " + std::to_string(length) +
                 " is not a multiple of 4 (chunks are 4-byte aligned)");
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
            found += (c >= 32 && c < 127) ? std::string(1, c)
                                          : "\\x" + std::to_string(unsigned(bytes[i]));
        }
        fail("not a binary glTF: bad magic '" + found + "' (expected 'glTF')");
    }
    if (magic && ext != ".glb")
        warn("binary glTF content in a file named '" + fp.filename().string() + "'");
    if (!magic && ext != ".gltf") {
        // Not a glTF by name or by its first bytes: say what is read rather than let the JSON
        // parser report on a file that was never JSON (an .obj, a .png).
        const size_t first =
            std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size())
                .find_first_not_of(" \t\r\n\xEF\xBB\xBF");
        if (first == std::string_view::npos || bytes[first] != '{')
            fail("unsupported format" + (ext.empty() ? std::string() : " '" + ext + "'") +
                 ": scenes are glTF 2.0 files (.gltf, .glb) or builtin:NAME");
        warn("glTF JSON content in a file named '" + fp.filename().string() + "'");
    }

    if (magic) checkGlbLayout(bytes);
    const std::string_view json = jsonText(bytes, magic);
    // 3.1 JSON encoding: UTF-8 without a byte order mark; exporters must not write one, and
    // clients may ignore it rather than fail, so it is a warning (an error under --strict).
    if (json.substr(0, 3) == "\xEF\xBB\xBF")
        warn(
            "the JSON starts with a UTF-8 byte order mark, which glTF 2.0 forbids; it was ignored");
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
            ok = gltf.LoadBinaryFromMemory(&model_, &err, &warnings, bytes.data(),
                                           unsigned(bytes.size()), baseDir_);
        } else {
            ok = gltf.LoadASCIIFromString(&model_, &err, &warnings,
                                          reinterpret_cast<const char*>(bytes.data()),
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
        warn(
            nodeLabel(int(n)) +
            " has both a matrix and translation/rotation/scale, which glTF 2.0 forbids; the matrix is used");
}

// What the glTF 2.0 specification requires and the parser lets through.
void Loader::checkAsset() {
    // 3.2 Asset: "version" is required, "<major>.<minor>"; a loader must not load a major version
    // it does not implement, and "minVersion" names the least version a loader must support.
    const std::string& v = model_.asset.version;
    if (v.empty()) fail("asset.version is missing (glTF 2.0 requires it)");
    if (v.rfind("2.", 0) != 0 || v.size() < 3)
        fail("asset.version '" + v + "': this loader reads glTF 2.x only");
    const std::string& min = model_.asset.minVersion;
    if (!min.empty() && min != "2.0")
        fail("asset.minVersion '" + min + "': this loader implements glTF 2.0");
    // 5.x glTF: "scene" (the default scene) must be defined only when "scenes" is.
    if (model_.defaultScene >= 0 && model_.scenes.empty())
        fail("scene " + std::to_string(model_.defaultScene) +
             " is set but the file has no scenes (glTF 2.0 forbids it)");
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
    if (!finite(node.matrix) || !finite(node.translation) || !finite(node.rotation) ||
        !finite(node.scale)) {
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
        t = glm::translate(glm::mat4(1.0f), glm::vec3(node.translation[0], node.translation[1],
                                                      node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(nodeLabel(n) + ": rotation must have 4 numbers");
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1],
                     node.rotation[2]);  // w, x, y, z
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
                fail(nodeLabel(c) + " has two parents (" + nodeLabel(parent_[size_t(c)]) + " and " +
                     nodeLabel(int(i)) + ")");
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
            glm::mat4 parentWorld =
                parent_[size_t(i)] >= 0 ? world_[size_t(parent_[size_t(i)])] : glm::mat4(1.0f);
            world_[size_t(i)] =
                checkedFinite(parentWorld * localTransform(i), i);  // products can overflow too
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
            if (auto* ext = findExtension(node.extensions, "KHR_lights_punctual"))
                addLight(n, *ext);
            if (node.extras.IsObject() && node.extras.Has("fe_emitter"))
                addEmitter(n, node.extras.Get("fe_emitter"));
            if (node.mesh >= 0) addMeshInstances(n);
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
                stack.push_back(*it);
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
        if (!(p.yfov > 0.0 && p.yfov < kPi) || !(p.znear > 0.0) ||
            !(p.zfar == 0.0 || p.zfar > p.znear) || !std::isfinite(p.znear) ||
            !std::isfinite(p.zfar)) {
            warn(label + " ignored: invalid yfov/znear/zfar");
            return;
        }
        c.yfov = float(p.yfov);
        c.znear = float(p.znear);
        c.zfar = p.zfar > 0.0 ? float(p.zfar) : std::numeric_limits<float>::infinity();
        if (p.aspectRatio > 0.0 && std::isfinite(p.aspectRatio))
            c.aspectRatio = float(p.aspectRatio);
    } else if (cam.type == "orthographic") {
        const auto& o = cam.orthographic;
        if (!(o.xmag != 0.0 && o.ymag != 0.0 && std::isfinite(o.xmag) && std::isfinite(o.ymag)) ||
            !(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar)) {
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

void Loader::addEmitter(int n, const tinygltf::Value& v) {
    const std::string where = nodeLabel(n) + ": extras.fe_emitter";
    if (!v.IsObject()) fail(where + " must be an object");
    ParticleEmitter e;
    e.name = model_.nodes[size_t(n)].name.empty() ? "node " + std::to_string(n)
                                                  : model_.nodes[size_t(n)].name;
    auto number = [&](const char* key, float& out) { readNumbers(v, key, where, &out, 0); };
    auto vector = [&](const char* key, float* out, int count) {
        readNumbers(v, key, where, out, count);
    };
    for (const std::string& key : v.Keys())
        if (key != "rate" && key != "lifetime" && key != "velocity" && key != "spread" &&
            key != "gravity" && key != "size" && key != "colorStart" && key != "colorEnd" &&
            key != "blend" && key != "softness")
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
        if (!b.IsString() ||
            (b.Get<std::string>() != "additive" && b.Get<std::string>() != "alpha"))
            fail(where + ".blend must be \"additive\" or \"alpha\"");
        e.blend = b.Get<std::string>() == "alpha" ? ParticleEmitter::Blend::Alpha
                                                  : ParticleEmitter::Blend::Additive;
    }
    if (!(e.rate > 0.0f) || !(e.lifetime > 0.0f) || !std::isfinite(e.rate * e.lifetime))
        fail(where + ": rate and lifetime must be positive numbers");
    e.position = glm::vec3(world_[size_t(n)][3]);
    scene_.emitters.push_back(e);
}

void Loader::addLight(int n, const tinygltf::Value& ext) {
    if (!ext.Get("light").IsNumber())
        fail(nodeLabel(n) + ": KHR_lights_punctual without a light index");
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
    if (!std::isfinite(l.intensity) || !std::isfinite(l.range) ||
        !std::isfinite(l.color.x + l.color.y + l.color.z)) {
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
                            fail(nodeLabel(n) + ": " + meshLabel(node.mesh) + " names joint " +
                                 std::to_string(v.joints[set][k]) + " of skin " +
                                 std::to_string(skin) + ", which has " + std::to_string(joints));
        if (std::none_of(scene_.meshes[mi].primitives.begin(), scene_.meshes[mi].primitives.end(),
                         [](const Primitive& p) { return !p.skin.empty(); }))
            warn(nodeLabel(n) +
                 ": skinned node whose mesh has no JOINTS_0/WEIGHTS_0; drawn unskinned");
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
        auto read = [&](const char* name, int type, uint32_t allowed, std::vector<float>& out,
                        size_t comps) {
            const tinygltf::Value& a = attrs.Get(name);
            if (!a.IsNumber()) return;
            out = readAccessor<float>(
                valueIndex(a), std::string(name) + " of EXT_mesh_gpu_instancing on " + nodeLabel(n),
                type, allowed);
            size_t c = out.size() / comps;
            if (count != SIZE_MAX && c != count)
                fail(nodeLabel(n) + ": EXT_mesh_gpu_instancing attribute counts differ");
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

}  // namespace gltf

Scene loadGltf(const std::string& path, const LoadOptions& options) {
    gltf::Loader loader(path, options);
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
