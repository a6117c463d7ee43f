#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Redeferred temporal accumulation (the seed's consideration D; TemporalAccumulation): the
// reduced-rate I-buffer's texels sit at a representative pixel that moves through its block
// from frame to frame (frame.temporal.xy). Each full-resolution pixel keeps the average of the
// exact sums it got on the frames it was representative, found in last frame's history by
// reprojection and kept only where the depth there matches (else it starts over from the
// G-buffer-guided upsampling). A still view thus converges to the full-rate sums after
// scale^2 frames; a moving one falls back to upsampling where history is lost.
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D iLdg;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D iLsg1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D iLsg2;
layout(binding = FE_SLOT_HISTORY0) uniform sampler2D hLdg;   // rgb L_dg, a frames averaged
layout(binding = FE_SLOT_HISTORY1) uniform sampler2D hLsg1;  // rgb L_sg1, a view depth
layout(binding = FE_SLOT_HISTORY2) uniform sampler2D hLsg2;  // rgb L_sg2
layout(location = 0) out vec4 outLdg;
layout(location = 1) out vec4 outLsg1;
layout(location = 2) out vec4 outLsg2;
#include "fe_ibuffer_upsample.glsl"
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const float depth = texelFetch(depthTexture, p, 0).r;
    if (depth >= 1.0 || feGBufferUnlit(texelFetch(gb2, p, 0).a)) {
        outLdg = outLsg1 = outLsg2 = vec4(0.0);
        return;
    }
    const vec4 g1 = texelFetch(gb1, p, 0);
    const int scale = int(frame.counts.y);
    const ivec2 q = p / scale;
    // This pixel was shaded exactly this frame when it is its texel's representative.
    const bool exact = all(equal(min(q * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1), p));
    IlluminationSums current;
    if (exact) {
        current.Ldg = texelFetch(iLdg, q, 0).rgb;
        current.Lsg1 = texelFetch(iLsg1, q, 0).rgb;
        current.Lsg2 = texelFetch(iLsg2, q, 0).rgb;
    } else {
        current = feUpsampleIBuffer(p, depth, normalize(g1.xyz), g1);
    }
    // Last frame's history at this surface point.
    const vec3 Pe = feEyeFromDepth(vec2(p) + 0.5, depth);  // camera-relative
    const vec3 P = frame.cameraPosition.xyz + Pe;
    const vec4 c = frame.prevViewProj * vec4(P, 1.0);
    const vec2 prev = (c.xy / c.w * 0.5 + 0.5) * frame.viewport.xy;
    // frame.temporal.z: 0 no history, 1 a still view (history read texel for texel, so the
    // average stays exact), 2 the camera moved (history resampled, clamped and forgotten).
    const bool moving = frame.temporal.z > 1.5;
    float count = 0.0;
    vec3 hist0 = vec3(0.0), hist1 = vec3(0.0), hist2 = vec3(0.0);
    if (frame.temporal.z > 0.0 && c.w > 0.0 && all(greaterThanEqual(prev, vec2(0.0))) && all(lessThan(prev, frame.viewport.xy))) {
        // The view depth stored at the nearest texel must be this point's depth as last frame saw
        // it (c.w): otherwise it is another surface (disocclusion) and its sums are not ours.
        const ivec2 h = ivec2(prev);
        const vec4 a = texelFetch(hLdg, h, 0), b = texelFetch(hLsg1, h, 0);
        if (a.a > 0.0 && abs(b.a - c.w) < 0.01 * c.w) {
            count = a.a;
            if (!moving) {  // still: the texel itself
                hist0 = a.rgb;
                hist1 = b.rgb;
                hist2 = texelFetch(hLsg2, h, 0).rgb;
            } else {  // moving: interpolated where the point was, not the nearest texel's point
                const vec2 uv = prev * frame.viewport.zw;
                hist0 = textureLod(hLdg, uv, 0.0).rgb;
                hist1 = textureLod(hLsg1, uv, 0.0).rgb;
                hist2 = textureLod(hLsg2, uv, 0.0).rgb;
            }
        }
    }
    if (moving && count > 0.0 && !exact) {
        // Under motion the history may belong to a neighbouring surface point and its
        // view-dependent sums age: it is clamped to the range of this frame's exact samples
        // around the pixel (the 2x2 I-buffer texels the upsampling reads), as temporal
        // antialiasing clamps colour history.
        const ivec2 isize = ivec2(frame.illumViewport.xy);
        const ivec2 q0 = ivec2(floor((vec2(p) - vec2(feRepOffset())) / float(scale)));
        vec3 lo0 = vec3(1e30), hi0 = vec3(-1e30), lo1 = lo0, hi1 = hi0, lo2 = lo0, hi2 = hi0;
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                const ivec2 qi = clamp(q0 + ivec2(i, j), ivec2(0), isize - 1);
                const vec3 a = texelFetch(iLdg, qi, 0).rgb, b = texelFetch(iLsg1, qi, 0).rgb, d = texelFetch(iLsg2, qi, 0).rgb;
                lo0 = min(lo0, a), hi0 = max(hi0, a);
                lo1 = min(lo1, b), hi1 = max(hi1, b);
                lo2 = min(lo2, d), hi2 = max(hi2, d);
            }
        hist0 = clamp(hist0, lo0, hi0);
        hist1 = clamp(hist1, lo1, hi1);
        hist2 = clamp(hist2, lo2, hi2);
    }
    vec3 s0 = current.Ldg, s1 = current.Lsg1, s2 = current.Lsg2;
    float n = 0.0;
    // Under motion the history is resampled every frame, which blurs it: it is forgotten
    // towards this frame's estimate, a tenth per frame, and entirely once the point moves a
    // pixel a frame or more (then the frame is the plain reduced rate: no worse than without).
    const float motion = length(prev - (vec2(p) + 0.5));
    const float forget = moving ? max(0.1, min(motion, 1.0)) : 0.0;
    if (exact) {
        // Shaded exactly this frame: nothing in the history is better (the sums are
        // deterministic, so on a still view they equal what the history holds).
        n = min(count + 1.0, frame.temporal.w);
    } else if (count > 0.0) {  // exact frames before beat this frame's upsampled estimate
        n = count;
        s0 = mix(hist0, current.Ldg, forget);
        s1 = mix(hist1, current.Lsg1, forget);
        s2 = mix(hist2, current.Lsg2, forget);
    }
    outLdg = vec4(s0, n);
    outLsg1 = vec4(s1, c.w > 0.0 ? feViewDepth(depth) : 0.0);
    outLsg2 = vec4(s2, 0.0);
}
