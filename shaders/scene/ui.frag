#version 450
// ImGui's colours are display (sRGB-encoded) values: decoded here so that the RGBA8_SRGB target's
// encoding on store gives back the colours ImGui asked for.
layout(binding = 1) uniform sampler2D atlas;
layout(location = 0) in vec2 vUv;
layout(location = 1) in vec4 vColour;
layout(location = 0) out vec4 outColour;
vec3 srgbToLinear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045))); }
void main() {
    vec4 c = vColour * texture(atlas, vUv);
    outColour = vec4(srgbToLinear(c.rgb), c.a);
}
