#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// The same 80 bytes of per-object data as per-draw constants (bench/PerDrawConstants).
layout(location = 0) in vec2 inPosition;
FE_CONSTANTS(Object) { vec4 offsetScale; vec4 color; vec4 extra[3]; } object;
layout(location = 0) out vec4 vColor;
void main() {
    gl_Position = vec4(inPosition * object.offsetScale.zw + object.offsetScale.xy, 0.0, 1.0);
    vColor = object.color + object.extra[2] * 0.0;
}
