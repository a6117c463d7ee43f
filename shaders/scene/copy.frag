#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// A texel-for-texel copy (TAA keeps this frame's result as the next frame's history).
layout(binding = FE_SLOT_RADIANCE) uniform sampler2D source;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(source, ivec2(gl_FragCoord.xy), 0); }
