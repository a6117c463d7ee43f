#version 450
layout(binding = 0, std140) uniform Params { vec4 color; vec4 depth; } params;
layout(location = 0) out vec4 outColor;
void main() { outColor = params.color; }
