#version 450
// The background pass for a colour or transparent background (RenderSettings::Background): one
// constant RGBA. Drawn at the far plane where nothing was drawn (0: no radiance, no coverage), and
// with only alpha written where a surface was (alpha 1: covered).
layout(std140, binding = 1) uniform BackgroundBlock {
    vec4 value;
} background;
layout(location = 0) out vec4 outRadiance;
void main() { outRadiance = background.value; }
