// The display pass: exposure x L_o tone-mapped (FE_TONEMAP, fe_tonemap.glsl), sRGB-encoded by
// the RGBA8_SRGB target on store. Non-finite radiance shows as white, as the CPU's toDisplay does.
#include "fe_scene.glsl"
#include "fe_tonemap.glsl"
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D radiance;
layout(location = 0) out vec4 outColor;
void main() {
    vec3 l = frame.cameraPosition.w * texelFetch(radiance, ivec2(gl_FragCoord.xy), 0).rgb;
    bvec3 bad = bvec3(ivec3(isnan(l)) | ivec3(isinf(l)));
    outColor = vec4(mix(feTonemap(l), vec3(1.0), bad), 1.0);
}
