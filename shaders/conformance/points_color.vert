#version 450
// A point per vertex with its colour, for point_quads.geom.
layout(location = 0) in vec2 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 vColor;
void main() {
    gl_Position = vec4(inPosition, 0.0, 1.0);
    vColor = inColor;
}
