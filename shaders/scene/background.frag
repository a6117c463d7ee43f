#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// The environment seen along each pixel's view ray (its top mip level).
layout(binding = FE_SLOT_ENVIRONMENT) uniform samplerCube environment;
layout(location = 0) out vec4 outRadiance;
void main() {
    const vec3 d = normalize(feEyeFromDepth(gl_FragCoord.xy, 0.5));
    outRadiance = vec4(textureLod(environment, d, 0.0).rgb, 1.0);
}
