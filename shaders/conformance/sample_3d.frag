#version 450
// Band b of four across the target shows depth slice b of a 4x4x4 texture, at slice centres.
layout(binding = 1) uniform sampler3D tex;
layout(location = 0) out vec4 outColor;
void main() {
    float u = gl_FragCoord.x * 4.0 / 64.0;
    outColor = texture(tex, vec3(fract(u), gl_FragCoord.y / 64.0, (floor(u) + 0.5) / 4.0));
}
