#version 450
// One sample of a multisampled texture: the sample index is params.a.x.
layout(binding = 0, std140) uniform Params { vec4 a; vec4 b; } params;
layout(binding = 1) uniform sampler2DMS tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(tex, ivec2(gl_FragCoord.xy), int(params.a.x)); }
