#version 450
// 80 bytes of per-object data from a uniform buffer slice (bench/PerDrawConstants).
layout(location = 0) in vec2 inPosition;
layout(binding = 0, std140) uniform Object { vec4 offsetScale; vec4 color; vec4 extra[3]; } object;
layout(location = 0) out vec4 vColor;
void main() {
    gl_Position = vec4(inPosition * object.offsetScale.zw + object.offsetScale.xy, 0.0, 1.0);
    vColor = object.color + object.extra[2] * 0.0;
}
