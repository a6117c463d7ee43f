#version 450
// Storage textures at slots 9 and 40: past the 8 image units of NVIDIA's GL and the 32 of Mesa's.
// Each gets its own pattern, so two slots that land on one unit show as a wrong image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 40, rgba8) uniform writeonly image2D second;
layout(binding = 3, std430) readonly buffer Scale { float scale; };
layout(binding = 9, rgba8) uniform writeonly image2D first;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(first, p, vec4(float(p.x) / 8.0, 0.0, scale, 1.0));
    imageStore(second, p, vec4(0.0, float(p.y) / 8.0, 1.0 - scale, 1.0));
}
