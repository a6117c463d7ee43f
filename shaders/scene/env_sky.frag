#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_environment.glsl"
// One face of the environment cube: builtin:sky evaluated at each texel's direction.
layout(location = 0) out vec4 outRadiance;
void main() {
    const vec3 d = feCubeFaceDirection(int(env.faceSize.x), gl_FragCoord.xy / env.faceSize.y);
    outRadiance = vec4(feSkyRadiance(d), 1.0);
}
