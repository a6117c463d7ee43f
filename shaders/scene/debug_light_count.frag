#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Debug view "light count": per pixel, how many lights reach the surface seen there (a light
// whose range window is non-zero at that point; unbounded lights always), as a heat map: black
// none, then blue, green, yellow, red at 32 or more; the background stays black. The quantity
// light volumes and tile culling spend their time on, the same for every technique.
layout(binding = FE_SLOT_DEPTH) uniform sampler2D sceneDepth;
layout(location = 0) out vec4 outColor;
vec3 heat(float t) {  // 0..1: blue -> cyan -> green -> yellow -> red
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(4.0 * t - 2.0, t < 0.5 ? 4.0 * t : 4.0 - 4.0 * t, 2.0 - 4.0 * t), 0.0, 1.0);
}
void main() {
    float depth = texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r;
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 h = frame.invViewProj * vec4(ndc, depth, 1.0);
    if (abs(h.w) < 1e-9) {  // nothing drawn here: the point is at infinity
        outColor = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 P = h.xyz / h.w;
    uint count = 0;
    for (uint i = 0; i < frame.lightRange.y; ++i) {
        GpuLight L = feLight(i);
        if (L.directionType.w == FE_LIGHT_DIRECTIONAL || L.positionRange.w <= 0.0 ||
            feRangeWindow(distance(L.positionRange.xyz, P), L.positionRange.w) > 0.0)
            ++count;
    }
    // Exposure scales the display: divided out so the colours read the same at any exposure.
    outColor = vec4(count == 0 ? vec3(0.0) : heat(float(count) / 32.0) / frame.cameraPosition.w, 1.0);
}
