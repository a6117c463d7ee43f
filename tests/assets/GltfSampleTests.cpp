// The Khronos glTF sample models in ../shared/assets: real files, checked against facts taken
// from their JSON and binary data (counts, factors, transforms) rather than from the loader.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <tuple>

#include "TestSupport.h"
#include "assets/GltfLoader.h"

using namespace fe::assets;
using namespace fe::assets::test;

namespace {

Scene load(const std::string& rel, const LoadOptions& o = {}) {
    Scene s = loadGltf(samplePath(rel), o);
    expectSceneInvariants(s, rel);
    return s;
}

bool hasWarning(const Scene& s, const std::string& needle) {
    return std::any_of(s.warnings.begin(), s.warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

}  // namespace

TEST(GltfSamples, BoxInAllThreeContainers) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel :
         {"Box/glTF/Box.gltf", "Box/glTF-Binary/Box.glb", "Box/glTF-Embedded/Box.gltf"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);
        ASSERT_EQ(s.meshes.size(), 1u);
        ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
        EXPECT_EQ(s.meshes[0].primitives[0].vertices.size(), 24u);
        EXPECT_EQ(s.meshes[0].primitives[0].indices.size(), 36u);
        ASSERT_EQ(s.instances.size(), 1u);
        const Material* red = findMaterial(s, "Red");
        ASSERT_NE(red, nullptr);
        EXPECT_NEAR(red->baseColorFactor.r, 0.8f, 1e-6f);
        EXPECT_EQ(red->baseColorFactor.g, 0.0f);
        EXPECT_EQ(red->metallic, 0.0f);
        EXPECT_EQ(red->roughness, 1.0f);  // glTF default
        EXPECT_EQ(red->alphaMode, AlphaMode::Opaque);
        expectNear(s.bounds.min, glm::vec3(-0.5f));
        expectNear(s.bounds.max, glm::vec3(0.5f));
    }
}

TEST(GltfSamples, DefaultCameraAndLightRigAreTheDocumentedOnes) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("Box/glTF/Box.gltf");
    ASSERT_TRUE(s.hasDefaultCamera && s.hasDefaultLights);
    ASSERT_TRUE(s.camera);
    // Bounds +-0.5: radius = half diagonal, distance = r / sin(22.5 deg), from the front, above
    // and to the right; up stays +Y's side (the camera's up is +Y made orthogonal to the view).
    const float r = std::sqrt(3.0f) * 0.5f;
    const float d = r / std::sin(3.14159265f / 8.0f);
    const glm::vec3 v = glm::normalize(glm::vec3(0.5f, 0.45f, 1.0f));
    expectNear(s.camera->eye(), v * d, 1e-4f);
    expectNear(s.camera->forward(), -v);
    EXPECT_NEAR(glm::dot(s.camera->up(), s.camera->forward()), 0.0f, 1e-6f);
    EXPECT_GT(s.camera->up().y, 0.8f);
    EXPECT_NEAR(s.camera->up().x * s.camera->forward().z - s.camera->up().z * s.camera->forward().x,
                0.0f, 1e-6f)
        << "up leans only towards the view, not sideways";
    EXPECT_NEAR(s.camera->yfov, 3.14159265f / 4.0f, 1e-6f);
    EXPECT_NEAR(s.camera->znear, 0.5f * (d - r), 1e-4f);
    EXPECT_NEAR(s.camera->zfar, d + 2.0f * r, 1e-4f);

    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    // Given in view space, turned with the camera.
    auto world = [&](glm::vec3 v) {
        return glm::normalize(glm::mat3(s.camera->worldFromView) * glm::normalize(v));
    };
    expectNear(s.lights[0].direction, world({0.5f, -1.0f, -1.0f}));
    EXPECT_EQ(s.lights[0].intensity, 2.5f);
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    expectNear(s.lights[1].direction, world({-0.7f, 0.2f, -1.0f}));
    EXPECT_EQ(s.lights[1].intensity, 0.8f);
    EXPECT_EQ(s.lights[2].type, LightType::Point);
    expectNear(s.lights[2].position, s.camera->eye());
    EXPECT_NEAR(s.lights[2].intensity, 0.7f * d * d, 1e-3f);

    LoadOptions bare;
    bare.defaultCamera = false;
    bare.defaultLights = false;
    Scene b = load("Box/glTF/Box.gltf", bare);
    EXPECT_FALSE(b.camera.has_value());
    EXPECT_TRUE(b.lights.empty());
    EXPECT_FALSE(b.hasDefaultCamera || b.hasDefaultLights);
}

