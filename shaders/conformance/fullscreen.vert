#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// A full-screen triangle with no inputs or uniforms (the fragment shader decides everything).
void main() {
    vec2 p = vec2((FE_VERTEX_ID << 1) & 2, FE_VERTEX_ID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
