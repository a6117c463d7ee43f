#version 450
// Comparison sampling: params.a.x is the reference depth; the result (0, 1 or a PCF fraction)
// goes to every channel.
layout(binding = 0, std140) uniform Params { vec4 a; vec4 b; } params;
layout(binding = 1) uniform sampler2DShadow tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(texture(tex, vec3(gl_FragCoord.xy / 64.0, params.a.x))); }
