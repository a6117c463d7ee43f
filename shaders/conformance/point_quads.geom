#version 450
// Each point becomes a 16x16-pixel square (0.25 in clip space either side on a 64x64 target)
// in its colour, with blue = the primitive's index / 4 (gl_PrimitiveIDIn counts the points).
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
layout(location = 0) in vec4 vColor[];
layout(location = 0) out vec3 gColor;
void main() {
    const vec2 corners[4] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(-1, 1), vec2(1, 1));
    for (int i = 0; i < 4; ++i) {
        gl_Position = gl_in[0].gl_Position + vec4(0.25 * corners[i], 0.0, 0.0);
        gColor = vec3(vColor[0].rg, float(gl_PrimitiveIDIn) * 0.25);
        EmitVertex();
    }
    EndPrimitive();
}
