#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// Arithmetic with no memory traffic but one store: a compute job whose cost is its iterations
// (fe_bench_execution's async-compute overlap). FE_CONSTANTS: the iteration count.
layout(local_size_x = 64) in;
layout(binding = 0, std430) buffer Results { float results[]; };
FE_CONSTANTS(Job) { uint iterations; } job;
void main() {
    float x = float(gl_GlobalInvocationID.x) * 1e-3;
    for (uint i = 0u; i < job.iterations; ++i) x = fract(x * 1.618034 + 0.3183099);
    results[gl_GlobalInvocationID.x] = x;
}
