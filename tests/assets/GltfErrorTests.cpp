// Malformed input: every case is written by the test into a temporary folder, starting from a
// small valid file that is shown to load, and must end in an AssetError whose message names the
// file and the offending element. Never a crash, a hang or another exception type.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include <turbojpeg.h>

#include "TestSupport.h"
#include "assets/GltfLoader.h"

using namespace fe::assets;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

class GltfErrors : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("fe_assets_" + std::string(info->name()) + "_" +
                                            std::to_string(std::random_device{}()));
        fs::create_directories(dir_);
        positions_ = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        indices_ = {0, 1, 2};
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    // tri.bin: 3 float3 positions (36 bytes) then u16 indices (padded to 4 bytes).
    std::vector<uint8_t> bin() const {
        std::vector<uint8_t> b(positions_.size() * 4);
        std::memcpy(b.data(), positions_.data(), b.size());
        size_t off = b.size();
        b.resize(off + ((indices_.size() * 2 + 3) & ~size_t(3)), 0);
        std::memcpy(b.data() + off, indices_.data(), indices_.size() * 2);
        return b;
    }

    // One triangle, mesh "Tri": accessor 0 = indices, accessor 1 = POSITION.
    json gltf() const {
        const size_t posBytes = positions_.size() * 4;
        return json{
            {"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", json::array({{{"nodes", {0}}}})},
            {"nodes", json::array({{{"mesh", 0}, {"name", "TriNode"}}})},
            {"meshes", json::array({{{"name", "Tri"},
                                     {"primitives", json::array({{{"attributes", {{"POSITION", 1}}},
                                                                  {"indices", 0}}})}}})},
            {"buffers", json::array({{{"uri", "tri.bin"}, {"byteLength", bin().size()}}})},
            {"bufferViews",
             json::array(
                 {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", posBytes}},
                  {{"buffer", 0}, {"byteOffset", posBytes}, {"byteLength", indices_.size() * 2}}})},
            {"accessors", json::array({{{"bufferView", 1},
                                        {"componentType", 5123},
                                        {"count", indices_.size()},
                                        {"type", "SCALAR"}},
                                       {{"bufferView", 0},
                                        {"componentType", 5126},
                                        {"count", positions_.size() / 3},
                                        {"type", "VEC3"}}})},
        };
    }

    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name, std::ios::binary) << text;
        return (dir_ / name).string();
    }
    std::string writeBytes(const std::string& name, const std::vector<uint8_t>& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return (dir_ / name).string();
    }
    // Writes tri.bin and the JSON; returns the .gltf path.
    std::string writeGltf(const json& j, const std::string& name = "tri.gltf") const {
        writeBytes("tri.bin", bin());
        return write(name, j.dump());
    }

    // A .glb container around JSON + one BIN chunk.
    static std::vector<uint8_t> glb(std::string jsonText, std::vector<uint8_t> binChunk) {
        while (jsonText.size() % 4) jsonText += ' ';
        while (binChunk.size() % 4) binChunk.push_back(0);
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) {
            uint8_t b[4];
            std::memcpy(b, &v, 4);
            out.insert(out.end(), b, b + 4);
        };
        uint32_t total = 12 + 8 + uint32_t(jsonText.size()) + 8 + uint32_t(binChunk.size());
        out.insert(out.end(), {'g', 'l', 'T', 'F'});
        u32(2);
        u32(total);
        u32(uint32_t(jsonText.size()));
        out.insert(out.end(), {'J', 'S', 'O', 'N'});
        out.insert(out.end(), jsonText.begin(), jsonText.end());
        u32(uint32_t(binChunk.size()));
        out.insert(out.end(), {'B', 'I', 'N', 0});
        out.insert(out.end(), binChunk.begin(), binChunk.end());
        return out;
    }

    // Loads `path`, requires an AssetError mentioning the file and every `needles` entry.
    void expectError(const std::string& path, std::initializer_list<std::string> needles) const {
        try {
            Scene s = loadGltf(path);
            ADD_FAILURE() << "expected AssetError for " << path;
        } catch (const AssetError& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(fs::path(path).filename().string()), std::string::npos)
                << "file not named: " << msg;
            for (const auto& n : needles)
                EXPECT_NE(msg.find(n), std::string::npos) << "missing '" << n << "' in: " << msg;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "wrong exception type: " << e.what();
        }
    }

    fs::path dir_;
    std::vector<float> positions_;
    std::vector<uint16_t> indices_;
};

}  // namespace

// Same fixture, for small valid files that cover what the samples do not.
class GltfSynthetic : public GltfErrors {
protected:
    // gltf() with texture 0: a 1x1 PNG (data URI) that resolves, for materials that name a texture.
    json gltfWithTexture() const {
        json j = gltf();
        j["images"] = json::array(
            {{{"uri",
               "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGP43+DwHwAHAAK/K9fH4gAAAABJRU5ErkJggg=="}}});
        j["textures"] = json::array({{{"source", 0}}});
        return j;
    }
};

TEST_F(GltfSynthetic, BaselineFileLoads) {
    Scene s = loadGltf(writeGltf(gltf()));
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(s.meshes[0].name, "Tri");
    Scene g = loadGltf(writeBytes("tri.glb", glb(
                                                 [&] {
                                                     json j = gltf();
                                                     j["buffers"][0].erase("uri");
                                                     return j.dump();
                                                 }(),
                                                 bin())));
    EXPECT_EQ(g.meshes[0].primitives[0].vertices.size(), 3u);
}

TEST_F(GltfErrors, NonExistentPath) {
    expectError((dir_ / "nope.gltf").string(), {"file not found"});
}

TEST_F(GltfErrors, DirectoryInsteadOfFile) {
    fs::create_directories(dir_ / "folder.gltf");
    expectError((dir_ / "folder.gltf").string(), {"not a regular file"});
}

TEST_F(GltfErrors, TruncatedJson) {
    std::string text = gltf().dump();
    expectError(write("trunc.gltf", text.substr(0, text.size() / 2)), {"parse error"});
}

TEST_F(GltfErrors, MissingBufferFile) {
    json j = gltf();
    j["buffers"][0]["uri"] = "missing.bin";
    expectError(writeGltf(j), {"missing.bin"});
}

TEST_F(GltfErrors, AccessorPastBufferViewEnd) {
    json j = gltf();
    j["accessors"][1]["count"] = 30;
    expectError(writeGltf(j), {"accessor 1 (POSITION of mesh 'Tri' primitive 0)",
                               "byteOffset+count*stride exceeds bufferView 0 length"});
}

TEST_F(GltfErrors, AccessorByteOffsetPastEnd) {
    json j = gltf();
    j["accessors"][1]["byteOffset"] = 4;
    expectError(writeGltf(j),
                {"accessor 1 (POSITION of mesh 'Tri' primitive 0)", "exceeds bufferView 0"});
}

TEST_F(GltfErrors, BufferViewPastBufferEnd) {
    json j = gltf();
    j["bufferViews"][0]["byteLength"] = 400;
    expectError(writeGltf(j), {"bufferView 0", "exceeds buffer 0"});
}

TEST_F(GltfErrors, IndexOutOfRange) {
    indices_ = {0, 27, 2};
    expectError(writeGltf(gltf()), {"index 27 >= vertex count 3 in mesh 'Tri' primitive 0"});
}

