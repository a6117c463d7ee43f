#version 450
// A control point of a tessellated patch (patch_quad.tesc / .tese).
layout(location = 0) in vec2 inPosition;
layout(location = 0) out vec2 vPosition;
void main() {
    vPosition = inPosition;
    gl_Position = vec4(inPosition, 0.0, 1.0);
}
