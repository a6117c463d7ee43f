#version 450
// Position + colour per vertex, offset per instance (instancing without gl_InstanceIndex).
layout(location = 0) in vec2 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 2) in vec2 inOffset;
layout(location = 0) out vec3 vColor;
void main() {
    gl_Position = vec4(inPosition + inOffset, 0.0, 1.0);
    vColor = inColor.rgb;
}
