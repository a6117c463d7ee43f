// Topology conversion, normal/tangent generation and builtin shapes (renderer/assets/Geometry.h).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "TestSupport.h"
#include "assets/Geometry.h"

using namespace fe::assets;

namespace {

glm::vec3 faceNormal(const Primitive& p, size_t t) {
    const glm::vec3& a = p.vertices[p.indices[t]].position;
    const glm::vec3& b = p.vertices[p.indices[t + 1]].position;
    const glm::vec3& c = p.vertices[p.indices[t + 2]].position;
    return glm::normalize(glm::cross(b - a, c - a));
}

// Quad in z = 0 with uv laid out the glTF way: u to the right, v down the image (v = 0 on top).
Primitive uvQuad(bool mirrorU) {
    Primitive p;
    const glm::vec3 pos[4] = {{-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}};
    for (const auto& q : pos) {
        Vertex v;
        v.position = q;
        v.normal = {0, 0, 1};
        float u = (q.x + 1) * 0.5f;
        v.uv0 = {mirrorU ? 1.0f - u : u, (1 - q.y) * 0.5f};
        v.tangent = {0, 0, 0, 0};
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

}  // namespace

TEST(Geometry, StripToListKeepsWindingPerGltfSpec) {
    EXPECT_EQ(triangleStripToList({0, 1, 2, 3, 4}),
              (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
    EXPECT_TRUE(triangleStripToList({0, 1}).empty());
}

TEST(Geometry, FanToListKeepsWindingPerGltfSpec) {
    EXPECT_EQ(triangleFanToList({0, 1, 2, 3}), (std::vector<uint32_t>{1, 2, 0, 2, 3, 0}));
    EXPECT_TRUE(triangleFanToList({}).empty());
}

TEST(Geometry, FlatNormalsUnweldAndFollowWinding) {
    // Two triangles folded along the x axis: one in z = 0 facing +Z, one in y = 0 facing -Y.
    Primitive p;
    for (glm::vec3 q :
         {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
        Vertex v;
        v.position = q;
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 1, 3};
    generateFlatNormals(p);
    ASSERT_EQ(p.vertices.size(), 6u);
    ASSERT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(p.vertices[i].normal, glm::vec3(0, 0, 1));
    for (int i = 3; i < 6; ++i) EXPECT_EQ(p.vertices[i].normal, glm::vec3(0, -1, 0));
}

TEST(Geometry, SmoothNormalsAverageSharedVertices) {
    Primitive p;
    for (glm::vec3 q :
         {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
        Vertex v;
        v.position = q;
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 1, 3};
    generateSmoothNormals(p);
    ASSERT_EQ(p.vertices.size(), 4u);
    // Vertices 0 and 1 are shared by both equal-area faces: halfway between +Z and -Y.
    glm::vec3 expected = glm::normalize(glm::vec3(0, -1, 1));
    EXPECT_NEAR(glm::distance(p.vertices[0].normal, expected), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(p.vertices[1].normal, expected), 0.0f, 1e-6f);
    EXPECT_EQ(p.vertices[2].normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(p.vertices[3].normal, glm::vec3(0, -1, 0));
}

TEST(Geometry, TangentsOfStandardQuadPointAlongUWithPositiveHandedness) {
    Primitive p = uvQuad(false);
    EXPECT_EQ(generateTangents(p), 0u);
    for (const auto& v : p.vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
        // bitangent = w * cross(n, t) = +Y = up the image, as glTF normal maps expect.
        EXPECT_EQ(v.tangent.w, 1.0f);
    }
}

TEST(Geometry, TangentsOfMirroredUvsFlipHandedness) {
    Primitive p = uvQuad(true);
    generateTangents(p);
    for (const auto& v : p.vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
        EXPECT_EQ(v.tangent.w, -1.0f);
    }
}

TEST(Geometry, TangentsFollowRotatedGeometryAndStretchedUvs) {
    // Rotate the quad arbitrarily and stretch u by 3: the tangent must follow dP/du in 3D,
    // stay unit length and orthogonal to the normal.
    Primitive p = uvQuad(false);
    glm::mat4 r = glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    for (auto& v : p.vertices) {
        v.position = glm::vec3(r * glm::vec4(v.position, 1.0f));
        v.normal = glm::mat3(r) * v.normal;
        v.uv0.x *= 3.0f;
    }
    generateTangents(p);
    glm::vec3 expected = glm::mat3(r) * glm::vec3(1, 0, 0);
    for (const auto& v : p.vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), expected), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-5f);
        EXPECT_EQ(v.tangent.w, 1.0f);
    }
}

TEST(Geometry, DegenerateUvsFallBackToAFrameOrthogonalToTheNormal) {
    Primitive p = uvQuad(false);
    for (auto& v : p.vertices) v.uv0 = {0.5f, 0.5f};
    EXPECT_EQ(generateTangents(p), 4u);
    for (const auto& v : p.vertices) {
        EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
    }
}

TEST(Geometry, AnyPerpendicularIsUnitAndOrthogonal) {
    for (glm::vec3 n :
         {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1),
          glm::normalize(glm::vec3(0.95f, 0.1f, -0.3f)), glm::normalize(glm::vec3(-1, 1, 1))}) {
        glm::vec3 t = anyPerpendicular(n);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-6f);
    }
}

TEST(Geometry, CubeHasOutwardCcwFacesAndConsistentTangents) {
    Primitive c = makeCube(1.0f, 0);
    ASSERT_EQ(c.vertices.size(), 24u);
    ASSERT_EQ(c.indices.size(), 36u);
    for (size_t t = 0; t < c.indices.size(); t += 3) {
        glm::vec3 n = faceNormal(c, t);
        const auto& v = c.vertices[c.indices[t]];
        EXPECT_NEAR(glm::distance(n, v.normal), 0.0f, 1e-6f);  // winding agrees with the normal
        EXPECT_GT(glm::dot(n, v.position), 0.0f);              // and points outwards
    }
    // The hand-set tangents must follow the same convention as generateTangents().
    Primitive g = c;
    generateTangents(g);
    for (size_t i = 0; i < c.vertices.size(); ++i) {
        EXPECT_NEAR(glm::distance(c.vertices[i].tangent, g.vertices[i].tangent), 0.0f, 1e-5f) << i;
    }
    EXPECT_EQ(c.bounds.min, glm::vec3(-1.0f));
    EXPECT_EQ(c.bounds.max, glm::vec3(1.0f));
}

TEST(Geometry, UvSphereHasOutwardCcwFacesAndConsistentTangents) {
    Primitive s = makeUVSphere(2.0f, 16, 8, 0);
    EXPECT_EQ(s.vertices.size(), 17u * 9u);
    EXPECT_EQ(s.indices.size(), (16u * 8u * 2u - 2u * 16u) * 3u);  // no pole slivers
    for (size_t t = 0; t < s.indices.size(); t += 3) {
        glm::vec3 centroid =
            (s.vertices[s.indices[t]].position + s.vertices[s.indices[t + 1]].position +
             s.vertices[s.indices[t + 2]].position) /
            3.0f;
        EXPECT_GT(glm::dot(faceNormal(s, t), centroid), 0.0f) << "triangle " << t / 3;
    }
    Primitive g = s;
    generateTangents(g);
    for (size_t i = 0; i < s.vertices.size(); ++i) {
        const auto& v = s.vertices[i];
        EXPECT_NEAR(glm::length(v.position), 2.0f, 1e-5f);
        if (std::abs(v.normal.y) > 0.999f) continue;       // poles: frame undefined
        if (v.uv0.x == 0.0f || v.uv0.x == 1.0f) continue;  // seam: faces on one side only
        EXPECT_NEAR(glm::distance(v.tangent, g.vertices[i].tangent), 0.0f, 0.05f) << i;
    }
}

TEST(Geometry, AabbTransformedCoversRotatedBox) {
    AABB b;
    b.extend(glm::vec3(-1, -2, -3));
    b.extend(glm::vec3(1, 2, 3));
    AABB t = b.transformed(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 0, 1)));
    EXPECT_NEAR(t.min.x, -2.0f, 1e-5f);
    EXPECT_NEAR(t.max.y, 1.0f, 1e-5f);
    EXPECT_NEAR(t.max.z, 3.0f, 1e-5f);
    EXPECT_TRUE(AABB{}.empty());
    EXPECT_TRUE(AABB{}.transformed(glm::mat4(1.0f)).empty());
}

TEST(Geometry, CameraLookAlongBuildsRigidRightHandedFrame) {
    Camera c = Camera::lookAlong({1, 2, 3}, {0, 0, 5}, {0, 1, 0}, 1.0f, 0.1f, 10.0f);
    EXPECT_NEAR(glm::distance(c.eye(), glm::vec3(1, 2, 3)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(c.forward(), glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(c.up(), glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::determinant(c.worldFromView), 1.0f, 1e-6f);
    glm::vec4 p = c.viewFromWorld() * glm::vec4(1, 2, 8, 1);  // 5 units ahead of the eye
    EXPECT_NEAR(p.x, 0.0f, 1e-5f);
    EXPECT_NEAR(p.y, 0.0f, 1e-5f);
    EXPECT_NEAR(p.z, -5.0f, 1e-5f);  // ahead = view -Z
    EXPECT_FALSE(c.infiniteFar());
}
