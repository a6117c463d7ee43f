#version 450
// Displacement: each generated vertex of the floor rises and falls in waves; its height colours it.
layout(quads, equal_spacing, ccw) in;
layout(binding = 0, std140) uniform Frame {
    mat4 viewProj;
    vec4 lightDir;
} frame;
layout(location = 0) in vec2 cPosition[];
layout(location = 0) out float tHeight;
void main() {
    const vec2 uv = gl_TessCoord.xy;
    const vec2 p = mix(mix(cPosition[0], cPosition[1], uv.x), mix(cPosition[2], cPosition[3], uv.x), uv.y);
    tHeight = 0.5 + 0.5 * sin(3.0 * p.x) * cos(3.0 * p.y);
    gl_Position = frame.viewProj * vec4(p.x, -1.2 + 0.3 * tHeight, p.y, 1.0);
}
