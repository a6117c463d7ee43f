#version 450
// The terrain in blue-green, lighter where it is higher.
layout(location = 0) in float tHeight;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(0.05, 0.3 + 0.5 * tHeight, 0.6, 1.0); }
