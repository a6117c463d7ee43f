// The body of lpp_material.frag and lpp_material_ibl.frag.
#include "fe_material.glsl"
#include "fe_light_prepass.glsl"
#ifdef FE_IBL
#include "fe_ibl.glsl"
#endif
// Light pre-pass, pass 3: the scene drawn again (depth EQUAL), each material combining its
// albedo and F0 with the light buffer at its pixel. With FE_IBL (lpp_material_ibl.frag) it adds
// the environment's light, exactly (the pass has the whole material), by fe_ibl.glsl's estimator.
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D lightBuffer;
layout(location = 0) out vec4 outRadiance;
void main() {
    MaterialSample m = feSampleMaterial(vUv, vColor, vNormal, vTangent, gl_FrontFacing);
    if (feAlphaDiscard(m.alpha)) discard;
    if (m.unlit) {
        outRadiance = vec4(m.baseColor, 1.0);
        return;
    }
    vec4 light = texelFetch(lightBuffer, ivec2(gl_FragCoord.xy), 0);
    vec3 wo = feViewDirection(vEye);
    float r = feClampRoughness(m.roughness);
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    float NoV = max(dot(m.n, wo), 1e-4);
    vec3 F0 = mix(vec3(0.04), m.baseColor, m.metallic);
    vec3 Ld = (1.0 - m.metallic) * (m.baseColor / FE_PI) * (1.0 - F0) * light.rgb;
    // Specular colour: the monochrome sum with the diffuse light's chromaticity; Fresnel at n.v.
    float lum = feLuminance(light.rgb);
    vec3 chroma = lum > 0.0 ? light.rgb / lum : vec3(1.0);
    vec3 F = F0 + (1.0 - F0) * pow(1.0 - NoV, 5.0);
    vec3 Ls = chroma * light.a * F / (NoV * (1.0 - k) + k);
    vec3 L = m.emissive + Ld + Ls;
#ifdef FE_IBL
    L += feOcclusion(vUv) * feShadeEnvironment(feMaterialSurface(m, vEye), frame.counts.z);
#endif
    outRadiance = vec4(L, 1.0);
}
