#version 450
layout(binding = 1) uniform sampler2D tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texture(tex, gl_FragCoord.xy / vec2(64.0)); }
