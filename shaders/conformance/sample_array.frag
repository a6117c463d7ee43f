#version 450
// Quadrant q of the 64x64 target shows layer q of a 2D array texture (q = column + 2 * row).
layout(binding = 1) uniform sampler2DArray tex;
layout(location = 0) out vec4 outColor;
void main() {
    vec2 cell = floor(gl_FragCoord.xy / 32.0);
    outColor = texture(tex, vec3(fract(gl_FragCoord.xy / 32.0), cell.x + 2.0 * cell.y));
}
