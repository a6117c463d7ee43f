#version 450
// storage_image_every_format: writes a RGBA16F storage image (exact values in the format).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform writeonly image2D target;
void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    imageStore(target, ivec2(p), vec4(float(p.x) / 16.0, float(p.y) / 16.0, 0.25, 1.0));
}
