#version 450
// gl_PointCoord in red and green: (0, 0) is the point's top left on every backend.
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(gl_PointCoord, 0.0, 1.0); }
