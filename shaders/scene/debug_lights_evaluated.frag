#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_EVERY_LIGHT (the technique's loop walks every unshadowed light: frame.lightRange.y)
// Debug view "lights evaluated" (SceneRenderer::kLightsEvaluatedView): per pixel, how many lights
// the technique's shading loop walks there, as the light-list statistics pass counted them (its
// tile or cluster list at the resolved depth, every light where a list overflowed). A heat map on a log scale, so 1 and 1000 both read: black where no
// surface was drawn, then blue (1 light), cyan (4), green (16), yellow (64), red (256 or more).
// The quantity Forward+ and clustering spend their time on; compare "light count", the lights
// that actually reach each pixel.
#include "fe_scene.glsl"
layout(binding = FE_SLOT_DEPTH) uniform sampler2D sceneDepth;
#ifndef FE_EVERY_LIGHT
layout(binding = FE_SLOT_TILE_LIGHTS) uniform usampler2D lightsEvaluated;  // R32U, ~0u: no surface
#endif
layout(location = 0) out vec4 outColor;
vec3 heat(float t) {  // 0..1: blue -> cyan -> green -> yellow -> red
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(4.0 * t - 2.0, t < 0.5 ? 4.0 * t : 4.0 - 4.0 * t, 2.0 - 4.0 * t), 0.0, 1.0);
}
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
#ifdef FE_EVERY_LIGHT
    const uint n = texelFetch(sceneDepth, p, 0).r < 1.0 ? frame.lightRange.y : 0xffffffffu;
#else
    const uint n = texelFetch(lightsEvaluated, p, 0).r;
#endif
    // log2(1 + n) / 8: 1 light -> 1/8, 255 or more -> 1; zero lights evaluated shows dark blue.
    const vec3 colour = n == 0xffffffffu ? vec3(0.0) : n == 0u ? vec3(0.0, 0.0, 0.25) : heat(log2(1.0 + float(n)) / 8.0);
    // Exposure scales the display: divided out so the colours read the same at any exposure.
    outColor = vec4(colour / frame.cameraPosition.w, 1.0);
}
