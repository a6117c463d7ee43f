#version 450
// A small per-object draw: position attribute + per-object constants (bench/AbstractionCost).
layout(location = 0) in vec2 inPosition;
layout(binding = 0) uniform Object {
    vec4 offsetScale;
    vec4 color;
} object;
layout(location = 0) out vec4 vColor;
void main() {
    gl_Position = vec4(inPosition * object.offsetScale.zw + object.offsetScale.xy, 0.0, 1.0);
    vColor = object.color;
}