TEST(GltfSamples, BoxInterleavedMatchesBox) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"BoxInterleaved/glTF/BoxInterleaved.gltf",
                            "BoxInterleaved/glTF-Binary/BoxInterleaved.glb"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);
        Scene box = load("Box/glTF/Box.gltf");
        ASSERT_EQ(totalVertices(s), 24u);
        ASSERT_EQ(totalIndices(s), 36u);
        // Same cube: every (position, normal) pair of Box appears in the interleaved file.
        std::set<std::tuple<float, float, float, float, float, float>> a, b;
        for (const auto& v : s.meshes[0].primitives[0].vertices)
            a.insert(
                {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z});
        for (const auto& v : box.meshes[0].primitives[0].vertices)
            b.insert(
                {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z});
        EXPECT_EQ(a, b);
    }
}

TEST(GltfSamples, BoxTexturedDecodesItsSrgbTextureAndSampler) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel :
         {"BoxTextured/glTF/BoxTextured.gltf", "BoxTextured/glTF-Binary/BoxTextured.glb",
          "BoxTextured/glTF-Embedded/BoxTextured.gltf"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);
        ASSERT_EQ(s.textures.size(), 1u);
        const TextureImage& t = s.textures[0];
        EXPECT_EQ(t.width, 256u);
        EXPECT_EQ(t.height, 256u);
        EXPECT_TRUE(t.srgb);
        // sampler: magFilter LINEAR, minFilter NEAREST_MIPMAP_LINEAR, REPEAT x2
        EXPECT_EQ(t.sampler.magFilter, Filter::Linear);
        EXPECT_EQ(t.sampler.minFilter, Filter::Nearest);
        EXPECT_EQ(t.sampler.mipFilter, MipFilter::Linear);
        EXPECT_TRUE(t.sampler.mipmaps);
        EXPECT_EQ(t.sampler.wrapS, Wrap::Repeat);
        // Not a blank image: the Cesium logo has several colours.
        std::set<uint32_t> colours;
        for (size_t i = 0; i < t.pixels.size(); i += 4 * 97)
            colours.insert(uint32_t(t.pixels[i]) | uint32_t(t.pixels[i + 1]) << 8 |
                           uint32_t(t.pixels[i + 2]) << 16);
        EXPECT_GT(colours.size(), 3u);
        const Material& m = s.materials[s.meshes[0].primitives[0].material];
        EXPECT_EQ(m.baseColorTexture.index, 0);
        // TEXCOORD_0 accessor min (0, 0), max (6, 1): u repeats the logo six times.
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (const auto& v : s.meshes[0].primitives[0].vertices)
            lo = glm::min(lo, v.uv0), hi = glm::max(hi, v.uv0);
        EXPECT_EQ(lo, glm::vec2(0.0f, 0.0f));
        EXPECT_EQ(hi, glm::vec2(6.0f, 1.0f));
    }
}

TEST(GltfSamples, NonPowerOfTwoTexture) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"BoxTexturedNonPowerOfTwo/glTF/BoxTexturedNonPowerOfTwo.gltf",
                            "BoxTexturedNonPowerOfTwo/glTF-Binary/BoxTexturedNonPowerOfTwo.glb"}) {
        Scene s = load(rel);
        ASSERT_EQ(s.textures.size(), 1u);
        EXPECT_EQ(s.textures[0].width, 211u);
        EXPECT_EQ(s.textures[0].height, 211u);
    }
}

TEST(GltfSamples, HardFileNames) {
    FE_REQUIRE_SAMPLES();
    Scene spaces = load("Box With Spaces/glTF/Box With Spaces.gltf");
    EXPECT_EQ(totalVertices(spaces), 24u);
    EXPECT_EQ(spaces.textures.size(),
              3u);  // "glTF Logo With Spaces.png", "Normal Map.png", "Roughness Metallic.png"
    const Material& m = spaces.materials[spaces.meshes[0].primitives[0].material];
    EXPECT_TRUE(m.baseColorTexture.valid() && m.normalTexture.valid() &&
                m.metallicRoughnessTexture.valid());
    for (const char* rel :
         {"Unicode❤♻Test/glTF/Unicode❤♻Test.gltf", "Unicode❤♻Test/glTF-Binary/Unicode❤♻Test.glb"}) {
        Scene u = load(rel);
        EXPECT_EQ(totalVertices(u), 4u);
        EXPECT_EQ(totalIndices(u), 6u);
        ASSERT_EQ(u.textures.size(), 1u);
        EXPECT_EQ(u.textures[0].width, 256u);
    }
}

