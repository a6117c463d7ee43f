#version 450
// Four control points pass through; the quad is cut 4 x 4 (every level 4).
layout(vertices = 4) out;
layout(location = 0) in vec2 vPosition[];
layout(location = 0) out vec2 cPosition[];
void main() {
    cPosition[gl_InvocationID] = vPosition[gl_InvocationID];
    if (gl_InvocationID == 0) {
        gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] =
            gl_TessLevelOuter[3] = 4.0;
        gl_TessLevelInner[0] = gl_TessLevelInner[1] = 4.0;
    }
}
