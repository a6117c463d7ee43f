#version 450
// Dear ImGui vertices: pixel position, font-atlas uv, sRGB colour (8 bits per channel).
layout(binding = 0) uniform UiConstants {
    vec4 scaleTranslate;  // clip = pos * xy + zw (clip space is y-down on every backend, as ImGui's)
} ui;
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 colour;
layout(location = 0) out vec2 vUv;
layout(location = 1) out vec4 vColour;
void main() {
    vUv = uv;
    vColour = colour;
    gl_Position = vec4(position * ui.scaleTranslate.xy + ui.scaleTranslate.zw, 0.0, 1.0);
}
