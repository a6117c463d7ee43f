#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_environment.glsl"
// One face of the environment cube: the equirectangular image sampled bilinearly (repeat in u,
// clamped in v, as Environment::radiance on the CPU) at each texel's direction.
layout(binding = FE_SLOT_ENVIRONMENT_SOURCE) uniform sampler2D equirect;
layout(location = 0) out vec4 outRadiance;
void main() {
    const vec3 d = feCubeFaceDirection(int(env.faceSize.x), gl_FragCoord.xy / env.faceSize.y);
    outRadiance = vec4(textureLod(equirect, feEquirectFromDirection(d), 0.0).rgb, 1.0);
}
