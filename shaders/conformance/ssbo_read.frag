#version 450
// Colour per 16-pixel column from a storage buffer read in the fragment stage.
layout(binding = 2, std430) readonly buffer Colors { vec4 colors[]; };
layout(location = 0) out vec4 outColor;
void main() { outColor = colors[int(gl_FragCoord.x) / 16]; }
