#version 450
// The normals in yellow.
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(1.0, 1.0, 0.0, 1.0); }
