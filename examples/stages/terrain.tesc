#version 450
// Each quad patch of the floor cut 8 x 8.
layout(vertices = 4) out;
layout(location = 0) in vec2 vPosition[];
layout(location = 0) out vec2 cPosition[];
void main() {
    cPosition[gl_InvocationID] = vPosition[gl_InvocationID];
    if (gl_InvocationID == 0) {
        gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = 8.0;
        gl_TessLevelInner[0] = gl_TessLevelInner[1] = 8.0;
    }
}
