#version 450
// uv = pixel / 64 * scale + offset; explicit level of detail (params.depth.y).
layout(binding = 0, std140) uniform Params { vec4 color; vec4 depth; } params;
layout(binding = 1) uniform sampler2D tex;
layout(location = 0) out vec4 outColor;
void main() {
    vec2 uv = gl_FragCoord.xy / vec2(64.0) * params.color.xy + params.color.zw;
    outColor = textureLod(tex, uv, params.depth.y);
}
