#version 450
#extension GL_GOOGLE_include_directive : require
#include "cube_direction.glsl"
// Each face of a depth cube compared with reference params.a.x.
layout(binding = 0, std140) uniform Params { vec4 a; vec4 b; } params;
layout(binding = 1) uniform samplerCubeShadow tex;
layout(location = 0) out vec4 outColor;
void main() {
    int face;
    outColor = vec4(texture(tex, vec4(cubeDirection(gl_FragCoord.xy, face), params.a.x)));
}