TEST(GltfSamples, MetalRoughSpheresFactorsUnclampedAndSameInGltfAndGlb) {
    FE_REQUIRE_SAMPLES();
    Scene a = load("MetalRoughSpheresNoTextures/glTF/MetalRoughSpheresNoTextures.gltf");
    Scene b = load("MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb");
    EXPECT_EQ(totalVertices(a), totalVertices(b));
    EXPECT_EQ(totalIndices(a), totalIndices(b));
    EXPECT_EQ(a.instances.size(), b.instances.size());
    EXPECT_TRUE(a.textures.empty());
    const Material* m0 = findMaterial(a, "mat_0");
    ASSERT_NE(m0, nullptr);
    EXPECT_NEAR(m0->baseColorFactor.r, 0.603827f, 1e-5f);
    EXPECT_EQ(m0->roughness, 0.0f) << "the 0.045 clamp belongs to the shaders";
    EXPECT_EQ(m0->metallic, 0.0f);
    EXPECT_TRUE(m0->doubleSided);
    const Material* m1 = findMaterial(a, "mat_1");
    ASSERT_NE(m1, nullptr);
    EXPECT_NEAR(m1->roughness, 1.0f / 6.0f, 1e-6f);
    int named = 0;
    for (const auto& m : a.materials) named += m.name.rfind("mat_", 0) == 0;
    EXPECT_EQ(named, 98);
}

TEST(GltfSamples, GeneratedTangentsForNormalTangentTest) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"NormalTangentTest/glTF/NormalTangentTest.gltf",
                            "NormalTangentTest/glTF-Binary/NormalTangentTest.glb"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);  // no TANGENT in the file, normal map present
        const Primitive& p = s.meshes.at(0).primitives.at(0);
        ASSERT_TRUE(s.materials[p.material].normalTexture.valid());
        size_t positive = 0, aligned = 0, triangles = 0;
        for (const auto& v : p.vertices) {
            EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-4f);
            EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-4f);
            positive += v.tangent.w > 0.0f;
        }
        // Independently of the generator: per triangle, the tangent must point along dP/du.
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            const Vertex& a = p.vertices[p.indices[t]];
            const Vertex& b = p.vertices[p.indices[t + 1]];
            const Vertex& c = p.vertices[p.indices[t + 2]];
            glm::vec2 d1 = b.uv0 - a.uv0, d2 = c.uv0 - a.uv0;
            float det = d1.x * d2.y - d2.x * d1.y;
            if (std::abs(det) < 1e-12f) continue;
            glm::vec3 dPdu =
                ((b.position - a.position) * d2.y - (c.position - a.position) * d1.y) / det;
            ++triangles;
            aligned += glm::dot(dPdu, glm::vec3(a.tangent)) > 0.0f;
        }
        EXPECT_GT(double(aligned) / double(triangles), 0.99);
        EXPECT_EQ(positive, p.vertices.size()) << "the model has no mirrored UVs";
    }
}

TEST(GltfSamples, NormalTangentMirrorTestKeepsFileTangentsWithBothHandedness) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("NormalTangentMirrorTest/glTF-Binary/NormalTangentMirrorTest.glb");
    const Primitive& p = s.meshes.at(0).primitives.at(0);
    size_t neg = 0;
    for (const auto& v : p.vertices) neg += v.tangent.w < 0.0f;
    EXPECT_GT(neg, 0u);
    EXPECT_LT(neg, p.vertices.size());
}

TEST(GltfSamples, OrientationTestNodeTransforms) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("OrientationTest/glTF/OrientationTest.gltf");
    EXPECT_EQ(s.instances.size(), 13u);
    // ArrowX1: translation (5,0,0), rotation quaternion (-0.3007, 0, 0, 0.9537) = -35 deg about X.
    const MeshInstance* x1 = findInstance(s, "ArrowX1");
    ASSERT_NE(x1, nullptr);
    expectNear(glm::vec3(x1->world[3]), glm::vec3(5, 0, 0));
    const float a = 2.0f * std::asin(-0.30070576f);
    expectNear(glm::mat3(x1->world) * glm::vec3(0, 1, 0), glm::vec3(0, std::cos(a), std::sin(a)),
               1e-4f);
    // ArrowX2 uses a matrix: translation (-5,0,0) in the last column.
    const MeshInstance* x2 = findInstance(s, "ArrowX2");
    ASSERT_NE(x2, nullptr);
    expectNear(glm::vec3(x2->world[3]), glm::vec3(-5, 0, 0));
    EXPECT_NEAR(x2->world[1][2], 0.08715573f, 1e-6f);  // column 1, row 2 of the file's matrix
    for (const auto& i : s.instances) EXPECT_FALSE(i.mirrored);
}

