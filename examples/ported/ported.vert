#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// A quad placed by per-draw constants (FE_CONSTANTS from the installed engine include).
FE_CONSTANTS(Quad) { vec4 rect; vec4 color; } quad;
void main() {
    const vec2 corner = vec2(FE_VERTEX_ID & 1, FE_VERTEX_ID >> 1);
    gl_Position = vec4(mix(quad.rect.xy, quad.rect.zw, corner), 0.0, 1.0);
}