TEST_F(GltfErrors, NaNAndInfinitePositions) {
    positions_[4] = std::numeric_limits<float>::quiet_NaN();
    expectError(writeGltf(gltf(), "nan.gltf"),
                {"non-finite POSITION", "vertex 1", "mesh 'Tri' primitive 0"});
    positions_[4] = 0.0f;
    positions_[8] = std::numeric_limits<float>::infinity();
    expectError(writeGltf(gltf(), "inf.gltf"), {"non-finite POSITION", "vertex 2"});
}

TEST_F(GltfErrors, UnsupportedComponentType) {
    json j = gltf();
    j["accessors"][1]["componentType"] = 5123;  // unsigned short positions (KHR_mesh_quantization)
    j["accessors"][1]["count"] = 3;
    expectError(writeGltf(j),
                {"accessor 1 (POSITION", "unsupported component type unsigned short"});
    json k = gltf();
    k["accessors"][0]["componentType"] = 5126;  // float indices
    k["bufferViews"][1]["byteLength"] = 12;
    expectError(writeGltf(k, "floatidx.gltf"), {"accessor 0 (indices of mesh 'Tri' primitive 0)",
                                                "unsupported component type float"});
}

TEST_F(GltfErrors, WrongAccessorType) {
    json j = gltf();
    j["accessors"][1]["type"] = "VEC2";
    expectError(writeGltf(j), {"accessor 1 (POSITION", "type VEC2, expected VEC3"});
}

TEST_F(GltfErrors, DanglingIndices) {
    json j = gltf();
    j["nodes"][0]["mesh"] = 5;
    expectError(writeGltf(j, "mesh.gltf"), {"mesh 5 does not exist"});
    j = gltf();
    j["meshes"][0]["primitives"][0]["material"] = 3;
    expectError(writeGltf(j, "material.gltf"), {"material 3 does not exist"});
    j = gltf();
    j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
    expectError(writeGltf(j, "accessor.gltf"), {"accessor 9 does not exist"});
    j = gltf();
    j["nodes"][0]["children"] = {4};
    expectError(writeGltf(j, "child.gltf"), {"child node 4 does not exist"});
    j = gltf();
    j["scenes"][0]["nodes"] = {7};
    expectError(writeGltf(j, "scene.gltf"), {"node 7 does not exist"});
}

TEST_F(GltfErrors, NodeCycleDoesNotHang) {
    json j = gltf();
    j["nodes"] = json::array({{{"children", {1}}}, {{"children", {0}}, {"mesh", 0}}});
    expectError(writeGltf(j, "cycle.gltf"), {"node"});
    j["nodes"] = json::array({{{"children", {0}}, {"mesh", 0}}});  // its own child
    expectError(writeGltf(j, "self.gltf"), {"node 0"});
}

TEST_F(GltfErrors, NodeWithTwoParents) {
    json j = gltf();
    j["nodes"] = json::array({{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}});
    j["scenes"][0]["nodes"] = {0, 1};
    expectError(writeGltf(j), {"node 2", "two parents"});
}

TEST_F(GltfErrors, NonFiniteNodeTransform) {
    // JSON cannot spell NaN or infinity; 1e39 is a finite double that overflows a float.
    json j = gltf();
    j["nodes"][0]["translation"] = {1e39, 0, 0};
    expectError(writeGltf(j, "inf.gltf"), {"TriNode", "non-finite transform"});
    // A number too large even for a double is tinygltf's JSON error, still an AssetError.
    std::string text = gltf().dump();
    text.replace(text.find("\"name\":\"TriNode\""), std::strlen("\"name\":\"TriNode\""),
                 "\"name\":\"TriNode\",\"translation\":[1e999,0,0]");
    expectError(write("overflow.gltf", text), {"1e999"});
}

TEST_F(GltfErrors, DeeplyNestedJsonIsRejectedNotAStackOverflow) {
    // tinygltf converts "extras" recursively: 100000 nested arrays would overflow the stack.
    std::string text = gltf().dump();
    text.pop_back();
    text += ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + "}";
    expectError(write("deep.gltf", text), {"nested deeper"});
    // Brackets inside strings do not count.
    json j = gltf();
    j["nodes"][0]["name"] = std::string(1000, '[');
    EXPECT_NO_THROW(loadGltf(writeGltf(j, "brackets.gltf")));
}

TEST_F(GltfErrors, HugeAccessorWithoutBufferViewIsRefused) {
    json j = gltf();
    j["accessors"][1].erase("bufferView");
    j["accessors"][1]["count"] = 4000000000u;
    expectError(writeGltf(j), {"accessor 1 (POSITION", "too large"});
}

TEST_F(GltfErrors, UnsupportedRequiredExtension) {
    json j = gltf();
    j["extensionsUsed"] = {"EXT_made_up"};
    j["extensionsRequired"] = {"EXT_made_up"};
    expectError(writeGltf(j), {"unsupported required extension EXT_made_up"});
    // Used but not required: loads with a warning.
    j.erase("extensionsRequired");
    Scene s = loadGltf(writeGltf(j, "used.gltf"));
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings[0].find("EXT_made_up"), std::string::npos);
}

