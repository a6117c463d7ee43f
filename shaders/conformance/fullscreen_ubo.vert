#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Full-screen triangle at a depth from the uniform block.
layout(binding = 0, std140) uniform Params { vec4 color; vec4 depth; } params;
void main() {
    vec2 p = vec2((FE_VERTEX_ID << 1) & 2, FE_VERTEX_ID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, params.depth.x, 1.0);
}
