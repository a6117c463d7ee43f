// Tone mapping (the GPU twin of renderer/shading/Tonemap.h; keep the two in step).
// FE_TONEMAP: 0 clamp, 1 ACES fit (Narkowicz 2016), 2 Khronos PBR Neutral.
#ifndef FE_TONEMAP_GLSL
#define FE_TONEMAP_GLSL

vec3 feTonemap(vec3 c) {
    c = max(c, vec3(0.0));
#if FE_TONEMAP == 1
    vec3 x = 0.6 * c;
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
#elif FE_TONEMAP == 2
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
#else
    return min(c, vec3(1.0));
#endif
}

#endif
