#version 450
// Sample 0 of a multisampled texture (sampler2DMS: textures with sampleCount > 1 and Sampled usage).
layout(binding = 0) uniform sampler2DMS tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(tex, ivec2(gl_FragCoord.xy), 0); }