TEST(GltfSamples, CesiumMilkTruckHierarchy) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"CesiumMilkTruck/glTF/CesiumMilkTruck.gltf",
                            "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);
        EXPECT_EQ(s.meshes.size(), 2u);
        EXPECT_EQ(s.instances.size(), 3u);
        const MeshInstance* w0 = findInstance(s, "Wheels");
        const MeshInstance* w1 = findInstance(s, "Wheels.001");
        ASSERT_TRUE(w0 && w1);
        EXPECT_EQ(w0->meshIndex, w1->meshIndex);
        // Their parents are translated by x = 1.43267 and -1.35233 under a common rotation.
        EXPECT_NEAR(glm::distance(glm::vec3(w0->world[3]), glm::vec3(w1->world[3])),
                    1.43267f + 1.35233f, 1e-4f);
        // Yup2Zup rotates the truck so it stands on y = 0 (wheels touch the ground near y = 0).
        EXPECT_NEAR(s.bounds.min.y, 0.0f, 0.1f);
        EXPECT_GT(s.bounds.max.y, 2.0f);
        // Two glTF textures share one image and sampler: decoded once.
        ASSERT_EQ(s.textures.size(), 1u);
        EXPECT_EQ(s.textures[0].width, 2048u);
        // The wheels' animation is kept, not ignored.
        EXPECT_FALSE(hasWarning(s, "animation"));
        ASSERT_EQ(s.animations.size(), 1u);
        EXPECT_EQ(s.animations[0].name, "Wheels");
        const Material* glass = findMaterial(s, "glass");
        ASSERT_NE(glass, nullptr);
        EXPECT_NEAR(glass->baseColorFactor.g, 0.0405063f, 1e-6f);
    }
}

TEST(GltfSamples, NegativeScaleTestMirroredInstances) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"NegativeScaleTest/glTF/NegativeScaleTest.gltf",
                            "NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb"}) {
        SCOPED_TRACE(rel);
        Scene s = load(rel);
        EXPECT_EQ(s.instances.size(), 11u);
        // One negative scale (own or parent's) mirrors; two cancel out.
        std::set<std::string> mirrored,
            expected = {"NegativeScaleFront", "NotShinyMinus1", "Shiny1", "Dark1"};
        for (const auto& i : s.instances)
            if (i.mirrored) mirrored.insert(i.name);
        EXPECT_EQ(mirrored, expected);
        const MeshInstance* both = findInstance(s, "ShinyMinus1");
        ASSERT_NE(both, nullptr);
        EXPECT_FALSE(both->mirrored);
    }
}

TEST(GltfSamples, AlphaModes) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf");
    struct Expect {
        const char* name;
        AlphaMode mode;
        float cutoff;
    };
    for (const Expect& e :
         {Expect{"MatBlend", AlphaMode::Blend, 0.5f}, Expect{"MatCutoff25", AlphaMode::Mask, 0.25f},
          Expect{"MatCutoff75", AlphaMode::Mask, 0.75f},
          Expect{"MatCutoffDefault", AlphaMode::Mask, 0.5f},
          Expect{"MatOpaque", AlphaMode::Opaque, 0.5f},
          Expect{"MatBed", AlphaMode::Opaque, 0.5f}}) {
        const Material* m = findMaterial(s, e.name);
        ASSERT_NE(m, nullptr) << e.name;
        EXPECT_EQ(m->alphaMode, e.mode) << e.name;
        EXPECT_EQ(m->alphaCutoff, e.cutoff) << e.name;
        EXPECT_EQ(m->doubleSided, std::string(e.name) != "MatBed") << e.name;
        EXPECT_NEAR(m->roughness, std::string(e.name) == "MatBed" ? 1.0f : 0.8f, 1e-6f) << e.name;
    }
    // MatBed packs occlusion + roughness + metallic in one linear texture.
    const Material* bed = findMaterial(s, "MatBed");
    EXPECT_EQ(bed->occlusionTexture.index, bed->metallicRoughnessTexture.index);
    EXPECT_TRUE(bed->normalTexture.valid());
    EXPECT_NE(bed->normalTexture.index, bed->baseColorTexture.index);
}

TEST(GltfSamples, LightsPunctualLamp) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("LightsPunctualLamp/glTF/LightsPunctualLamp.gltf");
    EXPECT_FALSE(s.hasDefaultLights);
    ASSERT_EQ(s.lights.size(), 5u);
    for (const auto& l : s.lights) EXPECT_EQ(l.type, LightType::Point);
    const Light& p = s.lights[0];  // node 3 holds light 0 "Point"
    EXPECT_EQ(p.name, "Point");
    expectNear(p.color, glm::vec3(1.0f, 0.631875f, 0.239100f), 1e-5f);
    EXPECT_EQ(p.intensity, 15.0f);
    EXPECT_EQ(p.range, 0.0f);
    expectNear(p.position, glm::vec3(0.04622355f, 0.90779734f, 0.00669663f));
    // The node matrix maps local -Z to world -Y.
    expectNear(p.direction, glm::vec3(0, -1, 0), 1e-6f);
    EXPECT_EQ(s.lights[4].intensity, 180.0f);
    // The lamp's shade: KHR_materials_transmission with a texture (material 2).
    EXPECT_FALSE(hasWarning(s, "KHR_materials_transmission"));
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[2].transmission, 1.0f);
    EXPECT_TRUE(s.materials[2].transmissionTexture.valid());
    EXPECT_TRUE(s.materials[2].transmissive());
}

