#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// The displayable image: clamp(exposure x L_o), sRGB-encoded by the RGBA8_SRGB target on store.
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D radiance;
layout(location = 0) out vec4 outColor;
void main() {
    vec3 l = texelFetch(radiance, ivec2(gl_FragCoord.xy), 0).rgb;
    outColor = vec4(clamp(frame.cameraPosition.w * l, 0.0, 1.0), 1.0);
}
