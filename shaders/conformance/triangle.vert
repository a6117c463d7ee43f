#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// One RGB triangle from gl_VertexIndex: no vertex buffer needed.
layout(location = 0) out vec3 vColor;
void main() {
    const vec2 pos[3] = vec2[](vec2(-0.8, 0.8), vec2(0.8, 0.8), vec2(0.0, -0.8));
    const vec3 col[3] = vec3[](vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1));
    gl_Position = vec4(pos[FE_VERTEX_ID], 0.0, 1.0);
    vColor = col[FE_VERTEX_ID];
}
