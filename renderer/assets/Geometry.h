// Layer 5 (Communication: Asset Loader): CPU geometry utilities used by the glTF loader and the
// builtin scenes: primitive topology conversion, normal and tangent generation, simple shapes.
#pragma once
#include <cstdint>
#include <vector>

#include "assets/Scene.h"

namespace fe::assets {

// glTF 2.0 spec section 3.7.2.1 triangle orderings, so converted strips/fans keep their winding.
// Strip triangle i: (i, i+1, i+2) for even i, (i, i+2, i+1) for odd i. Fan: (i+1, i+2, 0).
std::vector<uint32_t> triangleStripToList(const std::vector<uint32_t>& strip);
std::vector<uint32_t> triangleFanToList(const std::vector<uint32_t>& fan);

// Face normals, as the glTF spec asks for primitives without NORMAL: every triangle gets its
// own three vertices (the primitive is unwelded), indices become 0..3t-1.
void generateFlatNormals(Primitive& prim);

// Area-weighted average of the faces sharing each vertex index (no unwelding).
std::vector<glm::vec3> computeSmoothNormals(const Primitive& prim);
void generateSmoothNormals(Primitive& prim);

// Per-vertex tangent frames from positions, normals and a uv set, MikkTSpace-like: each triangle's
// dP/du and image-up direction (-dP/dv: glTF's v axis points down the image) are projected into
// the vertex's tangent plane, normalised and accumulated weighted by the corner angle; the sum
// is Gram-Schmidt orthonormalised against the normal, and w = +-1 records whether the
// accumulated image-up direction agrees with cross(n, t) (w = -1 for mirrored UVs).
// Written here because MikkTSpace itself has no Debian package; unlike MikkTSpace it never
// splits a vertex whose triangles disagree on handedness (glTF exporters already split UV
// seams), so results match MikkTSpace on ordinary meshes but can differ at such vertices.
// Vertices whose triangles all have degenerate UVs get anyPerpendicular(n), w = +1.
// Returns the number of vertices that needed that fallback.
// `texCoord`: the set the normal map samples (Vertex::uv0 or uv1).
size_t generateTangents(Primitive& prim, uint32_t texCoord = 0);

// Sets every tangent to anyPerpendicular(normal), w = +1: a well-formed frame for primitives
// that have no UVs / no normal map, so a shader can always build a TBN.
void setFallbackTangents(Primitive& prim);

// A deterministic unit vector orthogonal to unit vector n.
glm::vec3 anyPerpendicular(const glm::vec3& n);

void computeBounds(Primitive& prim);
void computeBounds(Mesh& mesh);  // primitives and mesh

// Shapes for builtin scenes and tests; counter-clockwise outward faces, uv origin top-left,
// tangents filled.
// Axis-aligned cube [-h, h]^3: 24 vertices (4 per face, per-face normals), 36 indices.
Primitive makeCube(float halfExtent, uint32_t material);
// UV sphere around the origin; u around +Y (slices), v from +Y pole (0) to -Y pole (1).
Primitive makeUVSphere(float radius, uint32_t slices, uint32_t stacks, uint32_t material);
// Quad in the z = 0 plane facing +Z, [-hw, hw] x [-hh, hh]: 4 vertices, 6 indices.
Primitive makeQuad(float halfWidth, float halfHeight, uint32_t material);

}  // namespace fe::assets
