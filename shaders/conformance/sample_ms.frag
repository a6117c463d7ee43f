#version 450
// A multisampled texture sampled directly: no texture of the device fits it (createShader refuses).
layout(binding = 0) uniform sampler2DMS tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(tex, ivec2(gl_FragCoord.xy), 0); }
