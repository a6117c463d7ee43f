// Helpers shared by the asset tests: where the Khronos samples are, scene invariants.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "assets/Scene.h"

namespace fe::assets::test {

// FE_SHARED_ASSETS (environment) overrides the folder CMake compiled in.
inline std::filesystem::path sharedAssetsDir() {
    if (const char* env = std::getenv("FE_SHARED_ASSETS"); env && *env) return env;
    return FE_SHARED_ASSETS;
}

inline bool sharedAssetsPresent() {
    std::error_code ec;
    return std::filesystem::is_directory(sharedAssetsDir(), ec);
}

inline std::string samplePath(const std::string& relative) {
    return (sharedAssetsDir() / relative).string();
}

// The samples are optional (the product works without them): skip, but only when the whole
// folder is absent. A present folder with a missing file is a failure, not a skip.
#define FE_REQUIRE_SAMPLES()                                                   \
    do {                                                                       \
        if (!::fe::assets::test::sharedAssetsPresent())                        \
            GTEST_SKIP() << "Khronos sample assets not found at "              \
                         << ::fe::assets::test::sharedAssetsDir()              \
                         << " (set FE_SHARED_ASSETS or FE_SHARED_ASSETS_DIR)"; \
    } while (0)

inline size_t totalVertices(const Scene& s) {
    size_t n = 0;
    for (const auto& m : s.meshes)
        for (const auto& p : m.primitives) n += p.vertices.size();
    return n;
}

inline size_t totalIndices(const Scene& s) {
    size_t n = 0;
    for (const auto& m : s.meshes)
        for (const auto& p : m.primitives) n += p.indices.size();
    return n;
}

inline const Material* findMaterial(const Scene& s, const std::string& name) {
    for (const auto& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

inline const MeshInstance* findInstance(const Scene& s, const std::string& name) {
    for (const auto& i : s.instances)
        if (i.name == name) return &i;
    return nullptr;
}

// What every loaded scene must satisfy for a renderer to upload it blindly.
inline void expectSceneInvariants(const Scene& s, const std::string& what) {
    SCOPED_TRACE(what);
    for (const auto& inst : s.instances) {
        ASSERT_LT(inst.meshIndex, s.meshes.size());
        EXPECT_EQ(inst.mirrored, glm::determinant(glm::mat3(inst.world)) < 0.0f) << inst.name;
    }
    for (const auto& m : s.meshes) {
        for (const auto& p : m.primitives) {
            ASSERT_LT(p.material, s.materials.size());
            ASSERT_EQ(p.indices.size() % 3, 0u);
            ASSERT_FALSE(p.vertices.empty());
            for (uint32_t i : p.indices) ASSERT_LT(i, p.vertices.size()) << m.name;
            for (const auto& v : p.vertices) {
                ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y) &&
                            std::isfinite(v.position.z));
                ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f) << m.name;
                ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-3f) << m.name;
                ASSERT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-3f) << m.name;
                ASSERT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f) << m.name;
                ASSERT_TRUE(p.bounds.min.x <= v.position.x && v.position.x <= p.bounds.max.x);
            }
        }
    }
    for (const auto& mat : s.materials) {
        for (const TextureRef* t :
             {&mat.baseColorTexture, &mat.metallicRoughnessTexture, &mat.normalTexture,
              &mat.emissiveTexture, &mat.occlusionTexture}) {
            if (t->valid()) {
                ASSERT_LT(size_t(t->index), s.textures.size()) << mat.name;
            }
        }
        if (mat.baseColorTexture.valid()) {
            EXPECT_TRUE(s.textures[size_t(mat.baseColorTexture.index)].srgb);
        }
        if (mat.normalTexture.valid()) {
            EXPECT_FALSE(s.textures[size_t(mat.normalTexture.index)].srgb);
        }
        if (mat.metallicRoughnessTexture.valid()) {
            EXPECT_FALSE(s.textures[size_t(mat.metallicRoughnessTexture.index)].srgb);
        }
    }
    for (const auto& t : s.textures) {
        ASSERT_GT(t.width, 0u);
        ASSERT_GT(t.height, 0u);
        ASSERT_EQ(t.pixels.size(), size_t(t.width) * t.height * 4) << t.name;
    }
    for (const auto& l : s.lights) {
        EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-4f);
        EXPECT_GE(l.range, 0.0f);
    }
    if (!s.instances.empty()) {
        EXPECT_FALSE(s.bounds.empty());
    }
}

}  // namespace fe::assets::test
