#version 450
// The quad domain over control points 0..3 = (x0, y0), (x1, y0), (x0, y1), (x1, y1); each
// generated vertex's colour is (u^2, v, 0), so the drawn red is u^2 interpolated linearly
// between the 5 vertex columns (0, 1/4, ... 1): the tessellation shows in the image.
layout(quads, equal_spacing, ccw) in;
layout(location = 0) in vec2 cPosition[];
layout(location = 0) out vec3 tColor;
void main() {
    const vec2 uv = gl_TessCoord.xy;
    const vec2 p = mix(mix(cPosition[0], cPosition[1], uv.x), mix(cPosition[2], cPosition[3], uv.x), uv.y);
    gl_Position = vec4(p, 0.0, 1.0);
    tColor = vec3(uv.x * uv.x, uv.y, 0.0);
}
