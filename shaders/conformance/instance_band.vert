#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Instance i draws an 8-pixel column at x = 8i (of 64), red = i / 16: firstInstance shows.
layout(location = 0) out vec4 vValue;
const vec2 kCorners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(0, 1), vec2(1, 0), vec2(1, 1));
void main() {
    const int i = FE_INSTANCE_ID;
    const vec2 c = kCorners[FE_VERTEX_ID % 6];
    gl_Position = vec4((8.0 * (float(i) + c.x)) / 32.0 - 1.0, c.y * 2.0 - 1.0, 0.0, 1.0);
    vValue = vec4(float(i) / 16.0, 0.5, 0.0, 1.0);
}
