#version 450
// One invocation per texel of a 3D storage image: (x/8, y/8, z/4).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image3D outImage;
void main() {
    uvec3 p = gl_GlobalInvocationID;
    imageStore(outImage, ivec3(p), vec4(float(p.x) / 8.0, float(p.y) / 8.0, float(p.z) / 4.0, 1.0));
}
