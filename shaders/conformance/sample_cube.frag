#version 450
#extension GL_GOOGLE_include_directive : require
#include "cube_direction.glsl"
layout(binding = 1) uniform samplerCube tex;
layout(location = 0) out vec4 outColor;
void main() {
    int face;
    outColor = texture(tex, cubeDirection(gl_FragCoord.xy, face));
}
