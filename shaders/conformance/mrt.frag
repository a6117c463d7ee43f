#version 450
// Four targets of mixed formats, each with a known value.
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out vec4 o2;
layout(location = 3) out vec4 o3;
void main() {
    o0 = vec4(0.2, 0.4, 0.6, 0.8);
    o1 = vec4(1.5, -2.0, 3.25, 1.0);
    o2 = vec4(0.125, 4.5, 0.0, 0.0);
    o3 = vec4(-7.75, 0.0, 0.0, 0.0);
}
