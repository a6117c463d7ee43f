// Tone mapping (the GPU twin of renderer/shading/Tonemap.h; keep the two in step).
// The operator: 0 clamp, 1 ACES fit (Narkowicz 2016), 2 Khronos PBR Neutral; feDisplayed(l) applies
// FE_TONEMAP (a define: the display pass's three shaders), feDisplayedBy(l, op) the one given (a
// specialization constant: the shading pass that writes the display image, fe_forward_pass.glsl).
#ifndef FE_TONEMAP_GLSL
#define FE_TONEMAP_GLSL

vec3 feTonemapAces(vec3 c) {
    vec3 x = 0.6 * max(c, vec3(0.0));
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 feTonemapPbrNeutral(vec3 c) {
    c = max(c, vec3(0.0));
    const float startCompression = 0.8 - 0.04, desaturation = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < startCompression) return c;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    c *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(c, vec3(newPeak), g);
}

vec3 feTonemapBy(vec3 c, uint op) {
    if (op == 1u) return feTonemapAces(c);
    if (op == 2u) return feTonemapPbrNeutral(c);
    return min(max(c, vec3(0.0)), vec3(1.0));
}

// What the display shows of exposed radiance l under operator op: non-finite values white, as the
// CPU's toDisplay shows them.
vec3 feDisplayedBy(vec3 l, uint op) {
    bvec3 bad = bvec3(ivec3(isnan(l)) | ivec3(isinf(l)));
    return mix(feTonemapBy(l, op), vec3(1.0), bad);
}

#ifdef FE_TONEMAP
vec3 feDisplayed(vec3 l) { return feDisplayedBy(l, uint(FE_TONEMAP)); }
#endif

#endif
