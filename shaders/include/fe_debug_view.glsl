// Debug views (fe view): one of the frame's intermediate textures shown in place of L_o, scaled
// by the exposure. FE_DEBUG_VIEW: 0 colour (rgb as stored, absolute values: normals and sums may
// be negative), 1 one channel as grey (depth, R16F/R32F), 2 layer 0 of a layered texture as grey
// (shadow maps). A texture of another size (reduced-rate I-buffers, shadow maps) is stretched
// over the view by nearest texel.
#include "fe_scene.glsl"
#if FE_DEBUG_VIEW == 2
layout(binding = FE_SLOT_RADIANCE) uniform sampler2DArray shown;
#else
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D shown;
#endif
layout(location = 0) out vec4 outColor;
void main() {
    vec2 uv = gl_FragCoord.xy * frame.viewport.zw;
#if FE_DEBUG_VIEW == 2
    ivec2 size = textureSize(shown, 0).xy;
    vec4 v = texelFetch(shown, ivec3(ivec2(uv * vec2(size)), 0), 0);
#else
    ivec2 size = textureSize(shown, 0);
    vec4 v = texelFetch(shown, ivec2(uv * vec2(size)), 0);
#endif
#if FE_DEBUG_VIEW == 0
    vec3 c = abs(v.rgb);
#else
    vec3 c = vec3(v.r);
#endif
    outColor = vec4(frame.cameraPosition.w * c, 1.0);
}
