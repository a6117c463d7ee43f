#include "assets/Geometry.h"

#include <algorithm>
#include <cmath>

namespace fe::assets {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// Length below which a direction is treated as zero (degenerate triangle, cancelled sum).
constexpr float kTiny = 1e-12f;

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
    float len2 = glm::dot(v, v);
    if (!(len2 > kTiny) || !std::isfinite(len2)) return fallback;
    return v / std::sqrt(len2);
}

// Angle between the two edges leaving corner a; used as the accumulation weight so a vertex's
// frame does not depend on how its fan is triangulated.
float cornerAngle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 e1 = b - a, e2 = c - a;
    float l1 = glm::length(e1), l2 = glm::length(e2);
    if (!(l1 > 0.0f) || !(l2 > 0.0f)) return 0.0f;
    float cosA = std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0f, 1.0f);
    return std::acos(cosA);
}

}  // namespace

std::vector<uint32_t> triangleStripToList(const std::vector<uint32_t>& strip) {
    std::vector<uint32_t> out;
    if (strip.size() < 3) return out;
    out.reserve((strip.size() - 2) * 3);
    for (size_t i = 0; i + 2 < strip.size(); ++i) {
        if (i % 2 == 0) {
            out.insert(out.end(), {strip[i], strip[i + 1], strip[i + 2]});
        } else {
            out.insert(out.end(), {strip[i], strip[i + 2], strip[i + 1]});
        }
    }
    return out;
}

std::vector<uint32_t> triangleFanToList(const std::vector<uint32_t>& fan) {
    std::vector<uint32_t> out;
    if (fan.size() < 3) return out;
    out.reserve((fan.size() - 2) * 3);
    for (size_t i = 0; i + 2 < fan.size(); ++i)
        out.insert(out.end(), {fan[i + 1], fan[i + 2], fan[0]});
    return out;
}

glm::vec3 anyPerpendicular(const glm::vec3& n) {
    // Gram-Schmidt against the axis least aligned with n: never degenerate for a unit n.
    glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return safeNormalize(a - n * glm::dot(a, n), glm::vec3(1, 0, 0));
}

void generateFlatNormals(Primitive& prim) {
    std::vector<Vertex> out;
    out.reserve(prim.indices.size());
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        Vertex v0 = prim.vertices[prim.indices[t]];
        Vertex v1 = prim.vertices[prim.indices[t + 1]];
        Vertex v2 = prim.vertices[prim.indices[t + 2]];
        glm::vec3 n = safeNormalize(
            glm::cross(v1.position - v0.position, v2.position - v0.position), glm::vec3(0, 0, 1));
        v0.normal = v1.normal = v2.normal = n;
        out.insert(out.end(), {v0, v1, v2});
    }
    prim.vertices = std::move(out);
    prim.indices.resize(prim.vertices.size());
    for (size_t i = 0; i < prim.indices.size(); ++i) prim.indices[i] = static_cast<uint32_t>(i);
}

std::vector<glm::vec3> computeSmoothNormals(const Primitive& prim) {
    std::vector<glm::vec3> acc(prim.vertices.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        uint32_t i0 = prim.indices[t], i1 = prim.indices[t + 1], i2 = prim.indices[t + 2];
        const glm::vec3& p0 = prim.vertices[i0].position;
        // Unnormalised cross product: its length is twice the area, the weight we want.
        glm::vec3 n = glm::cross(prim.vertices[i1].position - p0, prim.vertices[i2].position - p0);
        acc[i0] += n;
        acc[i1] += n;
        acc[i2] += n;
    }
    for (auto& n : acc) n = safeNormalize(n, glm::vec3(0, 0, 1));
    return acc;
}

void generateSmoothNormals(Primitive& prim) {
    std::vector<glm::vec3> n = computeSmoothNormals(prim);
    for (size_t i = 0; i < n.size(); ++i) prim.vertices[i].normal = n[i];
}