TEST_F(GltfErrors, ImageThatFailsToDecode) {
    write("bad.png", "this is not a png at all");
    json j = gltf();
    j["images"] = json::array({{{"uri", "bad.png"}}});
    j["textures"] = json::array({{{"source", 0}}});
    j["materials"] = json::array(
        {{{"name", "M"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    expectError(writeGltf(j),
                {"image 0 ('bad.png')", "baseColorTexture of material 'M'", "cannot decode"});
}

namespace {
// An 8x8 JPEG of one colour, encoded by libjpeg-turbo (4:4:4, quality 95).
std::vector<uint8_t> solidJpeg(uint8_t r, uint8_t g, uint8_t b) {
    std::vector<uint8_t> rgb(8 * 8 * 3);
    for (size_t i = 0; i < 64; ++i) rgb[i * 3] = r, rgb[i * 3 + 1] = g, rgb[i * 3 + 2] = b;
    tjhandle tj = tjInitCompress();
    unsigned char* out = nullptr;
    unsigned long size = 0;
    EXPECT_EQ(tjCompress2(tj, rgb.data(), 8, 0, 8, TJPF_RGB, &out, &size, TJSAMP_444, 95, 0), 0);
    std::vector<uint8_t> jpeg(out, out + size);
    tjFree(out);
    tjDestroy(tj);
    return jpeg;
}
// Offset of the first marker 0xFF `code` after the start-of-image marker.
size_t markerOffset(const std::vector<uint8_t>& jpeg, uint8_t code) {
    for (size_t i = 2; i + 1 < jpeg.size(); ++i)
        if (jpeg[i] == 0xFF && jpeg[i + 1] == code) return i;
    ADD_FAILURE() << "marker not found";
    return 0;
}
}  // namespace

TEST_F(GltfSynthetic, JpegTextureDecodesToItsColour) {
    writeBytes("red.jpg", solidJpeg(200, 40, 10));
    json j = gltf();
    j["images"] = json::array({{{"uri", "red.jpg"}}});
    j["textures"] = json::array({{{"source", 0}}});
    j["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    Scene s = loadGltf(writeGltf(j));
    ASSERT_EQ(s.textures.size(), 1u);
    const TextureImage& t = s.textures[0];
    ASSERT_EQ(t.width, 8u);
    ASSERT_EQ(t.height, 8u);
    ASSERT_EQ(t.pixels.size(), 8u * 8u * 4u);
    for (size_t p = 0; p < 64; ++p) {
        EXPECT_NEAR(t.pixels[p * 4 + 0], 200, 3);
        EXPECT_NEAR(t.pixels[p * 4 + 1], 40, 3);
        EXPECT_NEAR(t.pixels[p * 4 + 2], 10, 3);
        EXPECT_EQ(t.pixels[p * 4 + 3], 255);
    }
}

// A Huffman table declaring more than 256 codes made Debian's stb_image write past its tables
// (the glTF fuzzer found it); it must be an AssetError naming the image.
TEST_F(GltfErrors, JpegWithOversizedHuffmanTable) {
    std::vector<uint8_t> jpeg = solidJpeg(200, 40, 10);
    const size_t dht = markerOffset(jpeg, 0xC4);
    // 0xFF 0xC4, 2 length bytes, 1 class/id byte, then 16 code counts: 16 x 20 = 320 codes.
    for (size_t i = 0; i < 16; ++i) jpeg[dht + 5 + i] = 20;
    writeBytes("bogus.jpg", jpeg);
    json j = gltf();
    j["images"] = json::array({{{"uri", "bogus.jpg"}}});
    j["textures"] = json::array({{{"source", 0}}});
    j["materials"] = json::array(
        {{{"name", "M"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    expectError(writeGltf(j), {"image 0 ('bogus.jpg')", "cannot decode JPEG", "Huffman"});
}

// A JPEG cut inside its scan decodes to grey rows with only a warning in most decoders: here it
// is refused, never a half-grey texture.
TEST_F(GltfErrors, TruncatedJpegIsRefused) {
    std::vector<uint8_t> jpeg = solidJpeg(200, 40, 10);
    jpeg.resize(markerOffset(jpeg, 0xDA) + 20);
    writeBytes("cut.jpg", jpeg);
    json j = gltf();
    j["images"] = json::array({{{"uri", "cut.jpg"}}});
    j["textures"] = json::array({{{"source", 0}}});
    j["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    expectError(writeGltf(j), {"image 0 ('cut.jpg')", "cannot decode JPEG"});
}

TEST_F(GltfErrors, MissingImageFile) {
    json j = gltf();
    j["images"] = json::array({{{"uri", "gone.png"}}});
    j["textures"] = json::array({{{"source", 0}}});
    j["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    expectError(writeGltf(j), {"image 0 ('gone.png')", "missing"});
}

TEST_F(GltfErrors, SparseIndexOutOfRange) {
    // Sparse data appended to the buffer: one u16 index (7, but count is 3) and one float3.
    std::vector<uint8_t> b = bin();
    size_t sparseOff = b.size();
    uint16_t idx[2] = {7, 0};
    float val[3] = {5, 5, 5};
    b.resize(sparseOff + 4 + 12);
    std::memcpy(b.data() + sparseOff, idx, 4);
    std::memcpy(b.data() + sparseOff + 4, val, 12);
    writeBytes("sparse.bin", b);
    json j = gltf();
    j["buffers"][0] = {{"uri", "sparse.bin"}, {"byteLength", b.size()}};
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", sparseOff}, {"byteLength", 2}});
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", sparseOff + 4}, {"byteLength", 12}});
    j["accessors"][1]["sparse"] = {{"count", 1},
                                   {"indices", {{"bufferView", 2}, {"componentType", 5123}}},
                                   {"values", {{"bufferView", 3}}}};
    expectError(write("sparse.gltf", j.dump()),
                {"accessor 1 (POSITION", "sparse index 7 >= count 3"});
}

TEST_F(GltfSynthetic, SparseAccessorWithoutBufferViewIsZerosPlusSparse) {
    // The valid counterpart of the case above: a sparse accessor with no bufferView (zeros).
    std::vector<uint8_t> b = bin();
    size_t sparseOff = b.size();
    uint16_t idx[2] = {1, 0};
    float val[3] = {2, 3, 4};
    b.resize(sparseOff + 4 + 12);
    std::memcpy(b.data() + sparseOff, idx, 4);
    std::memcpy(b.data() + sparseOff + 4, val, 12);
    writeBytes("sparse.bin", b);
    json j = gltf();
    j["buffers"][0] = {{"uri", "sparse.bin"}, {"byteLength", b.size()}};
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", sparseOff}, {"byteLength", 2}});
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", sparseOff + 4}, {"byteLength", 12}});
    j["accessors"][1].erase("bufferView");
    j["accessors"][1]["sparse"] = {{"count", 1},
                                   {"indices", {{"bufferView", 2}, {"componentType", 5123}}},
                                   {"values", {{"bufferView", 3}}}};
    Scene s = loadGltf(write("sparse.gltf", j.dump()));
    const auto& v = s.meshes[0].primitives[0].vertices;  // unwelded: same order as the indices
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[0].position, glm::vec3(0, 0, 0));
    EXPECT_EQ(v[1].position, glm::vec3(2, 3, 4));
    EXPECT_EQ(v[2].position, glm::vec3(0, 0, 0));
}

TEST_F(GltfErrors, GlbWithBadMagic) {
    std::vector<uint8_t> bytes = glb(gltf().dump(), bin());
    std::memcpy(bytes.data(), "gLtF", 4);
    expectError(writeBytes("bad.glb", bytes), {"bad magic"});
    expectError(writeBytes("text.glb", std::vector<uint8_t>{'{', '}'}), {"bad magic"});
}

TEST_F(GltfErrors, TruncatedGlbNeverCrashes) {
    json j = gltf();
    j["buffers"][0].erase("uri");
    std::vector<uint8_t> full = glb(j.dump(), bin());
    ASSERT_NO_THROW(loadGltf(writeBytes("full.glb", full)));
    for (size_t len = 0; len < full.size(); ++len) {
        std::vector<uint8_t> cut(full.begin(), full.begin() + std::ptrdiff_t(len));
        EXPECT_THROW(loadGltf(writeBytes("cut.glb", cut)), AssetError) << "length " << len;
    }
}

// 4.4: chunk layout rules the loader enforces itself (tinygltf reads two chunks and stops).
class GlbLayout : public GltfErrors {
protected:
    struct Chunk {
        std::string type;  // four characters
        std::vector<uint8_t> data;
    };
    std::string jsonNoUri() const {
        json j = gltf();
        j["buffers"][0].erase("uri");
        std::string t = j.dump();
        while (t.size() % 4) t += ' ';
        return t;
    }
    static std::vector<uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }
    // A GLB of `chunks` as given (no padding added); `lengthDelta` corrupts the header's length.
    static std::vector<uint8_t> container(const std::vector<Chunk>& chunks, int lengthDelta = 0,
                                          uint32_t version = 2) {
        std::vector<uint8_t> out{'g', 'l', 'T', 'F'};
        auto u32 = [&](uint32_t v) {
            uint8_t b[4];
            std::memcpy(b, &v, 4);
            out.insert(out.end(), b, b + 4);
        };
        u32(version);
        u32(0);
        for (const Chunk& c : chunks) {
            u32(uint32_t(c.data.size()));
            out.insert(out.end(), c.type.begin(), c.type.begin() + 4);
            out.insert(out.end(), c.data.begin(), c.data.end());
        }
        const uint32_t total = uint32_t(int(out.size()) + lengthDelta);
        std::memcpy(out.data() + 8, &total, 4);
        return out;
    }
    Chunk jsonChunk() const { return {"JSON", bytesOf(jsonNoUri())}; }
    Chunk binChunk() const { return {std::string("BIN\0", 4), bin()}; }
};

TEST_F(GlbLayout, WellFormedLoadsAndUnknownChunksAreIgnored) {
    EXPECT_NO_THROW(loadGltf(writeBytes("ok.glb", container({jsonChunk(), binChunk()}))));
    Scene s = loadGltf(
        writeBytes("extra.glb", container({jsonChunk(), binChunk(), {"XTRA", {1, 2, 3, 4}}})));
    EXPECT_TRUE(s.warnings.empty())
        << s.warnings.front();  // the specification requires ignoring them
}

TEST_F(GlbLayout, DuplicateChunksAreRefused) {
    expectError(writeBytes("json2.glb", container({jsonChunk(), binChunk(), jsonChunk()})),
                {"GLB chunk 2", "duplicate JSON chunk"});
    expectError(writeBytes("bin2.glb", container({jsonChunk(), binChunk(), binChunk()})),
                {"GLB chunk 2", "duplicate BIN chunk"});
}

TEST_F(GlbLayout, ChunkOrderIsEnforced) {
    expectError(writeBytes("binfirst.glb", container({binChunk(), jsonChunk()})),
                {"GLB chunk 0", "first chunk must be JSON"});
    expectError(
        writeBytes("binlate.glb", container({jsonChunk(), {"XTRA", {0, 0, 0, 0}}, binChunk()})),
        {"GLB chunk 2", "must directly follow"});
}

TEST_F(GlbLayout, MisalignedChunkIsRefused) {
    Chunk j = jsonChunk();
    j.data.push_back(' ');  // 4n + 1 bytes: BIN would start unaligned
    expectError(writeBytes("misaligned.glb", container({j, binChunk()})),
                {"GLB chunk 0", "not a multiple of 4"});
    Chunk b = binChunk();
    b.data.resize(b.data.size() - 2);
    expectError(writeBytes("misbin.glb", container({jsonChunk(), b})),
                {"GLB chunk 1 at byte", "(BIN)", "multiple of 4"});
}

TEST_F(GlbLayout, HeaderMustDescribeTheFile) {
    expectError(writeBytes("long.glb", container({jsonChunk(), binChunk()}, +4)),
                {"GLB header length"});
    expectError(writeBytes("short.glb", container({jsonChunk(), binChunk()}, -8)),
                {"GLB header length"});
    expectError(writeBytes("v1.glb", container({jsonChunk(), binChunk()}, 0, 1)),
                {"GLB header version 1"});
    std::vector<uint8_t> tail = container({jsonChunk(), binChunk()}, 4);
    tail.insert(tail.end(), {0, 0, 0, 0});  // length matches, but 4 bytes are no chunk
    expectError(writeBytes("tail.glb", tail), {"GLB chunk 2", "truncated chunk header"});
}

// 3.1: JSON must be UTF-8 without a byte order mark; clients may ignore one, so it is a warning.
TEST_F(GlbLayout, ByteOrderMarkIsAWarning) {
    Scene plain = loadGltf(writeGltf(gltf()));
    EXPECT_TRUE(plain.warnings.empty());
    Scene text =
        loadGltf(write("bom.gltf", "\xEF\xBB\xBF" + gltf().dump()));  // tri.bin is written above
    ASSERT_EQ(text.warnings.size(), 1u);
    EXPECT_NE(text.warnings[0].find("byte order mark"), std::string::npos) << text.warnings[0];
    EXPECT_EQ(text.instances.size(), 1u);
    Scene binary = loadGltf(writeBytes(
        "bom.glb", container({{"JSON", bytesOf("\xEF\xBB\xBF" + jsonNoUri() + " ")}, binChunk()})));
    ASSERT_EQ(binary.warnings.size(), 1u);
    EXPECT_NE(binary.warnings[0].find("byte order mark"), std::string::npos) << binary.warnings[0];
}

// Random byte corruption of a valid .gltf + .bin: whatever happens, only AssetError may escape
// (crashes and other exceptions fail the test). Fixed seed, so failures reproduce.
TEST_F(GltfErrors, CorruptedFilesOnlyThrowAssetError) {
    json j = gltf();
    j["materials"] = json::array(
        {{{"name", "M"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.5, 0.25, 1}}}}}});
    j["meshes"][0]["primitives"][0]["material"] = 0;
    const std::string text = j.dump();
    const std::vector<uint8_t> goodBin = bin();
    std::mt19937 rng(1234);
    int loaded = 0, refused = 0;
    for (int iter = 0; iter < 400; ++iter) {
        std::string t = text;
        std::vector<uint8_t> b = goodBin;
        int edits = 1 + int(rng() % 3);
        for (int e = 0; e < edits; ++e) {
            if (rng() % 4 == 0) {
                b[rng() % b.size()] = uint8_t(rng());
            } else {
                const char alphabet[] = "0123456789-+.e\"{}[],:9999999999";
                t[rng() % t.size()] = alphabet[rng() % (sizeof(alphabet) - 1)];
            }
        }
        writeBytes("tri.bin", b);
        std::string path = write("fuzz.gltf", t);
        try {
            loadGltf(path);
            ++loaded;
        } catch (const AssetError&) {
            ++refused;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "iteration " << iter << ": non-AssetError exception " << e.what()
                          << "\n"
                          << t;
        }
    }
    EXPECT_GT(refused, 0);
    EXPECT_GT(loaded, 0);
}

TEST_F(GltfSynthetic, TrsOrderAndParentTimesChild) {
    const float h = std::sqrt(0.5f);
    json j = gltf();
    // Node 0: T (1,2,3) * R (90 deg about Z) * S (2,1,1). Point (1,0,0) -> S (2,0,0) -> R (0,2,0)
    // -> T (1,4,3). Node 1 (parent, 90 deg about Y) of node 2 (translation (1,0,0)): the child's
    // origin is R_y(90) (1,0,0) = (0,0,-1).
    j["nodes"] = json::array({{{"name", "trs"},
                               {"mesh", 0},
                               {"translation", {1, 2, 3}},
                               {"rotation", {0, 0, h, h}},
                               {"scale", {2, 1, 1}}},
                              {{"name", "parent"}, {"rotation", {0, h, 0, h}}, {"children", {2}}},
                              {{"name", "child"}, {"mesh", 0}, {"translation", {1, 0, 0}}}});
    j["scenes"][0]["nodes"] = {0, 1};
    Scene s = loadGltf(writeGltf(j));
    ASSERT_EQ(s.instances.size(), 2u);
    const MeshInstance* trs = fe::assets::test::findInstance(s, "trs");
    const MeshInstance* child = fe::assets::test::findInstance(s, "child");
    ASSERT_TRUE(trs && child);
    glm::vec3 p = glm::vec3(trs->world * glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(glm::distance(p, glm::vec3(1, 4, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(glm::vec3(child->world[3]), glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
}

TEST_F(GltfSynthetic, SpotAndDirectionalLightsFromNodes) {
    const float h = std::sqrt(0.5f);
    json j = gltf();
    j["extensionsUsed"] = {"KHR_lights_punctual"};
    j["extensions"] = {
        {"KHR_lights_punctual",
         {{"lights", json::array({{{"type", "spot"},
                                   {"name", "S"},
                                   {"color", {1, 0.5, 0.25}},
                                   {"intensity", 7},
                                   {"range", 9},
                                   {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
                                  {{"type", "directional"}, {"intensity", 3}, {"range", 5}}})}}}};
    // Spot at (1,2,3) turned 90 deg about Y: local -Z -> world -X. Sun turned -90 deg about X:
    // local -Z -> world -Y (straight down).
    j["nodes"].push_back({{"translation", {1, 2, 3}},
                          {"rotation", {0, h, 0, h}},
                          {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    j["nodes"].push_back(
        {{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    j["scenes"][0]["nodes"] = {0, 1, 2};
    Scene s = loadGltf(writeGltf(j));
    EXPECT_FALSE(s.hasDefaultLights);
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& spot = s.lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.name, "S");
    EXPECT_EQ(spot.color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(spot.intensity, 7.0f);
    EXPECT_EQ(spot.range, 9.0f);
    EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.5f);
    EXPECT_NEAR(glm::distance(spot.position, glm::vec3(1, 2, 3)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(spot.direction, glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
    const Light& sun = s.lights[1];
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_EQ(sun.range, 0.0f) << "range is meaningless for directional lights";
    EXPECT_NEAR(glm::distance(sun.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
}

TEST_F(GltfSynthetic, CameraWithInfiniteFarAndScaledNode) {
    json j = gltf();
    j["cameras"] =
        json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.05}}}}});
    j["nodes"].push_back({{"camera", 0}, {"translation", {0, 1, 5}}, {"scale", {2, 2, 2}}});
    j["scenes"][0]["nodes"] = {0, 1};
    Scene s = loadGltf(writeGltf(j));
    ASSERT_TRUE(s.camera);
    EXPECT_FALSE(s.hasDefaultCamera);
    EXPECT_TRUE(s.camera->infiniteFar());
    EXPECT_FALSE(s.camera->aspectRatio.has_value());
    EXPECT_FLOAT_EQ(s.camera->yfov, 0.9f);
    EXPECT_NEAR(glm::determinant(s.camera->worldFromView), 1.0f, 1e-5f) << "scale removed";
    EXPECT_EQ(s.camera->eye(), glm::vec3(0, 1, 5));
    EXPECT_NEAR(glm::distance(s.camera->forward(), glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
}

TEST_F(GltfSynthetic, NormalizedByteTexcoordsAndByteAndIntIndices) {
    // Buffer: positions (36 bytes) | u8 indices 0,1,2 (+1 pad) | u32 indices 2,1,0 | u8 normalized
    // texcoords (0,0) (255,0) (0,255) (+2 pad) | u16 normalized texcoords (0,0) (65535,0) (0,65535).
    std::vector<uint8_t> b(36);
    std::memcpy(b.data(), positions_.data(), 36);
    b.insert(b.end(), {0, 1, 2, 0});
    uint32_t i32[3] = {2, 1, 0};
    b.insert(b.end(), reinterpret_cast<uint8_t*>(i32), reinterpret_cast<uint8_t*>(i32) + 12);
    b.insert(b.end(), {0, 0, 255, 0, 0, 255, 0, 0});
    uint16_t t16[6] = {0, 0, 65535, 0, 0, 65535};
    b.insert(b.end(), reinterpret_cast<uint8_t*>(t16), reinterpret_cast<uint8_t*>(t16) + 12);
    writeBytes("mixed.bin", b);
    json j = gltf();
    j["buffers"][0] = {{"uri", "mixed.bin"}, {"byteLength", b.size()}};
    j["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                                    {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 3}},
                                    {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 12}},
                                    {{"buffer", 0}, {"byteOffset", 52}, {"byteLength", 6}},
                                    {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 12}}});
    j["accessors"] =
        json::array({{{"bufferView", 1}, {"componentType", 5121}, {"count", 3}, {"type", "SCALAR"}},
                     {{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                     {{"bufferView", 2}, {"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}},
                     {{"bufferView", 3},
                      {"componentType", 5121},
                      {"normalized", true},
                      {"count", 3},
                      {"type", "VEC2"}},
                     {{"bufferView", 4},
                      {"componentType", 5123},
                      {"normalized", true},
                      {"count", 3},
                      {"type", "VEC2"}}});
    j["meshes"][0]["primitives"] =
        json::array({{{"attributes", {{"POSITION", 1}, {"TEXCOORD_0", 3}}}, {"indices", 0}},
                     {{"attributes", {{"POSITION", 1}, {"TEXCOORD_0", 4}}}, {"indices", 2}}});
    Scene s = loadGltf(write("mixed.gltf", j.dump()));
    ASSERT_EQ(s.meshes[0].primitives.size(), 2u);
    const auto& a = s.meshes[0].primitives[0].vertices;  // flat normals: vertices in index order
    EXPECT_EQ(a[0].uv0, glm::vec2(0, 0));
    EXPECT_EQ(a[1].uv0, glm::vec2(1, 0));
    EXPECT_EQ(a[2].uv0, glm::vec2(0, 1));
    const auto& c = s.meshes[0].primitives[1].vertices;  // u32 indices 2, 1, 0
    EXPECT_EQ(c[0].position, glm::vec3(0, 1, 0));
    EXPECT_EQ(c[0].uv0, glm::vec2(0, 1));
    EXPECT_EQ(c[2].uv0, glm::vec2(0, 0));
    EXPECT_EQ(c[0].normal, glm::vec3(0, 0, -1)) << "reversed winding faces -Z";
    // Texcoords that are integers but not normalized are not valid glTF.
    j["accessors"][3]["normalized"] = false;
    expectError(write("unnormalized.gltf", j.dump()),
                {"TEXCOORD_0", "unsupported component type unsigned byte"});
}

TEST_F(GltfSynthetic, FirstPerspectiveCameraInDepthFirstNodeOrderWins) {
    // Roots [0, 1, 2]; node 1's child 3 holds camera "deep", root 2 holds camera "late".
    // Depth-first order visits 0, 1, 3, 2: "deep" wins (breadth-first would pick "late").
    json j = gltf();
    j["cameras"] = json::array({{{"type", "perspective"},
                                 {"name", "late"},
                                 {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                                {{"type", "perspective"},
                                 {"name", "deep"},
                                 {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    j["nodes"].push_back({{"children", {3}}});
    j["nodes"].push_back({{"camera", 0}});
    j["nodes"].push_back({{"camera", 1}, {"translation", {0, 0, 7}}});
    j["scenes"][0]["nodes"] = {0, 1, 2};
    Scene s = loadGltf(writeGltf(j));
    ASSERT_TRUE(s.camera);
    EXPECT_EQ(s.camera->name, "deep");
    EXPECT_FLOAT_EQ(s.camera->yfov, 0.6f);
    EXPECT_EQ(s.camera->eye(), glm::vec3(0, 0, 7));
}

// The fuzzers' seed corpus (tests/fuzz/make_seeds.py): one file per glTF 2.0 rule the loader
// enforces, each the valid triangle with that rule broken. The rule for invalid files: never
// rendered silently, so each is refused with an AssetError or loaded with a warning; the valid
// seeds load without one.
TEST(FuzzSeeds, EveryBrokenRuleIsRefusedOrWarnedAndValidFilesLoadCleanly) {
    int rules = 0, valid = 0;
    for (const auto& entry : fs::directory_iterator(FE_FUZZ_SEEDS "/gltf")) {
        const std::string name = entry.path().filename().string();
        SCOPED_TRACE(name);
        if (name.rfind("valid-", 0) == 0) {
            ++valid;
            Scene s = loadGltf(entry.path().string());
            EXPECT_FALSE(s.instances.empty());
            EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
            continue;
        }
        ++rules;
        try {
            Scene s = loadGltf(entry.path().string());
            EXPECT_FALSE(s.warnings.empty()) << "an invalid file loaded without a warning";
        } catch (const AssetError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos)
                << "the error names the file: " << e.what();
        }
    }
    EXPECT_GE(rules, 40);
    EXPECT_GE(valid, 4);
}

// COLOR_0 as normalized unsigned bytes (VEC4) and shorts (VEC3, alpha 1), and TEXCOORD_1 as
// floats, decoded as glTF 2.0 defines; a SCALAR colour is an error naming the attribute.
TEST_F(GltfSynthetic, VertexColoursAndSecondUvSet) {
    std::vector<uint8_t> b = bin();  // positions (36) + u16 indices (8)
    const size_t colors8 = b.size();
    b.insert(b.end(), {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0});
    const size_t colors16 = b.size();
    const uint16_t c16[9] = {65535, 0, 0, 0, 32768, 0, 0, 0, 65535};
    b.insert(b.end(), reinterpret_cast<const uint8_t*>(c16),
             reinterpret_cast<const uint8_t*>(c16) + 18);
    b.resize((b.size() + 3) & ~size_t(3), 0);
    const size_t uvs = b.size();
    const float uv1[6] = {0.25f, 0.5f, 1.0f, 0.0f, 0.0f, 1.0f};
    b.insert(b.end(), reinterpret_cast<const uint8_t*>(uv1),
             reinterpret_cast<const uint8_t*>(uv1) + 24);
    writeBytes("colored.bin", b);
    json j = gltf();
    j["buffers"][0] = {{"uri", "colored.bin"}, {"byteLength", b.size()}};
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", colors8}, {"byteLength", 12}});
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", colors16}, {"byteLength", 18}});
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", uvs}, {"byteLength", 24}});
    j["accessors"].push_back({{"bufferView", 2},
                              {"componentType", 5121},
                              {"normalized", true},
                              {"count", 3},
                              {"type", "VEC4"}});
    j["accessors"].push_back({{"bufferView", 3},
                              {"componentType", 5123},
                              {"normalized", true},
                              {"count", 3},
                              {"type", "VEC3"}});
    j["accessors"].push_back(
        {{"bufferView", 4}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    j["meshes"][0]["primitives"] = json::array(
        {{{"attributes", {{"POSITION", 1}, {"COLOR_0", 2}, {"TEXCOORD_1", 4}}}, {"indices", 0}},
         {{"attributes", {{"POSITION", 1}, {"COLOR_0", 3}}}, {"indices", 0}}});
    const Scene s = loadGltf(write("colored.gltf", j.dump()));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    const auto& a = s.meshes[0].primitives[0].vertices;
    EXPECT_EQ(a[0].color, glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(a[1].color.a, 128.0f / 255.0f, 1e-6f);
    EXPECT_EQ(a[2].color, glm::vec4(0, 0, 1, 0));
    EXPECT_EQ(a[0].uv1, glm::vec2(0.25f, 0.5f));
    EXPECT_EQ(a[2].uv1, glm::vec2(0.0f, 1.0f));
    const auto& c = s.meshes[0].primitives[1].vertices;
    EXPECT_EQ(c[0].color, glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(c[1].color.g, 32768.0f / 65535.0f, 1e-6f);
    EXPECT_EQ(c[1].color.a, 1.0f);
    EXPECT_EQ(c[0].uv1, glm::vec2(0.0f)) << "no TEXCOORD_1: zero";
    j["accessors"][2]["type"] = "SCALAR";
    j["accessors"][2]["count"] = 3;
    expectError(write("scalar_colour.gltf", j.dump()), {"COLOR_0", "expected VEC4"});
}

// KHR_texture_transform: values of the wrong shape or non-finite are errors that name the texture
// and the key; texCoord in the extension overrides the textureInfo's.
TEST_F(GltfSynthetic, TextureTransformIsReadOrRefused) {
    writeBytes("tri.bin", bin());
    json j = gltfWithTexture();
    j["extensionsUsed"] = json::array({"KHR_texture_transform"});
    auto withTransform = [&](const json& t) {
        json k = j;
        k["materials"] =
            json::array({{{"pbrMetallicRoughness",
                           {{"baseColorTexture",
                             {{"index", 0}, {"extensions", {{"KHR_texture_transform", t}}}}}}}}});
        k["meshes"][0]["primitives"][0]["material"] = 0;
        return k;
    };
    const Scene s = loadGltf(
        write("ok.gltf",
              withTransform(
                  {{"offset", {0.5, 0.25}}, {"rotation", 1.5}, {"scale", {2, 3}}, {"texCoord", 1}})
                  .dump()));
    const TextureRef& r = s.materials[0].baseColorTexture;
    EXPECT_EQ(r.texCoord, 1u);
    EXPECT_EQ(r.transform.offset, glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(r.transform.rotation, 1.5f);
    EXPECT_EQ(r.transform.scale, glm::vec2(2.0f, 3.0f));
    EXPECT_FALSE(std::any_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
        return w.find("KHR_texture_transform") != std::string::npos;
    }));
    expectError(write("short_offset.gltf", withTransform({{"offset", {0.5}}}).dump()),
                {"KHR_texture_transform", "offset", "array of 2"});
    expectError(write("text_rotation.gltf", withTransform({{"rotation", "a lot"}}).dump()),
                {"KHR_texture_transform", "rotation"});
    expectError(write("huge_scale.gltf", withTransform({{"scale", {1e39, 1}}}).dump()),
                {"KHR_texture_transform", "scale", "finite"});
    expectError(write("bad_set.gltf", withTransform({{"texCoord", -1}}).dump()), {"texCoord"});
}

// KHR_materials_ior and KHR_materials_specular: the factors are read (ior 0 is the extension's
// infinite index, F0 1), values out of their ranges are errors naming the key, and the textures
// (specular colour sRGB; the clearcoat's three, its normal map's scale) are read.
TEST_F(GltfSynthetic, DielectricIorAndSpecularAreReadOrRefused) {
    writeBytes("tri.bin", bin());
    json j = gltfWithTexture();
    j["extensionsUsed"] = json::array({"KHR_materials_ior", "KHR_materials_specular"});
    auto withMaterial = [&](const json& extensions) {
        json k = j;
        k["materials"] = json::array({{{"name", "glass"}, {"extensions", extensions}}});
        k["meshes"][0]["primitives"][0]["material"] = 0;
        return k;
    };
    const Scene s = loadGltf(
        write("ok.gltf",
              withMaterial({{"KHR_materials_ior", {{"ior", 2.0}}},
                            {"KHR_materials_specular",
                             {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 4.0}}}}})
                  .dump()));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.ior, 2.0f);
    EXPECT_EQ(m.specular, 0.5f);
    EXPECT_EQ(m.specularColor, glm::vec3(1.0f, 0.5f, 4.0f));
    // F0 = min((1/3)^2 (1, 0.5, 4), 1) x 0.5; F90 = 0.5.
    EXPECT_NEAR(m.dielectricF0().r, 0.5f / 9.0f, 1e-6f);
    EXPECT_NEAR(m.dielectricF0().g, 0.25f / 9.0f, 1e-6f);
    EXPECT_NEAR(m.dielectricF0().b, 2.0f / 9.0f, 1e-6f);
    EXPECT_EQ(m.dielectricF90(), 0.5f);
    EXPECT_FALSE(m.defaultDielectric());
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_NEAR(Material{}.dielectricF0().g, 0.04f, 1e-7f);
    EXPECT_TRUE(Material{}.defaultDielectric());
    const Scene infinite =
        loadGltf(write("ior0.gltf", withMaterial({{"KHR_materials_ior", {{"ior", 0}}}}).dump()));
    EXPECT_EQ(infinite.materials[0].dielectricF0(), glm::vec3(1.0f));
    const Scene textured =
        loadGltf(write("tex.gltf", withMaterial({{"KHR_materials_specular",
                                                  {{"specularTexture", {{"index", 0}}},
                                                   {"specularColorTexture", {{"index", 0}}}}}})
                                       .dump()));
    EXPECT_TRUE(textured.warnings.empty()) << textured.warnings.front();
    const Material& tm = textured.materials[0];
    ASSERT_TRUE(tm.specularTexture.valid() && tm.specularColorTexture.valid());
    EXPECT_TRUE(textured.textures[tm.specularColorTexture.index].srgb);
    EXPECT_FALSE(tm.defaultDielectric());  // the textures alone make it a full material
    EXPECT_NEAR(tm.dielectricF0(glm::vec3(0.5f), 0.5f).g, 0.04f * 0.5f * 0.5f, 1e-7f);
    expectError(
        write("ior_half.gltf", withMaterial({{"KHR_materials_ior", {{"ior", 0.5}}}}).dump()),
        {"glass", "ior", "at least 1"});
    expectError(write("spec_big.gltf",
                      withMaterial({{"KHR_materials_specular", {{"specularFactor", 2}}}}).dump()),
                {"specularFactor", "[0, 1]"});
    expectError(
        write("spec_neg.gltf",
              withMaterial({{"KHR_materials_specular", {{"specularColorFactor", {1, -1, 1}}}}})
                  .dump()),
        {"specularColorFactor", "negative"});
    expectError(
        write("spec_short.gltf",
              withMaterial({{"KHR_materials_specular", {{"specularColorFactor", {1, 1}}}}}).dump()),
        {"specularColorFactor", "array of 3"});
    // KHR_materials_clearcoat: its factors, its F0 from the material's ior, textures warned.
    json c = withMaterial({{"KHR_materials_clearcoat",
                            {{"clearcoatFactor", 0.75},
                             {"clearcoatRoughnessFactor", 0.25},
                             {"clearcoatTexture", {{"index", 0}}},
                             {"clearcoatRoughnessTexture", {{"index", 0}}},
                             {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
                           {"KHR_materials_ior", {{"ior", 2.0}}}});
    c["extensionsUsed"] = json::array({"KHR_materials_clearcoat", "KHR_materials_ior"});
    const Scene coated = loadGltf(write("coat.gltf", c.dump()));
    EXPECT_EQ(coated.materials[0].clearcoat, 0.75f);
    EXPECT_EQ(coated.materials[0].clearcoatRoughness, 0.25f);
    EXPECT_NEAR(coated.materials[0].clearcoatF0(), 1.0f / 9.0f, 1e-6f);
    EXPECT_TRUE(coated.materials[0].needsFullMaterial());
    EXPECT_TRUE(coated.warnings.empty()) << coated.warnings.front();
    EXPECT_TRUE(coated.materials[0].clearcoatTexture.valid());
    EXPECT_TRUE(coated.materials[0].clearcoatRoughnessTexture.valid());
    EXPECT_TRUE(coated.materials[0].clearcoatNormalTexture.valid());
    EXPECT_EQ(coated.materials[0].clearcoatNormalScale, 0.5f);
    expectError(
        write("coat_big.gltf",
              withMaterial({{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}}).dump()),
        {"clearcoatFactor", "[0, 1]"});
    expectError(
        write("coat_rough.gltf",
              withMaterial({{"KHR_materials_clearcoat", {{"clearcoatRoughnessFactor", -0.5}}}})
                  .dump()),
        {"clearcoatRoughnessFactor", "[0, 1]"});
}

// KHR_materials_transmission and KHR_materials_volume: factors and textures are read (the
// textures with their texCoord and transform), out-of-range values are errors naming the key,
// and transmission on a BLEND material (blended instead) or a volume without transmission is a
// warning saying so.
TEST_F(GltfSynthetic, TransmissionAndVolumeAreReadOrRefused) {
    writeBytes("tri.bin", bin());
    json j = gltfWithTexture();
    j["extensionsUsed"] = json::array(
        {"KHR_materials_transmission", "KHR_materials_volume", "KHR_texture_transform"});
    auto withMaterial = [&](const json& extensions, const char* alphaMode = "OPAQUE") {
        json k = j;
        k["materials"] = json::array(
            {{{"name", "glass"}, {"alphaMode", alphaMode}, {"extensions", extensions}}});
        k["meshes"][0]["primitives"][0]["material"] = 0;
        return k;
    };
    const Scene s = loadGltf(write(
        "ok.gltf",
        withMaterial({{"KHR_materials_transmission",
                       {{"transmissionFactor", 0.75},
                        {"transmissionTexture",
                         {{"index", 0},
                          {"texCoord", 1},
                          {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}}}}}}}}},
                      {"KHR_materials_volume",
                       {{"thicknessFactor", 0.5},
                        {"thicknessTexture", {{"index", 0}}},
                        {"attenuationDistance", 2.0},
                        {"attenuationColor", {0.5, 0.75, 1.0}}}}})
            .dump()));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.transmission, 0.75f);
    EXPECT_TRUE(m.transmissive());
    ASSERT_TRUE(m.transmissionTexture.valid());
    EXPECT_EQ(m.transmissionTexture.texCoord, 1u);
    EXPECT_EQ(m.transmissionTexture.transform.scale, glm::vec2(2.0f));
    EXPECT_EQ(m.thickness, 0.5f);
    EXPECT_TRUE(m.thicknessTexture.valid());
    EXPECT_EQ(m.attenuationDistance, 2.0f);
    EXPECT_EQ(m.attenuationColor, glm::vec3(0.5f, 0.75f, 1.0f));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_FALSE(Material{}.transmissive());
    EXPECT_TRUE(std::isinf(Material{}.attenuationDistance));

    const Scene blended = loadGltf(
        write("blend.gltf",
              withMaterial({{"KHR_materials_transmission", {{"transmissionFactor", 1}}}}, "BLEND")
                  .dump()));
    EXPECT_FALSE(blended.materials[0].transmissive());
    ASSERT_FALSE(blended.warnings.empty());
    EXPECT_NE(blended.warnings.front().find("BLEND material is not drawn"), std::string::npos)
        << blended.warnings.front();
    const Scene volumeAlone = loadGltf(write(
        "volume.gltf", withMaterial({{"KHR_materials_volume", {{"thicknessFactor", 1}}}}).dump()));
    ASSERT_FALSE(volumeAlone.warnings.empty());
    EXPECT_NE(volumeAlone.warnings.front().find("without KHR_materials_transmission"),
              std::string::npos);

    expectError(
        write("t_big.gltf",
              withMaterial({{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}).dump()),
        {"glass", "transmissionFactor", "[0, 1]"});
    expectError(write("t_tex.gltf", withMaterial({{"KHR_materials_transmission",
                                                   {{"transmissionTexture", {{"index", 7}}}}}})
                                        .dump()),
                {"transmissionTexture", "texture 7"});
    expectError(
        write("t_info.gltf",
              withMaterial({{"KHR_materials_transmission", {{"transmissionTexture", 3}}}}).dump()),
        {"transmissionTexture", "object with an index"});
    expectError(write("v_neg.gltf",
                      withMaterial({{"KHR_materials_volume", {{"thicknessFactor", -1}}}}).dump()),
                {"thicknessFactor", "negative"});
    expectError(
        write("v_dist.gltf",
              withMaterial({{"KHR_materials_volume", {{"attenuationDistance", 0}}}}).dump()),
        {"attenuationDistance", "positive"});
    expectError(
        write("v_color.gltf",
              withMaterial({{"KHR_materials_volume", {{"attenuationColor", {1, 2, 1}}}}}).dump()),
        {"attenuationColor", "[0, 1]"});
}

// KHR_materials_sheen: colour and roughness factors and both textures (the colour sRGB) are
// read; values out of [0, 1] are errors naming the key.
TEST_F(GltfSynthetic, SheenIsReadOrRefused) {
    writeBytes("tri.bin", bin());
    json j = gltfWithTexture();
    j["extensionsUsed"] = json::array({"KHR_materials_sheen"});
    auto withSheen = [&](const json& sheen) {
        json k = j;
        k["materials"] =
            json::array({{{"name", "velvet"}, {"extensions", {{"KHR_materials_sheen", sheen}}}}});
        k["meshes"][0]["primitives"][0]["material"] = 0;
        return k;
    };
    const Scene s = loadGltf(
        write("ok.gltf", withSheen({{"sheenColorFactor", {1.0, 0.5, 0.25}},
                                    {"sheenRoughnessFactor", 0.75},
                                    {"sheenColorTexture", {{"index", 0}}},
                                    {"sheenRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}})
                             .dump()));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.sheenColor, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(m.sheenRoughness, 0.75f);
    EXPECT_TRUE(m.hasSheen());
    EXPECT_TRUE(m.needsFullMaterial());
    ASSERT_TRUE(m.sheenColorTexture.valid());
    EXPECT_TRUE(s.textures[m.sheenColorTexture.index].srgb);
    ASSERT_TRUE(m.sheenRoughnessTexture.valid());
    EXPECT_EQ(m.sheenRoughnessTexture.texCoord, 1u);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_FALSE(Material{}.hasSheen());
    expectError(write("colour.gltf", withSheen({{"sheenColorFactor", {1.0, 1.5, 0.0}}}).dump()),
                {"velvet", "sheenColorFactor", "[0, 1]"});
    expectError(write("rough.gltf", withSheen({{"sheenRoughnessFactor", -0.1}}).dump()),
                {"sheenRoughnessFactor", "[0, 1]"});
    expectError(write("short.gltf", withSheen({{"sheenColorFactor", {1.0, 1.0}}}).dump()),
                {"sheenColorFactor", "array of 3"});
}

// Animation samplers that do not fit their keys are refused, saying which; a channel glTF does
// not allow (TRS on a node with a matrix) is a warning, the channel dropped.
TEST_F(GltfErrors, AnimationSamplersThatDoNotFit) {
    // Accessor 2: the 9 position floats read as key times (0, 0, 0, 1, 0, ...: decreasing).
    json j = gltf();
    j["accessors"].push_back(
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 9}, {"type", "SCALAR"}});
    j["accessors"].push_back(
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"}});
    j["animations"] = json::array(
        {{{"samplers", json::array({{{"input", 2}, {"output", 1}}})},
          {"channels",
           json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
    expectError(writeGltf(j, "decreasing.gltf"),
                {"animation 0 sampler 0", "key times decrease (1.000000 then 0.000000)"});
    // Accessor 3: two keys (0, 0) for three translations.
    j["animations"][0]["samplers"][0]["input"] = 3;
    expectError(writeGltf(j, "count.gltf"), {"animation 0 sampler 0", "output count 3 for 2 keys"});
    j["animations"][0]["samplers"][0]["interpolation"] = "BOUNCY";
    expectError(writeGltf(j, "interpolation.gltf"), {"unknown interpolation 'BOUNCY'"});
    j["animations"][0]["samplers"][0].erase("interpolation");
    j["animations"][0]["samplers"][0]["output"] = 0;  // the u16 indices: not float VEC3
    expectError(writeGltf(j, "type.gltf"),
                {"output of animation 0 sampler 0", "type SCALAR, expected VEC3"});
}

TEST_F(GltfSynthetic, AnimationOfANodeWithAMatrixIsDroppedWithAWarning) {
    json j = gltf();
    j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    j["accessors"].push_back(
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 1}, {"type", "SCALAR"}});
    j["accessors"].push_back(
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 1}, {"type", "VEC3"}});
    j["animations"] = json::array(
        {{{"name", "slide"},
          {"samplers", json::array({{{"input", 2}, {"output", 3}}})},
          {"channels",
           json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
    const Scene s = loadGltf(writeGltf(j));
    ASSERT_EQ(s.animations.size(), 1u);
    EXPECT_TRUE(s.animations[0].channels.empty());
    bool warned = false;
    for (const std::string& w : s.warnings)
        warned = warned || w.find("has a matrix, which glTF does not animate") != std::string::npos;
    EXPECT_TRUE(warned);
}

// A skinned mesh whose JOINTS_0 names a joint its node's skin lacks is refused, naming both.
TEST_F(GltfErrors, SkinJointBeyondTheSkin) {
    std::vector<uint8_t> skinData = {5, 0, 0, 0, 0, 0,
                                     0, 0, 0, 0, 0, 0};  // JOINTS_0: vertex 0 names joint 5
    for (int v = 0; v < 3; ++v)
        for (float w : {1.0f, 0.0f, 0.0f, 0.0f}) {
            uint8_t b[4];
            std::memcpy(b, &w, 4);
            skinData.insert(skinData.end(), b, b + 4);
        }
    static const char* kBase64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string uri = "data:application/octet-stream;base64,";
    for (size_t i = 0; i < skinData.size(); i += 3) {
        const uint32_t n = uint32_t(skinData[i]) << 16 |
                           uint32_t(i + 1 < skinData.size() ? skinData[i + 1] : 0) << 8 |
                           uint32_t(i + 2 < skinData.size() ? skinData[i + 2] : 0);
        uri += {kBase64[n >> 18 & 63], kBase64[n >> 12 & 63],
                i + 1 < skinData.size() ? kBase64[n >> 6 & 63] : '=',
                i + 2 < skinData.size() ? kBase64[n & 63] : '='};
    }
    json j = gltf();
    j["buffers"].push_back({{"uri", uri}, {"byteLength", skinData.size()}});
    j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 12}});
    j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 12}, {"byteLength", 48}});
    j["accessors"].push_back(
        {{"bufferView", 2}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
    j["accessors"].push_back(
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}});
    j["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 2;
    j["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = 3;
    j["skins"] = json::array({{{"joints", {0}}}});
    j["nodes"][0]["skin"] = 0;
    expectError(writeGltf(j, "skin.gltf"),
                {"node 0 'TriNode'", "names joint 5 of skin 0, which has 1"});
}
