#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: the mean of a multisampled G-buffer's samples)
#include "fe_scene.glsl"
// Deferred: emissive (and unlit colour) added after the lights.
layout(location = 0) out vec4 outRadiance;
#ifdef FE_MULTISAMPLED
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2DMS gb2;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const int n = textureSamples(gb2);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) sum += texelFetch(gb2, p, i).rgb;
    outRadiance = vec4(sum / float(n), 0.0);
}
#else
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
void main() { outRadiance = vec4(texelFetch(gb2, ivec2(gl_FragCoord.xy), 0).rgb, 0.0); }
#endif
