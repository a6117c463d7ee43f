#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_material.glsl"
// fe-variant: FE_GBUFFER_OCCLUSION (a material has an occlusion texture and the frame image-based light)
// G-buffer: GB0 RGBA8_SRGB base colour + metallic, GB1 RGBA16F world normal + roughness,
// GB2 RGBA16F emissive (or unlit colour) + w_o.n or the unlit flag (feGBufferUnlit), and with
// FE_GBUFFER_OCCLUSION GB3 R16F the occlusion 1 + strength (ao - 1). Position comes back from depth.
layout(location = 0) out vec4 outGb0;
layout(location = 1) out vec4 outGb1;
layout(location = 2) out vec4 outGb2;
#ifdef FE_GBUFFER_OCCLUSION
layout(location = 3) out vec4 outGb3;
#endif
void main() {
    MaterialSample m = feSampleMaterial(vUv, vColor, vNormal, vTangent, gl_FrontFacing);
    if (feAlphaDiscard(m.alpha)) discard;
    outGb0 = vec4(m.baseColor, m.metallic);
    outGb1 = vec4(m.n, m.roughness);
    const float NoV = clamp(dot(m.n, feViewDirection(vEye)), 0.0, 1.0);
    outGb2 = m.unlit ? vec4(m.baseColor, 2.0) : vec4(m.emissive, NoV);
#ifdef FE_GBUFFER_OCCLUSION
    outGb3 = vec4(feOcclusion(vUv));
#endif
}
