// Environments (renderer/assets/Environment.h, render/EnvironmentMap.h): the equirectangular
// mapping, builtin:sky's closed form, and the direction of a cube map face texel.
#ifndef FE_ENVIRONMENT_GLSL
#define FE_ENVIRONMENT_GLSL
#include "fe_common.glsl"
#include "fe_shading.glsl"  // FE_PI
#include "fe_cube.glsl"

// Slots of the face passes (ShaderSlots.h; they bind nothing else).
#define FE_SLOT_ENVIRONMENT_PARAMS 1
#ifndef FE_SLOT_ENVIRONMENT_SOURCE
#define FE_SLOT_ENVIRONMENT_SOURCE 20
#endif

// Parameters of the face passes (EnvironmentMap::Params, std140).
layout(binding = FE_SLOT_ENVIRONMENT_PARAMS, std140) uniform EnvironmentBlock {
    vec4 faceSize;      // x face index (0..5: +X -X +Y -Y +Z -Z), y face size in texels
    vec4 zenith, horizon, ground;
    vec4 sunDirection;  // towards the sun
    vec4 sunRadiance;
    vec4 sunCos;        // x cos(outer angle), y cos(inner angle)
} env;

// builtin:sky: SkyModel::radiance in Environment.cpp, the same formula in single precision.
vec3 feSkyRadiance(vec3 d) {
    vec3 l = d.y >= 0.0 ? mix(env.horizon.rgb, env.zenith.rgb, sqrt(d.y)) : env.ground.rgb;
    return l + smoothstep(env.sunCos.x, env.sunCos.y, dot(d, env.sunDirection.xyz)) * env.sunRadiance.rgb;
}

// u = atan2(d.x, -d.z) / (2 pi) + 1/2, v = acos(d.y) / pi.
vec2 feEquirectFromDirection(vec3 d) {
    return vec2(atan(d.x, -d.z) / (2.0 * FE_PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / FE_PI);
}

#endif
