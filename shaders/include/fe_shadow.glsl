// Shadow maps (renderer/render/ShadowMaps.h, ShadowPlan.h): the visibility of one shadowed light
// at a surface point. Included by the shadowed variants of the lighting shaders (FE_SHADOWED),
// with FE_SHADOW_CUBE for point lights.
#ifndef FE_SHADOW_GLSL
#define FE_SHADOW_GLSL
#include "fe_scene.glsl"

#define FE_SLOT_SHADOW 21
#define FE_SLOT_SHADOW_MAP 22

// ShadowMaps::Constants (std140).
layout(binding = FE_SLOT_SHADOW, std140) uniform ShadowBlock {
    mat4 viewProj[4];   // world -> map clip space: cascade i, or the spot map (0)
    vec4 cascadeEnds;   // view depth where cascade i ends
    vec4 texelWorld;    // world size of a texel: per cascade; spot and cube: at unit distance
    vec4 depthParams;   // cube: depth = x + y / (distance along the face's axis)
    uvec4 params;       // x the light's index in the light buffer, y cascade count
} shadow;

#ifdef FE_SHADOW_CUBE
layout(binding = FE_SLOT_SHADOW_MAP) uniform samplerCubeShadow shadowMap;
#else
layout(binding = FE_SLOT_SHADOW_MAP) uniform sampler2DArrayShadow shadowMap;
#endif

// The receiver moves this many texels along its normal before the lookup: with the casters'
// slope-scaled depth bias it keeps lit surfaces out of their own shadow (acne) at grazing light,
// without the large constant bias that detaches shadows from their casters (peter-panning).
const float FE_SHADOW_NORMAL_OFFSET = 1.5;

// 1 lit, 0 shadowed, between at a filtered (PCF) edge.
float feShadowVisibility(vec3 P, vec3 n) {
    const vec3 lightPos = feLight(shadow.params.x).positionRange.xyz;
#ifdef FE_SHADOW_CUBE
    const vec3 Q = P + n * (FE_SHADOW_NORMAL_OFFSET * shadow.texelWorld.x * distance(P, lightPos));
    const vec3 d = Q - lightPos;
    const float w = max(max(abs(d.x), abs(d.y)), abs(d.z));
    return texture(shadowMap, vec4(d, shadow.depthParams.x + shadow.depthParams.y / w));
#else
    int layer = 0;
    float texel;
    if (shadow.params.y > 0u) {  // cascades: the first whose slice of the view holds P
        const float z = -(frame.view * vec4(P, 1.0)).z;
        const vec4 ends = shadow.cascadeEnds;
        layer = z < ends.x ? 0 : z < ends.y ? 1 : z < ends.z ? 2 : 3;
        layer = min(layer, int(shadow.params.y) - 1);
        texel = shadow.texelWorld[layer];
    } else {
        texel = shadow.texelWorld.x * distance(P, lightPos);
    }
    const vec4 c = shadow.viewProj[layer] * vec4(P + n * (FE_SHADOW_NORMAL_OFFSET * texel), 1.0);
    const vec3 ndc = c.xyz / c.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    // Outside the map nothing was rendered: lit (a spot gives no light there anyway).
    if (c.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    return texture(shadowMap, vec4(uv, float(layer), ndc.z));
#endif
}
#endif
