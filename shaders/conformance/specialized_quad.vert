#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// One quadrant of the target, chosen by a specialization constant (0: top-left, 1: top-right,
// 2: bottom-left, 3: bottom-right); the default draws the top-left.
layout(constant_id = 4) const int kQuadrant = 0;
void main() {
    const vec2 corner = vec2(FE_VERTEX_ID & 1, FE_VERTEX_ID >> 1);
    const vec2 origin = vec2(kQuadrant & 1, kQuadrant >> 1) - 1.0;
    gl_Position = vec4(origin + corner, 0.0, 1.0);
}
