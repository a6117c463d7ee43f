#version 450
// storage_image_every_format: writes a R32U storage image (exact values in the format).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32ui) uniform writeonly uimage2D target;
void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    imageStore(target, ivec2(p), uvec4(p.x + 16u * p.y + 1u, 0u, 0u, 1u));
}