TEST(GltfSamples, TextureSamplerSettings) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("TextureSettingsTest/glTF/TextureSettingsTest.gltf");
    auto samplerOf = [&](const char* material) {
        const Material* m = findMaterial(s, material);
        EXPECT_NE(m, nullptr) << material;
        EXPECT_TRUE(m->baseColorTexture.valid()) << material;
        return s.textures.at(size_t(m->baseColorTexture.index)).sampler;
    };
    EXPECT_EQ(samplerOf("TextureMirrorMaterialT").wrapT, Wrap::MirroredRepeat);
    EXPECT_EQ(samplerOf("TextureMirrorMaterialT").wrapS, Wrap::Repeat);
    EXPECT_EQ(samplerOf("TextureMirrorMaterialS").wrapS, Wrap::MirroredRepeat);
    EXPECT_EQ(samplerOf("TextureClampMaterialT").wrapT, Wrap::ClampToEdge);
    EXPECT_EQ(samplerOf("TextureClampMaterialS").wrapS, Wrap::ClampToEdge);
    EXPECT_EQ(samplerOf("TextureRepeatMaterialT").wrapT, Wrap::Repeat);
    EXPECT_TRUE(findMaterial(s, "DoubleSidedMaterial")->doubleSided);
    EXPECT_NEAR(findMaterial(s, "BackgroundMaterial")->baseColorFactor.b, 0.64f, 1e-6f);
}

TEST(GltfSamples, TextureCoordinateTest) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"TextureCoordinateTest/glTF/TextureCoordinateTest.gltf",
                            "TextureCoordinateTest/glTF-Binary/TextureCoordinateTest.glb"}) {
        Scene s = load(rel);
        EXPECT_EQ(s.instances.size(), 5u);
        EXPECT_EQ(s.textures.size(), 1u);
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (const auto& m : s.meshes)
            for (const auto& p : m.primitives)
                for (const auto& v : p.vertices) lo = glm::min(lo, v.uv0), hi = glm::max(hi, v.uv0);
        EXPECT_NEAR(lo.x, 0.0f, 1e-6f);
        EXPECT_NEAR(hi.x, 1.0f, 1e-6f);
    }
}

TEST(GltfSamples, MeshPrimitiveModesStripsAndFansKeepWinding) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf");
    // TRIANGLES (18 indices), TRIANGLE_STRIP (6 -> 4 triangles), TRIANGLE_FAN (8 -> 6 triangles).
    EXPECT_EQ(s.instances.size(), 3u);
    EXPECT_EQ(totalIndices(s), 18u + 12u + 18u);
    for (const char* mode : {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"}) {
        EXPECT_TRUE(hasWarning(s, std::string(mode) + " primitive skipped")) << mode;
    }
    // The file has no normals: flat normals follow the winding, and every converted triangle
    // must face the viewer (+Z) like the TRIANGLES mesh does.
    for (const auto& m : s.meshes)
        for (const auto& p : m.primitives)
            for (const auto& v : p.vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-5f) << m.name;
}

TEST(GltfSamples, SparseAccessorIsApplied) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"SimpleSparseAccessor/glTF/SimpleSparseAccessor.gltf",
                            "SimpleSparseAccessor/glTF-Embedded/SimpleSparseAccessor.gltf"}) {
        Scene s = load(rel);
        // Base positions are a 7x2 grid with y in {0, 1}; the sparse part moves vertices
        // 8, 10, 12 to (1,2,0), (3,3,0), (5,4,0).
        std::set<std::pair<float, float>> xy;
        for (const auto& v : s.meshes.at(0).primitives.at(0).vertices)
            xy.insert({v.position.x, v.position.y});
        EXPECT_TRUE(xy.count({1.0f, 2.0f}));
        EXPECT_TRUE(xy.count({3.0f, 3.0f}));
        EXPECT_TRUE(xy.count({5.0f, 4.0f}));
        EXPECT_FALSE(xy.count({1.0f, 1.0f})) << "vertex 8 must have been replaced";
        EXPECT_EQ(s.bounds.max.y, 4.0f);
    }
}

