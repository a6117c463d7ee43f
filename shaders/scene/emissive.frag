#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Deferred: emissive (and unlit colour) added after the lights.
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(location = 0) out vec4 outRadiance;
void main() { outRadiance = vec4(texelFetch(gb2, ivec2(gl_FragCoord.xy), 0).rgb, 0.0); }
