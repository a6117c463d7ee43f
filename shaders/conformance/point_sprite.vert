#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Point v: centre (16, 16) and size 8 for v = 0, centre (40, 24) and size 4 for v = 1, in
// pixels of a 64x64 target (rows from the top).
void main() {
    const vec2 centre = FE_VERTEX_ID == 0 ? vec2(16.0, 16.0) : vec2(40.0, 24.0);
    gl_Position = vec4(centre / 32.0 - 1.0, 0.0, 1.0);
    gl_PointSize = FE_VERTEX_ID == 0 ? 8.0 : 4.0;
}
