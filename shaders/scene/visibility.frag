#version 450
#extension GL_GOOGLE_include_directive : require
#define FE_VISIBILITY_PASS
#include "fe_material.glsl"
// The visibility pass: the triangle's id (ObjectConstants: numbered from 1 across the scene's
// draws; 0, the clear value, is no surface). MASK materials are alpha tested here, as feAlphaDiscard.
layout(location = 0) flat in uint vTriangle;
layout(location = 1) in vec4 vUv;
layout(location = 2) in vec4 vColor;
layout(location = 0) out uint outId;
void main() {
    if (object.params.w == 1.0 && feAlphaDiscard(feCoverageAlpha(vUv, vColor))) discard;
    outId = vTriangle;
}