size_t generateTangents(Primitive& prim, uint32_t texCoord) {
    auto uvOf = [texCoord](const Vertex& v) { return texCoord == 1 ? v.uv1 : v.uv0; };
    const size_t n = prim.vertices.size();
    std::vector<glm::vec3> tAcc(n, glm::vec3(0.0f)), bAcc(n, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        const uint32_t idx[3] = {prim.indices[t], prim.indices[t + 1], prim.indices[t + 2]};
        const Vertex& v0 = prim.vertices[idx[0]];
        const Vertex& v1 = prim.vertices[idx[1]];
        const Vertex& v2 = prim.vertices[idx[2]];
        glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
        glm::vec2 d1 = uvOf(v1) - uvOf(v0), d2 = uvOf(v2) - uvOf(v0);
        float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) continue;  // degenerate UVs
        float r = 1.0f / det;
        glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) * r;
        glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) * r;
        glm::vec3 imageUp = -dPdv;  // glTF v grows downwards in the image
        for (int c = 0; c < 3; ++c) {
            const Vertex& v = prim.vertices[idx[c]];
            const Vertex& a = prim.vertices[idx[(c + 1) % 3]];
            const Vertex& b = prim.vertices[idx[(c + 2) % 3]];
            float w = cornerAngle(v.position, a.position, b.position);
            if (!(w > 0.0f)) continue;
            glm::vec3 nrm = safeNormalize(v.normal, glm::vec3(0, 0, 1));
            // Project into this vertex's tangent plane and normalise, so big triangles and
            // stretched UVs do not dominate (the MikkTSpace choice).
            glm::vec3 tp = dPdu - nrm * glm::dot(nrm, dPdu);
            glm::vec3 bp = imageUp - nrm * glm::dot(nrm, imageUp);
            float tl = glm::length(tp), bl = glm::length(bp);
            if (tl > kTiny) tAcc[idx[c]] += tp * (w / tl);
            if (bl > kTiny) bAcc[idx[c]] += bp * (w / bl);
        }
    }
    size_t fallbacks = 0;
    for (size_t i = 0; i < n; ++i) {
        Vertex& v = prim.vertices[i];
        glm::vec3 nrm = safeNormalize(v.normal, glm::vec3(0, 0, 1));
        glm::vec3 t = tAcc[i] - nrm * glm::dot(nrm, tAcc[i]);
        float tl = glm::length(t);
        if (!(tl > 1e-6f) || !std::isfinite(tl)) {
            v.tangent = glm::vec4(anyPerpendicular(nrm), 1.0f);
            ++fallbacks;
            continue;
        }
        t /= tl;
        float w = glm::dot(glm::cross(nrm, t), bAcc[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangent = glm::vec4(t, w);
    }
    return fallbacks;
}

void setFallbackTangents(Primitive& prim) {
    for (auto& v : prim.vertices) {
        v.tangent = glm::vec4(anyPerpendicular(safeNormalize(v.normal, glm::vec3(0, 0, 1))), 1.0f);
    }
}

void computeBounds(Primitive& prim) {
    prim.bounds = AABB{};
    for (const auto& v : prim.vertices) prim.bounds.extend(v.position);
}

void computeBounds(Mesh& mesh) {
    mesh.bounds = AABB{};
    for (auto& p : mesh.primitives) {
        computeBounds(p);
        mesh.bounds.extend(p.bounds);
    }
}

Primitive makeCube(float h, uint32_t material) {
    struct Face {
        glm::vec3 n, right, up;  // right = +u, up = -v (image up)
    };
    const Face faces[6] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    Primitive p;
    p.material = material;
    for (const Face& f : faces) {
        uint32_t base = static_cast<uint32_t>(p.vertices.size());
        // Corners: top-left, bottom-left, bottom-right, top-right in image space.
        const glm::vec2 c[4] = {{-1, 1}, {-1, -1}, {1, -1}, {1, 1}};
        for (const auto& k : c) {
            Vertex v;
            v.position = (f.n + f.right * k.x + f.up * k.y) * h;
            v.normal = f.n;
            v.uv0 = glm::vec2((k.x + 1.0f) * 0.5f, (1.0f - k.y) * 0.5f);
            v.tangent = glm::vec4(f.right, 1.0f);  // right x up == n for every face above
            p.vertices.push_back(v);
        }
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    computeBounds(p);
    return p;
}

Primitive makeUVSphere(float radius, uint32_t slices, uint32_t stacks, uint32_t material) {
    slices = std::max(slices, 3u);
    stacks = std::max(stacks, 2u);
    Primitive p;
    p.material = material;
    for (uint32_t i = 0; i <= stacks; ++i) {
        float v = float(i) / float(stacks);
        float theta = v * kPi;  // from +Y
        for (uint32_t j = 0; j <= slices; ++j) {
            float u = float(j) / float(slices);
            float phi = u * 2.0f * kPi;
            // phi = 0 at +Z, growing towards +X: u increases to the right seen from outside.
            glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
            Vertex vert;
            vert.position = n * radius;
            vert.normal = n;
            vert.uv0 = glm::vec2(u, v);
            // dP/dphi direction; well defined even at the poles.
            vert.tangent = glm::vec4(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
            p.vertices.push_back(vert);
        }
    }
    const uint32_t row = slices + 1;
    for (uint32_t i = 0; i < stacks; ++i) {
        for (uint32_t j = 0; j < slices; ++j) {
            uint32_t a = i * row + j, b = (i + 1) * row + j, c = (i + 1) * row + j + 1,
                     d = i * row + j + 1;
            if (i != 0) p.indices.insert(p.indices.end(), {a, b, d});  // skip pole slivers
            if (i + 1 != stacks) p.indices.insert(p.indices.end(), {d, b, c});
        }
    }
    computeBounds(p);
    return p;
}

Primitive makeQuad(float hw, float hh, uint32_t material) {
    Primitive p;
    p.material = material;
    const glm::vec2 c[4] = {{-1, 1}, {-1, -1}, {1, -1}, {1, 1}};
    for (const auto& k : c) {
        Vertex v;
        v.position = glm::vec3(k.x * hw, k.y * hh, 0.0f);
        v.normal = glm::vec3(0, 0, 1);
        v.uv0 = glm::vec2((k.x + 1.0f) * 0.5f, (1.0f - k.y) * 0.5f);
        v.tangent = glm::vec4(1, 0, 0, 1);
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 2, 3};
    computeBounds(p);
    return p;
}

}  // namespace fe::assets