TEST(GltfSamples, TrianglesWithAndWithoutIndices) {
    FE_REQUIRE_SAMPLES();
    Scene a = load("Triangle/glTF/Triangle.gltf");
    Scene b = load("TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf");
    for (const Scene* s : {&a, &b}) {
        ASSERT_EQ(totalVertices(*s), 3u);
        const Primitive& p = s->meshes[0].primitives[0];
        EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2}));
        for (const auto& v : p.vertices) expectNear(v.normal, glm::vec3(0, 0, 1));
        EXPECT_EQ(s->materials[p.material].name, "default");  // no material in the file
    }
}

TEST(GltfSamples, TwoSidedPlaneAndSuzanneKeepFileTangents) {
    FE_REQUIRE_SAMPLES();
    Scene p = load("TwoSidedPlane/glTF/TwoSidedPlane.gltf");
    EXPECT_TRUE(findMaterial(p, "TwoSidedPlane")->doubleSided);
    Scene s = load("Suzanne/glTF/Suzanne.gltf");
    EXPECT_EQ(totalVertices(s), 11808u);
    EXPECT_EQ(s.textures.size(), 2u);
}

TEST(GltfSamples, SimpleInstancingExtension) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"SimpleInstancing/glTF/SimpleInstancing.gltf",
                            "SimpleInstancing/glTF-Binary/SimpleInstancing.glb"}) {
        Scene s = load(rel);
        ASSERT_EQ(s.instances.size(), 125u);
        std::set<std::tuple<float, float, float>> origins;
        for (const auto& i : s.instances) {
            EXPECT_EQ(i.meshIndex, 0u);
            origins.insert({i.world[3].x, i.world[3].y, i.world[3].z});
        }
        EXPECT_EQ(origins.size(), 125u);
    }
}

TEST(GltfSamples, CamerasAreListedAndTheFirstIsDrawnFrom) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("Cameras/glTF/Cameras.gltf");
    ASSERT_TRUE(s.camera);
    EXPECT_FALSE(s.hasDefaultCamera);
    EXPECT_NEAR(s.camera->yfov, 0.7f, 1e-6f);
    EXPECT_NEAR(s.camera->znear, 0.01f, 1e-6f);
    EXPECT_EQ(s.camera->zfar, 100.0f);
    ASSERT_TRUE(s.camera->aspectRatio);
    EXPECT_EQ(*s.camera->aspectRatio, 1.0f);
    expectNear(s.camera->eye(), glm::vec3(0.5f, 0.5f, 3.0f));
    expectNear(s.camera->forward(), glm::vec3(0, 0, -1));
    // Both cameras are listed, the orthographic one with its half extents.
    EXPECT_FALSE(hasWarning(s, "orthographic"));
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_EQ(s.cameraIndex, 0);
    EXPECT_FALSE(s.cameras[0].orthographic);
    ASSERT_TRUE(s.cameras[1].orthographic);
    EXPECT_EQ(*s.cameras[1].orthographic, glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(s.cameras[1].znear, 0.01f);
    EXPECT_EQ(s.cameras[1].zfar, 100.0f);
    expectNear(s.cameras[1].eye(), glm::vec3(0.5f, 0.5f, 3.0f));
    // No lights in the file: the default rig follows the file's camera (headlight at its eye).
    ASSERT_TRUE(s.hasDefaultLights);
    ASSERT_EQ(s.lights.size(), 3u);
    expectNear(s.lights[2].position, s.camera->eye());
}

TEST(GltfSamples, MultipleScenesUsesTheDefaultSceneOrTheRequestedOne) {
    FE_REQUIRE_SAMPLES();
    // "scene": 1 -> the square (4 vertices, 2 triangles; unwelded to 6 for flat normals).
    Scene def = load("MultipleScenes/glTF/MultipleScenes.gltf");
    ASSERT_EQ(def.instances.size(), 1u);
    EXPECT_EQ(totalIndices(def), 6u);
    LoadOptions o;
    o.scene = 0;  // the triangle
    Scene first = load("MultipleScenes/glTF/MultipleScenes.gltf", o);
    ASSERT_EQ(first.instances.size(), 1u);
    EXPECT_EQ(totalIndices(first), 3u);
    o.scene = 2;
    try {
        loadGltf(samplePath("MultipleScenes/glTF/MultipleScenes.gltf"), o);
        FAIL() << "scene 2 does not exist";
    } catch (const AssetError& e) {
        EXPECT_NE(std::string(e.what()).find("scene 2"), std::string::npos) << e.what();
    }
}

TEST(GltfSamples, EmissiveStrength) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel : {"EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf",
                            "EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb"}) {
        Scene s = load(rel);
        const glm::vec3 base(0.1f, 0.5f, 0.9f);
        for (auto [name, k] : {std::pair{"Emit1", 1.0f},
                               {"Emit2", 2.0f},
                               {"Emit4", 4.0f},
                               {"Emit8", 8.0f},
                               {"Emit16", 16.0f}}) {
            const Material* m = findMaterial(s, name);
            ASSERT_NE(m, nullptr) << name;
            expectNear(m->emissiveFactor, base * k, 1e-5f);
            EXPECT_EQ(m->emissiveStrength, k);
        }
    }
}

