#version 450
// Layer params.a.y of a depth array, reference params.a.x.
layout(binding = 0, std140) uniform Params { vec4 a; vec4 b; } params;
layout(binding = 1) uniform sampler2DArrayShadow tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(texture(tex, vec4(gl_FragCoord.xy / 64.0, params.a.y, params.a.x))); }
