#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// The quad's colour plus its last 16 bytes (offset 112), so every byte of the block is seen.
FE_CONSTANTS(Quad) { vec4 rect; vec4 color; vec4 unused[5]; vec4 tail; } quad;
layout(location = 0) out vec4 outColor;
void main() { outColor = quad.color + quad.tail; }
