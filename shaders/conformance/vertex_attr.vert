#version 450
// Passes one attribute of the format under test through to the colour.
layout(location = 0) in vec2 inPosition;
layout(location = 1) in vec4 inAttr;
layout(location = 0) out vec4 vValue;
void main() {
    gl_Position = vec4(inPosition, 0.0, 1.0);
    vValue = inAttr;
}
