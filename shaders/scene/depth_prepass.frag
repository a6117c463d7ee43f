#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_material.glsl"
// Depth pre-pass: no colour, only MASK materials' alpha test, so the EQUAL-tested shading pass
// sees exactly the surfaces it will shade.
layout(location = 0) in vec3 vWorld;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec2 vUv;
void main() {
    if (object.params.w == 1.0 && object.baseColorFactor.a * texture(baseColorTexture, vUv).a < object.params.z) discard;
}
