// Debug views (fe view): one of the frame's intermediate textures shown in place of L_o, scaled
// by the exposure. FE_DEBUG_VIEW: 0 colour (rgb as stored, absolute values: normals and sums may
// be negative), 1 one channel as grey (depth, R16F/R32F), 2 layer 0 of a layered texture as grey
// (shadow maps), 3 a cube's six faces as grey, unfolded in a 3x2 grid (+X -X +Y / -Y +Z -Z).
// A texture of another size (reduced-rate I-buffers, shadow maps) is stretched
// over the view by nearest texel. FE_DEBUG_DEPTH: the texture holds depths (shown as 1 - depth).
#include "fe_scene.glsl"
#if FE_DEBUG_VIEW == 2
layout(binding = FE_SLOT_RADIANCE) uniform sampler2DArray shown;
#elif FE_DEBUG_VIEW == 3
layout(binding = FE_SLOT_RADIANCE) uniform samplerCube shown;
#else
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D shown;
#endif
layout(location = 0) out vec4 outColor;
void main() {
    vec2 uv = gl_FragCoord.xy * frame.viewport.zw;
#if FE_DEBUG_VIEW == 2
    ivec2 size = textureSize(shown, 0).xy;
    vec4 v = texelFetch(shown, ivec3(ivec2(uv * vec2(size)), 0), 0);
#elif FE_DEBUG_VIEW == 3
    // Face f of the 3x2 grid, (s, t) in [-1, 1] across it; the cube-map face directions of the
    // Vulkan / GL convention (sc, tc on face +X are -z, -y, and so on).
    int f = int(uv.x * 3.0) + 3 * int(uv.y * 2.0);
    vec2 st = fract(uv * vec2(3.0, 2.0)) * 2.0 - 1.0;
    vec3 dirs[6] = vec3[](vec3(1.0, -st.y, -st.x), vec3(-1.0, -st.y, st.x), vec3(st.x, 1.0, st.y),
                          vec3(st.x, -1.0, -st.y), vec3(st.x, -st.y, 1.0), vec3(-st.x, -st.y, -1.0));
    vec4 v = textureLod(shown, dirs[clamp(f, 0, 5)], 0.0);
#else
    ivec2 size = textureSize(shown, 0);
    vec4 v = texelFetch(shown, ivec2(uv * vec2(size)), 0);
#endif
#if FE_DEBUG_VIEW == 0
    vec3 c = abs(v.rgb);
#elif defined(FE_DEBUG_DEPTH)
    // Depth as 1 - depth: perspective depths crowd toward 1, so the far range would all show as
    // white; this way it shows dark and the exposure can stretch it.
    vec3 c = vec3(1.0 - v.r);
#else
    vec3 c = vec3(v.r);
#endif
    outColor = vec4(frame.cameraPosition.w * c, 1.0);
}
