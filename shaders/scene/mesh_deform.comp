#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Mesh deformation (render/MeshDeformation.h): one primitive of one animated instance, its rest
// pose morphed by the weighted targets, then skinned by the weighted joint matrices, written to
// the instance's own vertices, which every pass then draws. The formulas are glTF 2.0's
// (assets/Animation.h); reference/AnimationReference.cpp evaluates the same in double.
layout(local_size_x = 64) in;

// assets::Vertex: position 0-2, normal 3-5, tangent 6-9, uv0 10-11, uv1 12-13, colour 14-17.
const uint kVertexFloats = 18u;
layout(binding = 38, std430) buffer Vertices { float vertices[]; };
// assets::SkinInfluences: joints of sets 0 and 1, then their weights' bits.
layout(binding = 50, std430) readonly buffer Skin { uvec4 influences[]; };
// Per target, per vertex: position, normal and tangent deltas (9 floats).
layout(binding = 51, std430) readonly buffer Morph { float deltas[]; };
// The joint matrices (4 vec4 each) and the morph weights (4 per vec4) of the frame.
layout(binding = 52, std430) readonly buffer Pose { vec4 pose[]; };

// Every deformed primitive of the scene in one dispatch: each work group deforms 64 vertices of
// one of them (render::MeshDeformation's records, fixed for the scene; only the pose changes).
struct Deformation {
    uvec4 vertexRange;  // x: rest pose's first vertex, y: the output's, z: vertex count, w: 1 = flat normals
    uvec4 sources;      // x: first influence record (~0: not skinned), y: first joint's vec4, z: first delta, w: targets
    uvec4 weights;      // x: first weight (in floats of the pose buffer), y: its first work group
};
layout(binding = 53, std430) readonly buffer Deformations { Deformation deformations[]; };
layout(binding = 54, std430) readonly buffer Groups { uint groupDeformation[]; };
FE_CONSTANTS(DeformDispatch) {
    uvec4 firstGroup;  // x: the first work group of this dispatch (dispatches hold at most 65535)
} dispatchInfo;

Deformation c;

struct Deformed {
    vec3 position;
    vec3 normal;
    vec3 tangent;
};

vec3 restVec3(uint vertex, uint offset) {
    uint b = (c.vertexRange.x + vertex) * kVertexFloats + offset;
    return vec3(vertices[b], vertices[b + 1u], vertices[b + 2u]);
}

mat4 jointMatrix(uint j) {
    uint b = c.sources.y + 4u * j;
    return mat4(pose[b], pose[b + 1u], pose[b + 2u], pose[b + 3u]);
}

Deformed deform(uint vertex) {
    Deformed d;
    d.position = restVec3(vertex, 0u);
    d.normal = restVec3(vertex, 3u);
    d.tangent = restVec3(vertex, 6u);
    for (uint t = 0u; t < c.sources.w; ++t) {
        uint wi = c.weights.x + t;
        float w = pose[wi / 4u][wi % 4u];
        uint b = c.sources.z + (t * c.vertexRange.z + vertex) * 9u;
        d.position += w * vec3(deltas[b], deltas[b + 1u], deltas[b + 2u]);
        d.normal += w * vec3(deltas[b + 3u], deltas[b + 4u], deltas[b + 5u]);
        d.tangent += w * vec3(deltas[b + 6u], deltas[b + 7u], deltas[b + 8u]);
    }
    if (c.sources.x != 0xffffffffu) {
        uint r = (c.sources.x + vertex) * 4u;
        uvec4 j0 = influences[r], j1 = influences[r + 1u];
        vec4 w0 = uintBitsToFloat(influences[r + 2u]), w1 = uintBitsToFloat(influences[r + 3u]);
        mat4 m = mat4(0.0);
        for (int k = 0; k < 4; ++k) {
            if (w0[k] != 0.0) m += w0[k] * jointMatrix(j0[k]);
            if (w1[k] != 0.0) m += w1[k] * jointMatrix(j1[k]);
        }
        d.position = (m * vec4(d.position, 1.0)).xyz;
        mat3 m3 = mat3(m);
        if (abs(determinant(m3)) > 1e-30) d.normal = transpose(inverse(m3)) * d.normal;
        d.tangent = m3 * d.tangent;
    }
    return d;
}

void main() {
    uint group = dispatchInfo.firstGroup.x + gl_WorkGroupID.x;
    c = deformations[groupDeformation[group]];
    uint vertex = (group - c.weights.y) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    if (vertex >= c.vertexRange.z) return;
    Deformed d = deform(vertex);
    vec3 restNormal = restVec3(vertex, 3u), restTangent = restVec3(vertex, 6u);
    d.normal = dot(d.normal, d.normal) > 0.0 ? normalize(d.normal) : restNormal;
    if (c.vertexRange.w == 1u) {  // flat: the deformed triangle's face normal
        uint first = vertex - vertex % 3u;
        vec3 p[3];
        for (uint k = 0u; k < 3u; ++k) p[k] = first + k == vertex ? d.position : deform(first + k).position;
        vec3 f = cross(p[1] - p[0], p[2] - p[0]);
        if (dot(f, f) > 0.0) d.normal = normalize(f);
    }
    vec3 t = d.tangent - d.normal * dot(d.normal, d.tangent);
    t = dot(t, t) > 1e-24 ? normalize(t) : restTangent;
    uint o = (c.vertexRange.y + vertex) * kVertexFloats;
    vertices[o] = d.position.x;
    vertices[o + 1u] = d.position.y;
    vertices[o + 2u] = d.position.z;
    vertices[o + 3u] = d.normal.x;
    vertices[o + 4u] = d.normal.y;
    vertices[o + 5u] = d.normal.z;
    vertices[o + 6u] = t.x;
    vertices[o + 7u] = t.y;
    vertices[o + 8u] = t.z;
    // The tangent's handedness, uv sets and colour never change: uploaded with the rest pose.
}
