#version 450
#extension GL_GOOGLE_include_directive : require
#define FE_VISIBILITY_PASS
#include "fe_common.glsl"
#include "fe_material.glsl"
// The visibility pass (VisibilityBufferRenderer): each draw is drawn unindexed, its vertices
// pulled from the scene's index and vertex buffers, so that a triangle's three vertices know
// which triangle they make (vertex id / 3) without the Geometry capability gl_PrimitiveID needs
// in a fragment shader. Positions are computed exactly as mesh.vert's, so the shadowed lights'
// forward passes after the resolve meet this depth with an EQUAL test.
layout(binding = FE_SLOT_VERTICES, std430) readonly buffer VertexBlock {
    float vertexFloats[];  // assets::Vertex: position, normal, tangent, uv0, uv1, colour (18 floats)
};
layout(binding = FE_SLOT_INDICES, std430) readonly buffer IndexBlock {
    uint indices[];
};
layout(location = 0) flat out uint vTriangle;
layout(location = 1) out vec4 vUv;  // for MASK materials' alpha test
layout(location = 2) out vec4 vColor;
precise gl_Position;  // as mesh.vert: the same depths as the passes it shares a buffer with
void main() {
    const uint v = indices[object.flags.y + uint(FE_VERTEX_ID)] + object.flags.z;
    const uint f = v * 18u;
    const vec3 position = vec3(vertexFloats[f], vertexFloats[f + 1u], vertexFloats[f + 2u]);
    vUv = vec4(vertexFloats[f + 10u], vertexFloats[f + 11u], vertexFloats[f + 12u], vertexFloats[f + 13u]);
    vColor = vec4(vertexFloats[f + 14u], vertexFloats[f + 15u], vertexFloats[f + 16u], vertexFloats[f + 17u]);
    vTriangle = object.flags.w + uint(FE_VERTEX_ID) / 3u;
    const vec3 eye = mat3(object.world) * position + (object.world[3].xyz - frame.cameraPosition.xyz);
    gl_Position = frame.viewProjFromEye * vec4(eye, 1.0);
}
