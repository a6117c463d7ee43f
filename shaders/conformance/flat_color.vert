#version 450
// Position + colour per vertex, the colour passed flat: a triangle takes its provoking vertex's.
layout(location = 0) in vec2 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) flat out vec4 vColor;
void main() {
    gl_Position = vec4(inPosition, 0.0, 1.0);
    vColor = inColor;
}
