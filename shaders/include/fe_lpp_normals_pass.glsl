#include "fe_material.glsl"
#include "fe_light_prepass.glsl"
// Light pre-pass, pass 1: the shading normal and roughness (fe_light_prepass.glsl), with the
// scene depth written by the rasterizer.
layout(location = 0) out vec4 outNormal;
void main() {
    MaterialSample m = feSampleMaterial(vUv, vColor, vNormal, vTangent, gl_FrontFacing);
    if (feAlphaDiscard(m.alpha)) discard;
    outNormal = fePackNormalRoughness(m.n, m.roughness);
}
