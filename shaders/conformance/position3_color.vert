#version 450
// Position with depth + colour per vertex (MSAA edges, depth bias slopes, depth clamp).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec3 vColor;
void main() {
    gl_Position = vec4(inPosition, 1.0);
    vColor = inColor.rgb;
}
