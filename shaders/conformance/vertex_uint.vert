#version 450
// Integer attribute: the value / 1000 in red.
layout(location = 0) in vec2 inPosition;
layout(location = 1) in uint inValue;
layout(location = 0) out vec4 vValue;
void main() {
    gl_Position = vec4(inPosition, 0.0, 1.0);
    vValue = vec4(float(inValue) / 1000.0, 0.0, 0.0, 1.0);
}