TEST(GltfSamples, UnlitIsARequiredExtensionWeSupport) {
    FE_REQUIRE_SAMPLES();
    Scene s = load("UnlitTest/glTF/UnlitTest.gltf");
    ASSERT_NE(findMaterial(s, "Orange"), nullptr);
    EXPECT_TRUE(findMaterial(s, "Orange")->unlit);
    EXPECT_TRUE(findMaterial(s, "Blue")->unlit);
}

TEST(GltfSamples, SkinsMorphsAndAnimationsLoadInTheRestPose) {
    FE_REQUIRE_SAMPLES();
    Scene fox = load("Fox/glTF/Fox.gltf");
    EXPECT_EQ(totalVertices(fox), 1728u);
    EXPECT_EQ(fox.textures.size(), 1u);
    EXPECT_FALSE(hasWarning(fox, "skin"));
    EXPECT_FALSE(hasWarning(fox, "animation"));
    ASSERT_EQ(fox.animations.size(), 3u);
    EXPECT_EQ(fox.animations[0].name, "Survey");
    EXPECT_EQ(fox.animations[1].name, "Walk");
    EXPECT_EQ(fox.animations[2].name, "Run");
    ASSERT_EQ(fox.instances.size(), 1u);
    EXPECT_EQ(fox.instances[0].skin, 0);
    EXPECT_EQ(fox.instances[0].joints.size(), fox.skins[0].joints.size());
    // The mesh keeps its rest pose and every vertex its influences (unwelded with the flat normals).
    const Primitive& foxMesh = fox.meshes[0].primitives[0];
    EXPECT_TRUE(foxMesh.flatNormals);
    EXPECT_EQ(foxMesh.skin.size(), foxMesh.vertices.size());
    EXPECT_GT(fox.bounds.size().y,
              70.0f);  // standing fox, about 79 units tall (bounds are conservative)

    // RiggedSimple's mesh is a cylinder along +-4.575 on its own Z; the skeleton under the
    // "Z_UP" node stands it up: the posed bounds (conservative) hold it standing along Y.
    Scene rig = load("RiggedSimple/glTF/RiggedSimple.gltf");
    EXPECT_GE(rig.bounds.size().y, 2.0f * 4.575077f - 1e-3f);
    EXPECT_EQ(rig.instances[0].joints.size(), 2u);

    // SimpleMorph: mesh weights (0.5, 0.5) become the instance's; the vertices stay the base mesh
    // and vertex 2, (0.5, 0.5, 0) in the base, moves by (-1, 1, 0) and (1, 1, 0) in the targets.
    Scene morph = load("SimpleMorph/glTF/SimpleMorph.gltf");
    EXPECT_FALSE(hasWarning(morph, "morph targets"));
    ASSERT_EQ(totalVertices(morph), 3u);
    const Primitive& tri = morph.meshes[0].primitives[0];
    ASSERT_EQ(tri.targets.size(), 2u);
    EXPECT_EQ(morph.instances[0].weights, (std::vector<float>{0.5f, 0.5f}));
    std::set<std::pair<float, float>> xy;
    for (const auto& v : tri.vertices) xy.insert({v.position.x, v.position.y});
    EXPECT_EQ(xy, (std::set<std::pair<float, float>>{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.5f, 0.5f}}));
    EXPECT_GE(morph.bounds.max.y, 1.5f);  // the posed bounds hold the morphed vertex
}

TEST(GltfSamples, TextureTransformsAreRead) {
    FE_REQUIRE_SAMPLES();
    const Scene s = load("TextureTransformTest/glTF/TextureTransformTest.gltf");
    EXPECT_FALSE(hasWarning(s, "KHR_texture_transform"));
    const Material* rotation = findMaterial(s, "Rotation");
    const Material* all = findMaterial(s, "All");
    const Material* offsetU = findMaterial(s, "Offset U");
    ASSERT_TRUE(rotation && all && offsetU);
    EXPECT_NEAR(rotation->baseColorTexture.transform.rotation, 0.39269908f, 1e-6f);
    EXPECT_EQ(offsetU->baseColorTexture.transform.offset, glm::vec2(0.5f, 0.0f));
    EXPECT_EQ(all->baseColorTexture.transform.offset, glm::vec2(-0.2f, -0.1f));
    EXPECT_EQ(all->baseColorTexture.transform.scale, glm::vec2(1.5f));
    EXPECT_NEAR(all->baseColorTexture.transform.rotation, 0.3f, 1e-6f);
    // T R S as the Sample Viewer evaluates it: (0, 0) lands on the offset, (1, 0) scaled and
    // turned towards -v (v grows down the image: counter-clockwise as the image is seen).
    const TextureTransform& t = all->baseColorTexture.transform;
    const glm::vec2 o = t.apply({0.0f, 0.0f}), u = t.apply({1.0f, 0.0f});
    EXPECT_NEAR(o.x, -0.2f, 1e-6f);
    EXPECT_NEAR(o.y, -0.1f, 1e-6f);
    EXPECT_NEAR(u.x, -0.2f + 1.5f * std::cos(0.3f), 1e-6f);
    EXPECT_NEAR(u.y, -0.1f - 1.5f * std::sin(0.3f), 1e-6f);
}

