#version 450
// Normal visualisation: each vertex of each triangle becomes a thin quad from the vertex along
// its normal (0.4 long, about 2 pixels wide on screen), drawn in yellow by flat.frag.
layout(triangles) in;
layout(triangle_strip, max_vertices = 12) out;
layout(binding = 0, std140) uniform Frame {
    mat4 viewProj;
    vec4 lightDir;
} frame;
layout(location = 0) in vec3 vPosition[];
layout(location = 1) in vec3 vNormal[];
void main() {
    for (int i = 0; i < 3; ++i) {
        const vec4 a = frame.viewProj * vec4(vPosition[i], 1.0);
        const vec4 b = frame.viewProj * vec4(vPosition[i] + 0.4 * vNormal[i], 1.0);
        const vec2 along = b.xy / b.w - a.xy / a.w;
        const vec2 side = length(along) > 1e-6 ? normalize(vec2(-along.y, along.x)) * 0.012 : vec2(0.0);
        gl_Position = a + vec4(side * a.w, 0.0, 0.0);
        EmitVertex();
        gl_Position = a - vec4(side * a.w, 0.0, 0.0);
        EmitVertex();
        gl_Position = b + vec4(side * b.w, 0.0, 0.0);
        EmitVertex();
        gl_Position = b - vec4(side * b.w, 0.0, 0.0);
        EmitVertex();
        EndPrimitive();
    }
}
