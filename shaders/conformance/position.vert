#version 450
// Position only (vec2 at location 0); the colour is the fragment shader's (ubo_color.frag).
layout(location = 0) in vec2 inPosition;
void main() { gl_Position = vec4(inPosition, 0.0, 1.0); }
