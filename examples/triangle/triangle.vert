#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Three corners from the vertex index; no vertex buffer. Clip space is Vulkan's on every
// backend (y down), so this triangle points up on screen.
layout(location = 0) out vec3 colour;
void main() {
    const vec2 corners[3] = vec2[](vec2(0.0, -0.8), vec2(-0.8, 0.8), vec2(0.8, 0.8));
    const vec3 colours[3] = vec3[](vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0));
    gl_Position = vec4(corners[FE_VERTEX_ID], 0.0, 1.0);
    colour = colours[FE_VERTEX_ID];
}
