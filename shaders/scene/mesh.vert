#version 450
#extension GL_GOOGLE_include_directive : require
#define FE_MESH_VERTEX_STAGE
#include "fe_material.glsl"
// Scene meshes for every pass that draws geometry (forward, G-buffer, transparent).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;
layout(location = 0) out vec3 vEye;  // world minus the camera position
layout(location = 1) out vec3 vNormal;
layout(location = 2) out vec4 vTangent;
layout(location = 3) out vec4 vUv;     // both texture coordinate sets
layout(location = 4) out vec4 vColor;
// The depth pre-pass and the EQUAL-tested passes after it must compute bit-identical depths:
// both run this module, and `precise` (NoContraction on every operation leading to gl_Position)
// fixes its arithmetic, no fused or reassociated operations, whatever the rest of the pipeline
// lets the compiler drop. Not `invariant`: glslang puts it on the gl_PerVertex member, which
// Mesa 22.3 ignores with a warning under validation ("Decoration not allowed on struct members:
// SpvDecorationInvariant"), so passing runs printed it; `precise` alone was what held there.
precise gl_Position;
void main() {
    // Camera-relative: the object's translation minus the eye's is exact in float where both are
    // far from the origin and near each other (Sterbenz), so the offset keeps its precision.
    const vec3 eye = mat3(object.world) * inPosition + (object.world[3].xyz - frame.cameraPosition.xyz);
    vEye = eye;
    vNormal = mat3(object.normalMatrix) * inNormal;
    vTangent = vec4(mat3(object.world) * inTangent.xyz, inTangent.w);
    vUv = vec4(inUv, inUv1);
    vColor = inColor;
    gl_Position = frame.viewProjFromEye * vec4(eye, 1.0);
}
