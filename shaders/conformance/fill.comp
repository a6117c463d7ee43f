#version 450
// Writes a buffer (value = 3 * index + 1) and an image (a gradient) from one dispatch.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, std430) buffer Values { uint values[]; };
layout(binding = 1, rgba32f) uniform writeonly image2D outImage;
void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    values[p.y * 64u + p.x] = 3u * (p.y * 64u + p.x) + 1u;
    imageStore(outImage, ivec2(p), vec4(float(p.x) / 64.0, float(p.y) / 64.0, 0.5, 1.0));
}