TEST(GltfSamples, SecondTextureCoordinateSetIsRead) {
    FE_REQUIRE_SAMPLES();
    const Scene s = load("MultiUVTest/glTF/MultiUVTest.gltf");
    EXPECT_FALSE(hasWarning(s, "TEXCOORD_1"));
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].emissiveTexture.texCoord, 1u);
    EXPECT_EQ(s.materials[0].baseColorTexture.texCoord, 0u);
    // The two sets differ (the file maps its two images differently).
    size_t differ = 0;
    for (const Vertex& v : s.meshes[0].primitives[0].vertices) differ += v.uv0 != v.uv1;
    EXPECT_GT(differ, s.meshes[0].primitives[0].vertices.size() / 2);
}

TEST(GltfSamples, VertexColoursAreRead) {
    FE_REQUIRE_SAMPLES();
    const Scene test = load("VertexColorTest/glTF/VertexColorTest.gltf");
    EXPECT_FALSE(hasWarning(test, "COLOR_0"));
    std::set<std::tuple<float, float, float, float>> colours;
    for (const Mesh& m : test.meshes)
        for (const Primitive& p : m.primitives)
            for (const Vertex& v : p.vertices)
                colours.insert({v.color.r, v.color.g, v.color.b, v.color.a});
    EXPECT_GT(colours.size(), 2u);  // white (the label without COLOR_0) and the file's colours
    // BoxVertexColors: VEC3 colours, alpha 1.
    const Scene box = load("BoxVertexColors/glTF/BoxVertexColors.gltf");
    size_t coloured = 0;
    for (const Vertex& v : box.meshes[0].primitives[0].vertices) {
        EXPECT_EQ(v.color.a, 1.0f);
        coloured += glm::vec3(v.color) != glm::vec3(1.0f);
    }
    EXPECT_GT(coloured, 0u);
}

TEST(GltfSamples, IgnoredFeaturesAreReportedAsWarnings) {
    FE_REQUIRE_SAMPLES();
    const Scene boxAnimated = load("BoxAnimated/glTF/BoxAnimated.gltf");
    EXPECT_FALSE(hasWarning(boxAnimated, "animation"));
    EXPECT_EQ(boxAnimated.animations.size(), 1u);
    EXPECT_TRUE(load("Box/glTF/Box.gltf").warnings.empty());
}

TEST(GltfSamples, DracoVariantsFailWithUnsupportedRequiredExtension) {
    FE_REQUIRE_SAMPLES();
    for (const char* rel :
         {"Box/glTF-Draco/Box.gltf", "RiggedSimple/glTF-Draco/RiggedSimple.gltf"}) {
        try {
            loadGltf(samplePath(rel));
            FAIL() << rel << " should not load";
        } catch (const AssetError& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find("unsupported required extension KHR_draco_mesh_compression"),
                      std::string::npos)
                << msg;
            EXPECT_NE(msg.find(rel), std::string::npos) << "names the file: " << msg;
        }
    }
}

// Every .gltf/.glb in the folder either loads and satisfies the invariants, or (Draco) fails
// with an AssetError. Catches regressions on files no dedicated test covers.
TEST(GltfSamples, EverySampleLoadsOrFailsCleanly) {
    FE_REQUIRE_SAMPLES();
    size_t loaded = 0, refused = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(sharedAssetsDir())) {
        std::string ext = e.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        std::string rel = std::filesystem::relative(e.path(), sharedAssetsDir()).string();
        bool draco = rel.find("glTF-Draco") != std::string::npos;
        try {
            Scene s = loadGltf(e.path().string());
            expectSceneInvariants(s, rel);
            EXPECT_FALSE(draco) << rel;
            EXPECT_FALSE(s.instances.empty()) << rel;
            ++loaded;
        } catch (const AssetError& err) {
            EXPECT_TRUE(draco) << rel << ": " << err.what();
            ++refused;
        }
    }
    EXPECT_GE(loaded, 80u);
    EXPECT_EQ(refused, 2u);
}
