#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Temporal antialiasing (PostProcess, --aa taa). The projection is jittered by a sub-pixel
// Halton offset every frame; here each pixel's surface is reprojected into the previous frame
// (its position from depth, through the previous unjittered view-projection), the history is
// read there, clamped to the range of this frame's 3x3 neighbourhood (so disocclusions and
// moving objects do not ghost), and blended with this frame's sample.
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D current;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D sceneDepth;
layout(binding = FE_SLOT_HISTORY0) uniform sampler2D history;
layout(binding = FE_SLOT_TAA, std140) uniform TaaBlock {
    mat4 prevViewProj;  // the previous frame's, without jitter
    vec4 params;        // x 1 = history valid, y weight of this frame's sample
} taa;
layout(location = 0) out vec4 outColor;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(current, 0);
    // RGBA: with a transparent or coloured background, alpha is coverage (premultiplied) and is
    // resolved like the colour; otherwise it is 1 throughout.
    vec4 c = texelFetch(current, p, 0);
    // No branch on the uniform alone: Mesa 22.3's lavapipe compiles a variant of a shader whose
    // control flow depends only on uniforms at draw time, whenever their buffer changes (here every
    // frame), and never frees it. Combined with the per-pixel test below, the condition is not
    // inlinable, and nothing is compiled or leaked per frame.
    bool historyValid = taa.params.x >= 0.5;
    vec4 lo = c, hi = c;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            vec4 s = texelFetch(current, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0);
            lo = min(lo, s);
            hi = max(hi, s);
        }
    float depth = texelFetch(sceneDepth, p, 0).r;
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 h = frame.invViewProj * vec4(ndc, depth, 1.0);
    // A point at infinity (nothing drawn, infinite far plane) reprojects as a direction.
    vec4 q = abs(h.w) < 1e-9 ? taa.prevViewProj * vec4(h.xyz, 0.0) : taa.prevViewProj * vec4(h.xyz / h.w, 1.0);
    vec2 uv = q.xy / q.w * 0.5 + 0.5;
    if (!historyValid || q.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        outColor = c;  // nothing to reproject from: this frame's sample alone
        return;
    }
    vec4 previous = clamp(textureLod(history, uv, 0.0), lo, hi);
    outColor = mix(previous, c, taa.params.y);
}
