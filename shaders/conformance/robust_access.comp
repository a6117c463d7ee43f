#version 450
// Half the invocations write past the end of `written`; most read past the end of `source`
// (runtime-sized arrays: the bound range is the only bound).
layout(local_size_x = 32) in;
layout(std430, binding = 0) buffer Written { float written[]; };
layout(std430, binding = 1) readonly buffer Source { float source[]; };
layout(std430, binding = 2) buffer Read { float read[]; };
void main() {
    const uint i = gl_GlobalInvocationID.x;
    written[i] = float(i + 1u);  // 16 floats bound: 16 in range, 16 past the end
    read[i] = source[i + 8u];    // 16 floats bound: 8 in range, 24 past the end
}
