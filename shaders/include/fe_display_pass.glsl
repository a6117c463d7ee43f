// The display pass: exposure x L_o tone-mapped (FE_TONEMAP, fe_tonemap.glsl), sRGB-encoded by
// the RGBA8_SRGB target on store. Non-finite radiance shows as white, as the CPU's toDisplay does.
// forward-plus's shading pass writes the same for background 0 where it can (FE_DISPLAY_OUT).
// frame.shading.y is the background (RenderSettings::Background): 0 whatever L_o holds there; 1 a
// colour (frame.shading.z, sRGB RGBA8) and 2 transparent, where L_o's alpha is the coverage
// (0 where nothing was drawn, blended surfaces "over" it, premultiplied): the tone-mapped colour
// is composited over the background colour in display-linear space, or written with its alpha.
#include "fe_scene.glsl"
#include "fe_tonemap.glsl"
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D radiance;
layout(location = 0) out vec4 outColor;
// The background mode this pipeline is for (PostProcess::kBackgroundId; 3: frame.shading.y's): a
// constant, so the paths of the other modes are not run on CPU rasterizers (ShaderFeatures.h).
layout(constant_id = 204) const uint FE_BACKGROUND = 3u;
void main() {
    const vec4 source = texelFetch(radiance, ivec2(gl_FragCoord.xy), 0);
    const uint background = FE_BACKGROUND < 3u ? FE_BACKGROUND : frame.shading.y;
    const float coverage = background == 0u ? 1.0 : clamp(source.a, 0.0, 1.0);
    vec3 l = frame.cameraPosition.w * source.rgb / max(coverage, 1e-6);
    const vec3 shown = feDisplayed(l);
    if (background == 1u)
        outColor = vec4(mix(feSrgbToLinear(unpackUnorm4x8(frame.shading.z).rgb), shown, coverage), 1.0);
    else
        outColor = vec4(shown, coverage);
}
