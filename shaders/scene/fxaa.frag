#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Fast approximate antialiasing, after Lottes' FXAA (NVIDIA whitepaper, 2009) as the algorithm is
// described there: find pixels on a luma edge, walk along the edge to its ends, and resample the
// pixel across the edge in proportion to how near it is to the end where the edge leaves; a lone
// pixel that stands out of its neighbourhood (sub-pixel aliasing) is blended toward it as well.
// Input: the tone-mapped image (sRGB-encoded storage, read back as linear, filtered bilinearly).
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D ldr;
layout(location = 0) out vec4 outColor;

// Perceptual luma: the filter's thresholds are in gamma-like units (sqrt approximates sRGB).
float luma(vec3 c) { return sqrt(dot(c, vec3(0.299, 0.587, 0.114))); }
float lumaAt(ivec2 p, ivec2 size) { return luma(texelFetch(ldr, clamp(p, ivec2(0), size - 1), 0).rgb); }
float lumaUv(vec2 uv) { return luma(textureLod(ldr, uv, 0.0).rgb); }

const float kEdgeThresholdMin = 0.0312;  // darkest contrast considered an edge
const float kEdgeThreshold = 0.125;      // contrast relative to the local maximum
const float kSubpixelQuality = 0.75;     // how much a lone pixel is blended

void main() {
    ivec2 size = textureSize(ldr, 0);
    vec2 texel = 1.0 / vec2(size);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 uv = gl_FragCoord.xy * texel;
    const vec4 centreRgba = texelFetch(ldr, p, 0);  // alpha: a transparent background's coverage, kept
    vec3 centre = centreRgba.rgb;
    float m = luma(centre);
    float n = lumaAt(p + ivec2(0, 1), size), s = lumaAt(p + ivec2(0, -1), size);
    float e = lumaAt(p + ivec2(1, 0), size), w = lumaAt(p + ivec2(-1, 0), size);
    float lo = min(m, min(min(n, s), min(e, w))), hi = max(m, max(max(n, s), max(e, w)));
    float range = hi - lo;
    if (range < max(kEdgeThresholdMin, hi * kEdgeThreshold)) {
        outColor = vec4(centre, centreRgba.a);  // no edge: the pixel as it is
        return;
    }
    float ne = lumaAt(p + ivec2(1, 1), size), nw = lumaAt(p + ivec2(-1, 1), size);
    float se = lumaAt(p + ivec2(1, -1), size), sw = lumaAt(p + ivec2(-1, -1), size);

    // How far the centre stands out of its 3x3 neighbourhood, relative to the contrast.
    float average = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    float subpixel = smoothstep(0.0, 1.0, clamp(abs(average - m) / range, 0.0, 1.0));
    subpixel = subpixel * subpixel * kSubpixelQuality;

    // The edge's orientation: second differences across rows against across columns.
    float acrossRows = 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
    float acrossColumns = 2.0 * abs(e + w - 2.0 * m) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
    bool horizontal = acrossRows >= acrossColumns;  // the edge runs along x: blend along y

    // Which neighbour across the edge differs most: the edge lies between it and the centre.
    float l1 = horizontal ? s : w, l2 = horizontal ? n : e;
    float g1 = abs(l1 - m), g2 = abs(l2 - m);
    float across = horizontal ? texel.y : texel.x;
    float edgeLuma;
    if (g1 >= g2) {
        across = -across;
        edgeLuma = 0.5 * (l1 + m);
    } else {
        edgeLuma = 0.5 * (l2 + m);
    }
    float gradient = 0.25 * max(g1, g2);

    // Walk both ways along the edge (on the edge itself, half a texel across) until the luma
    // there leaves the edge's: that is where the edge ends.
    vec2 onEdge = uv + (horizontal ? vec2(0.0, 0.5 * across) : vec2(0.5 * across, 0.0));
    vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);
    vec2 uv1 = onEdge - along, uv2 = onEdge + along;
    float end1 = lumaUv(uv1) - edgeLuma, end2 = lumaUv(uv2) - edgeLuma;
    bool done1 = abs(end1) >= gradient, done2 = abs(end2) >= gradient;
    const float kSteps[10] = float[](1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 4.0, 8.0);
    for (int i = 0; i < 10 && !(done1 && done2); ++i) {
        if (!done1) {
            uv1 -= along * kSteps[i];
            end1 = lumaUv(uv1) - edgeLuma;
            done1 = abs(end1) >= gradient;
        }
        if (!done2) {
            uv2 += along * kSteps[i];
            end2 = lumaUv(uv2) - edgeLuma;
            done2 = abs(end2) >= gradient;
        }
    }
    float d1 = horizontal ? uv.x - uv1.x : uv.y - uv1.y;
    float d2 = horizontal ? uv2.x - uv.x : uv2.y - uv.y;
    bool nearer1 = d1 < d2;
    float offset = 0.5 - min(d1, d2) / (d1 + d2);
    // Blend only when the nearer end is where the edge turns away from the centre's side (the
    // staircase's step is on this pixel); otherwise this pixel is in the middle of a run.
    bool centreDarker = m < edgeLuma;
    bool stepHere = ((nearer1 ? end1 : end2) < 0.0) != centreDarker;
    float amount = max(stepHere ? offset : 0.0, subpixel);
    vec2 at = uv + (horizontal ? vec2(0.0, amount * across) : vec2(amount * across, 0.0));
    outColor = vec4(textureLod(ldr, at, 0.0).rgb, centreRgba.a);
}
