#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Redeferred temporal accumulation: this frame's accumulated sums become next frame's history.
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D a0;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D a1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D a2;
layout(location = 0) out vec4 out0;
layout(location = 1) out vec4 out1;
layout(location = 2) out vec4 out2;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    out0 = texelFetch(a0, p, 0);
    out1 = texelFetch(a1, p, 0);
    out2 = texelFetch(a2, p, 0);
}
